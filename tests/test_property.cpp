// The property test: seeded random and adversarial point sets, from 4 to 1e5 points, where the engine's
// hull must have exactly the vertices of an independent exact hull (exact_hull: exact QuickHull on exact
// predicates) and pass the independent checker (what `cudahull hull --verify` runs).  exact_hull is also
// how the engines finish, so the API slice below checks against a brute force that shares nothing with
// them but the exact predicates.
//
// Case i is always the same set (splitmix64 seeded by i), so a failure names a reproducible case.  Kinds, by
// i % 8: general position, lattices, cospherical points, coplanar subsets, duplicates, 1e-7 jitter, extreme
// coordinate ranges, clusters far apart.
//
// Each slice runs a fixed range of cases, printed as it ends: one range in the plain build and the range
// after it in the sanitizer build (kFloatRanges and the rest below), whatever the machine's speed.
// CUDAHULL_PROPERTY_FIRST=K and CUDAHULL_PROPERTY_CASES=N run cases [K, N) instead (scripts/soak);
// CUDAHULL_PROPERTY_VERBOSE=1 names each case before it runs.  The double slice runs the same sets in
// double, with variants that float cannot hold; the resident slices run them through the resident engine's
// host executor.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "cudahull/convex_hull.hpp"
#include "cudahull/cpu_backend.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/resident.hpp"
#include "support/oracles.hpp"
#include "support/property_cases.hpp"
#include "support/rng.hpp"

namespace cudahull {
namespace {

using testing::Case;
using testing::DoubleCase;
using testing::make_case;
using testing::make_double_case;
using testing::Rng;

// The stepping engine's options: CUDAHULL_BATCHED_SWAPS_FROM=N runs the cases with batched swap rounds from
// N candidates on (1: every iteration, docs/reliability.md), read here as the command line reads it (the
// library reads no environment for it).
EngineOptions engine_options() {
  EngineOptions options;
  if (const char* from = std::getenv("CUDAHULL_BATCHED_SWAPS_FROM"))
    options.batched_swaps_from = std::strtoull(from, nullptr, 10);
  return options;
}

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
    BasicEngine<Point> engine(points, make_cpu_backend<Point>(1), engine_options());
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
    Engine engine(f.points, make_cpu_backend(1), engine_options());
    engine.run();
    BasicEngine<Point3d> wide(c.points, make_cpu_backend<Point3d>(1), engine_options());
    wide.run();
    if (engine.result().vertex_ids != wide.result().vertex_ids)
      failure = "case " + std::to_string(id) + ": exact floats in double give other vertices than in float";
  }
  return failure;
}

// A slice's fixed range of cases: [first, end) in a plain build, and the range after it under the
// sanitizers (CUDAHULL_SANITIZER_BUILD), so that the two builds together cover more cases and neither's
// coverage depends on the machine's speed.  CUDAHULL_PROPERTY_FIRST and CUDAHULL_PROPERTY_CASES override it
// with [FIRST, CASES) (scripts/soak runs long ranges so).
struct CaseRange {
  std::uint64_t first, end;
};
struct SliceRanges {
  CaseRange plain, sanitized;
};

// A guard, not a budget: a fixed range that runs past it fails, naming the case it stopped at.
constexpr double kGuardSeconds = 900;

template <class Run>
void run_slice(SliceRanges ranges, const char* label, Run&& run) {
#ifdef CUDAHULL_SANITIZER_BUILD
  CaseRange range = ranges.sanitized;
#else
  CaseRange range = ranges.plain;
#endif
  const char* first = std::getenv("CUDAHULL_PROPERTY_FIRST");
  const char* end = std::getenv("CUDAHULL_PROPERTY_CASES");
  if (first) range.first = std::strtoull(first, nullptr, 10);
  if (end) range.end = std::strtoull(end, nullptr, 10);
  const bool guarded = !first && !end;  // a range of your own runs as long as it takes
  const bool verbose = std::getenv("CUDAHULL_PROPERTY_VERBOSE") != nullptr;
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  std::uint64_t done = 0, failed = 0;
  for (std::uint64_t id = range.first; id < range.end; ++id) {
    if (verbose) std::fprintf(stderr, "case %llu\n", static_cast<unsigned long long>(id));
    if (guarded && elapsed() > kGuardSeconds) {
      ADD_FAILURE() << label << ": stopped by the " << kGuardSeconds << " s guard at case " << id << " of ["
                    << range.first << ", " << range.end << ")";
      break;
    }
    const std::string failure = run(id);
    ++done;
    if (range.end - range.first >= 100000 && done % ((range.end - range.first) / 10) == 0)
      std::fprintf(stderr, "property (%s): %llu of %llu cases, %.0f s\n", label,
                   static_cast<unsigned long long>(done),
                   static_cast<unsigned long long>(range.end - range.first), elapsed());
    if (!failure.empty()) {
      ++failed;
      ADD_FAILURE() << failure;
      if (failed >= 10) break;
    }
  }
  std::printf("property (%s): cases [%llu, %llu): %llu run, %llu failed, %.1f s\n", label,
              static_cast<unsigned long long>(range.first), static_cast<unsigned long long>(range.end),
              static_cast<unsigned long long>(done), static_cast<unsigned long long>(failed), elapsed());
}

