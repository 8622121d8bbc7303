// What `hull` and `bench` share: the request their flags make, the plan with the environment's tuning, the
// engine's backend said on stderr, and the resident engine's stats as JSON.
#pragma once

#include <cstddef>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/hull_options.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/hull_runner.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/tuning.hpp"

namespace cudahull::cli {

// --backend, --engine and --precision as plan_hull() (hull_plan.hpp) takes them; CLI11 has checked the names.
ConvexHullOptions request_of(const std::string& backend, const std::string& engine,
                             const std::string& precision);

// The library's thresholds as this process's environment sets them, for A/B runs (docs/cli.md, "Environment
// variables"): the command line is the one place that reads them, the library never does.  A variable
// that is not set leaves the default (cudahull/tuning.hpp, EngineOptions); a set one is read as
// strtoull() reads it.  The library caps the batch's block and warp sizes as it always did.
struct Tuning {
  ResidentTuning resident;
  BatchTuning batch;
  std::size_t batched_swaps_from = EngineOptions{}.batched_swaps_from;
};

Tuning tuning_from_environment();
// The worker pool's watch (set_worker_watch()) from CUDAHULL_WORKER_WATCH_US, where it is set.
void pool_settings_from_environment();

// plan_hull()'s plan for the request, with the resident engine's thresholds from the environment.
HullPlan plan_with_tuning(const ConvexHullOptions& request, const HullInput& input, const Tuning& tuning);

// A request this machine cannot meet (`--backend cuda` without a usable device) is a device failure (exit 4),
// named by its flag.
inline void require_runnable(const HullPlan& plan) {
  if (!plan.unavailable.empty()) throw DeviceError("--" + plan.unavailable);
}

// How a run goes is plan_hull()'s choice (hull_plan.hpp): the precision first, since the points are read in
// it, from the input's own (io's resolve_precision() reads a file's header only where --precision auto asks
// for it); the engine and the backend once the points are read and their range is known.
Precision planned_precision(const ConvexHullOptions& request, const std::string& input);

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

// The resident engine's stats as one JSON object (`hull --stats`, `bench --json`): every field, then each
// phase with its distance to the hardware ("phases": name, ms, bytes, launches, host_waits, floor_ms) and
// the pace the floors were taken at.
nlohmann::json resident_stats_json(const ResidentStats& stats);

}  // namespace cudahull::cli
