// Qhull (libqhull_r) run in-process on the same points (Qhull computes in double: float32 points are widened
// exactly, double points go as they are): the reference the benchmarks measure against and one of the
// oracles the tests compare with.
#pragma once

#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

struct QhullResult {
  std::vector<PointIndex> vertex_ids;  // sorted ascending
  std::size_t facets = 0;
  double milliseconds = 0;  // qh_new_qhull through the vertex listing, excluding the copy into Qhull's array
};

// Runs Qhull with `options` (default "Qt", as in the paper's comparison).  Throws std::runtime_error with
// Qhull's message if Qhull fails (for example on fewer than 4 affinely independent points).  Point3 or
// Point3d (one implementation, defined for both).
template <class Point = Point3>
QhullResult run_qhull(const std::vector<Point>& points, const std::string& options = "Qt");

extern template QhullResult run_qhull(const std::vector<Point3>&, const std::string&);
extern template QhullResult run_qhull(const std::vector<Point3d>&, const std::string&);

}  // namespace cudahull
