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

// The batch's fast path for a small cloud on the CPU: convex_hull_without_neighbors()'s hull, bit for bit,
// where plan_hull() would take the small-cloud hull (`options` as the batch resolved them: backend cpu,
// engine auto, no merging; 4 to kSmallHullPoints points) and it succeeds, read without a copy of the points,
// a plan or an allocation but the result's.  False (`hull` untouched) otherwise, a bad coordinate included:
// convex_hull_without_neighbors() then, which names it.
template <class Scalar>
bool small_cloud_hull(const Scalar* xyz, std::size_t count, const ConvexHullOptions& options,
                      ConvexHull& hull);

}  // namespace cudahull
