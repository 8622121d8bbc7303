// What `hull` and `bench` share: the request, the tuning, the plan and the stats' JSON (command_support.hpp).
#include "command_support.hpp"

#include <chrono>
#include <cstdlib>

#include "cudahull/parallel.hpp"
#include "cudahull/point_io.hpp"

namespace cudahull::cli {

ConvexHullOptions request_of(const std::string& backend, const std::string& engine,
                             const std::string& precision) {
  ConvexHullOptions request;
  request.backend = backend_from_name(backend);
  request.engine = engine_from_name(engine);
  request.precision = precision_from_name_strict(precision);
  return request;
}

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

void pool_settings_from_environment() {
  if (const char* text = std::getenv("CUDAHULL_WORKER_WATCH_US"))
    set_worker_watch(std::chrono::microseconds(std::strtoll(text, nullptr, 10)));
}

HullPlan plan_with_tuning(const ConvexHullOptions& request, const HullInput& input, const Tuning& tuning) {
  HullPlan plan = plan_hull(request, input);
  plan.resident_tuning = tuning.resident;
  return plan;
}

Precision planned_precision(const ConvexHullOptions& request, const std::string& input) {
  return plan_precision(request.precision, resolve_precision(request.precision, input)).precision;
}

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

}  // namespace cudahull::cli
