// planar_hull(): the exact convex hull of points in the plane, behind the API's 2-D input (scipy's 2-D
// ConvexHull).  Every decision is an exact orient2d or an exact comparison of coordinates.
//
// design:
//   round one: the extremes of a strided sample (at most 2^16 points) in 64 directions, in plain double
//              arithmetic: any input points span an inner polygon, whichever are chosen.  Its exact hull
//              is the inner polygon; where that is a point or a segment, the extremes of every point in the
//              8 directions +-x, +-y, +-(x+y), +-(x-y), then a pass for any point off it, and with none
//              the input is one point or a segment (its ends: the least and greatest (x, y))
//   filter:    every point strictly inside the inner polygon is dropped, exactly, on all cores: inside a box
//              within it by 4 comparisons, else by 3 orient2d in its sector of a fan; points on its
//              boundary stay
//   round two: where over 2^16 points stay, the polygon grown by a sample of them in 128 directions, and
//              those points filtered again if that drops a quarter of the sample
//   chain:     the survivors sorted by (x, y, index), identical coordinates reduced to the lowest index,
//              Andrew's monotone chain popping on orient2d <= 0 (points inside an edge are no corners)
#pragma once

#include <cstddef>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

struct PlanarHull {
  int dimension = -1;  // 2 (a polygon), 1 (a segment), 0 (one distinct point), -1 (no points)
  // dimension 2: the strict corners, counter-clockwise, starting at the lowest (x, then y) corner;
  // dimension 1: the two ends, the lowest (x, y) first; dimension 0: the one point.
  std::vector<PointIndex> polygon;
};

// The exact convex hull of `count` points given as x, y pairs (contiguous).  Vertices are exactly the
// strictly extreme points (a point inside an edge is not a corner); among points with identical coordinates
// the lowest input index is the one named.  Exact on the coordinates as given (orient2d), for finite
// coordinates whose products neither overflow nor underflow (magnitudes within 2^-250 .. 2^250, or zero);
// the caller checks for NaN and infinity.  At most 2^32 - 1 points (std::length_error beyond).
PlanarHull planar_hull(const double* xy, std::size_t count);
PlanarHull planar_hull(const float* xy, std::size_t count);

}  // namespace cudahull
