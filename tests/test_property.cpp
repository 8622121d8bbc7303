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
#include "support/rng.hpp"

namespace cudahull {
namespace {

using testing::Rng;

struct Case {
  const char* kind;
  std::vector<Point3> points;
};

// Mostly small sets (fast, and where degeneracies bite), some large: 4..2000, one case in 50 up to 1e5.
std::size_t case_size(Rng& r, std::uint64_t id) {
  if (id % 50 == 49) return 10000 + r.below(90001);
  const double u = static_cast<double>(r.below(1 << 20)) / (1 << 20);
  return 4 + static_cast<std::size_t>(std::exp(u * u * std::log(2000.0)));
}

Case make_case(std::uint64_t id) {
  Rng r(id * 0x2545F4914F6CDD1Dull + 17);
  const std::size_t n = case_size(r, id);
  std::vector<Point3> p;
  p.reserve(n);
  auto lattice_point = [&](int side) {
    return Point3{float(int(r.below(side)) - side / 2), float(int(r.below(side)) - side / 2),
                  float(int(r.below(side)) - side / 2)};
  };
  switch (id % 8) {
    case 0:  // general position
      while (p.size() < n)
        p.push_back({r.unit(), r.unit(), r.unit()});
      return {"general position", p};
    case 1: {  // a lattice: coplanar faces, collinear edges, many points on the hull's faces
      const int side = 2 + static_cast<int>(r.below(10));
      while (p.size() < n)
        p.push_back(lattice_point(side));
      return {"lattice", p};
    }
    case 2: {  // exactly cospherical integer points (x^2 + y^2 + z^2 = 625) plus points inside
      static const std::vector<Point3> sphere = [] {
        std::vector<Point3> s;
        for (int x = -25; x <= 25; ++x)
          for (int y = -25; y <= 25; ++y)
            for (int z = -25; z <= 25; ++z)
              if (x * x + y * y + z * z == 625) s.push_back({float(x), float(y), float(z)});
        return s;
      }();
      while (p.size() < n) {
        if (r.below(2) == 0) {
          p.push_back(sphere[r.below(sphere.size())]);
        } else {
          p.push_back({14 * r.unit(), 14 * r.unit(), 14 * r.unit()});
        }
      }
      return {"cospherical", p};
    }
    case 3: {  // coplanar subsets: random points, many of them pushed onto a few axis and diagonal planes
      while (p.size() < n) {
        Point3 q{r.unit(), r.unit(), r.unit()};
        switch (r.below(5)) {
          case 0:
            q.z = 1;
            break;
          case 1:
            q.x = -1;
            break;
          case 2:
            q.y = q.x;
            break;  // the plane x = y
          default:
            break;
        }
        p.push_back(q);
      }
      return {"coplanar subsets", p};
    }
    case 4: {  // duplicates: few distinct points, each many times
      std::vector<Point3> distinct(4 + r.below(n / 4 + 1));
      for (auto& q : distinct)
        q = {r.unit(), r.unit(), r.unit()};
      while (p.size() < n)
        p.push_back(distinct[r.below(distinct.size())]);
      return {"duplicates", p};
    }
    case 5: {  // a lattice jittered by about 1e-7 of its size: nearly degenerate everywhere
      const int side = 3 + static_cast<int>(r.below(6));
      while (p.size() < n) {
        Point3 q = lattice_point(side);
        q = {q.x + 1e-7f * side * r.unit(), q.y + 1e-7f * side * r.unit(), q.z + 1e-7f * side * r.unit()};
        p.push_back(q);
      }
      return {"1e-7 jitter", p};
    }
    case 6: {  // extreme coordinate ranges: huge, tiny, or a tiny set far from the origin
      const int mode = static_cast<int>(r.below(3));
      while (p.size() < n) {
        const Point3 q{r.unit(), r.unit(), r.unit()};
        if (mode == 0) p.push_back({q.x * 1e30f, q.y * 1e30f, q.z * 1e30f});
        if (mode == 1) p.push_back({q.x * 1e-30f, q.y * 1e-30f, q.z * 1e-30f});
        if (mode == 2) p.push_back({1e6f + q.x * 0.5f, -3e5f + q.y * 0.5f, 7e5f + q.z * 0.5f});
      }
      return {"extreme ranges", p};
    }
    default: {  // clusters far apart: a few tiny clusters, 1e6 apart
      const std::size_t clusters = 2 + r.below(5);
      std::vector<Point3> centre(clusters);
      for (auto& c : centre)
        c = {1e6f * r.unit(), 1e6f * r.unit(), 1e6f * r.unit()};
      while (p.size() < n) {
        const Point3& c = centre[r.below(clusters)];
        p.push_back({c.x + 1e-3f * r.unit(), c.y + 1e-3f * r.unit(), c.z + 1e-3f * r.unit()});
      }
      return {"clusters far apart", p};
    }
  }
}

// The double cases (issue 14): case i's set in double, then by i % 4 (i / 8 picks among them, so every
// float kind meets every double variant): as it is (exact floats: the hull must be the float run's), jittered
// by 1e-12 of its size (below float resolution: the answer changes under rounding), scaled by 2^200 or
// 2^-200 (beyond float's range), or moved 1e9 away from the origin with a unit size (float's spacing there
// is 64).
struct DoubleCase {
  const char* kind;
  std::vector<Point3d> points;
};

DoubleCase make_double_case(std::uint64_t id) {
  const Case base = make_case(id);
  Rng r(id * 0x9E3779B97F4A7C15ull + 5);
  std::vector<Point3d> p(base.points.size());
  for (std::size_t k = 0; k < p.size(); ++k)
    p[k] = {base.points[k].x, base.points[k].y, base.points[k].z};
  double size = 0;
  for (const Point3d& q : p)
    size = std::max({size, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
  switch ((id / 8) % 4) {
    case 0:
      return {"exact floats", p};
    case 1:
      for (Point3d& q : p)
        q = {q.x + 1e-12 * size * r.unit(), q.y + 1e-12 * size * r.unit(), q.z + 1e-12 * size * r.unit()};
      return {"1e-12 jitter", p};
    case 2: {
      const double scale = r.below(2) ? 0x1p200 : 0x1p-200;
      for (Point3d& q : p)
        q = {q.x * scale, q.y * scale, q.z * scale};
      return {"scaled by 2^+-200", p};
    }
    default:
      for (Point3d& q : p) {
        const double k = size > 0 ? 1 / size : 1;
        q = {1e9 + q.x * k, -2e9 + q.y * k, 3e9 + q.z * k};
      }
      return {"1e9 from the origin", p};
  }
}

// One case: the engine against exact_hull and the checker, in the points' own precision.  Returns "" or
// what went wrong.
template <class Point>
std::string check_case(std::uint64_t id, const char* kind, const std::vector<Point>& points) {
  BasicEngine<Point> engine(points, make_cpu_backend<Point>(1));
  engine.run();
  const BasicHullMesh<Point>& hull = engine.result();
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

}  // namespace
}  // namespace cudahull
