// Batched exact hulls (issue 27): the hulls of B point clouds packed in one array, in one call.
//
//   #include <cudahull/convex_hull_batch.hpp>
//   std::vector<cudahull::Point3> points = ...;          // cloud c is points[offsets[c] .. offsets[c + 1])
//   std::vector<std::size_t> offsets = {0, 1000, 1500, 4000};   // B + 1 boundaries: 3 clouds
//   cudahull::ConvexHullBatch hulls = cudahull::convex_hull_batch(points, offsets);
//   for (std::size_t c = 0; c < hulls.size(); ++c)
//     for (std::size_t k = hulls.vertex_offsets[c]; k < hulls.vertex_offsets[c + 1]; ++k)
//       use(points[offsets[c] + hulls.vertices[k]]);     // indices into cloud c
//
// Each cloud's hull is convex_hull()'s on that cloud alone (convex_hull.hpp): the same vertex set, planes,
// volume, area and dimension, whatever the thread count; the same faces (on the GPU's batch kernel, in
// general position, in another order).  Flat clouds give their lower-dimensional answer as convex_hull()
// does.
//
// design:
//   the offsets checked (B + 1 of them, from 0, never decreasing, to the point count)
//   one plan for the batch (plan_hull() on all its points): where it runs, CPU or CUDA
//   CPU: the clouds on all cores, a cloud a worker at a time in cloud order (each cloud's engine passes on
//     its worker's thread, SerialScope); a cloud too large to share the cores runs alone on all of them; a
//     cloud of 4 to kSmallHullPoints points takes convex_hull()'s small-cloud hull (the batch warps'
//     small_hull() on the host, small_hull_host()) read in place, with no plan, copy or neighbours
//   CUDA: the points checked once and on the device (host points uploaded once, as given); a launch of the
//     batch kernel (cuda/batch_cuda.hpp: a block a cloud, the resident engine's iteration) a kind of block
//     for the clouds of 4 to 131,072 points (BatchTuning's defaults: 128 threads; four blocks an SM above 256
//     points; 512 threads above 16,384), one more for those whose hulls outgrew the first's room; flat, tiny
//     and larger clouds, and those with defects, through the single-cloud path (convex_hull(),
//     convex_hull_device()); then the result laid out on the device (offsets from every cloud's sizes), the
//     kernel's meshes described there as convex_hull() describes one (the same code:
//     cudahull/detail/plane_impl.hpp), the other clouds' hulls copied up into place; read back only for a
//     host result.  Merged facets (ConvexHullOptions::merge other than exact) and the stepping engine run
//     cloud by cloud through the single-cloud path
//   errors: the first bad point in packed order raises, named by its cloud, its index in the cloud and its
//     row in the packed array; clouds after a failed one are not started
//   the per-cloud hulls packed into flat arrays with offsets, in cloud order
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cudahull/convex_hull.hpp"
#include "cudahull/tuning.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

struct ConvexHullBatchOptions {
  // Every cloud's hull is convex_hull(cloud, hull) (backend, engine, precision, merging); backend and
  // precision "auto" are resolved once for the whole batch.  On the CUDA backend, merging (merge other than
  // exact) and the stepping engine take the single-cloud path cloud by cloud, not the batch kernel.
  ConvexHullOptions hull;
  // CPU backend: how many clouds are hulled at once (0: every core, hardware_workers()).  With 1 every
  // cloud's hull runs on the calling thread.  The result is the same for every value.
  unsigned threads = 0;
  // CUDA backend: which clouds the batch kernel takes, and on which kind of team (cudahull/tuning.hpp; the
  // defaults unless set, as the command line does from its environment for A/B runs).  Each cloud's hull
  // is convex_hull()'s for every value.
  BatchTuning tuning;
};

// What ran, for both kinds of result.
struct ConvexHullBatchReport {
  Precision precision = Precision::kFloat;  // what the hulls were computed in (never kAuto)
  // The backends that ran, as convex_hull()'s names ("cpu", "cpu-resident", "cuda-resident", "cpu-wide"),
  // in the order first met, joined by "+" where the clouds differ (a wide-range cloud takes "cpu-wide").
  std::string backend;
  // The CUDA backend: the clouds its batch kernel hulled (the rest took the single-cloud path), the
  // launches it made (one a size of block, and one more for clouds whose hulls outgrew the first's room),
  // and the most device memory it held at once, the points and the result included.
  std::size_t clouds_batched = 0;
  unsigned batch_launches = 0;
  std::size_t device_bytes_peak = 0;
  // Milliseconds: the whole device part (the batch kernel's launches, the other clouds' single-cloud path,
  // the describe; the points' upload and check before it not included), and of it the batch kernel's
  // launches alone and the describe (planes, volumes, areas, on the device) with the result's assembly.
  double device_ms = 0, describe_ms = 0, kernel_ms = 0;
};

