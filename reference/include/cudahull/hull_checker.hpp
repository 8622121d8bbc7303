// The independent hull checker behind `cudahull hull --verify` (like Qhull's Tv).  It knows nothing of how
// the hull was built and decides everything with exact predicates.
#pragma once

#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

struct CheckResult {
  bool ok = true;
  std::vector<std::string> failures;  // one line each, e.g. "point 17 is above face 3"
};

// Checks, for dimension 3:
//  1. the mesh is a closed 2-manifold: every edge in exactly two faces with opposite directions, V-E+F = 2,
//     no unused vertex, no degenerate (collinear) triangle;
//  2. faces are outward: every input point is below or on every face's plane;
//  3. every edge is convex or flat;
//  4. every vertex is strictly extreme (not inside a face, on an edge, or a duplicate);
//  5. vertex coordinates equal their input points, and each vertex id is the lowest index among input
//     points with the same coordinates.
// For dimension 0..2 it checks the lower-dimensional analogues (all points on the line/plane, inside the
// segment/polygon, ends/corners strictly extreme).  Reports at most `max_failures` lines.
// `Point` is Point3 or Point3d (defined in hull_checker.cpp for both); every test is exact on the given
// coordinates, and messages print them in full precision (9 significant digits for float, 17 for double).
template <class Point = Point3>
CheckResult check_hull(const std::vector<Point>& points, const BasicHullMesh<Point>& hull,
                       std::size_t max_failures = 20);

extern template CheckResult check_hull(const std::vector<Point3>&, const HullMesh&, std::size_t);
extern template CheckResult check_hull(const std::vector<Point3d>&, const HullMeshd&, std::size_t);

}  // namespace cudahull
