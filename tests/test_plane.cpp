// Facet planes (cudahull/plane.hpp) against an independent exact reference, on slivers and needles where the
// double-precision cross product cancels.
//
// Reference: the test points are built on a grid (every coordinate an integer multiple of 2^e, below 2^61 of
// them), so the cross product is an exact 128-bit integer in units of 2^2e.  Its correct rounding is the
// integer converted to double; the reference unit normal comes from it in long double.  Nothing is shared
// with the expansion arithmetic under test.  "Below the plane" is decided by orient3d.
#include "cudahull/plane.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "cudahull/detail/plane_impl.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull {
namespace {

using Int = __int128;
using Plane = std::array<double, 4>;

constexpr double kTolerance = 1e-13;  // the goal: n . p + d <= 1e-13 x scale for every point on or below
constexpr double kU = 0x1p-53;        // unit roundoff
// plane.cpp's error bounds: the unit normal within 5u of the exact one, n . p + d < 28u x scale.
constexpr double kNormalBound = 5 * kU, kHeightBound = 28 * kU;

// ---------------------------------------------------------------------------------------------------------
// The exact reference.

// Exponent of the lowest set bit of x (x != 0): x is an odd integer times 2^low_exponent(x).
int low_exponent(double x) {
  int e = 0;
  const double m = std::frexp(x, &e);
  const auto mantissa = static_cast<std::int64_t>(std::ldexp(std::fabs(m), 53));
  return e - 53 + std::countr_zero(static_cast<std::uint64_t>(mantissa));
}

struct ExactCross {
  int unit = 0;   // the components are integers times 2^unit
  Int n[3] = {};  // (b - a) x (c - a) / 2^unit, exactly
};

ExactCross exact_cross(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double coords[9] = {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z};
  int emin = std::numeric_limits<int>::max();
  for (double v : coords)
    if (v != 0) emin = std::min(emin, low_exponent(v));
  if (emin == std::numeric_limits<int>::max()) emin = 0;
  Int s[9];
  for (int i = 0; i < 9; ++i) {
    const double scaled = std::ldexp(coords[i], -emin);  // an integer, exactly
    // Below 2^61: differences below 2^62, products below 2^124, the minors below 2^125, all in an Int.
    EXPECT_LT(std::fabs(scaled), 0x1p61) << "test point off the reference's range";
    s[i] = static_cast<Int>(static_cast<std::int64_t>(scaled));
  }
  const Int ux = s[3] - s[0], uy = s[4] - s[1], uz = s[5] - s[2];
  const Int vx = s[6] - s[0], vy = s[7] - s[1], vz = s[8] - s[2];
  ExactCross r;
  r.unit = 2 * emin;
  r.n[0] = uy * vz - uz * vy;
  r.n[1] = uz * vx - ux * vz;
  r.n[2] = ux * vy - uy * vx;
  return r;
}

// The exact component rounded to the nearest double, ties to even (the conversion from a 128-bit integer
// rounds correctly; the scaling by a power of two is exact away from the subnormal range).
double rounded(const ExactCross& e, int i) {
  return std::ldexp(static_cast<double>(e.n[i]), e.unit);
}

std::array<long double, 3> reference_unit_normal(const ExactCross& e) {
  const long double x = static_cast<long double>(e.n[0]), y = static_cast<long double>(e.n[1]),
                    z = static_cast<long double>(e.n[2]);
  const long double length = std::sqrt(x * x + y * y + z * z);
  return {x / length, y / length, z / length};
}

// ---------------------------------------------------------------------------------------------------------
// Test geometry.

Vec3d add(const Vec3d& p, const Vec3d& q) {
  return {p.x + q.x, p.y + q.y, p.z + q.z};
}
Vec3d scaled(const Vec3d& p, double s) {
  return {p.x * s, p.y * s, p.z * s};
}

// The nearest multiple of 2^grid (exact as long as |x| < 2^(53 + grid)).
double snap(double x, int grid) {
  return std::ldexp(std::nearbyint(std::ldexp(x, -grid)), grid);
}
Vec3d snap(const Vec3d& p, int grid) {
  return {snap(p.x, grid), snap(p.y, grid), snap(p.z, grid)};
}

Vec3d random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  for (;;) {
    const Vec3d v{normal(rng), normal(rng), normal(rng)};
    const double length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (length > 1e-3) return scaled(v, 1 / length);
  }
}

double largest_magnitude(std::initializer_list<Vec3d> points) {
  double m = 0;
  for (const Vec3d& p : points)
    m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  return m;
}

