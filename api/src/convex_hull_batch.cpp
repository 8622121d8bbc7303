// convex_hull_batch(): B clouds' hulls in one call (issue 27).  The design is in convex_hull_batch.hpp's
// header; here the CPU runs the clouds on all cores, and the CUDA backend runs every small cloud on a block
// (a launch a kind of block, batch_cuda.hpp) and the rest through the single-cloud path.
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
#include "cudahull/convex_hull_batch.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "batch_cuda.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "device_points.hpp"
#include "host_hull.hpp"

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

// The clouds in turn through the single-cloud path, `hull_of(c)`, but those `skip` marks (when given), each
// hull handed to `keep(c, hull)`; the first failing cloud's exception is thrown (an InputError named by its
// cloud), and no cloud after it starts.
template <class HullOf, class Keep>
void run_each_on_device(const std::size_t* offsets, std::size_t clouds, HullOf hull_of, Keep keep,
                        const std::vector<std::uint8_t>* skip = nullptr) {
  for (std::size_t c = 0; c < clouds; ++c) {
    if (skip && (*skip)[c]) continue;
    try {
      keep(c, hull_of(c));
    } catch (const InputError& error) {
      throw in_cloud(error, c, offsets[c]);
    }
  }
}

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

// `name` joined to the report's backends unless it is there ("+" between them, in the order first met).
void add_backend(ConvexHullBatchReport& report, const std::string& name) {
  if (report.backend.empty()) {
    report.backend = name;
  } else if (!name.empty() && ("+" + report.backend + "+").find("+" + name + "+") == std::string::npos) {
    report.backend += "+" + name;
  }
}

template <class T>
DeviceColumn<T> device_column(std::size_t size, const char* what) {
  return {std::static_pointer_cast<T>(batch_column(size * sizeof(T), what)), size};
}

// The packed result on the device: the offsets laid out there from every cloud's sizes (the kernel's hulls'
// from their results, which stay there; the hosted ones' from the host: lay_out_batch_offsets()), the
// kernel's hulls described into place (describe_batch_cuda()), the hosted hulls copied up, a run of
// consecutive hosted clouds at a time (their places are consecutive in both).
template <class Point>
DeviceConvexHullBatch assemble_on_device(const BatchRun<Point>& run, HostedHulls&& hosted,
                                         std::size_t clouds) {
  PhaseLaps laps("batch assembly");
  DeviceConvexHullBatch batch;
  batch.device = current_cuda_device();
  batch.clouds_batched = run.clouds_done;
  // The backends in the order first met, cloud by cloud: the kernel's before the first hosted cloud after
  // its first done one.
  const std::size_t first_done =
      run.clouds_done == 0
          ? clouds
          : static_cast<std::size_t>(std::find(run.done.begin(), run.done.end(), 1) - run.done.begin());
  std::vector<HostedSizes> sizes;
  sizes.reserve(hosted.size());
  for (const auto& [c, hull] : hosted) {
    if (c > first_done) add_backend(batch, "cuda-resident");
    add_backend(batch, hull.backend);
    sizes.push_back({c, hull.vertices.size(), hull.faces.size(), hull.polygon.size()});
  }
  if (first_done < clouds) add_backend(batch, "cuda-resident");
  batch.device_vertex_offsets = device_column<std::int64_t>(clouds + 1, "the vertex offsets");
  batch.device_face_offsets = device_column<std::int64_t>(clouds + 1, "the face offsets");
  batch.device_polygon_offsets = device_column<std::int64_t>(clouds + 1, "the polygon offsets");
  const BatchTotals totals =
      lay_out_batch_offsets(run, sizes, clouds, batch.device_vertex_offsets.data.get(),
                            batch.device_face_offsets.data.get(), batch.device_polygon_offsets.data.get());
  const std::size_t vertices = totals.vertices, faces = totals.faces, polygons = totals.polygons;
  laps.lap("offsets");
  batch.vertices = device_column<std::int32_t>(vertices, "the vertices");
  batch.faces = device_column<std::int32_t>(3 * faces, "the faces");
  batch.polygons = device_column<std::int32_t>(polygons, "the polygons");
  batch.dimensions = device_column<std::int32_t>(clouds, "the dimensions");
  batch.planes = device_column<double>(4 * faces, "the planes");
  batch.volumes = device_column<double>(clouds, "the volumes");
  batch.areas = device_column<double>(clouds, "the areas");
  laps.lap("columns");
  if (batch.clouds_batched != 0) {
    const BatchColumns columns{batch.device_vertex_offsets.data.get(),
                               batch.device_face_offsets.data.get(),
                               batch.vertices.data.get(),
                               batch.faces.data.get(),
                               batch.dimensions.data.get(),
                               batch.planes.data.get(),
                               batch.volumes.data.get(),
                               batch.areas.data.get()};
    describe_batch_cuda(run, columns);
    laps.lap("describe");
  }
  // The hosted clouds, a run of consecutive ones at a time, at the offsets of each run's first cloud (read
  // back for these alone).
  std::vector<std::size_t> run_starts;
  for (std::size_t k = 0; k < hosted.size(); ++k)
    if (k == 0 || hosted[k].first != hosted[k - 1].first + 1) run_starts.push_back(hosted[k].first);
  // Per run: its first cloud's vertex, face and polygon offsets.
  const std::vector<std::array<std::int64_t, 3>> run_at =
      read_offsets_at(batch.device_vertex_offsets.data.get(), batch.device_face_offsets.data.get(),
                      batch.device_polygon_offsets.data.get(), run_starts);
  const auto up = [](auto& column, const auto& values, std::size_t at = 0) {
    copy_to_device(column.data.get() + at, values.data(), values.size() * sizeof(values[0]));
  };
  for (std::size_t first = 0, r = 0; first < hosted.size(); ++r) {
    std::size_t end = first + 1;
    while (end < hosted.size() && hosted[end].first == hosted[end - 1].first + 1)
      ++end;
    const std::size_t c0 = hosted[first].first;
    std::vector<std::int32_t> ids, corners, polygon, dimensions;
    std::vector<double> planes, volumes, areas;
    for (std::size_t k = first; k < end; ++k) {
      ConvexHull& hull = hosted[k].second;
      ids.insert(ids.end(), hull.vertices.begin(), hull.vertices.end());
      for (const auto& face : hull.faces)
        corners.insert(corners.end(), face.begin(), face.end());
      for (const auto& plane : hull.planes)
        planes.insert(planes.end(), plane.begin(), plane.end());
      polygon.insert(polygon.end(), hull.polygon.begin(), hull.polygon.end());
      volumes.push_back(hull.volume);
      areas.push_back(hull.area);
      dimensions.push_back(hull.dimension);
      hull = ConvexHull{};  // its memory back now
    }
    up(batch.vertices, ids, static_cast<std::size_t>(run_at[r][0]));
    up(batch.faces, corners, 3 * static_cast<std::size_t>(run_at[r][1]));
    up(batch.planes, planes, 4 * static_cast<std::size_t>(run_at[r][1]));
    up(batch.polygons, polygon, static_cast<std::size_t>(run_at[r][2]));
    up(batch.volumes, volumes, c0);
    up(batch.areas, areas, c0);
    up(batch.dimensions, dimensions, c0);
    first = end;
  }
  std::size_t result_bytes = 0;
  for (const std::size_t bytes : {3 * (clouds + 1) * sizeof(std::int64_t),
                                  (vertices + 3 * faces + polygons + clouds) * sizeof(std::int32_t),
                                  (4 * faces + 2 * clouds) * sizeof(double)})
    result_bytes += bytes;
  batch.device_bytes_peak = std::max(run.device_bytes, run.kept_bytes + result_bytes);
  finish_device_work();  // the last copies landed before a library on another stream reads the columns
  laps.lap("hosted up");
  return batch;
}

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
    add_backend(batch, hull.backend);
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
  return plan_hull(options, input, cuda_presence);
}

