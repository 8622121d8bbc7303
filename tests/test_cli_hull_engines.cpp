// `cudahull hull` and `bench` on each backend and engine, and with what the environment sets: --backend auto
// and cuda, --engine resident (with records or without, its phases in `bench --json`), CUDAHULL_THREADS,
// CUDAHULL_BATCHED_SWAPS_FROM and the huge-page tunable; the hull the same whatever they are.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/point_writer.hpp"
#include "qhull_reference.hpp"
#include "support/cli_hull_run.hpp"
#include "support/cli_runner.hpp"

namespace cudahull {
namespace {

using ::testing::HasSubstr;

TEST(CliHull, BackendAutoSaysWhichAndCudaNeedsADevice) {
  TempDir dir;
  write_points((dir / "in.xyz").string(), generate_points(Distribution::kCube, 100, 1));
  const CliRun automatic = run_cli({"hull", (dir / "in.xyz").string()});
  ASSERT_EQ(automatic.exit_code, kExitOk) << describe(automatic);
  EXPECT_THAT(automatic.err, HasSubstr("backend: "));
  const bool has_gpu = automatic.err.find("backend: cuda") != std::string::npos;
  // With a usable GPU, --backend cuda works; without one it is a device failure: exit 4, one line.
  const CliRun cuda = run_cli({"hull", (dir / "in.xyz").string(), "--backend", "cuda"});
  if (has_gpu) {
    EXPECT_EQ(cuda.exit_code, kExitOk) << describe(cuda);
  } else {
    EXPECT_THAT(automatic.err, HasSubstr("auto: no usable CUDA device"));
    EXPECT_EQ(cuda.exit_code, kExitDevice) << describe(cuda);
    EXPECT_THAT(cuda.err, HasSubstr("cudahull: error: --backend cuda: no usable CUDA device"));
  }
}

// --engine resident (issue 15): the same vertices as Qhull, verified, with its counts in --stats; with
// --table and --trace it steps with records, the same hull, a trace line and a table row per step.
TEST(CliHull, ResidentEngineMatchesQhullWithAndWithoutRecords) {
  for (Distribution dist : {Distribution::kBall, Distribution::kSphere, Distribution::kCylinder}) {
    const auto points = generate_points(dist, 20000, 7);
    const HullRun r = hull_of(points, {"--engine", "resident"});
    EXPECT_EQ(r.ids, run_qhull(points).vertex_ids) << distribution_name(dist);
    const nlohmann::json& stats = r.stats;
    EXPECT_EQ(stats.at("engine"), "resident");
    EXPECT_EQ(stats.at("backend"), "cpu-resident");
    EXPECT_EQ(stats.at("verified"), true);
    EXPECT_GT(stats.at("host_syncs").get<int>(), 0);
    // Every counter of the run (for_each_stat), agreeing with the summary's.
    const nlohmann::json& counters = stats.at("resident");
    EXPECT_EQ(counters.at("host_syncs"), stats.at("host_syncs"));
    EXPECT_EQ(counters.at("iterations"), stats.at("iterations"));
    EXPECT_EQ(counters.at("edits"), stats.at("swaps"));
    EXPECT_GE(counters.at("work_items").get<std::uint64_t>(), counters.at("edits").get<std::uint64_t>());
    EXPECT_EQ(counters.at("round_phase_ms").size(), 4u);  // the device's clock: zero on the host
  }
  TempDir dir;
  const auto sphere = generate_points(Distribution::kSphere, 3000, 2);
  write_points((dir / "in.xyz").string(), sphere);
  const std::string trace = (dir / "trace.jsonl").string(), vertices = (dir / "v.txt").string();
  const CliRun table = run_cli({"hull", (dir / "in.xyz").string(), "--engine", "resident", "--table",
                                "--trace", trace, "--vertices-out", vertices});
  ASSERT_EQ(table.exit_code, kExitOk) << describe(table);
  std::ifstream lines(trace);
  std::size_t steps = 0, performed = 0;
  for (std::string line; std::getline(lines, line); ++steps) {
    const nlohmann::json j = nlohmann::json::parse(line);
    EXPECT_EQ(j.at("iteration").get<std::size_t>(), steps);
    performed += j.at("swaps_regular").get<std::size_t>() + j.at("swaps_complementary").get<std::size_t>();
  }
  EXPECT_GT(steps, 3u);
  EXPECT_GT(performed, 0u);
  // A table row per step after the header.
  EXPECT_EQ(static_cast<std::size_t>(std::count(table.out.begin(), table.out.end(), '\n')), steps + 1)
      << table.out;
  std::ifstream ids(vertices);
  std::vector<PointIndex> listed;
  for (std::string line; std::getline(ids, line);)
    listed.push_back(static_cast<PointIndex>(std::stoul(line)));  // "id x y z"
  EXPECT_EQ(listed, run_qhull(sphere).vertex_ids);
  const CliRun bad = run_cli({"hull", (dir / "in.xyz").string(), "--engine", "fast"});
  EXPECT_EQ(bad.exit_code, kExitUsage) << describe(bad);
}

// CUDAHULL_THREADS sets the host threads (README); the hull and the trace do not depend on their number.
TEST(CliHull, ThreadCountFromTheEnvironmentChangesNothingButTheThreads) {
  TempDir dir;
  // Enough refinements for batched swap rounds (from 4096 candidates) to run on the threads.
  write_points((dir / "in.xyz").string(), generate_points(Distribution::kSphere, 20000, 5));
  auto run_with = [&](const char* threads, const std::string& tag) {
    if (threads != nullptr) {
      ::setenv("CUDAHULL_THREADS", threads, 1);
    } else {
      ::unsetenv("CUDAHULL_THREADS");
    }
    const CliRun r = run_cli({"hull", (dir / "in.xyz").string(), "--backend", "cpu", "--vertices-out",
                              (dir / ("v" + tag)).string(), "--trace", (dir / ("t" + tag)).string()});
    ::unsetenv("CUDAHULL_THREADS");
    EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
    return r;
  };
  EXPECT_THAT(run_with("1", "1").err, HasSubstr("backend: cpu (1 thread)"));
  EXPECT_THAT(run_with("3", "3").err, HasSubstr("backend: cpu (3 threads)"));
  const std::string vertices = slurp(dir / "v1");
  ASSERT_FALSE(vertices.empty());
  EXPECT_EQ(slurp(dir / "v3"), vertices);
  // The traces match but for their timings.
  auto without_times = [](std::string trace) {
    for (const char* key : {"\"host_ms\":", "\"backend_ms\":", "\"upload_ms\":"}) {
      for (std::size_t at = trace.find(key); at != std::string::npos; at = trace.find(key, at + 1)) {
        const std::size_t value = at + std::strlen(key);
        trace.erase(value, trace.find_first_of(",}", value) - value);
      }
    }
    return trace;
  };
  const std::string trace = without_times(slurp(dir / "t1"));
  EXPECT_NE(trace.find("\"swaps\":[{"), std::string::npos);
  EXPECT_EQ(without_times(slurp(dir / "t3")), trace);
  // Not a positive number: the hardware's count, as without the variable.
  auto backend_line = [](const std::string& err) {
    const std::size_t at = err.find("backend: cpu (");
    return at == std::string::npos ? std::string("(none)") : err.substr(at, err.find('\n', at) - at);
  };
  const std::string hardware = backend_line(run_with(nullptr, "u").err);
  EXPECT_NE(hardware, "(none)");
  EXPECT_EQ(backend_line(run_with("zero", "z").err), hardware);
  EXPECT_EQ(slurp(dir / "vz"), vertices);
}

// The command line reads the library's thresholds from its environment for A/B runs (docs/cli.md), the
// library itself none: CUDAHULL_BATCHED_SWAPS_FROM turns the stepping engine's batched swap rounds on (8) or
// off (SIZE_MAX), as scripts/compare-traces counts them (CUDAHULL_PHASE_TIMES=1), for `hull` and `bench`
// alike, and the vertices stay the same.
TEST(CliHull, BatchedSwapsFromTheEnvironmentReachTheEngine) {
  TempDir dir;
  write_points((dir / "in.xyz").string(), generate_points(Distribution::kSphere, 20000, 5));
  auto rounds_with = [&](const char* from, const std::vector<std::string>& args) {
    ::setenv("CUDAHULL_PHASE_TIMES", "1", 1);
    ::setenv("CUDAHULL_BATCHED_SWAPS_FROM", from, 1);
    const CliRun r = run_cli(args);
    ::unsetenv("CUDAHULL_BATCHED_SWAPS_FROM");
    ::unsetenv("CUDAHULL_PHASE_TIMES");
    EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
    int rounds = 0;
    for (std::size_t at = r.err.find("batched swaps: "); at != std::string::npos;
         at = r.err.find("batched swaps: ", at + 1))
      rounds += std::atoi(r.err.c_str() + at + std::strlen("batched swaps: "));
    return rounds;
  };
  const std::string input = (dir / "in.xyz").string();
  const std::string never = std::to_string(std::numeric_limits<std::size_t>::max());
  auto hull = [&](const std::string& out) {
    return std::vector<std::string>{"hull", input, "--backend", "cpu", "-q", "--vertices-out", out};
  };
  const std::string v8 = (dir / "v8").string(), vnever = (dir / "vnever").string();
  EXPECT_GT(rounds_with("8", hull(v8)), 0);
  EXPECT_EQ(rounds_with(never.c_str(), hull(vnever)), 0);
  const std::string vertices = slurp(v8);
  ASSERT_FALSE(vertices.empty());
  EXPECT_EQ(slurp(vnever), vertices);
  const std::vector<std::string> bench{"bench", input, "--backend", "cpu", "--engine", "stepping", "--json"};
  EXPECT_GT(rounds_with("8", bench), 0);
  EXPECT_EQ(rounds_with(never.c_str(), bench), 0);
}

// Every resident run reports its distance to the hardware: `bench --json` lists the phases (setup, refine,
// rounds, route, finish, host) with their time, least bytes, launches, waits and floor.  The phases' times
// add up to the run's total within 5%, no floor exceeds its phase's time, the setup reads every point once,
// and the floors come from a measured pace.
TEST(CliBench, ResidentPhasesAddUpAndNoFloorExceedsItsTime) {
  for (const char* dist : {"ball", "sphere", "cube"}) {
    const CliRun r = run_cli({"bench", "--dist", dist, "--n", "100000", "--repeat", "1", "--backend", "cpu",
                              "--engine", "resident", "--json"});
    ASSERT_EQ(r.exit_code, kExitOk) << describe(r);
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const nlohmann::json& stats = j.at("resident");
    const nlohmann::json& phases = stats.at("phases");
    std::vector<std::string> names;
    double sum = 0;
    for (const nlohmann::json& p : phases) {
      names.push_back(p.at("name"));
      const double ms = p.at("ms"), floor = p.at("floor_ms");
      sum += ms;
      EXPECT_GE(floor, 0) << dist << " " << names.back();
      EXPECT_LE(floor, ms) << dist << " " << names.back() << ": a floor above the time it bounds";
    }
    EXPECT_EQ(names, (std::vector<std::string>{"setup", "refine", "rounds", "route", "finish", "host"}));
    const double total = j.at("total_ms");
    EXPECT_NEAR(sum, total, 0.05 * total) << dist << ": the phases do not add up to the run";
    EXPECT_EQ(phases.at(0).at("bytes").get<std::uint64_t>(), 100000u * 3 * sizeof(float)) << dist;
    EXPECT_GT(phases.at(3).at("launches").get<std::uint64_t>(), 0u) << dist << ": no routing launched";
    EXPECT_GT(stats.at("pace").at("bytes_per_ms").get<double>(), 0) << dist;
  }
}

// The CLI runs with glibc's huge-page tunable unless told not to (cli/huge_pages.hpp), and a caller's own
// setting of it wins; the hull is the same either way.
TEST(CliHull, HugePagesByDefaultOffOnRequestAndTheCallersChoiceKept) {
  auto bench_with = [](const char* huge_pages, const char* tunables) {
    auto set = [](const char* name, const char* value) {
      if (value != nullptr) {
        ::setenv(name, value, 1);
      } else {
        ::unsetenv(name);
      }
    };
    set("CUDAHULL_HUGE_PAGES", huge_pages);
    set("GLIBC_TUNABLES", tunables);
    const CliRun r =
        run_cli({"bench", "--dist", "ball", "--n", "20000", "--repeat", "1", "--backend", "cpu", "--json"});
    ::unsetenv("CUDAHULL_HUGE_PAGES");
    ::unsetenv("GLIBC_TUNABLES");
    EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
    return nlohmann::json::parse(r.out.empty() ? "{}" : r.out);
  };
  const auto by_default = bench_with(nullptr, nullptr);
  const auto off = bench_with("0", nullptr);
  const auto callers = bench_with(nullptr, "glibc.malloc.hugetlb=0");
  EXPECT_EQ(by_default.value("host_huge_pages", false), true);
  EXPECT_EQ(off.value("host_huge_pages", true), false);
  EXPECT_EQ(callers.value("host_huge_pages", true), false);
  EXPECT_GT(by_default.value("hull_vertices", 0), 0);
  EXPECT_EQ(off.value("hull_vertices", -1), by_default.value("hull_vertices", -2));
  EXPECT_EQ(callers.value("hull_vertices", -1), by_default.value("hull_vertices", -2));
}

}  // namespace
}  // namespace cudahull
