// A small, exact, sequential 3D convex hull: exact QuickHull with outside sets on exact predicates, followed
// by merging coplanar facets so that only strictly extreme points remain as vertices.
//
// The engine uses it to finish (and, where the paper's local procedure could not, repair) the hull from its
// candidate vertices; it also computes the lower-dimensional answer for degenerate inputs.
#pragma once

#include <vector>

#include "cudahull/types.hpp"
#include "cudahull/wide_predicates.hpp"  // in_fast_exact_range() and the wide predicates

namespace cudahull {

// Exact convex hull of points[ids[i]] (all of `points` when `ids` is empty).
//  - Vertices are exactly the strictly extreme points; among points with identical coordinates the one with
//    the lowest input index is the vertex.  vertex_ids are sorted ascending.
//  - dimension 3: outward counter-clockwise triangles; coplanar facets are triangulated using corners only.
//  - dimension 2: the polygon's strict corners in order, no triangles.  dimension 1: the two segment ends.
//    dimension 0: a single point.  An empty input gives dimension -1 and no vertices.
// `Point` is Point3 or Point3d (defined in exact_hull.cpp for both); the hull is exact on the coordinates as
// given, so a double input is not rounded to float (barring overflow or underflow in the predicates).
template <class Point = Point3>
BasicHullMesh<Point> exact_hull(const std::vector<Point>& points, const std::vector<PointIndex>& ids = {});

// The affine dimension (-1 for no points, 0..3) of the point set, exactly.  Point3 or Point3d.
template <class Point = Point3>
int affine_dimension(const std::vector<Point>& points);

// The exact hull of double points with ANY finite coordinates: where every nonzero magnitude lies in
// 2^-250..2^250 this is exact_hull(); where the input's nonzero magnitudes span few enough binades (their
// floor(log2 |c|) within 499 of each other) it is exact_hull() of the points scaled by one power of two
// (exact), reported in the input's coordinates; else exact_hull() on the wide predicates
// (wide_predicates.hpp: a filter, and GMP where a predicate's own coordinates need it), slower.  Same
// contract as exact_hull(): the vertices are the input's own coordinates, unscaled.  Only the points taking
// part (points[ids[i]], or all) are looked at; a NaN or infinite coordinate among them throws
// std::invalid_argument.
HullMeshd exact_hull_any(const std::vector<Point3d>& points, const std::vector<PointIndex>& ids = {});

// Whether every coordinate of `points` (or of the `count` points at `points`) is inside the fast exact range
// (in_fast_exact_range(), predicates.hpp): then exact_hull() and the engines are exact on them, and
// exact_hull_any() is exact_hull().
bool in_fast_exact_range(const std::vector<Point3d>& points);
bool in_fast_exact_range(const Point3d* points, std::size_t count);

extern template HullMesh exact_hull(const std::vector<Point3>&, const std::vector<PointIndex>&);
extern template HullMeshd exact_hull(const std::vector<Point3d>&, const std::vector<PointIndex>&);
extern template int affine_dimension(const std::vector<Point3>&);
extern template int affine_dimension(const std::vector<Point3d>&);

}  // namespace cudahull
