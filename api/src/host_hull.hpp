// convex_hull() for the batch's single-cloud path (convex_hull_batch.cpp): the same hull without the faces'
// neighbours, which a batch does not keep (finding them was a tenth of a small cloud's time).
#pragma once

#include <cstddef>

#include "cudahull/convex_hull.hpp"

namespace cudahull {

// convex_hull(xyz, count, options) with `neighbors` left empty where the hull is computed on the host (a
// merged hull keeps them).
ConvexHull convex_hull_without_neighbors(const float* xyz, std::size_t count,
                                         const ConvexHullOptions& options);
ConvexHull convex_hull_without_neighbors(const double* xyz, std::size_t count,
                                         const ConvexHullOptions& options);

}  // namespace cudahull
