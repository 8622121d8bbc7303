// The property test of issue 7: seeded random and adversarial point sets, from 4 to 1e5 points, where the
// engine's hull must have exactly the vertices of an independent exact hull (exact_hull: exact QuickHull on
// exact predicates) and pass the independent checker (what `cudahull hull --verify` runs).
//
// Case i is always the same set (splitmix64 seeded by i), so a failure names a reproducible case.  Kinds, by
// i % 8: general position, lattices, cospherical points, coplanar subsets, duplicates, 1e-7 jitter, extreme
// coordinate ranges, clusters far apart.
//
// By default (CI) a slice runs: cases from 0 on for CUDAHULL_PROPERTY_SECONDS (60) seconds.
// CUDAHULL_PROPERTY_CASES=N runs exactly cases 0..N-1 instead (the full run, N = 10000: docs/benchmarks.md);
// CUDAHULL_PROPERTY_FIRST=K starts at case K, CUDAHULL_PROPERTY_VERBOSE=1 names each case before it runs.
// The double test (30 s by default) runs the same sets in double, with variants that float cannot hold.
// The resident engine's slices (20 s float, 10 s double) run the same sets through its host executor.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "cudahull/cpu_backend.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/resident.hpp"
#include "support/property_cases.hpp"
#include "support/rng.hpp"

namespace cudahull {
namespace {

using testing::Case;
using testing::DoubleCase;
using testing::make_case;
using testing::make_double_case;
using testing::Rng;

// One case: the engine against exact_hull and the checker, in the points' own precision.  Returns "" or
// what went wrong.
template <class Point>
std::string check_case(std::uint64_t id, const char* kind, const std::vector<Point>& points,
                       bool resident = false) {
  BasicHullMesh<Point> hull;
  if (resident) {
    // Odd cases take the GPU executor's paths on the host (the device loop, its room checks and regrowth).
    hull = resident_hull_host(points, nullptr, id % 2 ? ResidentPath::kDevice : ResidentPath::kHost);
  } else {
    BasicEngine<Point> engine(points, make_cpu_backend<Point>(1));
    engine.run();
    hull = engine.result();
  }
  const BasicHullMesh<Point> oracle = exact_hull(points);
  const std::string where = "case " + std::to_string(id) + " (" + kind + ", " +
                            std::to_string(points.size()) +
                            (sizeof(points[0].x) == 8 ? " double" : " float") + " points): ";
  if (hull.dimension != oracle.dimension)
    return where + "dimension " + std::to_string(hull.dimension) + ", exact " +
           std::to_string(oracle.dimension);
  if (hull.vertex_ids != oracle.vertex_ids)
    return where + std::to_string(hull.vertex_ids.size()) + " vertices, the exact hull has " +
           std::to_string(oracle.vertex_ids.size()) + " (or others)";
  const CheckResult check = check_hull(points, hull, 3);
  if (!check.ok) return where + "the checker rejects the hull: " + check.failures.front();
  return "";
}

std::string run_case(std::uint64_t id) {
  const Case c = make_case(id);
  return check_case(id, c.kind, c.points);
}

// A double case; an exact-floats case must also give the float run's vertices.
std::string run_double_case(std::uint64_t id) {
  const DoubleCase c = make_double_case(id);
  std::string failure = check_case(id, c.kind, c.points);
  if (failure.empty() && (id / 8) % 4 == 0) {
    const Case f = make_case(id);
    Engine engine(f.points, make_cpu_backend(1));
    engine.run();
    BasicEngine<Point3d> wide(c.points, make_cpu_backend<Point3d>(1));
    wide.run();
    if (engine.result().vertex_ids != wide.result().vertex_ids)
      failure = "case " + std::to_string(id) + ": exact floats in double give other vertices than in float";
  }
  return failure;
}

// Cases from 0 on, for `default_seconds` (CUDAHULL_PROPERTY_SECONDS overrides) or CUDAHULL_PROPERTY_CASES.
template <class Run>
void run_slice(double default_seconds, const char* label, Run&& run) {
  const char* cases_env = std::getenv("CUDAHULL_PROPERTY_CASES");
  const char* seconds_env = std::getenv("CUDAHULL_PROPERTY_SECONDS");
  const std::uint64_t cases = cases_env ? std::strtoull(cases_env, nullptr, 10) : UINT64_MAX;
  const double seconds = seconds_env ? std::atof(seconds_env) : default_seconds;
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t done = 0, failed = 0;
  const char* first_env = std::getenv("CUDAHULL_PROPERTY_FIRST");  // to rerun from a failing case
  const bool verbose = std::getenv("CUDAHULL_PROPERTY_VERBOSE") != nullptr;
  for (std::uint64_t id = first_env ? std::strtoull(first_env, nullptr, 10) : 0; id < cases; ++id) {
    if (verbose) std::fprintf(stderr, "case %llu\n", static_cast<unsigned long long>(id));
    if (!cases_env && std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > seconds)
      break;
    const std::string failure = run(id);
    ++done;
    if (!failure.empty()) {
      ++failed;
      ADD_FAILURE() << failure;
      if (failed >= 10) break;
    }
  }
  std::printf("property (%s): %llu cases, %llu failed, %.1f s\n", label,
              static_cast<unsigned long long>(done), static_cast<unsigned long long>(failed),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  if (!cases_env && !first_env) EXPECT_GT(done, 100u) << "the slice must cover more than the first few cases";
}

TEST(Property, EngineEqualsExactHullOnAdversarialSets) {
  run_slice(60.0, "float", run_case);
}

// The same in double, on the double variants of the same sets (issue 14).
TEST(Property, DoubleEngineEqualsExactHullOnAdversarialSets) {
  run_slice(30.0, "double", run_double_case);
}

// The resident engine (issue 15) on its host executor, the operations the GPU runs: the same sets, float
// and double.  test_resident_cuda runs them on the device.
TEST(Property, ResidentEngineEqualsExactHullOnAdversarialSets) {
  run_slice(20.0, "resident float", [](std::uint64_t id) {
    const Case c = make_case(id);
    return check_case(id, c.kind, c.points, true);
  });
}

TEST(Property, DoubleResidentEngineEqualsExactHullOnAdversarialSets) {
  run_slice(10.0, "resident double", [](std::uint64_t id) {
    const DoubleCase c = make_double_case(id);
    return check_case(id, c.kind, c.points, true);
  });
}

}  // namespace
}  // namespace cudahull
