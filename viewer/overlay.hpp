// The debugger's overlay geometry (issue 6), built from the engine's current mesh: what the renderer draws
// over the hull for the cells and normals layers, and the face under the mouse.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "cudahull/engine.hpp"
#include "render_data.hpp"

namespace cudahull::viewer {

struct Overlay {
  std::vector<OverlayVertex> triangles;  // translucent
  std::vector<OverlayVertex> lines;
  std::vector<OverlayLabel> labels;  // the swaps' and removals' sequence numbers
};

// cells: face `selected`'s three separating planes (Fig. 2: each through an edge, containing the average of
// the unit normals of the edge's two faces) as translucent quads standing on the edges, the face's outline,
// and a cross on its extreme point when it has external points.  normals: every edge's normal (the
// direction its separating plane rises along) as an arrow from the edge's midpoint.  Nothing for an
// engine without a 3-d mesh or a face id out of range.
//
// refinement (Fig. 3a): each face the last step refined, outlined, with its apex marked and the edges from
// the apex to its corners.  swaps (Figs. 3b, 4, 5): each swap of the last step as its old edge (dim red)
// and new edge (green for regular, light blue for complementary); each rejected foldover as its old edge
// (orange), the would-be edge (grey), the vertex beneath marked and the triangle it lies beneath outlined
// (magenta); each degree-3 removal as the removed vertex marked and its new face outlined (purple).
struct OverlayLayers {
  bool cells = false, normals = false, refinement = false, swaps = false;
  int sequence_limit = 1 << 30;  // swaps: only those up to this sequence number (sub-steps)
};
void build_overlay(const SteppingEngine& engine, long long selected, const OverlayLayers& layers,
                   Overlay& out);

// The palette of the swaps layer, shared with the tests that look for it.
inline constexpr std::uint32_t kRegularSwapRgba = 0xff40d050u;        // green
inline constexpr std::uint32_t kComplementarySwapRgba = 0xfff0c060u;  // light blue
inline constexpr std::uint32_t kOldEdgeRgba = 0xff3030b0u;            // dim red
inline constexpr std::uint32_t kFoldoverRgba = 0xff2090ffu;           // orange
inline constexpr std::uint32_t kBeneathRgba = 0xffff40ffu;            // magenta
inline constexpr std::uint32_t kRemovalRgba = 0xffd050a0u;            // purple

// The nearest face of the current mesh hit by the ray origin + t * direction (t > 0), or -1.
long long pick_face(const SteppingEngine& engine, const glm::dvec3& origin, const glm::dvec3& direction);

}  // namespace cudahull::viewer