// The ranges: about the same time per slice on the CI machine; the sanitizers run about 5x slower.
constexpr SliceRanges kFloatRanges{{0, 40000}, {40000, 48000}};
constexpr SliceRanges kDoubleRanges{{0, 16000}, {16000, 19000}};
constexpr SliceRanges kResidentFloatRanges{{0, 12000}, {12000, 14400}};
constexpr SliceRanges kResidentDoubleRanges{{0, 6000}, {6000, 7200}};
constexpr SliceRanges kApiRanges{{0, 6000}, {6000, 7200}};

TEST(Property, EngineEqualsExactHullOnAdversarialSets) {
  run_slice(kFloatRanges, "float", run_case);
}

// The same in double, on the double variants of the same sets (issue 14).
TEST(Property, DoubleEngineEqualsExactHullOnAdversarialSets) {
  run_slice(kDoubleRanges, "double", run_double_case);
}

// The resident engine (issue 15) on its host executor, the operations the GPU runs: the same sets, float
// and double.  test_resident_cuda runs them on the device.
TEST(Property, ResidentEngineEqualsExactHullOnAdversarialSets) {
  run_slice(kResidentFloatRanges, "resident float", [](std::uint64_t id) {
    const Case c = make_case(id);
    return check_case(id, c.kind, c.points, true);
  });
}

TEST(Property, DoubleResidentEngineEqualsExactHullOnAdversarialSets) {
  run_slice(kResidentDoubleRanges, "resident double", [](std::uint64_t id) {
    const DoubleCase c = make_double_case(id);
    return check_case(id, c.kind, c.points, true);
  });
}

// --- the one-call API as users call it, against the brute force --------------------------------------------
// convex_hull() on a float or a double array, convex_hull_2d() on x, y pairs: the vertex set must be the
// brute force's (oracles.hpp: nothing shared with the engines but the exact predicates, GMP for wide
// coordinates), every point must lie on or below every face, and the faces must use exactly the vertices.
// Sets of at most 24 points (the brute force is O(n^4)), cut from the property cases; by id % 4: float xyz,
// double xyz (the double variants), wide doubles (magnitudes outside the engines' range: scaled by
// 2^+-(300..1000), each coordinate in its own binade, or subnormal), and 2-D (float, double or wide).
constexpr std::size_t kApiMaxPoints = 24;

// The float case's set, its largest magnitude brought to [0.5, 1) by a power of two, then moved beyond the
// engines' exact range (nonzero magnitudes 2^-250..2^250).  Subnormal results may round: the oracle and the
// API see the same rounded points.
std::vector<Point3d> wide_variant(const std::vector<Point3>& base, std::uint64_t id) {
  Rng r(id * 0xD1B54A32D192ED03ull + 11);
  double size = 0;
  for (const Point3& q : base)
    size = std::max({size, std::fabs(double(q.x)), std::fabs(double(q.y)), std::fabs(double(q.z))});
  const int unit = size > 0 ? -std::ilogb(size) - 1 : 0;
  std::vector<Point3d> p;
  for (const Point3& q : base)
    p.push_back(
        {std::ldexp(double(q.x), unit), std::ldexp(double(q.y), unit), std::ldexp(double(q.z), unit)});
  switch ((id / 4) % 4) {
    case 0: {  // the whole set far beyond the fast range, up or down
      const int e = 300 + static_cast<int>(r.below(700));
      const double scale = std::ldexp(1.0, r.below(2) ? e : -e);
      for (Point3d& q : p)
        q = {q.x * scale, q.y * scale, q.z * scale};
      return p;
    }
    case 1:  // every coordinate in a binade of its own, from 2^-600 to 2^600
      for (Point3d& q : p) {
        auto spread = [&](double v) { return std::ldexp(v, static_cast<int>(r.below(1201)) - 600); };
        q = {spread(q.x), spread(q.y), spread(q.z)};
      }
      return p;
    case 2:  // subnormal
      for (Point3d& q : p)
        q = {std::ldexp(q.x, -1040), std::ldexp(q.y, -1040), std::ldexp(q.z, -1040)};
      return p;
    default:  // near the top of the double range, one axis tiny
      for (Point3d& q : p)
        q = {std::ldexp(q.x, 1000), std::ldexp(q.y, 1000), std::ldexp(q.z, -700)};
      return p;
  }
}

