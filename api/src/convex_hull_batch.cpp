// convex_hull_batch(): B clouds' hulls in one call (issue 27).  The design is in convex_hull_batch.hpp's
// header; here the CPU runs the clouds on all cores, and the CUDA backend, for now, runs them one at a time
// through the single-cloud path.
//
// design: where a batched device path plugs in
//   run_batch_on_device() is the one place the CUDA backend runs a batch.  Today it loops over the clouds,
//   each through convex_hull() (host points) or convex_hull_device() (points in GPU memory).  The one-launch
//   batch kernel replaces that loop: it takes the packed points (in GPU memory, or uploaded once), the
//   offsets and the options, and returns one ConvexHull per cloud (from each cloud's exact mesh through
//   hull_from_mesh(), so planes, volumes and areas are computed as convex_hull() computes them), or throws
//   for the lowest failing cloud.  Everything around it (the checks, the plan, the errors' wording, the
//   packing) stays as it is.
#include "cudahull/convex_hull_batch.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "cudahull/errors.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/parallel.hpp"

namespace cudahull {

namespace {

// A cloud's share of the cores, below which it runs on one worker among the others: a cloud this large
// (and a large part of the batch) runs alone with its engine's passes on every core instead.
constexpr std::size_t kLargeCloud = std::size_t{1} << 15;

void check_offsets(std::size_t count, const std::size_t* offsets, std::size_t clouds) {
  if (offsets == nullptr)
    throw std::invalid_argument("convex_hull_batch: no offsets (B + 1 of them are needed)");
  if (offsets[0] != 0)
    throw std::invalid_argument("convex_hull_batch: offsets[0] is " + std::to_string(offsets[0]) +
                                ", not 0 (offsets are the B + 1 cloud boundaries in the packed points)");
  for (std::size_t c = 0; c < clouds; ++c) {
    if (offsets[c + 1] < offsets[c])
      throw std::invalid_argument("convex_hull_batch: offsets decrease at cloud " + std::to_string(c) + " (" +
                                  std::to_string(offsets[c]) + " then " + std::to_string(offsets[c + 1]) +
                                  ")");
  }
  if (offsets[clouds] != count)
    throw std::invalid_argument("convex_hull_batch: the last offset is " + std::to_string(offsets[clouds]) +
                                ", not the point count " + std::to_string(count));
}

// convex_hull()'s InputError for a point of cloud `cloud`, whose first point is row `first_row` of the
// packed points: "cloud C: point I: ... (row R of the packed points)".
InputError in_cloud(const InputError& error, std::size_t cloud, std::size_t first_row) {
  std::string message = "cloud " + std::to_string(cloud) + ": " + error.what();
  const std::string_view what = error.what();
  constexpr std::string_view kPoint = "point ";
  if (what.substr(0, kPoint.size()) == kPoint) {
    std::size_t point = 0;
    const char* digits = what.data() + kPoint.size();
    const auto [end, status] = std::from_chars(digits, what.data() + what.size(), point);
    if (status == std::errc() && end != digits && *end == ':')
      message += " (row " + std::to_string(first_row + point) + " of the packed points)";
  }
  return InputError(message);
}

// The hulls of every cloud into `hulls`, `hull_of(c)` making cloud c's, on `threads` workers: the clouds
// handed out in order, each on its worker's thread.  A cloud that fails stops the clouds after it from
// starting; the lowest failing cloud's exception is thrown, an InputError named by its cloud.
template <class HullOf>
void run_batch_on_host(const std::size_t* offsets, std::size_t clouds, unsigned threads,
                       std::vector<ConvexHull>& hulls, HullOf hull_of) {
  std::vector<std::exception_ptr> errors(clouds);
  std::atomic<std::size_t> first_failed{clouds};
  auto run = [&](std::size_t c) {
    if (c > first_failed.load(std::memory_order_relaxed)) return;
    try {
      hulls[c] = hull_of(c);
    } catch (const InputError& error) {
      errors[c] = std::make_exception_ptr(in_cloud(error, c, offsets[c]));
    } catch (...) {
      errors[c] = std::current_exception();
    }
    if (errors[c]) {
      std::size_t seen = first_failed.load(std::memory_order_relaxed);
      while (c < seen && !first_failed.compare_exchange_weak(seen, c, std::memory_order_relaxed)) {
      }
    }
  };
  const std::size_t total = offsets[clouds];
  std::vector<char> large(clouds, 0);
  if (threads > 1) {
    // A cloud this large would keep its worker busy long after the others finish: it runs alone, first,
    // its engine's passes on every core.
    for (std::size_t c = 0; c < clouds; ++c) {
      const std::size_t n = offsets[c + 1] - offsets[c];
      large[c] = n >= kLargeCloud && n * 2 * threads > total;
    }
    for (std::size_t c = 0; c < clouds; ++c)
      if (large[c]) run(c);
  }
  std::atomic<std::size_t> next{0};
  parallel_chunks(
      threads, threads,
      [&](std::size_t begin, std::size_t end, unsigned) {
        // One slot a worker (or, where the pool is busy and this runs inline, all of them on this thread).
        for (std::size_t slot = begin; slot < end; ++slot) {
          const SerialScope serial;  // the cloud's engine passes stay on this worker's thread
          for (std::size_t c = next.fetch_add(1, std::memory_order_relaxed); c < clouds;
               c = next.fetch_add(1, std::memory_order_relaxed)) {
            if (!large[c]) run(c);
          }
        }
      },
      1);
  const std::size_t failed = first_failed.load();
  if (failed != clouds) std::rethrow_exception(errors[failed]);
}

// The one place the CUDA backend runs a batch (see the design note at the top).  Interim: the clouds in
// turn through the single-cloud path, `hull_of(c)`; the first failing cloud's exception is thrown (an
// InputError named by its cloud).
template <class HullOf>
void run_batch_on_device(const std::size_t* offsets, std::size_t clouds, std::vector<ConvexHull>& hulls,
                         HullOf hull_of) {
  for (std::size_t c = 0; c < clouds; ++c) {
    try {
      hulls[c] = hull_of(c);
    } catch (const InputError& error) {
      throw in_cloud(error, c, offsets[c]);
    }
  }
}

// The per-cloud hulls packed into flat arrays, in cloud order (the copies on all cores: a batch of 100,000
// clouds has millions of faces).
ConvexHullBatch pack(std::vector<ConvexHull>&& hulls, Precision precision) {
  ConvexHullBatch batch;
  batch.precision = precision;
  const std::size_t clouds = hulls.size();
  batch.vertex_offsets.assign(clouds + 1, 0);
  batch.face_offsets.assign(clouds + 1, 0);
  batch.polygon_offsets.assign(clouds + 1, 0);
  batch.volumes.resize(clouds);
  batch.areas.resize(clouds);
  batch.dimensions.resize(clouds);
  for (std::size_t c = 0; c < clouds; ++c) {
    const ConvexHull& hull = hulls[c];
    batch.vertex_offsets[c + 1] = batch.vertex_offsets[c] + hull.vertices.size();
    batch.face_offsets[c + 1] = batch.face_offsets[c] + hull.faces.size();
    batch.polygon_offsets[c + 1] = batch.polygon_offsets[c] + hull.polygon.size();
    batch.volumes[c] = hull.volume;
    batch.areas[c] = hull.area;
    batch.dimensions[c] = hull.dimension;
    if (batch.backend.empty()) {
      batch.backend = hull.backend;
    } else if (!hull.backend.empty() &&
               ("+" + batch.backend + "+").find("+" + hull.backend + "+") == std::string::npos) {
      batch.backend += "+" + hull.backend;
    }
  }
  batch.vertices.resize(batch.vertex_offsets[clouds]);
  batch.faces.resize(batch.face_offsets[clouds]);
  batch.planes.resize(batch.face_offsets[clouds]);
  batch.polygons.resize(batch.polygon_offsets[clouds]);
  parallel_chunks(
      clouds, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t c = begin; c < end; ++c) {
          ConvexHull& hull = hulls[c];
          std::copy(hull.vertices.begin(), hull.vertices.end(),
                    batch.vertices.begin() + static_cast<std::ptrdiff_t>(batch.vertex_offsets[c]));
          std::copy(hull.faces.begin(), hull.faces.end(),
                    batch.faces.begin() + static_cast<std::ptrdiff_t>(batch.face_offsets[c]));
          std::copy(hull.planes.begin(), hull.planes.end(),
                    batch.planes.begin() + static_cast<std::ptrdiff_t>(batch.face_offsets[c]));
          std::copy(hull.polygon.begin(), hull.polygon.end(),
                    batch.polygons.begin() + static_cast<std::ptrdiff_t>(batch.polygon_offsets[c]));
          hull = ConvexHull{};  // its memory back now
        }
      },
      256);
  return batch;
}

