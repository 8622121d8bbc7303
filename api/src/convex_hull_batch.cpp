// convex_hull_batch(): B clouds' hulls in one call (issue 27).  The design is in convex_hull_batch.hpp's
// header; here are the entry points, which check the offsets, plan the batch once and run it: on the CPU's
// cores (batch_on_host.hpp), or on the CUDA backend, every small cloud on a block and the rest through the
// single-cloud path (batch_on_device.hpp, with the device path's design).
#include "cudahull/convex_hull_batch.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>

#include "batch_common.hpp"
#include "batch_on_device.hpp"
#include "batch_on_host.hpp"
#include "cudahull/convex_hull_batch_results.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/parallel.hpp"
#include "host_hull.hpp"

namespace cudahull {

namespace {

using namespace batch;

// The batch of host points (`count` x, y, z triples at `xyz`): `hull_of(begin, n, options)` is convex_hull()
// on the n points from row `begin`.
template <class Scalar, class HullOf>
std::variant<ConvexHullBatch, DeviceConvexHullBatch> host_batch(const Scalar* xyz, std::size_t count,
                                                                const std::size_t* offsets,
                                                                std::size_t clouds,
                                                                const ConvexHullBatchOptions& options,
                                                                HullOf hull_of) {
  constexpr Precision own = precision_of<Scalar>();
  check_offsets(count, offsets, clouds);
  const HullPlan plan = batch_plan(count, own, false, options.hull);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  // Each cloud runs where the batch's plan says, whatever "auto" would say for the cloud alone.
  ConvexHullOptions each = options.hull;
  each.backend = plan.backend;
  each.precision = plan.precision;
  auto cloud = [&](std::size_t c) { return hull_of(offsets[c], offsets[c + 1] - offsets[c], each); };
  // On the device: the batch kernel, unless the stepping engine or merged facets (which the device's describe
  // does not make) are asked for, which run cloud by cloud.
  if (plan.backend == BackendChoice::kCuda && plan.engine != EngineChoice::kStepping &&
      each.merge == MergeMode::kExact) {
    DeviceConvexHullBatch batch =
        plan.precision == Precision::kDouble
            ? run_host_batch_on_device<Point3d>(xyz, count, offsets, clouds, options.tuning, cloud)
            : run_host_batch_on_device<Point3>(xyz, count, offsets, clouds, options.tuning, cloud);
    batch.precision = plan.precision;
    return batch;
  }
  std::vector<ConvexHull> hulls(clouds);
  if (plan.backend == BackendChoice::kCuda) {
    run_each_on_device(offsets, clouds, cloud,
                       [&](std::size_t c, ConvexHull&& hull) { hulls[c] = std::move(hull); });
  } else {
    const unsigned threads = options.threads != 0 ? options.threads : hardware_workers();
    run_batch_on_host(offsets, clouds, std::max(1u, threads), hulls, cloud);
  }
  return pack(std::move(hulls), plan.precision);
}

// A cloud's hull on the host: the small-cloud path where it takes the cloud, else convex_hull()'s (without
// the neighbours, which the batch does not keep); the same hull either way.
template <class Scalar>
ConvexHull cloud_hull(const Scalar* xyz, std::size_t n, const ConvexHullOptions& each) {
  ConvexHull hull;
  if (small_cloud_hull(xyz, n, each, hull)) return hull;
  return convex_hull_without_neighbors(xyz, n, each);
}

template <class Scalar>
std::variant<ConvexHullBatch, DeviceConvexHullBatch> array_batch_results(
    const Scalar* xyz, std::size_t count, const std::size_t* offsets, std::size_t clouds,
    const ConvexHullBatchOptions& options) {
  return host_batch(xyz, count, offsets, clouds, options,
                    [xyz](std::size_t begin, std::size_t n, const ConvexHullOptions& each) {
                      return cloud_hull(xyz + 3 * begin, n, each);
                    });
}

// The batch's result on the host, read back where it was made on the device.
ConvexHullBatch on_host(std::variant<ConvexHullBatch, DeviceConvexHullBatch>&& result) {
  if (const auto* on_device = std::get_if<DeviceConvexHullBatch>(&result)) return on_device->to_host();
  return std::get<ConvexHullBatch>(std::move(result));
}

template <class Scalar>
ConvexHullBatch array_batch(const Scalar* xyz, std::size_t count, const std::size_t* offsets,
                            std::size_t clouds, const ConvexHullBatchOptions& options) {
  return on_host(array_batch_results(xyz, count, offsets, clouds, options));
}

template <class Point>
ConvexHullBatch vector_batch(const std::vector<Point>& points, const std::vector<std::size_t>& offsets,
                             const ConvexHullBatchOptions& options) {
  if (offsets.empty())
    throw std::invalid_argument("convex_hull_batch: no offsets (B + 1 of them are needed, {0} for none)");
  using Scalar = decltype(Point::x);
  static_assert(sizeof(Point) == 3 * sizeof(Scalar), "x, y, z packed");
  // The packed coordinates in place: the array form reads the same values.
  return array_batch(reinterpret_cast<const Scalar*>(points.data()), points.size(), offsets.data(),
                     offsets.size() - 1, options);
}

// `int32_indices`: the result is kept on the device, whose index columns are int32 (a cloud of 2^31 points
// or more is refused); a host result's indices are PointIndex, read back bit for bit.
template <class Scalar>
DeviceConvexHullBatch device_batch(const Scalar* device_xyz, std::size_t count, const std::size_t* offsets,
                                   std::size_t clouds, const ConvexHullBatchOptions& options,
                                   bool int32_indices = false) {
  check_offsets(count, offsets, clouds);
  for (std::size_t c = 0; int32_indices && c < clouds; ++c) {
    if (offsets[c + 1] - offsets[c] >= (std::size_t{1} << 31))
      throw std::invalid_argument(
          "convex_hull_batch_device_results: cloud " + std::to_string(c) + " has " +
          std::to_string(offsets[c + 1] - offsets[c]) +
          " points, more than the result's int32 indices hold (convex_hull_batch_device "
          "returns the result on the host)");
  }
  constexpr Precision own = precision_of<Scalar>();
  const HullPlan plan = batch_plan(count, own, true, options.hull);
  if (plan.backend == BackendChoice::kCpu) throw std::invalid_argument(plan.unavailable);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  ConvexHullOptions each = options.hull;
  each.precision = plan.precision;
  const auto cloud = [&](std::size_t c) {
    return convex_hull_device(device_xyz + 3 * offsets[c], offsets[c + 1] - offsets[c], each);
  };
  const auto on_device = [&](auto point) {
    using Point = decltype(point);
    // The stepping engine, or merged facets (which the device's describe does not make), asked for: cloud by
    // cloud.
    if (plan.engine == EngineChoice::kStepping || each.merge != MergeMode::kExact)
      return run_each_into_device(offsets, clouds, cloud);
    return checked_batch_on_device<Point>(device_xyz, count, offsets, clouds, options.tuning, cloud);
  };
  DeviceConvexHullBatch batch =
      plan.precision == Precision::kDouble ? on_device(Point3d{}) : on_device(Point3{});
  batch.precision = plan.precision;
  return batch;
}

}  // namespace

ConvexHullBatch convex_hull_batch(const std::vector<Point3>& points, const std::vector<std::size_t>& offsets,
                                  const ConvexHullBatchOptions& options) {
  return vector_batch(points, offsets, options);
}

ConvexHullBatch convex_hull_batch(const std::vector<Point3d>& points, const std::vector<std::size_t>& offsets,
                                  const ConvexHullBatchOptions& options) {
  return vector_batch(points, offsets, options);
}

ConvexHullBatch convex_hull_batch(const float* xyz, std::size_t count, const std::size_t* offsets,
                                  std::size_t clouds, const ConvexHullBatchOptions& options) {
  return array_batch(xyz, count, offsets, clouds, options);
}

ConvexHullBatch convex_hull_batch(const double* xyz, std::size_t count, const std::size_t* offsets,
                                  std::size_t clouds, const ConvexHullBatchOptions& options) {
  return array_batch(xyz, count, offsets, clouds, options);
}

std::variant<ConvexHullBatch, DeviceConvexHullBatch> convex_hull_batch_results(
    const float* xyz, std::size_t count, const std::size_t* offsets, std::size_t clouds,
    const ConvexHullBatchOptions& options) {
  return array_batch_results(xyz, count, offsets, clouds, options);
}

std::variant<ConvexHullBatch, DeviceConvexHullBatch> convex_hull_batch_results(
    const double* xyz, std::size_t count, const std::size_t* offsets, std::size_t clouds,
    const ConvexHullBatchOptions& options) {
  return array_batch_results(xyz, count, offsets, clouds, options);
}

ConvexHullBatch convex_hull_batch_device(const float* device_xyz, std::size_t count,
                                         const std::size_t* offsets, std::size_t clouds,
                                         const ConvexHullBatchOptions& options) {
  return device_batch(device_xyz, count, offsets, clouds, options).to_host();
}

ConvexHullBatch convex_hull_batch_device(const double* device_xyz, std::size_t count,
                                         const std::size_t* offsets, std::size_t clouds,
                                         const ConvexHullBatchOptions& options) {
  return device_batch(device_xyz, count, offsets, clouds, options).to_host();
}

DeviceConvexHullBatch convex_hull_batch_device_results(const float* device_xyz, std::size_t count,
                                                       const std::size_t* offsets, std::size_t clouds,
                                                       const ConvexHullBatchOptions& options) {
  return device_batch(device_xyz, count, offsets, clouds, options, true);
}

DeviceConvexHullBatch convex_hull_batch_device_results(const double* device_xyz, std::size_t count,
                                                       const std::size_t* offsets, std::size_t clouds,
                                                       const ConvexHullBatchOptions& options) {
  return device_batch(device_xyz, count, offsets, clouds, options, true);
}

}  // namespace cudahull
