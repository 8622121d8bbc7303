// The checker on every finite double (issue 25): check_hull and `cudahull hull --verify` on inputs beyond the
// fast exact range, against the GMP rationals' brute force (support/rational_oracle.hpp) where small.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/wide_predicates.hpp"
#include "support/cli_runner.hpp"
#include "support/rational_oracle.hpp"

namespace cudahull {
namespace {

// ---------------------------------------------------------------------------------------------------------
// The checker (check_hull, `hull --verify`) on every finite double: property cases of 100 to 5,000 points
// scaled by 2^+-300 (beyond the fast range), spread over many binades, or offset by 1e9 at 2^300, with fixed
// seeds.  Each exact_hull_any() hull passes; the same hull broken (a face dropped, a point pushed out)
// fails for its reason.

std::vector<Point3d> unit_ball(std::mt19937_64& rng, std::size_t n) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3d> p;
  while (p.size() < n) {
    const double x = g(rng), y = g(rng), z = g(rng), r = std::sqrt(x * x + y * y + z * z);
    const double s = std::cbrt(u(rng)) / r;
    if (r > 0) p.push_back({x * s, y * s, z * s});
  }
  return p;
}

struct WideCase {
  const char* name;
  std::vector<Point3d> points;
};

std::vector<WideCase> wide_cases() {
  std::vector<WideCase> out;
  std::mt19937_64 rng(4321);
  auto scaled = [&](std::size_t n, int e) {
    std::vector<Point3d> p = unit_ball(rng, n);
    for (Point3d& q : p)
      q = {std::ldexp(q.x, e), std::ldexp(q.y, e), std::ldexp(q.z, e)};
    return p;
  };
  out.push_back({"ball x 2^300, 100", scaled(100, 300)});
  out.push_back({"ball x 2^-300, 1000", scaled(1000, -300)});
  out.push_back({"ball x 2^300, 5000", scaled(5000, 300)});
  // Each point scaled by its own power of two in 2^-500..2^500: the call's magnitudes span ~1000 binades.
  for (const std::size_t n : {100, 2000}) {
    std::vector<Point3d> p = unit_ball(rng, n);
    std::uniform_int_distribution<int> e(-500, 500);
    for (Point3d& q : p) {
      const int k = e(rng);
      q = {std::ldexp(q.x, k), std::ldexp(q.y, k), std::ldexp(q.z, k)};
    }
    out.push_back({n == 100 ? "binades 2^-500..2^500, 100" : "binades 2^-500..2^500, 2000", p});
  }
  // A unit ball at 1e9 (rounded there), all of it scaled by 2^300.
  {
    std::vector<Point3d> p = unit_ball(rng, 3000);
    for (Point3d& q : p)
      q = {std::ldexp(1e9 + q.x, 300), std::ldexp(1e9 + q.y, 300), std::ldexp(-1e9 + q.z, 300)};
    out.push_back({"1e9 offset x 2^300, 3000", p});
  }
  // A ball of subnormal-scale interior points and one at 2^200: the fast range on neither side.
  {
    std::vector<Point3d> p = scaled(400, -1000);
    for (const Point3d& q : scaled(400, 200))
      p.push_back(q);
    out.push_back({"2^-1000 and 2^200, 800", p});
  }
  return out;
}

TEST(WideChecker, PropertyCasesPassAndBrokenOnesFail) {
  for (const WideCase& c : wide_cases()) {
    SCOPED_TRACE(c.name);
    ASSERT_FALSE(in_fast_exact_range(c.points));
    const HullMeshd h = exact_hull_any(c.points);
    ASSERT_EQ(h.dimension, 3);
    const CheckResult ok = check_hull(c.points, h);
    EXPECT_TRUE(ok.ok) << (ok.failures.empty() ? "" : ok.failures.front());
    if (c.points.size() <= 100) expect_matches_oracle(c.points, h, c.name);

    HullMeshd open = h;
    open.triangles.pop_back();
    const CheckResult no = check_hull(c.points, open);
    ASSERT_FALSE(no.ok);
    EXPECT_NE(no.failures.front().find("not closed"), std::string::npos) << no.failures.front();

    // A point that is not a vertex pushed out along a vertex's direction, far beyond it.
    std::vector<Point3d> moved = c.points;
    std::size_t inner = 0;
    while (std::binary_search(h.vertex_ids.begin(), h.vertex_ids.end(), inner))
      ++inner;
    const Point3d& v = h.vertices[0];
    moved[inner] = {v.x * 4, v.y * 4, v.z * 4};
    const CheckResult out = check_hull(moved, h);
    ASSERT_FALSE(out.ok);
    EXPECT_NE(out.failures.front().find("point " + std::to_string(inner) + " "), std::string::npos)
        << out.failures.front();
    EXPECT_NE(out.failures.front().find("is above face"), std::string::npos) << out.failures.front();
  }
}

// `cudahull hull --verify` runs the checker on wide input too, and says so in --stats.
TEST(WideChecker, CliVerifiesWideInput) {
  TempDir dir;
  const std::vector<WideCase> all = wide_cases();
  for (const std::size_t k : {std::size_t{2}, std::size_t{4}, std::size_t{6}}) {
    const WideCase& c = all[k];
    SCOPED_TRACE(c.name);
    std::FILE* f = std::fopen((dir / "w.xyz").c_str(), "w");
    ASSERT_NE(f, nullptr);
    for (const Point3d& p : c.points)
      std::fprintf(f, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    std::fclose(f);
    const CliRun r = run_cli({"hull", (dir / "w.xyz").string(), "--backend", "cpu", "--verify", "--stats",
                              "-", "-o", (dir / "h.obj").string()});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_NE(r.err.find("verified exact"), std::string::npos) << describe(r);
    EXPECT_NE(r.out.find("\"verified\": true"), std::string::npos) << r.out;
    const CliRun chk = run_cli({"check", (dir / "w.xyz").string(), (dir / "h.obj").string()});
    EXPECT_EQ(chk.exit_code, 0) << describe(chk);
  }
}

}  // namespace
}  // namespace cudahull
