// The batch on the CUDA backend: every small cloud on a warp or a block (a launch a kind of team,
// batch_cuda.hpp), the rest through the single-cloud path, the result assembled on the device
// (batch_device_result.cpp).
//
// design: the device path
//   points: in GPU memory, checked there once (check_device_points); host points uploaded once as given
//     and checked there alike.  A double cloud outside the fast exact range takes the single-cloud path
//     (its wide path), the others stay on the kernel (clouds_with_bad_points()); a NaN or an infinity sends
//     its cloud and those after it there, which names the point
//   batch_run_cuda(): the exact meshes of the clouds a warp or a block takes, left on the device with their
//     sizes; only the clouds that did not end read back
//   the other clouds through convex_hull() or convex_hull_device(), in cloud order
//   the result assembled on the device (assemble_on_device()): offsets laid out there from the sizes (the
//     kernel's hulls' never cross to the host; lay_out_batch_offsets()), the kernel's meshes described there
//     (describe_batch_cuda(): the planes, volumes and areas as convex_hull() computes them, the same code),
//     the other clouds' hulls copied up; read back in one copy a column for a host result
//     (DeviceConvexHullBatch::to_host())
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "batch_common.hpp"
#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/cuda/batch_cuda.hpp"
#include "cudahull/cuda/device_points.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/tuning.hpp"