// n . p + d as a user evaluates it, in double.
double height(const Plane& plane, const Vec3d& p) {
  return plane[0] * p.x + plane[1] * p.y + plane[2] * p.z + plane[3];
}

// What describe() used to do: cross(b - a, c - a) in double, normalised.
Plane naive_plane(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d u{b.x - a.x, b.y - a.y, b.z - a.z}, v{c.x - a.x, c.y - a.y, c.z - a.z};
  const Vec3d n{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
  const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  const Vec3d unit = scaled(n, 1 / length);
  const auto h = [&](const Vec3d& p) { return unit.x * p.x + unit.y * p.y + unit.z * p.z; };
  return {unit.x, unit.y, unit.z, -std::max({h(a), h(b), h(c)})};
}

struct Triangle {
  Vec3d a, b, c;
  int grid;  // every coordinate a multiple of 2^grid
};

// A needle: b and c `width` apart (at least one grid step), a `length` away along a random direction, the
// whole at a random place `offset` from the origin.  a is the far corner, as in the bug report.
Triangle needle(std::mt19937_64& rng, double offset, double length, double width, int grid) {
  const Vec3d centre = scaled(random_unit(rng), offset);
  const Vec3d b = snap(centre, grid);
  const Vec3d a = snap(add(b, scaled(random_unit(rng), length)), grid);
  Vec3d c;
  do {
    c = snap(add(b, scaled(random_unit(rng), width)), grid);
  } while (c.x == b.x && c.y == b.y && c.z == b.z);
  return {a, b, c, grid};
}

// The needles of the tests: ~1e-12 wide and 1 long near the origin (the bug report's case), and a few grid
// steps wide and 1e3 long at 1e6 from the origin (where the grid is 2^-32 ~ 2.3e-10).  Exactly collinear
// draws are skipped.
std::vector<Triangle> needles(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::vector<Triangle> out;
  while (static_cast<int>(out.size()) < count) {
    Triangle t;
    switch (out.size() % 4) {
      case 0:
        t = needle(rng, 0.5, 1.0, 1e-12, -52);
        break;
      case 1:
        t = needle(rng, 0.0, 1.0, 1e-12, -53);
        break;
      case 2:
        t = needle(rng, 1e6, 1e3, 3 * 0x1p-32, -32);
        break;
      default:
        t = needle(rng, 1e6, 1e3, 0x1p-32, -32);
        break;
    }
    if (collinear3d(t.a, t.b, t.c)) continue;
    out.push_back(t);
  }
  return out;
}

// A coordinate with a random number of significant bits (1..53) at a random magnitude, a multiple of 2^grid
// below 2^(grid + 60): a triangle of these has differences that double cannot hold (the general exact
// path), unlike the needles, whose corners are close.
double mixed_coordinate(std::mt19937_64& rng, int grid) {
  const int bits = std::uniform_int_distribution<int>(1, 53)(rng);
  const int shift = std::uniform_int_distribution<int>(0, 60 - bits)(rng);
  const std::uint64_t mantissa = (rng() >> (64 - bits)) | (std::uint64_t{1} << (bits - 1));
  const double v = std::ldexp(static_cast<double>(mantissa), grid + shift);
  return (rng() & 1) ? v : -v;
}

// The largest |n - N| and (n . p + d) / scale over points on or below the exact plane so far.
double worst_normal_error = 0, worst_height = 0;
int probes_on_plane = 0;  // probes that orient3d put exactly on the plane

// Checks one triangle's plane against the reference: unit normal, corners, and (when `probes` > 0) points
// near the plane classified by orient3d.  Returns the largest |n . p + d| / scale over the corners.
double check_triangle(const Triangle& t, std::mt19937_64& rng, int probes) {
  const Plane plane = plane_through(t.a, t.b, t.c);
  const ExactCross exact = exact_cross(t.a, t.b, t.c);
  const std::array<long double, 3> ref = reference_unit_normal(exact);
  long double error = 0;
  for (int i = 0; i < 3; ++i) {
    const long double e = static_cast<long double>(plane[i]) - ref[i];
    error += e * e;
  }
  error = std::sqrt(error);
  EXPECT_LE(static_cast<double>(error), kNormalBound);
  worst_normal_error = std::max(worst_normal_error, static_cast<double>(error));
  const double scale = largest_magnitude({t.a, t.b, t.c});
  double worst = 0, highest = -INFINITY;
  for (const Vec3d& p : {t.a, t.b, t.c}) {
    const double h = height(plane, p);
    EXPECT_LE(std::fabs(h), kTolerance * scale);
    EXPECT_LE(std::fabs(h), kHeightBound * scale);
    worst = std::max(worst, std::fabs(h) / scale);
    highest = std::max(highest, h);
  }
  // d is -max(n . corner), evaluated as height() evaluates it: the highest corner exactly on the plane.
  EXPECT_EQ(highest, 0.0);
  // Points spread over the plane's neighbourhood, as far from the needle across it as along it: a tilted
  // normal shows most there.  Snapped to the grid, they fall on either side (or on the plane).
  const Vec3d along{t.a.x - t.b.x, t.a.y - t.b.y, t.a.z - t.b.z},
      across{t.c.x - t.b.x, t.c.y - t.b.y, t.c.z - t.b.z};
  const double ratio = std::sqrt((along.x * along.x + along.y * along.y + along.z * along.z) /
                                 (across.x * across.x + across.y * across.y + across.z * across.z));
  std::uniform_real_distribution<double> s_dist(-1.0, 2.0), t_dist(-ratio, ratio);
  std::uniform_int_distribution<int> jitter(-2, 2);
  const auto probe = [&](const Vec3d& p) {
    const double probe_scale = std::max(scale, largest_magnitude({p}));
    const int side = orient3d(t.a, t.b, t.c, p);
    const double h = height(plane, p);
    if (side <= 0) {
      EXPECT_LE(h, kTolerance * probe_scale) << "on or below the exact plane";
      EXPECT_LE(h, kHeightBound * probe_scale) << "on or below the exact plane";
      worst_height = std::max(worst_height, h / probe_scale);
    }
    if (side >= 0) {
      EXPECT_GE(h, -kTolerance * probe_scale) << "on or above the exact plane";
    }
    if (side == 0) ++probes_on_plane;
  };
  for (int k = 0; k < probes; ++k) {
    Vec3d p = add(t.b, add(scaled(along, s_dist(rng)), scaled(across, t_dist(rng))));
    p = snap(p, t.grid);
    probe(add(p, {std::ldexp(jitter(rng), t.grid), std::ldexp(jitter(rng), t.grid),
                  std::ldexp(jitter(rng), t.grid)}));
  }
  // Integer combinations of the edges: on the plane wherever the arithmetic is exact.
  if (probes > 0) {
    for (int j = -2; j <= 3; ++j)
      for (int k = -2; k <= 3; ++k)
        probe(add(t.b, add(scaled(along, j), scaled(across, k))));
  }
  return worst;
}

bool extended_long_double() {
  return std::numeric_limits<long double>::digits >= 64;
}

// ---------------------------------------------------------------------------------------------------------

TEST(CrossRounded, EveryComponentIsTheExactValueRoundedToNearest) {
  std::mt19937_64 rng(11);
  int checked = 0;
  const auto check = [&](const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const std::array<double, 3> n = cross_rounded(a, b, c);
    const ExactCross exact = exact_cross(a, b, c);
    for (int i = 0; i < 3; ++i)
      ASSERT_EQ(std::bit_cast<std::uint64_t>(n[i]), std::bit_cast<std::uint64_t>(rounded(exact, i)))
          << "component " << i << ": " << n[i] << " vs " << rounded(exact, i);
    ++checked;
  };
  // Needles: exact differences, heavy cancellation in the products.
  for (const Triangle& t : needles(1, 400))
    check(t.a, t.b, t.c);
  // Mixed magnitudes: differences that double cannot hold (two-component expansions).
  for (int k = 0; k < 4000; ++k) {
    Vec3d p[3];
    for (Vec3d& q : p)
      q = {mixed_coordinate(rng, -40), mixed_coordinate(rng, -40), mixed_coordinate(rng, -40)};
    check(p[0], p[1], p[2]);
  }
  // Small integers whose minors need 55 to 57 bits: many fall exactly half way between two doubles.
  std::uniform_int_distribution<std::int64_t> coordinate(-(std::int64_t{1} << 27), std::int64_t{1} << 27);
  for (int k = 0; k < 4000; ++k) {
    Vec3d p[3];
    for (Vec3d& q : p)
      q = {static_cast<double>(coordinate(rng)), static_cast<double>(coordinate(rng)),
           static_cast<double>(coordinate(rng))};
    check(p[0], p[1], p[2]);
  }
  // Float32 input over a wide range of magnitudes.
  std::uniform_real_distribution<double> exponent(-10, 20);
  for (int k = 0; k < 4000; ++k) {
    Vec3d p[3];
    for (Vec3d& q : p) {
      const auto f = [&] {
        const float v = static_cast<float>(std::exp2(exponent(rng)));
        return static_cast<double>((rng() & 1) ? v : -v);
      };
      q = {f(), f(), f()};
    }
    check(p[0], p[1], p[2]);
  }
  // Near powers of two, a few ulps off: the exact minors are often a tie plus or minus a tiny remainder,
  // where a rounded partial sum (Compress's largest component alone, say) rounds the wrong way.
  std::uniform_int_distribution<int> power(-3, 3), ulps(-3, 3), ulp_scale(0, 2);
  for (int k = 0; k < 20000; ++k) {
    Vec3d p[3];
    for (Vec3d& q : p) {
      const auto f = [&] {
        const double s = std::ldexp(1.0, power(rng));
        const double v = s + ulps(rng) * std::ldexp(s, -52 + ulp_scale(rng));
        return (rng() & 1) ? v : -v;
      };
      q = {f(), f(), f()};
    }
    check(p[0], p[1], p[2]);
  }
  EXPECT_EQ(checked, 400 + 3 * 4000 + 20000);
}

// The host's double-double path (rounded_minor_fast()) against the exact expansion's rounding, on random
// doubles (where it answers: two-component differences, no cancellation) and on the cases above that it
// must leave to the exact path (ties, near-ties and cancellations: it may decline, never differ).
TEST(CrossRounded, FastMinorIsTheExactRoundingWhereItAnswers) {
  std::mt19937_64 rng(12);
  std::normal_distribution<double> normal;
  int answered = 0, declined = 0;
  const auto check = [&](double a, double b, double c, double d, double e, double f, double g, double h) {
    const detail::Pair uj = detail::exact_diff(a, b), vk = detail::exact_diff(c, d),
                       uk = detail::exact_diff(e, f), vj = detail::exact_diff(g, h);
    double fast = 0;
    if (!detail::rounded_minor_fast(uj, vk, uk, vj, &fast)) {
      ++declined;
      return;
    }
    ++answered;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(fast + 0.0),
              std::bit_cast<std::uint64_t>(detail::rounded_minor_exact(uj, vk, uk, vj)));
  };
  for (int k = 0; k < 200000; ++k)
    check(normal(rng), normal(rng), normal(rng), normal(rng), normal(rng), normal(rng), normal(rng),
          normal(rng));
  EXPECT_GT(answered, 199000);  // the fast path is the common one
  // Products that cancel to a few ulps, and near-ties: one ulp off the operands of an exact cancellation.
  std::uniform_int_distribution<int> ulps(-2, 2);
  for (int k = 0; k < 200000; ++k) {
    const double x = normal(rng), y = normal(rng);
    const auto off = [&](double v) { return v + ulps(rng) * std::ldexp(std::fabs(v), -52); };
    check(off(x), 0.0, off(y), 0.0, off(y), 0.0, off(x), 0.0);
  }
  EXPECT_GT(declined, 1000);  // the cancellations reached the exact path
}

