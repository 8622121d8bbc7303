// The final exact check and repair, once no external point is left.
//
// design:
//   The mesh is the exact hull when every edge is strictly convex (so every vertex is strictly extreme),
//   the interior point c is strictly below every face, and every vertex a removal dropped lies inside.
//   Every other point was discarded inside a tetrahedron of c and input points, so nothing is outside.
//   check:   the edges that are not strictly convex (exact orient3d over all edges, on all cores)
//   repair:  rejected swaps can leave concave edges: the paper's local steps (swaps, complementary swaps,
//            removals; local_edits.hpp) from each faulty edge, up to 8 rounds
//   locate:  each dropped vertex by a walk through the radial cones from a face of its old ring
//   result:  the mesh's vertices and faces renumbered; or, when faults remain (coplanar or cospherical
//            input where the local steps stop short, or a stall), the exact reference hull of the
//            candidates (every vertex ever used, and the points still outside), which hold every extreme
//            point.  IterationRecord::repairs counts the faults.
#pragma once

#include <functional>
#include <vector>

#include "cudahull/backend.hpp"
#include "phases/local_edits.hpp"

namespace cudahull::phases {

// The exact hull from the mesh that `edits` edit (their record gets the repairs and a note); `geometry`
// matches the compacted mesh on entry and after.  `external` points are still outside after a stall;
// `point_faces` then lists every point's face (>= 0 while outside).
template <class Point>
BasicHullMesh<Point> final_check(LocalEdits<Point>& edits, BasicFaceGeometryArray<Point>& geometry,
                                 std::vector<PointIndex>& used_vertices, std::size_t external,
                                 const std::function<std::vector<std::int32_t>()>& point_faces);

}  // namespace cudahull::phases
