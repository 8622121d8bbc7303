// The exact hull's sites: the distinct input points, sorted along a Morton curve and deduplicated
// (sort_and_dedupe), and the mesh built from the sites kept as vertices (make_mesh).  Internal to reference/.
#pragma once

#include <cstdint>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull::exact {

// A distinct input point: coordinates (float for Point3, double for Point3d) plus the lowest input index
// among the points with these coordinates.
template <class Point>
struct Site {
  using Coord = decltype(Point::x);
  Coord x, y, z;
  PointIndex id;
};

// Builds the mesh from local site indices `keep` (each a strict extreme point): vertex_ids ascending.
// Returns the map site -> output vertex (kNone for sites not kept) through `out_index`.
template <class Point>
BasicHullMesh<Point> make_mesh(const std::vector<Site<Point>>& sites, std::vector<std::uint32_t> keep,
                               int dimension, std::vector<std::uint32_t>& out_index);

// Sorts sites along a Morton curve of their bounding box and removes duplicates, keeping the lowest id of
// each coordinate triple.  The Morton order is for memory locality only: QuickHull touches the points of a
// region together.  Identical coordinates get identical keys, so duplicates end up in one run of equal keys,
// sorted there by coordinates and id.  (+0 and -0 compare equal and get equal keys.)
template <class Point>
void sort_and_dedupe(std::vector<Site<Point>>& sites);

}  // namespace cudahull::exact
