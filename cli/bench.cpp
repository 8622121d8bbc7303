// `cudahull bench`: one cloud's hull timed on the planned engine, optionally against Qhull; a batch of
// clouds goes to run_bench_batch() (bench_batch.cpp).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "command_support.hpp"
#include "commands.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/resident.hpp"
#include "huge_pages.hpp"
#include "qhull_reference.hpp"

namespace cudahull::cli {

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

}  // namespace

int run_bench(const BenchOptions& o) {
  if (o.batch > 0) return run_bench_batch(o);
  const ConvexHullOptions request = request_of(o.backend, o.engine, o.precision);
  if (o.versus == "loop") throw std::invalid_argument("--vs loop compares a batch: it needs --batch B");
  return planned_precision(request, o.input) == Precision::kDouble ? bench_in<Point3d>(o, request)
                                                                   : bench_in<Point3>(o, request);
}

}  // namespace cudahull::cli
