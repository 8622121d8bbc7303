#include "commands.hpp"
#include "huge_pages.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <type_traits>

#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/cpu_backend.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/face_io.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/hull_runner.hpp"
#include "cudahull/mesh_io.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/point_writer.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/trace.hpp"
#include "cudahull/tuning.hpp"
#include "qhull_reference.hpp"

namespace cudahull::cli {

namespace {

// A progress line on stderr for long loads, only when stderr is a terminal.
ProgressFn stderr_progress(const std::string& what, bool quiet) {
  if (quiet || !isatty(STDERR_FILENO)) return {};
  return [what, last = -1](double fraction) mutable {
    const int percent = static_cast<int>(fraction * 100);
    if (percent == last) return;
    last = percent;
    std::fprintf(stderr, "\r%s %3d%%%s", what.c_str(), percent, percent >= 100 ? "\n" : "");
    std::fflush(stderr);
  };
}

// --backend, --engine and --precision as plan_hull() (hull_plan.hpp) takes them; CLI11 has checked the names.
ConvexHullOptions request_of(const std::string& backend, const std::string& engine,
                             const std::string& precision) {
  ConvexHullOptions request;
  request.backend = backend_from_name(backend);
  request.engine = engine_from_name(engine);
  request.precision = precision_from_name_strict(precision);
  return request;
}

// The library's thresholds as this process's environment sets them, for A/B runs (docs/cli.md, "Environment
// variables"): the command line is the one place that reads them, the library never does.  A variable
// that is not set leaves the default (cudahull/tuning.hpp, EngineOptions); a set one is read as
// strtoull() reads it.  The library caps the batch's block and warp sizes as it always did.
struct Tuning {
  ResidentTuning resident;
  BatchTuning batch;
  std::size_t batched_swaps_from = EngineOptions{}.batched_swaps_from;
};

Tuning tuning_from_environment() {
  const auto read = [](const char* name, std::size_t& value) {
    if (const char* text = std::getenv(name)) value = std::strtoull(text, nullptr, 10);
  };
  Tuning t;
  read("CUDAHULL_LOOP_POINTS", t.resident.loop_points);
  read("CUDAHULL_LOOP_FACES", t.resident.loop_faces);
  read("CUDAHULL_LOOP_FEW_POINTS_FACES", t.resident.loop_few_points_faces);
  read("CUDAHULL_ONE_BLOCK_FACES", t.resident.one_block_faces);
  read("CUDAHULL_BATCH_BLOCK_POINTS", t.batch.block_points);
  read("CUDAHULL_BATCH_LARGE_BLOCK_POINTS", t.batch.large_block_points);
  read("CUDAHULL_BATCH_MID_BLOCK_POINTS", t.batch.mid_block_points);
  read("CUDAHULL_BATCH_WARP_POINTS", t.batch.warp_points);
  read("CUDAHULL_BATCHED_SWAPS_FROM", t.batched_swaps_from);
  return t;
}

// plan_hull()'s plan for the request, with the resident engine's thresholds from the environment.
HullPlan plan_with_tuning(const ConvexHullOptions& request, const HullInput& input, const Tuning& tuning) {
  HullPlan plan = plan_hull(request, input);
  plan.resident_tuning = tuning.resident;
  return plan;
}

// A request this machine cannot meet (`--backend cuda` without a usable device) is a device failure (exit 4),
// named by its flag.
void require_runnable(const HullPlan& plan) {
  if (!plan.unavailable.empty()) throw DeviceError("--" + plan.unavailable);
}

// The stepping engine's backend that `plan` chose (hull_runner.hpp), said in one line with the plan's reason.
template <class Point>
std::unique_ptr<BasicBackend<Point>> planned_backend(const HullPlan& plan, bool quiet, std::string* device) {
  auto backend = cudahull::planned_backend<Point>(plan);
  if (!quiet)
    std::fprintf(stderr, "backend: %s (%s)\n", backend->name().c_str(), plan.backend_reason.c_str());
  *device = plan.backend == BackendChoice::kCuda ? plan.device : "cpu";
  return backend;
}

// --engine resident (issue 15): the whole run where the points are, the GPU's when --backend allows one
// (hull_runner.hpp), said in one line with the plan's reason.
template <class Point>
ResidentRun<Point> run_resident(const std::vector<Point>& points, const HullPlan& plan, bool quiet) {
  ResidentRun<Point> r = cudahull::run_resident(points, plan);
  if (!quiet) std::fprintf(stderr, "backend: %s (%s)\n", r.backend_name.c_str(), plan.backend_reason.c_str());
  if (!quiet && r.stats.exact_finish) std::fprintf(stderr, "note: exact finish: %s\n", r.stats.note.c_str());
  return r;
}

// A stepped engine's result with its coordinates (lower-dimensional input: the exact hull it answered
// with, polygon and all).
template <class Point>
BasicHullMesh<Point> stepped_hull(const SteppingEngine& engine, const std::vector<Point>& points) {
  if (engine.dimension() < 3) return exact_hull(points);
  BasicHullMesh<Point> hull;
  hull.vertex_ids = engine.result_vertex_ids();
  hull.triangles = engine.result_triangles();
  for (const PointIndex v : hull.vertex_ids)
    hull.vertices.push_back(points[v]);
  return hull;
}

}  // namespace

// hull_in() takes coordinates outside the engines' exact range to exact_hull_any().
template <>
std::vector<Point3> read_input<Point3>(const std::string& path, bool quiet) {
  return read_points(path, stderr_progress("reading " + path, quiet));
}

template <>
std::vector<Point3d> read_input<Point3d>(const std::string& path, bool quiet) {
  DoublePoints read = read_points_double(path, stderr_progress("reading " + path, quiet));
  return std::move(read.points);
}

namespace {

// A generated distribution is float; in double its points are the same values, widened exactly.
template <class Point>
std::vector<Point> load_or_generate(const std::string& input, const std::string& dist, std::uint64_t n,
                                    std::uint64_t seed, bool quiet) {
  if (!input.empty()) return read_input<Point>(input, quiet);
  std::vector<Point3> generated = generate_points(distribution_from_name(dist), n, seed);
  if constexpr (std::is_same_v<Point, Point3>) {
    return generated;
  } else {
    std::vector<Point> widened(generated.size());
    std::transform(generated.begin(), generated.end(), widened.begin(), [](const Point3& p) {
      return Point{p.x, p.y, p.z};
    });
    return widened;
  }
}

void write_text(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

// The faces -o writes: the triangles, the one polygon of a planar hull, none for a segment or a point.
template <class Point>
std::size_t face_count(const BasicHullMesh<Point>& hull) {
  if (hull.dimension == 3) return hull.triangles.size();
  return hull.dimension == 2 && hull.polygon.size() >= 3 ? 1 : 0;
}

const char* dimension_name(int d) {
  switch (d) {
    case -1:
      return "empty";
    case 0:
      return "a single point";
    case 1:
      return "a segment";
    case 2:
      return "a convex polygon";
    default:
      return "a polyhedron";
  }
}

}  // namespace

int run_info(const InfoOptions& o) {
  const auto t0 = Clock::now();
  const std::vector<Point3> points = read_points(o.input, stderr_progress("reading " + o.input, false));
  const double read_ms = ms_since(t0);
  nlohmann::json j;
  j["file"] = o.input;
  j["points"] = points.size();
  if (!points.empty()) {
    Point3 lo = points[0], hi = points[0];
    for (const Point3& p : points) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    j["bbox"] = {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}};
  } else {
    j["bbox"] = nullptr;
  }
  j["dimension"] = affine_dimension(points);
  // What `--precision auto` picks for this file (from its format and PLY header; the points above are float).
  j["precision"] = precision_name(auto_precision(o.input));
  j["read_ms"] = read_ms;
  std::cout << j.dump() << "\n";
  return kExitOk;
}

int run_gen(const GenOptions& o) {
  const Distribution dist = distribution_from_name(o.distribution);
  const std::vector<Point3> points = generate_points(dist, o.count, o.seed);
  write_points(o.output, points);
  std::fprintf(stderr, "gen: %zu %s points (seed %llu) -> %s\n", points.size(), o.distribution.c_str(),
               static_cast<unsigned long long>(o.seed), o.output.c_str());
  return kExitOk;
}

namespace {

// The resident engine's stats as one JSON object (`hull --stats`, `bench --json`): every field, then each
// phase with its distance to the hardware ("phases": name, ms, bytes, launches, host_waits, floor_ms) and
// the pace the floors were taken at.
nlohmann::json resident_stats_json(const ResidentStats& stats) {
  nlohmann::json j = nlohmann::json::object();
  for_each_stat(stats, [&](const char* name, const auto& value) { j[name] = value; });
  nlohmann::json phases = nlohmann::json::array();
  for_each_phase(stats, [&](const char* name, const PhaseStat& p) {
    phases.push_back({{"name", name},
                      {"ms", p.ms},
                      {"bytes", p.bytes},
                      {"launches", p.launches},
                      {"host_waits", p.host_waits},
                      {"floor_ms", p.floor_ms}});
  });
  j["phases"] = phases;
  j["phases_total_ms"] = stats.total_ms;
  j["pace"] = {{"bytes_per_ms", stats.pace.bytes_per_ms},
               {"launch_ms", stats.pace.launch_ms},
               {"wait_ms", stats.pace.wait_ms}};
  return j;
}

// `cudahull hull` in the precision of Point (Point3 or Point3d): one code path for both.
template <class Point>
int hull_in(const HullOptions& o, const ConvexHullOptions& request) {
  constexpr Precision precision = precision_of<Point>();
  const auto t_read = Clock::now();
  const std::vector<Point> points = read_input<Point>(o.input, o.quiet);
  const double read_ms = ms_since(t_read);
  HullInput input;
  input.precision = precision;
  input.count = points.size();
  // Coordinates outside the engines' exact range (a subnormal, 1e300): exact_hull_any() on the host, exact
  // for every finite double (exponent scaling, else GMP), with no iterations to record.
  if constexpr (std::is_same_v<Point, Point3d>) input.outside_exact_range = !in_fast_exact_range(points);
  const Tuning tuning = tuning_from_environment();
  const HullPlan plan = plan_with_tuning(request, input, tuning);
  const bool wide = plan.wide_range;
  if (wide && !o.quiet) std::fprintf(stderr, "note: %s\n", plan.backend_reason.c_str());
  require_runnable(plan);
  // The resident engine with records (--trace, --table) steps an iteration at a time and reads back what
  // each did; without them it runs in one go, hearing O(1) bytes an iteration.
  const bool resident = plan.engine == EngineChoice::kResident && !wide;
  const bool recorded_resident = resident && (!o.trace.empty() || o.table);
  std::string device, backend_name;
  std::unique_ptr<BasicBackend<Point>> backend;
  std::unique_ptr<SteppingEngine> recorded;
  if (recorded_resident) {
    recorded = resident_stepper(points, plan);
    device = plan.backend == BackendChoice::kCuda ? plan.device : "cpu";
    backend_name = recorded->backend_name();
    if (!o.quiet)
      std::fprintf(stderr, "backend: %s (%s)\n", backend_name.c_str(), plan.backend_reason.c_str());
  }
  if (!resident && !wide) {
    backend = planned_backend<Point>(plan, o.quiet, &device);
    backend_name = backend->name();
  }
  if (wide) backend_name = device = "cpu-wide";
  const std::size_t point_count = points.size();

  std::optional<BasicEngine<Point>> engine;
  if (!resident && !wide)  // borrows the points
    engine.emplace(points, std::move(backend),
                   EngineOptions{.batched_swaps_from = tuning.batched_swaps_from});
  ResidentRun<Point> resident_run;
  std::ostringstream trace;
  double host_ms = 0, backend_ms = 0;
  std::size_t repairs = 0, swaps = 0, rejected = 0, removed = 0;
  std::uint64_t bytes_to = 0, bytes_from = 0;
  int iterations = 0;
  if (o.table) {
    std::printf("%4s %9s %9s %8s %7s %7s %7s %7s %11s %11s %9s %9s\n", "iter", "faces", "refined", "regular",
                "compl", "reject", "removed", "entries", "ext before", "ext after", "host ms", "back ms");
  }
  auto on_record = [&](const IterationRecord& r) {
    ++iterations;
    host_ms += r.host_ms;
    backend_ms += r.backend_ms;
    repairs += r.repairs;
    swaps += r.swaps_regular + r.swaps_complementary;
    rejected += r.swaps_rejected;
    removed += r.vertices_removed;
    bytes_to += r.bytes_to_backend;
    bytes_from += r.bytes_from_backend;
    if (!o.trace.empty()) trace << iteration_to_json(r).dump() << "\n";
    if (o.table) {
      std::printf("%4d %9zu %9zu %8zu %7zu %7zu %7zu %7zu %11zu %11zu %9.3f %9.3f\n", r.iteration,
                  r.faces_after, r.faces_refined, r.swaps_regular, r.swaps_complementary, r.swaps_rejected,
                  r.vertices_removed, r.decision_entries, r.external_before, r.external_after, r.host_ms,
                  r.backend_ms);
    }
    if (!o.quiet && !r.note.empty()) std::fprintf(stderr, "note: %s\n", r.note.c_str());
  };
  const auto t_run = Clock::now();
  if (recorded_resident) {
    recorded->run(on_record);
    resident_run.hull = stepped_hull(*recorded, points);
    if (const ResidentStats* stats = recorded->resident_stats()) resident_run.stats = *stats;
  } else if (resident) {
    resident_run = run_resident(points, plan, o.quiet);
    backend_name = resident_run.backend_name;
    device = plan.backend == BackendChoice::kCuda ? plan.device : "cpu";
    iterations = static_cast<int>(resident_run.stats.iterations);
    swaps = resident_run.stats.edits;
    repairs = resident_run.stats.faults;
    bytes_to = resident_run.stats.bytes_to_device;
    bytes_from = resident_run.stats.bytes_from_device;
    backend_ms = resident_run.upload_ms + resident_run.run_ms;
  } else if (wide) {
    if constexpr (std::is_same_v<Point, Point3d>) resident_run.hull = exact_hull_any(points);
  } else {
    engine->run(on_record);
  }
  const double run_ms = ms_since(t_run);
  const BasicHullMesh<Point>& hull = resident || wide ? resident_run.hull : engine->result();
  if (!o.quiet && hull.dimension < 3) {
    std::fprintf(stderr, "warning: the input is %d-dimensional; its hull is %s\n", hull.dimension,
                 dimension_name(hull.dimension));
  }

  bool verified = false;
  double verify_ms = 0;
  if (o.verify) {
    const auto t_verify = Clock::now();
    const CheckResult check = check_hull(points, hull);
    verify_ms = ms_since(t_verify);
    if (!check.ok) {
      for (const auto& line : check.failures)
        std::fprintf(stderr, "verify: %s\n", line.c_str());
      std::fprintf(stderr, "cudahull: error: --verify failed: %zu problem(s), first: %s\n",
                   check.failures.size(), check.failures.empty() ? "?" : check.failures.front().c_str());
      return kExitVerifyFailed;
    }
    verified = true;
  }

  if (!o.output.empty()) write_mesh(o.output, hull);
  if (!o.vertices_out.empty()) write_vertices(o.vertices_out, hull);
  if (!o.trace.empty()) write_text(o.trace, trace.str());

  if (!o.stats.empty()) {
    nlohmann::json j{{"input", o.input},
                     {"points", point_count},
                     {"dimension", hull.dimension},
                     {"hull_vertices", hull.vertex_ids.size()},
                     {"hull_faces", face_count(hull)},
                     {"iterations", iterations},
                     {"swaps", swaps},
                     {"swaps_rejected", rejected},
                     {"vertices_removed", removed},
                     {"repairs", repairs},
                     {"backend", backend_name},
                     {"engine", choice_name(plan.engine)},
                     {"device", device},
                     {"precision", precision_name(precision)},
                     {"plan", plan.reason},
                     {"read_ms", read_ms},
                     {"total_ms", run_ms},
                     {"host_ms", host_ms},
                     {"backend_ms", backend_ms},
                     {"bytes_to_backend", bytes_to},
                     {"bytes_from_backend", bytes_from},
                     {"verified", verified}};
    if (o.verify) j["verify_ms"] = verify_ms;
    if (resident) {
      j["host_syncs"] = resident_run.stats.host_syncs;
      j["device_bytes_peak"] = resident_run.stats.device_bytes_peak;
      j["exact_finish"] = resident_run.stats.exact_finish;
      j["resident"] = resident_stats_json(resident_run.stats);
    }
    if (o.stats == "-") {
      std::cout << j.dump(2) << "\n";
    } else {
      write_text(o.stats, j.dump(2) + "\n");
    }
  }
  if (!o.quiet) {
    std::fprintf(stderr,
                 "hull: %zu points (%s) -> %zu vertices, %zu faces (%s) in %d iterations, %.1f ms%s\n",
                 point_count, precision_name(precision), hull.vertex_ids.size(), face_count(hull),
                 dimension_name(hull.dimension), iterations, run_ms, verified ? "; verified exact" : "");
  }
  return kExitOk;
}

// `cudahull bench` in the precision of Point (Point3 or Point3d): one code path for both.
template <class Point>
int bench_in(const BenchOptions& o, const ConvexHullOptions& request) {
  constexpr Precision precision = precision_of<Point>();
  const std::vector<Point> points = load_or_generate<Point>(o.input, o.distribution, o.count, o.seed, o.json);
  // The engines are what bench times: they are exact only inside their range (`hull` takes the rest).
  if constexpr (std::is_same_v<Point, Point3d>)
    check_double_range(points, o.input == "-" ? "<stdin>" : o.input);
  HullInput input;
  input.precision = precision;
  input.count = points.size();
  const Tuning tuning = tuning_from_environment();
  const HullPlan plan = plan_with_tuning(request, input, tuning);
  require_runnable(plan);
  const bool resident = plan.engine == EngineChoice::kResident;
  const std::string label = o.input.empty() ? o.distribution + " " + std::to_string(points.size()) : o.input;
  std::string device;
  std::string backend_name;
  std::vector<double> total, host, dev, upload;
  BasicHullMesh<Point> hull;
  std::uint64_t host_syncs = 0, bytes_from_device = 0, device_bytes_peak = 0;
  ResidentStats resident_stats;  // the last run's
  for (int r = 0; r < o.repeat && resident; ++r) {
    // The resident engine: uploaded once per run, the upload listed apart (as below).
    ResidentRun<Point> run = run_resident(points, plan, o.json || r > 0);
    backend_name = run.backend_name;
    const bool on_host = plan.backend != BackendChoice::kCuda;
    device = on_host ? "cpu" : plan.device;
    total.push_back(run.run_ms);
    host.push_back(on_host ? run.run_ms : 0);
    dev.push_back(on_host ? 0 : run.run_ms);
    upload.push_back(run.upload_ms);
    host_syncs = run.stats.host_syncs;
    bytes_from_device = run.stats.bytes_from_device;
    device_bytes_peak = run.stats.device_bytes_peak;
    resident_stats = run.stats;
    hull = std::move(run.hull);
  }
  for (int r = 0; r < o.repeat && !resident; ++r) {
    auto backend = planned_backend<Point>(plan, o.json || r > 0, &device);
    backend_name = backend->name();
    BasicEngine<Point> engine(
        points, std::move(backend),
        EngineOptions{.keep_decisions = false, .batched_swaps_from = tuning.batched_swaps_from});
    double h = 0, d = 0, u = 0;
    const auto t0 = Clock::now();
    std::uint64_t from = 0;
    engine.run([&](const IterationRecord& rec) {
      h += rec.host_ms;
      d += rec.backend_ms;
      u += rec.upload_ms;
      from += rec.bytes_from_backend;
    });
    bytes_from_device = from;
    // The headline is device-resident: the upload is listed on its own and not counted.
    total.push_back(ms_since(t0) - u);
    host.push_back(h);
    dev.push_back(d - u);
    upload.push_back(u);
    hull = engine.result();
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  nlohmann::json j{{"input", label},
                   {"points", points.size()},
                   {"hull_vertices", hull.vertex_ids.size()},
                   {"backend", backend_name},
                   {"engine", choice_name(plan.engine)},
                   {"device", device},
                   {"precision", precision_name(precision)},
                   {"plan", plan.reason},
                   {"repeat", o.repeat},
                   {"bytes_from_device", bytes_from_device},
                   {"total_ms", median(total)},
                   {"host_ms", median(host)},
                   {"device_ms", median(dev)},
                   {"upload_ms", median(upload)},
                   {"host_huge_pages", huge_pages_in_use()}};
  // Waits for the device with a value coming back, counted by the resident engine (the stepping engine
  // waits a fixed few times an iteration, reading its O(faces) extremes).
  if (resident) {
    j["host_syncs"] = host_syncs;
    j["device_bytes_peak"] = device_bytes_peak;
    // Device memory per hull vertex (0 on the CPU), the measure issue 26 sets its memory goals in.
    j["bytes_per_hull_vertex"] =
        hull.vertex_ids.empty() ? 0.0 : static_cast<double>(device_bytes_peak) / hull.vertex_ids.size();
    // Where the last run's time went, for profiling: host-clock laps (on the GPU the phases are queued
    // without a wait between them, so a lap is where the host waited), and the device clock inside the
    // rounds (finding and claiming, judging, numbering, applying).
    j["resident"] = resident_stats_json(resident_stats);
  }
  double qhull_ms = 0;
  bool same = false;
  if (o.versus == "qhull") {
    std::vector<double> q;
    QhullResult ref;
    for (int r = 0; r < o.repeat; ++r) {
      ref = run_qhull(points, "Qt");  // the same coordinates: doubles go to Qhull unrounded
      q.push_back(ref.milliseconds);
    }
    qhull_ms = median(q);
    same = ref.vertex_ids == hull.vertex_ids;
    j["qhull_ms"] = qhull_ms;
    j["qhull_vertices"] = ref.vertex_ids.size();
    j["speedup"] = qhull_ms / median(total);
    j["same_vertices"] = same;
  }
  if (o.json) {
    std::cout << j.dump() << "\n";
    return kExitOk;
  }
  const double t = median(total), h = median(host);
  std::printf("%-28s %10s %10s %10s %10s %7s %9s %10s %s\n", "input", "qhull ms", "total ms", "host ms",
              "device ms", "host %", "speedup", "upload ms", "vertices");
  std::printf(
      "%-28s %10s %10.2f %10.2f %10.2f %6.1f%% %9s %10.2f %zu%s\n", label.c_str(),
      o.versus.empty() ? "-" : std::to_string(qhull_ms).substr(0, 9).c_str(), t, h, median(dev),
      t > 0 ? 100.0 * h / t : 0.0,
      o.versus.empty() ? "-" : (std::to_string(qhull_ms / t).substr(0, 6) + "x").c_str(), median(upload),
      hull.vertex_ids.size(),
      o.versus.empty() ? "" : (same ? " (same vertices as Qhull)" : " (DIFFERENT vertices from Qhull)"));
  std::printf("backend: %s, precision: %s\n", backend_name.c_str(), precision_name(precision));
  return kExitOk;
}

// `cudahull bench --batch B --n N` (issue 27): B clouds of N points of --dist (cloud c from seed + c),
// packed, timed through convex_hull_batch(); with --vs qhull a loop of Qhull over the same clouds, with
// --vs loop a loop of single convex_hull() calls, each checked cloud for cloud against the batch.
template <class Point>
int bench_batch(const BenchOptions& o, const ConvexHullOptions& request) {
  if (!o.input.empty())
    throw std::invalid_argument("bench --batch takes generated clouds (--dist, --n), not INPUT");
  constexpr Precision precision = precision_of<Point>();
  const Distribution dist = distribution_from_name(o.distribution);
  std::vector<Point> points;
  points.reserve(o.batch * o.count);
  std::vector<std::size_t> offsets{0};
  for (std::uint64_t c = 0; c < o.batch; ++c) {
    for (const Point3& p : generate_points(dist, o.count, o.seed + c))
      points.push_back(Point{p.x, p.y, p.z});
    offsets.push_back(points.size());
  }
  HullInput input;
  input.precision = precision;
  input.count = points.size();
  const HullPlan plan = plan_hull(request, input);
  require_runnable(plan);
  ConvexHullBatchOptions options;
  options.hull = request;
  options.tuning = tuning_from_environment().batch;
  std::vector<double> total;
  ConvexHullBatch hulls;
  for (int r = 0; r < o.repeat; ++r) {
    const auto t0 = Clock::now();
    hulls = convex_hull_batch(points, offsets, options);
    total.push_back(ms_since(t0));
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  auto cloud_of = [&](std::size_t c) {
    return std::vector<Point>(points.begin() + static_cast<std::ptrdiff_t>(offsets[c]),
                              points.begin() + static_cast<std::ptrdiff_t>(offsets[c + 1]));
  };
  auto batch_vertices = [&](std::size_t c) {
    return std::vector<PointIndex>(
        hulls.vertices.begin() + static_cast<std::ptrdiff_t>(hulls.vertex_offsets[c]),
        hulls.vertices.begin() + static_cast<std::ptrdiff_t>(hulls.vertex_offsets[c + 1]));
  };
  const std::string label = o.distribution + " " + std::to_string(o.batch) + "x" + std::to_string(o.count);
  const double t = median(total);
  nlohmann::json j{{"input", label},
                   {"clouds", o.batch},
                   {"points_per_cloud", o.count},
                   {"points", points.size()},
                   {"hull_vertices", hulls.vertices.size()},
                   {"hull_faces", hulls.faces.size()},
                   {"backend", hulls.backend},
                   {"engine", choice_name(plan.engine)},
                   {"device", plan.backend == BackendChoice::kCuda ? plan.device : "cpu"},
                   {"precision", precision_name(precision)},
                   {"plan", plan.reason},
                   {"threads", plan.backend == BackendChoice::kCuda ? 0u : hardware_workers()},
                   {"repeat", o.repeat},
                   {"total_ms", t},
                   {"us_per_cloud", o.batch ? 1000 * t / static_cast<double>(o.batch) : 0.0},
                   {"clouds_batched", hulls.clouds_batched},
                   {"batch_launches", hulls.batch_launches},
                   {"device_bytes_peak", hulls.device_bytes_peak},
                   {"device_ms", hulls.device_ms},
                   {"describe_ms", hulls.describe_ms},
                   {"kernel_ms", hulls.kernel_ms},
                   {"host_huge_pages", huge_pages_in_use()}};
  // The same clouds one call at a time: Qhull's loop (the reference), or convex_hull()'s.
  double versus_ms = 0;
  std::size_t differ = 0;
  if (!o.versus.empty()) {
    std::vector<double> loop;
    for (int r = 0; r < o.repeat; ++r) {
      differ = 0;
      double ms = 0;
      for (std::size_t c = 0; c < o.batch; ++c) {
        const std::vector<Point> cloud = cloud_of(c);
        const auto t0 = Clock::now();
        std::vector<PointIndex> vertices;
        if (o.versus == "qhull") {
          try {
            vertices = run_qhull(cloud, "Qt").vertex_ids;
          } catch (const std::runtime_error&) {
            vertices.clear();  // a flat or too small cloud: Qhull refuses it, counted as differing
          }
        } else {
          vertices = convex_hull(cloud, request).vertices;
        }
        ms += ms_since(t0);
        differ += vertices != batch_vertices(c);
      }
      loop.push_back(ms);
    }
    versus_ms = median(loop);
    j["versus"] = o.versus;
    j["versus_ms"] = versus_ms;
    j["speedup"] = t > 0 ? versus_ms / t : 0.0;
    j["clouds_with_different_vertices"] = differ;
  }
  if (o.json) {
    std::cout << j.dump() << "\n";
    return kExitOk;
  }
  std::printf("%-28s %8s %10s %10s %12s %12s %9s %s\n", "input", "clouds", "points", "total ms", "us/cloud",
              o.versus.empty() ? "-" : (o.versus + " ms").c_str(), "speedup", "vertices");
  std::printf("%-28s %8llu %10zu %10.2f %12.2f %12s %9s %zu%s\n", label.c_str(),
              static_cast<unsigned long long>(o.batch), points.size(), t,
              o.batch ? 1000 * t / static_cast<double>(o.batch) : 0.0,
              o.versus.empty() ? "-" : std::to_string(versus_ms).substr(0, 10).c_str(),
              o.versus.empty() || t <= 0 ? "-" : (std::to_string(versus_ms / t).substr(0, 6) + "x").c_str(),
              hulls.vertices.size(),
              o.versus.empty() ? ""
              : differ == 0
                  ? (" (same vertices as " + o.versus + ", every cloud)").c_str()
                  : (" (" + std::to_string(differ) + " clouds DIFFER from " + o.versus + ")").c_str());
  std::printf("backend: %s, precision: %s\n", hulls.backend.c_str(), precision_name(precision));
  return kExitOk;
}

// How a run goes is plan_hull()'s choice (hull_plan.hpp): the precision first, since the points are read in
// it, from the input's own (io's resolve_precision() reads a file's header only where --precision auto asks
// for it); the engine and the backend once the points are read and their range is known.
Precision planned_precision(const ConvexHullOptions& request, const std::string& input) {
  return plan_precision(request.precision, resolve_precision(request.precision, input)).precision;
}

}  // namespace

int run_hull(const HullOptions& o) {
  const ConvexHullOptions request = request_of(o.backend, o.engine, o.precision);
  return planned_precision(request, o.input) == Precision::kDouble ? hull_in<Point3d>(o, request)
                                                                   : hull_in<Point3>(o, request);
}

int run_bench(const BenchOptions& o) {
  const ConvexHullOptions request = request_of(o.backend, o.engine, o.precision);
  if (o.batch > 0)
    return planned_precision(request, "") == Precision::kDouble ? bench_batch<Point3d>(o, request)
                                                                : bench_batch<Point3>(o, request);
  if (o.versus == "loop") throw std::invalid_argument("--vs loop compares a batch: it needs --batch B");
  return planned_precision(request, o.input) == Precision::kDouble ? bench_in<Point3d>(o, request)
                                                                   : bench_in<Point3>(o, request);
}

}  // namespace cudahull::cli
