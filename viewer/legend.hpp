// The colour key (issue 17): what each colour of the layers in use means.  One list for both legends: the
// window's panel (Dear ImGui) and the one the renderer draws into the picture (`set legend on`), so the two
// never disagree with the shaders' palette (renderer.hpp, overlay.hpp).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "renderer.hpp"

namespace cudahull::viewer {

struct LegendEntry {
  std::string group;  // "points", "faces", "swaps", "refinement", "cell"
  std::string name;
  glm::vec3 color;
};

// The entries for the layers `settings` shows; the selected cell's only with a face selected and the cells
// layer on.
std::vector<LegendEntry> legend_entries(const RenderSettings& settings, bool face_selected);

// The palette's RGBA8 (R in the low byte, as overlay.hpp packs it) as a colour.
glm::vec3 rgb_of(std::uint32_t rgba);

}  // namespace cudahull::viewer