TEST(CrossRounded, TiesGoToEven) {
  // (b - a) x (c - a) with a = 0: the z component is u.x v.y - u.y v.x.
  const Vec3d o{0, 0, 0};
  // 2^54 - (2^53 - 1) = 2^53 + 1, half way between 2^53 and 2^53 + 2: to 2^53 (even).
  EXPECT_EQ(cross_rounded(o, {0x1p27, 0x1p53 - 1, 0}, {1, 0x1p27, 0})[2], 0x1p53);
  // 2^54 - (2^53 - 3) = 2^53 + 3, half way between 2^53 + 2 and 2^53 + 4: to 2^53 + 4 (even).
  EXPECT_EQ(cross_rounded(o, {0x1p27, 0x1p53 - 3, 0}, {1, 0x1p27, 0})[2], 0x1p53 + 4);
  // Just past half way between 2^53 and 2^53 + 2: 2^54 + 4 - (2^53 + 4)(1 - 2^-53) = 2^53 + 1 + 2^-51, so
  // up to 2^53 + 2, where a tie would have gone down.
  EXPECT_EQ(cross_rounded(o, {0x1p27, 0x1p53 + 4, 0}, {1 - 0x1p-53, 0x1p27 + 0x1p-25, 0})[2], 0x1p53 + 2);
  // And past 2^53 + 3: 2^54 + 4 - (2^53 + 2)(1 - 2^-53) = 2^53 + 3 + 2^-52, up to 2^53 + 4.
  EXPECT_EQ(cross_rounded(o, {0x1p27, 0x1p53 + 2, 0}, {1 - 0x1p-53, 0x1p27 + 0x1p-25, 0})[2], 0x1p53 + 4);
  // Found by a search: the exact value lies just below half way between these two doubles, and Compress's
  // largest component alone rounds up, to 0x1.e400000000018p+4.
  EXPECT_EQ(cross_rounded({0x1p+3, 0x1.ffffffffffff8p-4, -0x1.0000000000001p-1},
                          {0x1.fffffffffffe8p+1, -0x1.000000000000cp-2, -0x1.ffffffffffffap-4},
                          {0x1.0000000000004p+1, -0x1p+3, -0x1.0000000000001p+3})[2],
            0x1.e400000000017p+4);
  // Negative: -(2^53 + 1) to -2^53.
  EXPECT_EQ(cross_rounded(o, {1, 0x1p27, 0}, {0x1p27, 0x1p53 - 1, 0})[2], -0x1p53);
}

