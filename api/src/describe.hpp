// A result from an exact mesh (describe.cpp): its faces as input indices, neighbours, planes and measures
// in double from the coordinates the hull was computed on, merged as Qhull merges where the options ask
// (facet_merge.hpp).  Internal to api/: every hull path ends here.
#pragma once

#include <string>

#include "cudahull/convex_hull.hpp"
#include "cudahull/types.hpp"

namespace cudahull::detail {

// The exact hull's result; `neighbors` false leaves them out (the batch keeps none).
template <class Point>
ConvexHull describe_exact(const BasicHullMesh<Point>& mesh, std::string backend, bool neighbors = true);

// The result convex_hull() returns for the exact hull `mesh`, merged where `options` ask for it (a flat hull
// has nothing to merge).
template <class Point>
ConvexHull describe(const BasicHullMesh<Point>& mesh, std::string backend, const ConvexHullOptions& options,
                    bool neighbors = true);

}  // namespace cudahull::detail
