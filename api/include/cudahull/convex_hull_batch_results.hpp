// A batch's result placed by the caller: for callers that make the result's arrays themselves (the Python
// module's NumPy arrays), where DeviceConvexHullBatch::to_host()'s vectors would first be zeroed, on one
// core, and then copied into through the driver's staging.
//
//   auto result = cudahull::convex_hull_batch_results(xyz, count, offsets, clouds);
//   if (auto* on_device = std::get_if<cudahull::DeviceConvexHullBatch>(&result))
//     cudahull::copy_to_host(*on_device, columns);  // arrays of the caller's, as large as the columns
//   else
//     use(std::get<cudahull::ConvexHullBatch>(result));
#pragma once

#include <cstddef>
#include <cstdint>
#include <variant>

#include "cudahull/convex_hull_batch.hpp"

namespace cudahull {

// convex_hull_batch() on host points, the result left where it was made: the batch kernel's in device memory
// (its indices PointIndex's bits in int32 columns), any other's on the host.  The same hulls either way.
// Throws as convex_hull_batch() does.
std::variant<ConvexHullBatch, DeviceConvexHullBatch> convex_hull_batch_results(
    const float* xyz, std::size_t count, const std::size_t* offsets, std::size_t clouds,
    const ConvexHullBatchOptions& options = {});
std::variant<ConvexHullBatch, DeviceConvexHullBatch> convex_hull_batch_results(
    const double* xyz, std::size_t count, const std::size_t* offsets, std::size_t clouds,
    const ConvexHullBatchOptions& options = {});

// Host memory for each column of a DeviceConvexHullBatch, each at least as large as its column.
struct BatchHostColumns {
  std::int64_t *vertex_offsets, *face_offsets, *polygon_offsets;  // B + 1 each
  std::int32_t *vertices, *faces, *polygons, *dimensions;
  double *planes, *volumes, *areas;
};

// The columns of `batch` read into `into`, the large ones at the bus's pace (through pinned staging on all
// cores: cudahull/cuda/host_transfer.hpp).  Throws DeviceError.
void copy_to_host(const DeviceConvexHullBatch& batch, const BatchHostColumns& into);

}  // namespace cudahull