TEST(PlaneThrough, NeedleNormalsMatchTheExactNormal) {
  if (!extended_long_double()) GTEST_SKIP() << "the reference needs an extended long double";
  std::mt19937_64 rng(2);
  double worst = 0;
  for (const Triangle& t : needles(3, 2000))
    worst = std::max(worst, check_triangle(t, rng, 0));
  std::printf("needles: largest |n . corner + d| / scale = %.3g, largest |n - N| = %.3g u\n", worst,
              worst_normal_error / kU);
}

TEST(PlaneThrough, PointsBelowTheExactPlaneStayBelow) {
  if (!extended_long_double()) GTEST_SKIP() << "the reference needs an extended long double";
  std::mt19937_64 rng(4);
  for (const Triangle& t : needles(5, 200))
    check_triangle(t, rng, 500);
  // Well-shaped and mixed-magnitude triangles too.
  for (int k = 0; k < 200; ++k) {
    Triangle t;
    t.grid = -40;
    for (Vec3d* q : {&t.a, &t.b, &t.c})
      *q = {mixed_coordinate(rng, -40), mixed_coordinate(rng, -40), mixed_coordinate(rng, -40)};
    if (collinear3d(t.a, t.b, t.c)) continue;
    check_triangle(t, rng, 0);
  }
  EXPECT_GT(probes_on_plane, 1000);
  std::printf("%d probes on the plane\n", probes_on_plane);
  std::printf("largest (n . p + d) / scale on or below: %.3g (%.3g u); largest |n - N| = %.3g u\n",
              worst_height, worst_height / kU, worst_normal_error / kU);
}