// The plan for the whole batch: where it runs (backend and precision resolved once), from all its points.
HullPlan batch_plan(std::size_t count, Precision own, bool on_device, const ConvexHullOptions& options) {
  HullInput input;
  input.precision = own;
  input.count = count;
  input.on_device = on_device;
  return plan_hull(options, input);
}

// The batch of host points: `hull_of(begin, n, options)` is convex_hull() on the n points from row `begin`.
template <class HullOf>
ConvexHullBatch host_batch(std::size_t count, const std::size_t* offsets, std::size_t clouds, Precision own,
                           const ConvexHullBatchOptions& options, HullOf hull_of) {
  check_offsets(count, offsets, clouds);
  const HullPlan plan = batch_plan(count, own, false, options.hull);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  // Each cloud runs where the batch's plan says, whatever "auto" would say for the cloud alone.
  ConvexHullOptions each = options.hull;
  each.backend = plan.backend;
  each.precision = plan.precision;
  std::vector<ConvexHull> hulls(clouds);
  auto cloud = [&](std::size_t c) { return hull_of(offsets[c], offsets[c + 1] - offsets[c], each); };
  if (plan.backend == BackendChoice::kCuda) {
    run_batch_on_device(offsets, clouds, hulls, cloud);
  } else {
    const unsigned threads = options.threads != 0 ? options.threads : hardware_workers();
    run_batch_on_host(offsets, clouds, std::max(1u, threads), hulls, cloud);
  }
  return pack(std::move(hulls), plan.precision);
}

