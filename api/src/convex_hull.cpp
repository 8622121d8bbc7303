// convex_hull(), convex_hull_device() and their relatives: the input checked (checked_input.hpp), planned
// once (plan_hull()), run on the engine the plan names, and described from the exact mesh (describe.hpp).
// 2-D input: convex_hull_2d.cpp.
#include "cudahull/convex_hull.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <type_traits>

#include "checked_input.hpp"
#include "cudahull/cpu_backend.hpp"
#include "cudahull/cuda/cuda_backend.hpp"
#include "cudahull/cuda/device_info.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/device_points.hpp"
#include "cudahull/cuda/planar_filter.hpp"
#include "cudahull/cuda/resident_cuda.hpp"
#include "cudahull/detail/plane_impl.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/plane.hpp"
#include "cudahull/resident.hpp"
#include "describe.hpp"
#include "facet_merge.hpp"
#include "host_hull.hpp"
#include "planar_hull.hpp"

namespace cudahull {

namespace detail {

// The plan for `count` points of `dimension` in GPU memory, whose own precision is `own`.
HullPlan device_plan(std::size_t count, int dimension, Precision own, const ConvexHullOptions& options) {
  HullInput input;
  input.precision = own;
  input.dimension = dimension;
  input.count = count;
  input.on_device = true;
  return plan_hull(options, input, cuda_presence);
}

// What points in GPU memory need before they are read: a CUDA backend, a device (plan_hull() says which is
// missing), and memory of the current device.  Throws as convex_hull_device() documents.
void require_device_points(const void* device_points, std::size_t count, const HullPlan& plan) {
  if (plan.backend == BackendChoice::kCpu) throw std::invalid_argument(plan.unavailable);
  check_count(count);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  if (count != 0) require_current_device_memory(device_points);
}

}  // namespace detail

namespace {

using detail::array_coordinate;
using detail::check_count;
using detail::copy_checked;
using detail::describe;
using detail::describe_exact;
using detail::device_plan;
using detail::rejection;
using detail::require_device_points;
using detail::throw_if_rejected;

// The hull of checked points in Point, run as `plan` says (plan_hull(): engine and backend definite).
template <class Point>
ConvexHull run_planned(const std::vector<Point>& points, const HullPlan& plan,
                       const ConvexHullOptions& options, bool neighbors) {
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  if (plan.engine == EngineChoice::kResident) {
    ResidentStats stats;
    ConvexHull hull;
    if (plan.backend == BackendChoice::kCuda) {
      ResidentCudaHull<Point> resident(plan.resident_tuning);
      resident.upload(points);
      hull = describe(resident.run(&stats), "cuda-resident", options);
    } else {
      hull = describe(resident_hull_host(points, &stats), "cpu-resident", options);
    }
    hull.resident_stats = std::move(stats);
    return hull;
  }
  if (plan.small_cloud) {
    BasicHullMesh<Point> mesh;
    if (small_hull_host(points.data(), points.size(), mesh)) return describe(mesh, "cpu", options, neighbors);
  }
  std::unique_ptr<BasicBackend<Point>> backend =
      plan.backend == BackendChoice::kCuda ? make_cuda_backend<Point>() : make_cpu_backend<Point>();
  std::string name = backend->name();
  BasicEngine<Point> engine(points, std::move(backend), EngineOptions{.keep_decisions = false});
  engine.run();
  return describe(engine.result(), std::move(name), options, neighbors);
}

// run_planned(), the result saying how it ran.
template <class Point>
ConvexHull hull_in(const std::vector<Point>& points, const HullPlan& plan, const ConvexHullOptions& options,
                   bool neighbors = true) {
  ConvexHull hull = run_planned(points, plan, options, neighbors);
  hull.plan = plan.reason;
  return hull;
}

// Double points with a coordinate outside the engines' exact range (a subnormal, 1e300): exact_hull_any()
// on the host, exact for every finite double.  Merging needs plane_through()'s range for its heights and
// certificate: where the hull's vertices are outside it the exact hull is returned (tolerance 0).
ConvexHull wide_hull(const std::vector<Point3d>& points, const ConvexHullOptions& options) {
  const HullMeshd mesh = exact_hull_any(points);
  ConvexHullOptions exact = options;
  if (!in_fast_exact_range(mesh.vertices)) exact.merge = MergeMode::kExact;
  return describe(mesh, "cpu-wide", exact);
}

// The hull of `count` points read by `coordinate(i, axis)`, whose own precision is `own`: read in the
// plan's precision, then planned with their range known.
template <class Coordinate>
ConvexHull checked_hull(std::size_t count, Coordinate coordinate, Precision own,
                        const ConvexHullOptions& options, bool neighbors = true,
                        const HullPlan* in_range_plan = nullptr) {
  HullInput input;
  input.precision = own;
  input.count = count;
  // `in_range_plan`: the caller's plan for this input in the exact range, kept unless the points are not.
  const auto planned = [&] {
    return in_range_plan && !input.outside_exact_range ? *in_range_plan
                                                       : plan_hull(options, input, cuda_presence);
  };
  if (plan_precision(options.precision, own).precision == Precision::kDouble) {
    const std::vector<Point3d> points = copy_checked<Point3d>(count, coordinate);
    input.outside_exact_range = !in_fast_exact_range(points);
    const HullPlan plan = planned();
    if (plan.wide_range) {
      ConvexHull hull = wide_hull(points, options);
      hull.plan = plan.reason;
      return hull;
    }
    return hull_in(points, plan, options, neighbors);
  }
  return hull_in(copy_checked<Point3>(count, coordinate), planned(), options, neighbors);
}

// The hull of points that only the current device holds, in Point: checked (and converted) there, then
// borrowed by the resident engine (with `tuning`, the plan's).
template <class Point, class Scalar>
ConvexHull device_hull_in(const Scalar* device_xyz, std::size_t count, const ConvexHullOptions& options,
                          const ResidentTuning& tuning) {
  CheckedDevicePoints<Point> checked = check_device_points<Point>(device_xyz, count);
  if (checked.first_bad != count) {
    // Named from its own coordinates by the host path's check, so the message is the same word for word.
    const std::array<double, 3> p = read_device_point(device_xyz, checked.first_bad);
    const double widened[3] = {p[0], p[1], p[2]};
    throw_if_rejected<Point>(checked.first_bad, widened);
    // Finite, but outside the engines' exact range (the device's check refuses that too): the host's wide
    // path, on a copy of every point, checked there again.
    if constexpr (std::is_same_v<Point, Point3d>) {
      const std::vector<Scalar> host = download_values(device_xyz, 3 * count);
      return checked_hull(count, array_coordinate(host.data()), Precision::kDouble, options);
    }
    throw std::logic_error("convex_hull_device: point " + std::to_string(checked.first_bad) +
                           " failed the device's check but passes the host's");
  }
  ResidentCudaHull<Point> resident(tuning);
  resident.use_device_points(checked.points, count);
  ResidentStats stats;
  const Clock::time_point run_start = Clock::now();
  const BasicHullMesh<Point> mesh = resident.run(&stats);
  const Clock::time_point describe_start = Clock::now();
  ConvexHull hull = describe(mesh, "cuda-resident", options);
  hull.engine_ms = std::chrono::duration<double, std::milli>(describe_start - run_start).count();
  hull.describe_ms = ms_since(describe_start);
  stats.host_syncs += checked.host_syncs;
  stats.bytes_from_device += checked.bytes_from_device;
  hull.resident_stats = std::move(stats);
  return hull;
}

// Points in GPU memory, run as `plan` (the resident engine on the device) says.
template <class Scalar>
ConvexHull planned_device_hull(const Scalar* device_xyz, std::size_t count, const ConvexHullOptions& options,
                               const HullPlan& plan) {
  ConvexHull hull = plan.precision == Precision::kDouble
                        ? device_hull_in<Point3d>(device_xyz, count, options, plan.resident_tuning)
                        : device_hull_in<Point3>(device_xyz, count, options, plan.resident_tuning);
  if (hull.plan.empty()) hull.plan = plan.reason;  // the wide path's host hull says its own
  return hull;
}

template <class Scalar>
ConvexHull device_hull(const Scalar* device_xyz, std::size_t count, Precision own,
                       const ConvexHullOptions& options) {
  const HullPlan plan = device_plan(count, 3, own, options);
  require_device_points(device_xyz, count, plan);
  return planned_device_hull(device_xyz, count, options, plan);
}

// The hull of `count` x, y, z triples in host memory.  For the resident engine on the GPU they are uploaded
// as they are and checked (or converted) there, as convex_hull_device() does: the engine needs no host
// copy of them (it reads back the few coordinates its exact checks need), and the copy would cost more
// than the hull.  Otherwise they are checked into a host copy.
template <class Scalar>
ConvexHull array_hull(const Scalar* xyz, std::size_t count, Precision own, const ConvexHullOptions& options,
                      bool neighbors = true) {
  HullInput input;
  input.precision = own;
  input.count = count;
  const HullPlan plan = plan_hull(options, input, cuda_presence);
  if (plan.upload_first) {
    check_count(count);
    // The host points' plan serves their uploaded copy: it chose the resident engine on a usable device,
    // as a plan for the copy would, and the copy is that device's memory.
    const std::shared_ptr<void> copy = upload_to_device(xyz, count * 3 * sizeof(Scalar));
    return planned_device_hull(static_cast<const Scalar*>(copy.get()), count, options, plan);
  }
  // Planned once: checked_hull() plans again only for points outside the exact range.
  return checked_hull(count, array_coordinate(xyz), own, options, neighbors, &plan);
}

template <class Point>
auto vector_coordinate(const std::vector<Point>& points) {
  return [&points](std::size_t i, int axis) -> double {
    return axis == 0 ? points[i].x : axis == 1 ? points[i].y : points[i].z;
  };
}

}  // namespace

template <class Point>
std::unique_ptr<BasicBackend<Point>> make_backend(BackendChoice choice, std::string* chosen_because) {
  ConvexHullOptions request;
  request.backend = choice;
  request.engine = EngineChoice::kStepping;  // the backends are the stepping engine's
  HullInput input;
  input.precision = precision_of<Point>();
  const HullPlan plan = plan_hull(request, input);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  if (chosen_because) *chosen_because = plan.backend_reason;
  if (plan.backend == BackendChoice::kCuda) return make_cuda_backend<Point>();
  return make_cpu_backend<Point>();
}

template <class Point, class Scalar>
std::vector<Point> checked_points(const Scalar* xyz, std::size_t count) {
  return copy_checked<Point>(count, array_coordinate(xyz));
}

template std::vector<Point3> checked_points<Point3>(const float*, std::size_t);
template std::vector<Point3> checked_points<Point3>(const double*, std::size_t);
template std::vector<Point3d> checked_points<Point3d>(const float*, std::size_t);
template std::vector<Point3d> checked_points<Point3d>(const double*, std::size_t);

template std::unique_ptr<BasicBackend<Point3>> make_backend(BackendChoice, std::string*);
template std::unique_ptr<BasicBackend<Point3d>> make_backend(BackendChoice, std::string*);

ConvexHull convex_hull(const std::vector<Point3>& points, const ConvexHullOptions& options) {
  return checked_hull(points.size(), vector_coordinate(points), Precision::kFloat, options);
}

ConvexHull convex_hull(const std::vector<Point3d>& points, const ConvexHullOptions& options) {
  return checked_hull(points.size(), vector_coordinate(points), Precision::kDouble, options);
}

ConvexHull convex_hull(const float* xyz, std::size_t count, const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kFloat, options);
}

