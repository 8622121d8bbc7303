// Qhull (libqhull_r) run in-process on the same float32 points converted to double: the reference the
// benchmarks measure against and one of the oracles the tests compare with.
#pragma once

#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

struct QhullResult {
  std::vector<PointIndex> vertex_ids;  // sorted ascending
  std::size_t facets = 0;
  double milliseconds = 0;  // qh_new_qhull through the vertex listing, excluding the float->double copy
};

// Runs Qhull with `options` (default "Qt", as in the paper's comparison).  Throws std::runtime_error with
// Qhull's message if Qhull fails (for example on fewer than 4 affinely independent points).
QhullResult run_qhull(const std::vector<Point3>& points, const std::string& options = "Qt");

}  // namespace cudahull