template <class Scalar>
ConvexHullBatch array_batch(const Scalar* xyz, std::size_t count, const std::size_t* offsets,
                            std::size_t clouds, const ConvexHullBatchOptions& options) {
  constexpr Precision own = std::is_same_v<Scalar, double> ? Precision::kDouble : Precision::kFloat;
  return host_batch(count, offsets, clouds, own, options,
                    [xyz](std::size_t begin, std::size_t n, const ConvexHullOptions& each) {
                      return convex_hull(xyz + 3 * begin, n, each);
                    });
}

template <class Point>
ConvexHullBatch vector_batch(const std::vector<Point>& points, const std::vector<std::size_t>& offsets,
                             const ConvexHullBatchOptions& options) {
  if (offsets.empty())
    throw std::invalid_argument("convex_hull_batch: no offsets (B + 1 of them are needed, {0} for none)");
  constexpr Precision own = std::is_same_v<Point, Point3d> ? Precision::kDouble : Precision::kFloat;
  return host_batch(points.size(), offsets.data(), offsets.size() - 1, own, options,
                    [&points](std::size_t begin, std::size_t n, const ConvexHullOptions& each) {
                      const auto first = points.begin() + static_cast<std::ptrdiff_t>(begin);
                      return convex_hull(std::vector<Point>(first, first + static_cast<std::ptrdiff_t>(n)),
                                         each);
                    });
}

template <class Scalar>
ConvexHullBatch device_batch(const Scalar* device_xyz, std::size_t count, const std::size_t* offsets,
                             std::size_t clouds, const ConvexHullBatchOptions& options) {
  check_offsets(count, offsets, clouds);
  constexpr Precision own = std::is_same_v<Scalar, double> ? Precision::kDouble : Precision::kFloat;
  const HullPlan plan = batch_plan(count, own, true, options.hull);
  if (plan.backend == BackendChoice::kCpu) throw std::invalid_argument(plan.unavailable);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  ConvexHullOptions each = options.hull;
  each.precision = plan.precision;
  std::vector<ConvexHull> hulls(clouds);
  run_batch_on_device(offsets, clouds, hulls, [&](std::size_t c) {
    return convex_hull_device(device_xyz + 3 * offsets[c], offsets[c + 1] - offsets[c], each);
  });
  return pack(std::move(hulls), plan.precision);
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

ConvexHullBatch convex_hull_batch_device(const float* device_xyz, std::size_t count,
                                         const std::size_t* offsets, std::size_t clouds,
                                         const ConvexHullBatchOptions& options) {
  return device_batch(device_xyz, count, offsets, clouds, options);
}

ConvexHullBatch convex_hull_batch_device(const double* device_xyz, std::size_t count,
                                         const std::size_t* offsets, std::size_t clouds,
                                         const ConvexHullBatchOptions& options) {
  return device_batch(device_xyz, count, offsets, clouds, options);
}

}  // namespace cudahull