TEST(PlaneThrough, NaiveCrossProductFailsOnTheSameNeedles) {
  // Shows that the needles above do test something: the double-precision cross(b - a, c - a) puts a corner
  // far outside its own plane, by orders of magnitude more than the tolerance.
  double worst = 0;
  int failing = 0;
  for (const Triangle& t : needles(3, 2000)) {
    const Plane plane = naive_plane(t.a, t.b, t.c);
    const double scale = largest_magnitude({t.a, t.b, t.c});
    double h = 0;
    for (const Vec3d& p : {t.a, t.b, t.c})
      h = std::max(h, std::fabs(height(plane, p)) / scale);
    worst = std::max(worst, h);
    if (!(h <= kTolerance)) ++failing;  // NaN counts as failing
  }
  std::printf("naive cross product: largest |n . corner + d| / scale = %.3g, %d of 2000 needles over %g\n",
              worst, failing, kTolerance);
  EXPECT_GT(worst, 1e3 * kTolerance);
  EXPECT_GT(failing, 100);
}

TEST(PlaneThrough, OrientationAndCyclicOrder) {
  for (const Triangle& t : needles(7, 200)) {
    const Plane p = plane_through(t.a, t.b, t.c);
    // The exact cross product is the same for every cyclic order, so the rounded planes agree bit for bit.
    EXPECT_EQ(plane_through(t.b, t.c, t.a), p);
    EXPECT_EQ(plane_through(t.c, t.a, t.b), p);
    // The other order flips the normal exactly.
    const Plane q = plane_through(t.a, t.c, t.b);
    for (int i = 0; i < 3; ++i)
      EXPECT_EQ(q[i], -p[i]);
    // The normal points to the side orient3d calls above.
    const Vec3d above = add(t.b, {p[0], p[1], p[2]});
    const Vec3d below = add(t.b, {-p[0], -p[1], -p[2]});
    EXPECT_EQ(orient3d(t.a, t.b, t.c, above), 1);
    EXPECT_EQ(orient3d(t.a, t.b, t.c, below), -1);
    const double length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    EXPECT_NEAR(length, 1.0, 1e-15);
  }
}