template <class Exact, class Point>
std::string check_api_hull(const std::string& where, const std::vector<Point>& points,
                           const ConvexHull& hull) {
  int dimension = 0;
  const std::vector<PointIndex> expected = testing::brute_force_extreme_any<Point, Exact>(points, &dimension);
  if (hull.dimension != dimension)
    return where + "dimension " + std::to_string(hull.dimension) + ", the brute force's " +
           std::to_string(dimension);
  if (hull.vertices != expected)
    return where + std::to_string(hull.vertices.size()) + " vertices, the brute force finds " +
           std::to_string(expected.size()) + " (or others)";
  if (dimension == 3) {
    std::vector<PointIndex> used;
    for (const auto& f : hull.faces) {
      used.insert(used.end(), f.begin(), f.end());
      for (const Point& p : points)
        if (Exact::orient3d(to_vec3d(points[f[0]]), to_vec3d(points[f[1]]), to_vec3d(points[f[2]]),
                            to_vec3d(p)) > 0)
          return where + "a point lies above a face";
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    if (used != expected) return where + "the faces do not use exactly the vertices";
  }
  return "";
}

std::string run_api_case(std::uint64_t id) {
  const Case base = make_case(id);
  const std::size_t n = std::min(base.points.size(), kApiMaxPoints);
  const std::vector<Point3> floats(base.points.begin(), base.points.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<Point3d> doubles = make_double_case(id).points;
  doubles.resize(n);
  const std::string where =
      "api case " + std::to_string(id) + " (" + base.kind + ", " + std::to_string(n) + " points, ";
  try {
    switch (id % 4) {
      case 0:
        return check_api_hull<testing::FilteredExact>(where + "float): ", floats,
                                                      convex_hull(&floats[0].x, n));
      case 1:
        return check_api_hull<testing::FilteredExact>(where + "double): ", doubles,
                                                      convex_hull(&doubles[0].x, n));
      case 2: {
        const std::vector<Point3d> wide = wide_variant(floats, id);
        return check_api_hull<testing::GmpExact>(where + "wide double): ", wide, convex_hull(&wide[0].x, n));
      }
      default: {  // 2-D: the x, y of the float, double or wide set
        std::vector<Point3d> source = doubles;
        if ((id / 4) % 3 == 0)
          for (std::size_t i = 0; i < n; ++i)
            source[i] = {floats[i].x, floats[i].y, floats[i].z};
        if ((id / 4) % 3 == 2) source = wide_variant(floats, id);
        std::vector<std::array<double, 2>> plane(n);
        std::vector<double> xy(2 * n);
        for (std::size_t i = 0; i < n; ++i) {
          plane[i] = {source[i].x, source[i].y};
          xy[2 * i] = source[i].x;
          xy[2 * i + 1] = source[i].y;
        }
        const ConvexHull hull = convex_hull_2d(xy.data(), n);
        const std::vector<PointIndex> expected = testing::brute_force_extreme_2d<testing::GmpExact>(plane);
        if (hull.vertices != expected)
          return where + "2-D): " + std::to_string(hull.vertices.size()) +
                 " vertices, the brute force finds " + std::to_string(expected.size()) + " (or others)";
        std::vector<PointIndex> corners = hull.polygon;
        std::sort(corners.begin(), corners.end());
        if (hull.dimension == 2 && corners != expected)
          return where + "2-D): the polygon is not the vertices";
        return "";
      }
    }
  } catch (const std::exception& e) {
    return where + "threw: " + e.what();
  }
}

TEST(Property, ConvexHullApiEqualsBruteForce) {
  run_slice(kApiRanges, "api", run_api_case);
}

}  // namespace
}  // namespace cudahull