// The batch of host points (`count` x, y, z triples at `xyz`): `hull_of(begin, n, options)` is convex_hull()
// on the n points from row `begin`.
template <class Scalar, class HullOf>
ConvexHullBatch host_batch(const Scalar* xyz, std::size_t count, const std::size_t* offsets,
                           std::size_t clouds, const ConvexHullBatchOptions& options, HullOf hull_of) {
  constexpr Precision own = std::is_same_v<Scalar, double> ? Precision::kDouble : Precision::kFloat;
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
    ConvexHullBatch batch =
        plan.precision == Precision::kDouble
            ? run_host_batch_on_device<Point3d>(xyz, count, offsets, clouds, options.tuning, cloud).to_host()
            : run_host_batch_on_device<Point3>(xyz, count, offsets, clouds, options.tuning, cloud).to_host();
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
ConvexHullBatch array_batch(const Scalar* xyz, std::size_t count, const std::size_t* offsets,
                            std::size_t clouds, const ConvexHullBatchOptions& options) {
  return host_batch(xyz, count, offsets, clouds, options,
                    [xyz](std::size_t begin, std::size_t n, const ConvexHullOptions& each) {
                      return cloud_hull(xyz + 3 * begin, n, each);
                    });
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
  constexpr Precision own = std::is_same_v<Scalar, double> ? Precision::kDouble : Precision::kFloat;
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

ConvexHullBatch DeviceConvexHullBatch::to_host() const {
  ConvexHullBatch batch;
  static_cast<ConvexHullBatchReport&>(batch) = *this;
  const std::size_t clouds = size();
  for (auto [to, from] : {std::pair{&batch.vertex_offsets, &device_vertex_offsets},
                          std::pair{&batch.face_offsets, &device_face_offsets},
                          std::pair{&batch.polygon_offsets, &device_polygon_offsets}}) {
    std::vector<std::int64_t> offsets(clouds + 1, 0);
    if (from->data) copy_to_host(offsets.data(), from->data.get(), offsets.size() * sizeof(std::int64_t));
    to->assign(offsets.begin(), offsets.end());
  }
  batch.vertices.resize(vertices.size);
  batch.faces.resize(faces.size / 3);
  batch.planes.resize(planes.size / 4);
  batch.polygons.resize(polygons.size);
  batch.volumes.resize(clouds);
  batch.areas.resize(clouds);
  batch.dimensions.resize(clouds);
  // int32 indices into PointIndex (uint32: the same bytes for indices under 2^31).
  static_assert(sizeof(PointIndex) == sizeof(std::int32_t) &&
                sizeof(batch.faces[0]) == 3 * sizeof(PointIndex));
  copy_to_host(batch.vertices.data(), vertices.data.get(), vertices.size * sizeof(std::int32_t));
  copy_to_host(batch.faces.data(), faces.data.get(), faces.size * sizeof(std::int32_t));
  copy_to_host(batch.planes.data(), planes.data.get(), planes.size * sizeof(double));
  copy_to_host(batch.polygons.data(), polygons.data.get(), polygons.size * sizeof(std::int32_t));
  copy_to_host(batch.volumes.data(), volumes.data.get(), clouds * sizeof(double));
  copy_to_host(batch.areas.data(), areas.data.get(), clouds * sizeof(double));
  copy_to_host(batch.dimensions.data(), dimensions.data.get(), clouds * sizeof(std::int32_t));
  return batch;
}

}  // namespace cudahull