// The hulls of B clouds, packed: cloud c's vertices are vertices[vertex_offsets[c] .. vertex_offsets[c + 1])
// and its faces (with their planes) faces[face_offsets[c] .. face_offsets[c + 1]).  Indices are into each
// cloud (0 is the cloud's first point), as convex_hull() gives them for the cloud alone.
struct ConvexHullBatch : ConvexHullBatchReport {
  std::vector<std::size_t> vertex_offsets{0}, face_offsets{0};  // B + 1 each
  // Per cloud: the strictly extreme points, ascending (among duplicates the lowest index).
  std::vector<PointIndex> vertices;
  // Per cloud of dimension 3: outward triangles, counter-clockwise seen from outside; their planes: unit
  // outward normal and offset (n . x + d <= 0 inside).
  std::vector<std::array<PointIndex, 3>> faces;
  std::vector<std::array<double, 4>> planes;
  // Per cloud, convex_hull()'s `polygon`: for dimension 2 the polygon's corners in order; else none.
  std::vector<std::size_t> polygon_offsets{0};  // B + 1
  std::vector<PointIndex> polygons;
  // Per cloud, as convex_hull()'s: volume and area (a flat cloud: volume 0, area both sides of its
  // polygon), and the affine dimension (3; 2, 1, 0 for flat input; -1 for an empty cloud).
  std::vector<double> volumes, areas;
  std::vector<std::int32_t> dimensions;

  std::size_t size() const { return volumes.size(); }
};

// `size` values of T in the memory of CUDA device `device`, alive while any copy of `data` is.
template <class T>
struct DeviceColumn {
  std::shared_ptr<T> data;
  std::size_t size = 0;
};

// ConvexHullBatch's arrays left in device memory, where the points were (convex_hull_batch_device_results):
// the same values, the indices as int32 (a cloud of 2^31 points or more is refused), the offsets as int64
// (laid out on the device: to_host() reads them back).  Faces are 3 corners a row, planes 4 values a row,
// packed.  The default stream's work is done when it is returned; a column's memory goes back to the cache
// (in the default stream's order) with the last copy of its `data`: work of the caller's on other streams
// must be done by then.
struct DeviceConvexHullBatch : ConvexHullBatchReport {
  int device = 0;  // the CUDA device that holds the columns
  DeviceColumn<std::int64_t> device_vertex_offsets, device_face_offsets,
      device_polygon_offsets;  // B + 1 each
  DeviceColumn<std::int32_t> vertices, faces, polygons, dimensions;
  DeviceColumn<double> planes, volumes, areas;

  std::size_t size() const { return volumes.size; }
  // The same hulls read back (one copy a column).  Throws DeviceError.
  ConvexHullBatch to_host() const;
};

// The hulls of the clouds of `points` that `offsets` bound (B + 1 values: 0, then each cloud's end, the last
// the point count; an empty cloud repeats its start).  Throws std::invalid_argument for bad offsets;
// InputError for a NaN or infinite coordinate (or, in float, a double beyond float's range), naming the
// cloud, the point's index in it and its row in `points` ("cloud 2: point 7: y coordinate nan is not finite
// (row 1507 of the packed points)"); DeviceError as convex_hull() does.
ConvexHullBatch convex_hull_batch(const std::vector<Point3>& points, const std::vector<std::size_t>& offsets,
                                  const ConvexHullBatchOptions& options = {});
ConvexHullBatch convex_hull_batch(const std::vector<Point3d>& points, const std::vector<std::size_t>& offsets,
                                  const ConvexHullBatchOptions& options = {});
// The same on `count` x, y, z triples in one contiguous array, with `clouds` + 1 offsets.
ConvexHullBatch convex_hull_batch(const float* xyz, std::size_t count, const std::size_t* offsets,
                                  std::size_t clouds, const ConvexHullBatchOptions& options = {});
ConvexHullBatch convex_hull_batch(const double* xyz, std::size_t count, const std::size_t* offsets,
                                  std::size_t clouds, const ConvexHullBatchOptions& options = {});

// The same on `count` x, y, z triples in the current CUDA device's memory (the offsets in host memory), read
// in place, on the batch kernel (the rest through convex_hull_device()).
// Throws as convex_hull_device() does (std::invalid_argument for backend cpu).
ConvexHullBatch convex_hull_batch_device(const float* device_xyz, std::size_t count,
                                         const std::size_t* offsets, std::size_t clouds,
                                         const ConvexHullBatchOptions& options = {});
ConvexHullBatch convex_hull_batch_device(const double* device_xyz, std::size_t count,
                                         const std::size_t* offsets, std::size_t clouds,
                                         const ConvexHullBatchOptions& options = {});

// The same, the result left in the current device's memory: no hull crosses to the host but those of the
// clouds that take the single-cloud path (fewer than 4 points, flat, too large for a block), which cross
// up.  What the Python module hands to CuPy and PyTorch.  Throws std::invalid_argument for a cloud of 2^31
// points or more (the int32 indices).
DeviceConvexHullBatch convex_hull_batch_device_results(const float* device_xyz, std::size_t count,
                                                       const std::size_t* offsets, std::size_t clouds,
                                                       const ConvexHullBatchOptions& options = {});
DeviceConvexHullBatch convex_hull_batch_device_results(const double* device_xyz, std::size_t count,
                                                       const std::size_t* offsets, std::size_t clouds,
                                                       const ConvexHullBatchOptions& options = {});

}  // namespace cudahull
