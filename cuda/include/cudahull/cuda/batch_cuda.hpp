// Batched hulls on the device (issue 27): every small cloud of a batch on one team, in a launch a kind of
// team: a warp a cloud of up to 256 points, a furthest point at a time (cudahull/resident/small_hull.hpp), a
// block a larger cloud, running the resident engine's own iteration (cudahull/resident/batch.hpp); one more
// launch for the clouds a block had no room for, and one on warps for those a block sent to the single-cloud
// path; then the hulls described on the device, into the packed result, where they stay.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "cudahull/tuning.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

// The batch kernel's run: which clouds it hulled, and their hulls kept on the device (each pass's output,
// with its results: the sizes stay there) for lay_out_batch_offsets() and describe_batch_cuda().
template <class Point>
struct BatchRun {
  // A run of `clouds` clouds in which none is done yet (or none will be: the single-cloud path takes all).
  explicit BatchRun(std::size_t clouds = 0) : done(clouds, 0) {}
  // Per cloud: 1 when its exact hull (dimension 3) is on the device; 0 when the single-cloud path must take
  // it (fewer than 4 points or more than a block takes, a flat cloud, a stall, or a defect that the
  // single-cloud path's local repair mends).
  std::vector<std::uint8_t> done;
  std::size_t clouds_done = 0;
  unsigned passes = 0;                    // launches (a kind of team each, and the later passes')
  std::size_t clouds_in_second_pass = 0;  // on blocks, with room for every point
  std::size_t device_bytes = 0;  // the most device memory the run held at once (the points not included)
  std::size_t kept_bytes = 0;    // what the passes' outputs hold until they are described
  double kernel_ms = 0;          // the launches alone (CUDA events)
  struct PassOutput;             // a pass's hulls and results on the device (batch_shared.cuh)
  std::vector<std::shared_ptr<PassOutput>> outputs;
};

// The clouds of `count` points at `device_points` (the current device's memory), bounded by `offsets`
// (B + 1 of them, in host memory), each on one team, but those `skip` marks (when given: B flags); which
// clouds a team takes, and which kind of team, as `tuning` says (cudahull/tuning.hpp).
// Throws DeviceError (OutOfDeviceMemory where the device has no room for the batch).
template <class Point>
BatchRun<Point> batch_run_cuda(const Point* device_points, std::size_t count, const std::size_t* offsets,
                               std::size_t clouds, const std::uint8_t* skip = nullptr,
                               const BatchTuning& tuning = {});

// Where describe_batch_cuda() writes, in the current device's memory: the packed result's columns
// (convex_hull_batch.hpp's DeviceConvexHullBatch), the offsets already there.
struct BatchColumns {
  const std::int64_t *vertex_offsets, *face_offsets;  // B + 1 each
  std::int32_t *vertices, *faces, *dimensions;        // faces: 3 corners a face
  double *planes, *volumes, *areas;                   // planes: 4 a face
};

// A cloud's hull from the single-cloud path, its sizes: what lay_out_batch_offsets() places.
struct HostedSizes {
  std::size_t cloud, vertices, faces, polygon;
};
struct BatchTotals {
  std::size_t vertices = 0, faces = 0, polygons = 0;
};

// The packed result's offsets (B + 1 each, in the current device's memory) laid out there: each done
// cloud's sizes from its pass's results (which never cross to the host), each hosted cloud's as given, then
// a prefix sum of each column.  Returns the totals (the last offsets, read back).
template <class Point>
BatchTotals lay_out_batch_offsets(const BatchRun<Point>& run, const std::vector<HostedSizes>& hosted,
                                  std::size_t clouds, std::int64_t* vertex_offsets,
                                  std::int64_t* face_offsets, std::int64_t* polygon_offsets);

// The three offset columns' values (int64, the current device's memory) at each index of `at` (vertex, face,
// polygon), read back in one copy.
std::vector<std::array<std::int64_t, 3>> read_offsets_at(const std::int64_t* vertex_offsets,
                                                         const std::int64_t* face_offsets,
                                                         const std::int64_t* polygon_offsets,
                                                         const std::vector<std::size_t>& at);

// The done clouds of `run` described into `columns`, as convex_hull() describes an exact mesh: the vertex
// ids, the faces on them, each face's plane (detail::facet_plane_in_range), the volume and area (summed
// face by face in the mesh's order), dimension 3.  Waits for the device.
template <class Point>
void describe_batch_cuda(const BatchRun<Point>& run, const BatchColumns& columns);

// What the device's pool keeps after a batch (a share of the device's memory: what the next batch of its
// size needs, the last result's columns included), and the pool trimmed to it: after a batch of host points,
// whose upload goes back to the pool once the batch is done.
std::size_t batch_pool_keep();
void trim_batch_pool();

// The result's plumbing for the API, which sees no CUDA header: a column of `bytes` in the current device's
// memory (given back with the last pointer), copies on the default stream (the host waits), the device.
// Each throws DeviceError.
std::shared_ptr<void> batch_column(std::size_t bytes, const char* what);
void copy_to_device(void* device, const void* host, std::size_t bytes);
void copy_to_host(void* host, const void* device, std::size_t bytes);
// The default stream's work done (a pageable copy to the device may return before its data has landed):
// before a result is handed to a library whose streams do not wait for the default stream.
void finish_device_work();
int current_cuda_device();

}  // namespace cudahull