ConvexHull convex_hull(const double* xyz, std::size_t count, const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kDouble, options);
}

namespace {

// small_cloud_hull() in Point: the points read into this thread's buffer (rejection() converts them as
// copy_checked() does), the small hull into this thread's mesh, described as hull_in() describes it.
template <class Point, class Scalar>
bool small_cloud_in(const Scalar* xyz, std::size_t count, ConvexHull& hull) {
  thread_local std::vector<Point> points;
  thread_local BasicHullMesh<Point> mesh;
  points.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double widened[3] = {static_cast<double>(xyz[3 * i]), static_cast<double>(xyz[3 * i + 1]),
                               static_cast<double>(xyz[3 * i + 2])};
    int axis = 0;
    if (rejection(widened, axis, points[i])) return false;
  }
  if constexpr (std::is_same_v<Point, Point3d>) {
    if (!in_fast_exact_range(points.data(), count)) return false;
  }
  if (!small_hull_host(points.data(), count, mesh)) return false;
  hull = describe_exact(mesh, "cpu", false);
  return true;
}

}  // namespace

template <class Scalar>
bool small_cloud_hull(const Scalar* xyz, std::size_t count, const ConvexHullOptions& options,
                      ConvexHull& hull) {
  // As plan_hull() sets small_cloud, for a request whose backend and precision the batch has resolved.
  if (options.merge != MergeMode::kExact || options.engine != EngineChoice::kAuto ||
      options.backend != BackendChoice::kCpu || count < 4 || count > kSmallHullPoints)
    return false;
  const Precision own = precision_of<Scalar>();
  if (plan_precision(options.precision, own).precision == Precision::kDouble)
    return small_cloud_in<Point3d>(xyz, count, hull);
  return small_cloud_in<Point3>(xyz, count, hull);
}

template bool small_cloud_hull(const float*, std::size_t, const ConvexHullOptions&, ConvexHull&);
template bool small_cloud_hull(const double*, std::size_t, const ConvexHullOptions&, ConvexHull&);

ConvexHull convex_hull_without_neighbors(const float* xyz, std::size_t count,
                                         const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kFloat, options, false);
}

ConvexHull convex_hull_without_neighbors(const double* xyz, std::size_t count,
                                         const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kDouble, options, false);
}

ConvexHull convex_hull_device(const float* device_xyz, std::size_t count, const ConvexHullOptions& options) {
  return device_hull(device_xyz, count, Precision::kFloat, options);
}

ConvexHull convex_hull_device(const double* device_xyz, std::size_t count, const ConvexHullOptions& options) {
  return device_hull(device_xyz, count, Precision::kDouble, options);
}

}  // namespace cudahull
