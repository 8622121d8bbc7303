#include "legend.hpp"

#include <algorithm>
#include <cmath>

#include "overlay.hpp"

namespace cudahull::viewer {

namespace {

// As shaders/colors.glsl's hsv_to_rgb, for the "by age" ramp.
glm::vec3 hsv_to_rgb(float h, float s, float v) {
  glm::vec3 k;
  for (int i = 0; i < 3; ++i) {
    const float offset = i == 0 ? 0.0f : i == 1 ? 4.0f : 2.0f;
    k[i] = std::clamp(std::abs(std::fmod(h * 6.0f + offset, 6.0f) - 3.0f) - 1.0f, 0.0f, 1.0f);
  }
  return v * glm::mix(glm::vec3(1.0f), k, s);
}

}  // namespace

glm::vec3 rgb_of(std::uint32_t rgba) {
  return {(rgba & 0xff) / 255.0f, ((rgba >> 8) & 0xff) / 255.0f, ((rgba >> 16) & 0xff) / 255.0f};
}

std::vector<LegendEntry> legend_entries(const RenderSettings& s, bool face_selected) {
  std::vector<LegendEntry> out;
  const bool by_face = s.point_colors == PointColors::kFace;
  if (s.shown(Layer::kExternal))
    out.push_back({"points", by_face ? "external (one colour per face)" : "external (outside the hull)",
                   by_face ? hsv_to_rgb(0.35f, 0.7f, 0.85f) : kExternalColor});
  if (s.shown(Layer::kInternal))
    out.push_back({"points", "internal (proven inside)", by_face ? glm::vec3(0.32f) : kInternalColor});
  if (s.shown(Layer::kVertices)) out.push_back({"points", "hull vertices", kVertexColor});
  const bool cell = s.shown(Layer::kCells) && face_selected;
  if (cell) out.push_back({"points", "selected cell's points", kSelectedColor});
  if (s.shown(Layer::kHull)) {
    if (s.face_colors == FaceColors::kState) {
      out.push_back({"faces", "refined this step", kFaceStateColors[static_cast<int>(FaceState::kRefined)]});
      out.push_back({"faces", "made by a swap", kFaceStateColors[static_cast<int>(FaceState::kSwapped)]});
      out.push_back({"faces", "made by a removal", kFaceStateColors[static_cast<int>(FaceState::kRemoval)]});
      out.push_back({"faces", "unchanged", kFaceStateColors[static_cast<int>(FaceState::kUnchanged)]});
    } else {
      out.push_back({"faces", "new this step", hsv_to_rgb(0.08f, 0.7f, 0.92f)});
      out.push_back({"faces", "older", hsv_to_rgb(0.62f, 0.7f, 0.92f)});
    }
  }
  if (s.shown(Layer::kSwaps)) {
    out.push_back({"swaps", "regular swap: new edge", rgb_of(kRegularSwapRgba)});
    out.push_back({"swaps", "complementary swap: new edge", rgb_of(kComplementarySwapRgba)});
    out.push_back({"swaps", "swapped: old edge", rgb_of(kOldEdgeRgba)});
    out.push_back({"swaps", "rejected foldover: edge", rgb_of(kFoldoverRgba)});
    out.push_back({"swaps", "foldover: vertex beneath", rgb_of(kBeneathRgba)});
    out.push_back({"swaps", "removal: vertex, new face", rgb_of(kRemovalRgba)});
  }
  if (s.shown(Layer::kRefinement)) {
    out.push_back({"refinement", "refined face", glm::vec3(1.0f)});
    out.push_back({"refinement", "apex and its edges", glm::vec3(1.0f, 0.62f, 0.16f)});
  }
  if (cell) out.push_back({"cell", "separating planes", glm::vec3(0.2f, 0.85f, 0.95f)});
  if (s.shown(Layer::kInput)) out.push_back({"model", "the input's own surface", glm::vec3(0.78f * 0.75f)});
  return out;
}

}  // namespace cudahull::viewer
