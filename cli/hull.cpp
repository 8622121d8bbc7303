// `cudahull hull`: a point file's exact hull through the planned engine, with its checks, records and
// outputs (--verify, --trace, --table, --stats, -o).
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "command_support.hpp"
#include "commands.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/hull_runner.hpp"
#include "cudahull/mesh_io.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/trace.hpp"

namespace cudahull::cli {

namespace {

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

}  // namespace

int run_hull(const HullOptions& o) {
  const ConvexHullOptions request = request_of(o.backend, o.engine, o.precision);
  return planned_precision(request, o.input) == Precision::kDouble ? hull_in<Point3d>(o, request)
                                                                   : hull_in<Point3>(o, request);
}

}  // namespace cudahull::cli
