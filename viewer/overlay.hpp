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
};

// cells: face `selected`'s three separating planes (Fig. 2: each through an edge, containing the average of
// the unit normals of the edge's two faces) as translucent quads standing on the edges, the face's outline,
// and a cross on its extreme point when it has external points.  normals: every edge's normal (the
// direction its separating plane rises along) as an arrow from the edge's midpoint.  Nothing for an
// engine without a 3-d mesh or a face id out of range.
void build_overlay(const Engine& engine, long long selected, bool cells, bool normals, Overlay& out);

// The nearest face of the current mesh hit by the ray origin + t * direction (t > 0), or -1.
long long pick_face(const Engine& engine, const glm::dvec3& origin, const glm::dvec3& direction);

}  // namespace cudahull::viewer