TEST(PlaneThrough, AxisAlignedPlanesAreExact) {
  EXPECT_EQ(plane_through({0, 0, 5}, {1, 0, 5}, {0, 1, 5}), (Plane{0, 0, 1, -5}));
  EXPECT_EQ(plane_through({0, 0, 5}, {0, 1, 5}, {1, 0, 5}), (Plane{0, 0, -1, 5}));
  EXPECT_EQ(plane_through({3, 0, 0}, {3, 1, 0}, {3, 0, 1}), (Plane{1, 0, 0, -3}));
  EXPECT_EQ(plane_through({0, -2, 0}, {0, -2, 1}, {1, -2, 0}), (Plane{0, 1, 0, 2}));
  // No negative zeros in the normal.
  const Plane p = plane_through({0, 0, 5}, {1, 0, 5}, {0, 1, 5});
  EXPECT_FALSE(std::signbit(p[0]));
  EXPECT_FALSE(std::signbit(p[1]));
}

TEST(PlaneThrough, ScalingByPowersOfTwoChangesOnlyTheOffset) {
  // The normal does not depend on the scale: the same bits at 2^-300 and 2^300 as at 1.
  for (const Triangle& t : needles(8, 200)) {
    const Plane p = plane_through(t.a, t.b, t.c);
    for (double s : {0x1p-300, 0x1p300}) {
      const Plane q = plane_through(scaled(t.a, s), scaled(t.b, s), scaled(t.c, s));
      for (int i = 0; i < 3; ++i)
        EXPECT_EQ(q[i], p[i]);
      EXPECT_EQ(q[3], p[3] * s);
    }
  }
}

TEST(PlaneThrough, DegenerateTrianglesHaveNoPlane) {
  const Plane none{0, 0, 0, 0};
  const Vec3d a{1e6 + 0.25, -3e5, 7.5};
  EXPECT_EQ(plane_through(a, a, a), none);
  EXPECT_EQ(plane_through(a, a, {1, 2, 3}), none);
  EXPECT_EQ(plane_through({1, 2, 3}, a, a), none);
  EXPECT_EQ(plane_through({0, 0, 0}, {0, 0, 0}, {0, 0, 0}), none);
  // Exactly collinear, far from the origin.
  const Vec3d step{0x1p-30, 3 * 0x1p-30, -5 * 0x1p-30};
  for (double k : {-3.0, 1.0, 2.0, 1e3, 0x1p20}) {
    const Vec3d b = add(a, scaled(step, k)), c = add(a, scaled(step, 2 * k + 1));
    ASSERT_TRUE(collinear3d(a, b, c));
    EXPECT_EQ(plane_through(a, b, c), none);
    EXPECT_EQ(plane_through(c, a, b), none);
  }
  // Collinear through the origin at magnitudes 2^-20 to 2^40: differences double cannot hold.
  const Vec3d direction{1, 3, -5};
  for (const auto& [s, t, u] : {std::array<double, 3>{0x1p40, 0x1p-20, 0x1p10},
                                {-0x1p40, 0x1p-20, 3.0},
                                std::array<double, 3>{0x1p-900, 3 * 0x1p-900, 0x1p-899}}) {
    const Vec3d p = scaled(direction, s), q = scaled(direction, t), r = scaled(direction, u);
    ASSERT_TRUE(collinear3d(p, q, r));
    EXPECT_EQ(plane_through(p, q, r), none);
    EXPECT_EQ(cross_rounded(p, q, r), (std::array<double, 3>{0, 0, 0}));
  }
  // One grid step off the line: a plane after all.
  const Vec3d b = add(a, scaled(step, 1e3));
  Vec3d c = add(a, scaled(step, 2e3));
  c.x += std::ldexp(1.0, low_exponent(c.x));
  ASSERT_FALSE(collinear3d(a, b, c));
  const Plane p = plane_through(a, b, c);
  EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 1.0, 1e-15);
  for (const Vec3d& q : {a, b, c})
    EXPECT_LE(std::fabs(height(p, q)), kTolerance * 1e6);
}

}  // namespace
}  // namespace cudahull