namespace cudahull::batch {

// The other clouds' hulls (the single-cloud path's), by cloud, in cloud order.
using HostedHulls = std::vector<std::pair<std::size_t, ConvexHull>>;

// The single-cloud path's hulls of the clouds `skip` does not mark (when given), in cloud order.
template <class HullOf>
HostedHulls hosted_hulls(const std::size_t* offsets, std::size_t clouds, HullOf hull_of,
                         const std::vector<std::uint8_t>* skip = nullptr) {
  HostedHulls hosted;
  run_each_on_device(
      offsets, clouds, hull_of,
      [&](std::size_t c, ConvexHull&& hull) { hosted.emplace_back(c, std::move(hull)); }, skip);
  return hosted;
}

// The packed result on the device: the offsets laid out there from every cloud's sizes (the kernel's hulls'
// from their results, which stay there; the hosted ones' from the host: lay_out_batch_offsets()), the
// kernel's hulls described into place (describe_batch_cuda()), the hosted hulls copied up, a run of
// consecutive hosted clouds at a time (their places are consecutive in both).
template <class Point>
DeviceConvexHullBatch assemble_on_device(const BatchRun<Point>& run, HostedHulls&& hosted,
                                         std::size_t clouds);

// The one place the CUDA backend runs a batch of checked points in device memory: the clouds a warp or a
// block takes, in a launch a kind of team (batch_run_cuda(), and the later passes: room on blocks, a
// block's leftovers on warps); the rest (too small or too large for a team, flat, or with a defect the
// single-cloud path repairs) and those `single` marks through `hull_of(c)`, in cloud order; the result
// assembled on the device (assemble_on_device()).  `tuning`: which clouds take which kind of team.
template <class Point, class HullOf>
DeviceConvexHullBatch run_batch_on_device(const Point* device_points, std::size_t count,
                                          const std::size_t* offsets, std::size_t clouds,
                                          const BatchTuning& tuning, HullOf hull_of,
                                          const std::vector<std::uint8_t>& single = {}) {
  const Clock::time_point start = Clock::now();
  PhaseLaps laps("batch on the device");
  BatchRun<Point> run;
  try {
    run = batch_run_cuda(device_points, count, offsets, clouds, single.empty() ? nullptr : single.data(),
                         tuning);
  } catch (const OutOfDeviceMemory&) {
    // No room for the batch: every cloud through the single-cloud path, which grows its room as it goes.
    run = BatchRun<Point>(clouds);
  }
  laps.lap("batch run and trim");
  HostedHulls hosted = hosted_hulls(offsets, clouds, hull_of, &run.done);
  laps.lap("hosted");
  const Clock::time_point describe_start = Clock::now();
  DeviceConvexHullBatch batch = assemble_on_device(run, std::move(hosted), clouds);
  batch.describe_ms = ms_since(describe_start);
  laps.lap("assembly");
  batch.device_ms = ms_since(start);
  batch.kernel_ms = run.kernel_ms;
  batch.batch_launches = run.passes;
  batch.device_bytes_peak += count * sizeof(Point);
  return batch;
}

// Every cloud through the single-cloud path (`hull_of(c)`), the result assembled on the device.
template <class HullOf>
DeviceConvexHullBatch run_each_into_device(const std::size_t* offsets, std::size_t clouds, HullOf hull_of) {
  return assemble_on_device(BatchRun<Point3>(clouds), hosted_hulls(offsets, clouds, hull_of), clouds);
}

// The clouds that must take the single-cloud path for a point the batch kernel cannot take (`first_bad`:
// the device check's first, or `count`): a double cloud outside the fast exact range is no error (the wide
// path hulls it alone, the others stay on the kernel); a NaN or an infinity (or, from the other precision,
// a value it cannot hold) marks its cloud and every one after it (the single-cloud path raises there,
// naming the point, before a later cloud runs).  Only when a point is bad, one more pass over them
// (check_device_clouds()).  Empty: no cloud.
template <class Point, class Scalar>
std::vector<std::uint8_t> clouds_with_bad_points(const Scalar* device_xyz, std::size_t count,
                                                 const std::size_t* offsets, std::size_t clouds,
                                                 std::size_t first_bad) {
  if (first_bad == count) return {};
  std::vector<std::uint8_t> single = check_device_clouds<Point>(device_xyz, count, offsets, clouds);
  std::fill(std::find(single.begin(), single.end(), kCloudBad), single.end(), kCloudBad);
  for (std::uint8_t& mark : single)
    mark = mark != kCloudGood;
  return single;
}

// Points in device memory (the caller's, or host points uploaded as given), in their own precision:
// checked there once and converted to the plan's (check_device_points), the clouds with a point the kernel
// cannot take marked (clouds_with_bad_points()), and the batch run; `hull_of(c)`: the single-cloud path.
// `upload`: host points' copy, let go once converted (the batch reads the converted points).
template <class Point, class Scalar, class HullOf>
DeviceConvexHullBatch checked_batch_on_device(const Scalar* device_xyz, std::size_t count,
                                              const std::size_t* offsets, std::size_t clouds,
                                              const BatchTuning& tuning, HullOf hull_of,
                                              std::shared_ptr<void> upload = nullptr) {
  PhaseLaps laps("batch check");
  const CheckedDevicePoints<Point> checked = check_device_points<Point>(device_xyz, count);
  laps.lap("points");
  const std::vector<std::uint8_t> single =
      clouds_with_bad_points<Point>(device_xyz, count, offsets, clouds, checked.first_bad);
  laps.lap("clouds");
  if (checked.converted) upload.reset();
  return run_batch_on_device(checked.points, count, offsets, clouds, tuning, hull_of, single);
}

// Host points for the device: uploaded as given and checked on the device, as device input is (the host's
// check and packed copy of every point cost more than the batch itself: docs/benchmarks.md, "Shorter code
// for the batch kernel").  The single-cloud path reads them on the host.
template <class Point, class Scalar, class HullOf>
DeviceConvexHullBatch run_host_batch_on_device(const Scalar* xyz, std::size_t count,
                                               const std::size_t* offsets, std::size_t clouds,
                                               const BatchTuning& tuning, HullOf hull_of) {
  // A column of the batch's (no trim of the pool when it goes: the batch's own keeps what the next batch of
  // its size needs, where upload_to_device()'s handed it all back and the next batch mapped it again).
  std::shared_ptr<void> upload = batch_column(3 * count * sizeof(Scalar), "the points");
  copy_to_device(upload.get(), xyz, 3 * count * sizeof(Scalar));
  const auto* device_xyz = static_cast<const Scalar*>(upload.get());
  DeviceConvexHullBatch batch =
      checked_batch_on_device<Point>(device_xyz, count, offsets, clouds, tuning, hull_of, std::move(upload));
  trim_batch_pool();  // the upload is back in the pool: what is beyond the batch's share goes to the driver
  return batch;
}

}  // namespace cudahull::batch
