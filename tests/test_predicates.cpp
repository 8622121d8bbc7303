// Exact predicates (cudahull/predicates.hpp) against an independent exact reference
// (support/exact_reference.hpp).
#include "cudahull/predicates.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "support/exact_reference.hpp"

namespace cudahull {
namespace {

// The determinant in plain double arithmetic, the way a naive implementation would do it.
int naive_orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  double wx = d.x - a.x, wy = d.y - a.y, wz = d.z - a.z;
  double det = (uy * vz - uz * vy) * wx + (uz * vx - ux * vz) * wy + (ux * vy - uy * vx) * wz;
  return (det > 0) - (det < 0);
}

Vec3d vf(float x, float y, float z) {
  return {x, y, z};
}

// Every property orient3d must have on one query; returns the reference sign.
int check_orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  int s = ref_orient3d(a, b, c, d);
  EXPECT_EQ(orient3d(a, b, c, d), s) << "a=(" << a.x << "," << a.y << "," << a.z << ") b=(" << b.x << ","
                                     << b.y << "," << b.z << ") c=(" << c.x << "," << c.y << "," << c.z
                                     << ") d=(" << d.x << "," << d.y << "," << d.z << ")";
  // Even permutations keep the sign, odd ones flip it.
  EXPECT_EQ(orient3d(b, c, a, d), s);
  EXPECT_EQ(orient3d(d, c, b, a), s);
  EXPECT_EQ(orient3d(b, a, c, d), -s);
  EXPECT_EQ(orient3d(a, b, d, c), -s);
  EXPECT_EQ(orient3d(d, b, c, a), -s);
  return s;
}

// ---------------------------------------------------------------------------------------------------------
// orient3d

TEST(Orient3d, SignConvention) {
  Vec3d a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_EQ(orient3d(a, b, c, Vec3d{0, 0, 1}), 1);
  EXPECT_EQ(orient3d(a, b, c, Vec3d{0, 0, -1}), -1);
  EXPECT_EQ(orient3d(a, c, b, Vec3d{0, 0, 1}), -1);
  EXPECT_EQ(orient3d(a, b, c, Vec3d{5, -7, 0}), 0);
  EXPECT_GT(orient3d_fast(a, b, c, Vec3d{0, 0, 1}), 0.0);
  EXPECT_EQ(orient3d_fast(a, b, c, Vec3d{0, 0, 2}), 2.0);  // det[b-a, c-a, d-a] exactly
  EXPECT_LT(orient3d_fast(a, b, c, Vec3d{0, 0, -1}), 0.0);
  EXPECT_EQ(ref_orient3d(a, b, c, Vec3d{0, 0, 1}), 1);  // the reference agrees on the convention
}

TEST(Orient3d, DegenerateInputsGiveZero) {
  Vec3d a{1.5, -2, 3}, b{4, 0.25, -1}, c{-3, 2, 7};
  EXPECT_EQ(orient3d(a, a, a, a), 0);
  EXPECT_EQ(orient3d(a, b, c, a), 0);
  EXPECT_EQ(orient3d(a, b, c, b), 0);
  EXPECT_EQ(orient3d(a, a, b, c), 0);
  EXPECT_EQ(orient3d(a, b, Vec3d{a.x + 2 * (b.x - a.x), a.y + 2 * (b.y - a.y), a.z + 2 * (b.z - a.z)}, c), 0);
}

// Exactly coplanar float points (parallelogram d = b + c - a on an integer lattice, scaled by a power of
// two and translated) where the naive double determinant is often nonzero.
TEST(Orient3d, ExactlyCoplanarWhereNaiveDoubleFails) {
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<int> coord(-(1 << 21), (1 << 21));
  std::uniform_int_distribution<int> scale(-60, 60);
  int naive_wrong = 0;
  const int kCases = 20000;
  for (int i = 0; i < kCases; ++i) {
    int k = scale(rng);
    auto p = [&] { return std::array<int, 3>{coord(rng), coord(rng), coord(rng)}; };
    auto a = p(), b = p(), c = p();
    auto mk = [&](int x, int y, int z) {
      return vf(std::ldexp(float(x), k), std::ldexp(float(y), k), std::ldexp(float(z), k));
    };
    Vec3d va = mk(a[0], a[1], a[2]), vb = mk(b[0], b[1], b[2]), vc = mk(c[0], c[1], c[2]);
    Vec3d vd = mk(b[0] + c[0] - a[0], b[1] + c[1] - a[1], b[2] + c[2] - a[2]);  // |.| < 2^23: exact float
    ASSERT_EQ(check_orient3d(va, vb, vc, vd), 0);
    naive_wrong += naive_orient3d(va, vb, vc, vd) != 0;
  }
  EXPECT_GT(naive_wrong, kCases / 20) << "the test set should defeat naive double evaluation";
}

TEST(Orient3d, CoplanarConstructions) {
  // Identical z.
  EXPECT_EQ(orient3d(vf(0.1f, 0.7f, 3.3f), vf(-5e6f, 2.f, 3.3f), vf(1e-7f, 9e5f, 3.3f), vf(7.f, 7.f, 3.3f)),
            0);
  // On x + y + z = 2^20 with small integers scaled by powers of two.
  std::mt19937 rng(2);
  std::uniform_int_distribution<int> small(-1000, 1000);
  for (int i = 0; i < 2000; ++i) {
    auto p = [&] {
      float x = std::ldexp(float(small(rng)), -3), y = std::ldexp(float(small(rng)), 5);
      return vf(x, y, 1048576.f - x - y);  // exact: all terms are multiples of 2^-3 below 2^21
    };
    Vec3d a = p(), b = p(), c = p(), d = p();
    ASSERT_EQ(check_orient3d(a, b, c, d), 0);
    // One ulp off the plane is no longer coplanar (unless a, b, c are degenerate).
    Vec3d e{d.x, d.y, ulp_step(float(d.z), 1)};
    check_orient3d(a, b, c, e);
  }
  // Collinear a, b, c: every d is coplanar with them.
  Vec3d a = vf(1.25f, -3.5f, 1e3f), b = vf(9.75f, 6.5f, -2e3f);
  for (double t : {-4.0, -0.5, 0.25, 0.5, 1.0, 2.0, 1024.0}) {
    Vec3d c{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
    ASSERT_EQ(float(c.x), c.x);
    EXPECT_EQ(check_orient3d(a, b, c, vf(123.f, -77.f, 5e-3f)), 0);
  }
}

// Shewchuk-style: the query point is one ulp away from an exactly coplanar one, where the filter cannot
// decide and the exact stage must.
TEST(Orient3d, UlpPerturbationsNeedExactStage) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> coord(-(1 << 20), (1 << 20));
  std::uniform_int_distribution<int> steps(-3, 3), axis(0, 2);
  reset_predicate_stats();
  int positive = 0, negative = 0;
  for (int i = 0; i < 5000; ++i) {
    auto a = std::array<float, 3>{float(coord(rng)), float(coord(rng)), float(coord(rng))};
    auto b = std::array<float, 3>{float(coord(rng)), float(coord(rng)), float(coord(rng))};
    auto c = std::array<float, 3>{float(coord(rng)), float(coord(rng)), float(coord(rng))};
    std::array<float, 3> d{b[0] + c[0] - a[0], b[1] + c[1] - a[1], b[2] + c[2] - a[2]};
    int ax = axis(rng);
    d[ax] = ulp_step(d[ax], steps(rng));
    // Translate far away: differences stay exact, but the magnitudes defeat the filter even more.
    const float kOffset = 1 << 23;
    auto v = [&](const std::array<float, 3>& p) { return vf(p[0] / 64, p[1] / 64 + kOffset, p[2] / 64); };
    int s = check_orient3d(v(a), v(b), v(c), v(d));
    positive += s > 0;
    negative += s < 0;
  }
  EXPECT_GT(positive, 500);
  EXPECT_GT(negative, 500);
  PredicateStats stats = predicate_stats();
  EXPECT_EQ(stats.orient3d_calls, 5000u * 6u);
  EXPECT_GT(stats.orient3d_exact, 4000u);  // the coplanar ones and many perturbed ones need the exact stage
}

// 10^5 random near-degenerate float queries of several kinds against the big-integer reference.
TEST(Orient3d, RandomNearDegenerateFloatAgainstReference) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> unit(-1, 1), param(-3, 3);
  std::uniform_int_distribution<int> scale(-40, 40), kind(0, 3), ulps(-2, 2), axis(0, 2), bits(1, 24);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 100000; ++i) {
    double sc = std::ldexp(1.0, scale(rng));
    auto rp = [&] { return std::array<double, 3>{unit(rng) * sc, unit(rng) * sc, unit(rng) * sc}; };
    auto a = rp(), b = rp(), c = rp();
    std::array<double, 3> d{};
    switch (kind(rng)) {
      case 0: {  // near the plane: rounding to float moves it off (or not)
        double s = param(rng), t = param(rng);
        for (int j = 0; j < 3; ++j)
          d[j] = a[j] + s * (b[j] - a[j]) + t * (c[j] - a[j]);
        break;
      }
      case 1: {  // near a line through a and b (a, b, c nearly collinear), d anywhere
        double s = param(rng);
        for (int j = 0; j < 3; ++j)
          c[j] = a[j] + s * (b[j] - a[j]);
        d = rp();
        break;
      }
      case 2: {  // coordinates with few significant bits: many exact coplanarities
        int nb = bits(rng);
        auto q = [&](std::array<double, 3>& p) {
          for (double& x : p)
            x = std::ldexp(std::round(std::ldexp(x / sc, nb)), -nb) * sc;
        };
        q(a), q(b), q(c);
        double s = std::round(param(rng) * 4) / 4, t = std::round(param(rng) * 4) / 4;
        for (int j = 0; j < 3; ++j)
          d[j] = a[j] + s * (b[j] - a[j]) + t * (c[j] - a[j]);
        break;
      }
      default: {  // a far translation of a tiny configuration
        double off = std::ldexp(unit(rng), 20);
        for (int j = 0; j < 3; ++j) {
          a[j] = off + a[j] * 1e-6;
          b[j] = off + b[j] * 1e-6;
          c[j] = off + c[j] * 1e-6;
        }
        double s = param(rng), t = param(rng);
        for (int j = 0; j < 3; ++j)
          d[j] = a[j] + s * (b[j] - a[j]) + t * (c[j] - a[j]);
        break;
      }
    }
    auto f = [](const std::array<double, 3>& p) { return vf(float(p[0]), float(p[1]), float(p[2])); };
    Vec3d fd = f(d);
    int u = ulps(rng);
    if (u != 0) {
      double* coord = axis(rng) == 0 ? &fd.x : (axis(rng) == 1 ? &fd.y : &fd.z);
      *coord = ulp_step(float(*coord), u);
    }
    Vec3d fa = f(a), fb = f(b), fc = f(c);
    int s = ref_orient3d(fa, fb, fc, fd);
    ASSERT_EQ(orient3d(fa, fb, fc, fd), s) << "case " << i;
    ASSERT_EQ(orient3d(fb, fa, fc, fd), -s) << "case " << i;
    ++counts[s + 1];
  }
  // Sanity of the generator: all three outcomes well represented.
  EXPECT_GT(counts[0], 10000);
  EXPECT_GT(counts[1], 10000);
  EXPECT_GT(counts[2], 10000);
}

TEST(Orient3d, ExtremeMagnitudes) {
  const float kMax = std::numeric_limits<float>::max();
  const float kDenormMin = std::numeric_limits<float>::denorm_min();  // 1.4e-45
  const float kNormMin = std::numeric_limits<float>::min();
  std::vector<float> pool = {
      0.f,    kMax,    -kMax, kDenormMin, -kDenormMin, 2 * kDenormMin,   kNormMin,           1e30f, -1e30f,
      1e-30f, -1e-30f, 1.f,   -1.f,       3.f,         ulp_step(1.f, 1), ulp_step(kMax, -1), 1e38f, -3e-38f,
      7e-45f, 1e-40f};
  // Scaled copies of the canonical tetrahedron and of a coplanar configuration.
  for (float s : {kDenormMin, kNormMin, 1e-30f, 1e30f, 1e38f}) {
    EXPECT_EQ(check_orient3d(vf(0, 0, 0), vf(s, 0, 0), vf(0, s, 0), vf(0, 0, s)), 1) << s;
    EXPECT_EQ(check_orient3d(vf(0, 0, 0), vf(s, 0, 0), vf(0, s, 0), vf(s, s, 0)), 0) << s;
    EXPECT_EQ(check_orient3d(vf(s, s, s), vf(-s, s, -s), vf(s, -s, -s), vf(-s, -s, s)), 1) << s;
  }
  EXPECT_EQ(check_orient3d(vf(-kMax, -kMax, -kMax), vf(kMax, -kMax, -kMax), vf(-kMax, kMax, -kMax),
                           vf(kDenormMin, kDenormMin, kMax)),
            1);
  EXPECT_EQ(check_orient3d(vf(kDenormMin, 0, 0), vf(0, kDenormMin, 0), vf(0, 0, kDenormMin), vf(0, 0, 0)),
            -1);
  // Random mixtures drawn from the pool, many with huge cancellation.
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
  int nonzero = 0;
  for (int i = 0; i < 20000; ++i) {
    auto p = [&] { return vf(pool[pick(rng)], pool[pick(rng)], pool[pick(rng)]); };
    nonzero += check_orient3d(p(), p(), p(), p()) != 0;
  }
  EXPECT_GT(nonzero, 1000);
}

// Double (not float) inputs, including differences that are not exactly representable (the general exact
// path with two-component differences) and an engine-style double interior point.
TEST(Orient3d, DoubleInputs) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> scale(-60, 60), ulps(-2, 2);
  int zero = 0;
  for (int i = 0; i < 20000; ++i) {
    // Points on x + y + z = 0 with mixed magnitudes, where x + y is exact in double.
    auto p = [&] {
      for (;;) {
        double x = std::ldexp(std::round(std::ldexp(unit(rng), 20)), scale(rng));
        double y = std::ldexp(std::round(std::ldexp(unit(rng), 20)), scale(rng));
        double s = x + y;
        if (s - x == y && s - y == x) return Vec3d{x, y, -s};  // exact sum
      }
    };
    Vec3d a = p(), b = p(), c = p(), d = p();
    zero += check_orient3d(a, b, c, d) == 0;
    int u = ulps(rng);
    double z = d.z;
    for (int k = 0; k < std::abs(u); ++k)
      z = std::nextafter(z, u > 0 ? 1e300 : -1e300);
    check_orient3d(a, b, c, Vec3d{d.x, d.y, z});
  }
  EXPECT_EQ(zero, 20000);
  // Random doubles near a plane, wide exponent spread.
  for (int i = 0; i < 20000; ++i) {
    auto rp = [&] {
      return Vec3d{std::ldexp(unit(rng), scale(rng)), std::ldexp(unit(rng), scale(rng)),
                   std::ldexp(unit(rng), scale(rng))};
    };
    Vec3d a = rp(), b = rp(), c = rp();
    double s = unit(rng), t = unit(rng);
    Vec3d d{a.x + s * (b.x - a.x) + t * (c.x - a.x), a.y + s * (b.y - a.y) + t * (c.y - a.y),
            a.z + s * (b.z - a.z) + t * (c.z - a.z)};
    check_orient3d(a, b, c, d);
  }
  // A double centroid of float points against float faces.
  std::vector<Vec3d> pts;
  std::uniform_real_distribution<float> uf(-1, 1);
  for (int i = 0; i < 200; ++i)
    pts.push_back(vf(uf(rng), uf(rng), uf(rng)));
  Vec3d centroid{};
  for (const Vec3d& q : pts)
    centroid = {centroid.x + q.x / 3, centroid.y + q.y / 3, centroid.z + q.z / 3};
  for (std::size_t i = 0; i + 2 < pts.size(); ++i)
    check_orient3d(pts[i], pts[i + 1], pts[i + 2], centroid);
}

TEST(Orient3d, FastAgreesWhenFarFromDegenerate) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uf(-100, 100);
  for (int i = 0; i < 10000; ++i) {
    auto p = [&] { return vf(uf(rng), uf(rng), uf(rng)); };
    Vec3d a = p(), b = p(), c = p(), d = p();
    double fast = orient3d_fast(a, b, c, d);
    if (std::abs(fast) > 1e-6) {
      EXPECT_EQ((fast > 0) - (fast < 0), orient3d(a, b, c, d));
    }
  }
}

TEST(Orient3d, StatsCountAcrossThreads) {
  reset_predicate_stats();
  Vec3d a{0, 0, 0}, b{1, 0, 1}, c{0, 1, 1};
  auto work = [&] {
    for (int i = 0; i < 1000; ++i) {
      EXPECT_EQ(orient3d(a, b, c, Vec3d{1, 1, 3}), 1);  // filter decides
      EXPECT_EQ(orient3d(a, b, c, Vec3d{1, 1, 2}), 0);  // tilted coplanar: exact stage
      EXPECT_EQ(orient3d(Vec3d{0, 0, 5}, Vec3d{1, 0, 5}, Vec3d{0, 1, 5}, Vec3d{.5, .25, 5}),
                0);  // permanent 0
    }
  };
  std::thread t1(work), t2(work);
  t1.join();
  t2.join();
  work();  // this thread too
  PredicateStats stats = predicate_stats();
  EXPECT_EQ(stats.orient3d_calls, 9000u);
  EXPECT_EQ(stats.orient3d_exact, 3000u);
  reset_predicate_stats();
  EXPECT_EQ(predicate_stats().orient3d_calls, 0u);
  EXPECT_EQ(predicate_stats().orient3d_exact, 0u);
}

// ---------------------------------------------------------------------------------------------------------
// orient2d and collinear3d

TEST(Orient2d, SignConventionAndBasics) {
  EXPECT_EQ(orient2d(0, 0, 1, 0, 0, 1), 1);
  EXPECT_EQ(orient2d(0, 0, 0, 1, 1, 0), -1);
  EXPECT_EQ(orient2d(0, 0, 1, 1, 2, 2), 0);
  EXPECT_EQ(orient2d(3, 3, 3, 3, 3, 3), 0);
  EXPECT_EQ(orient2d(1, 2, 1, 2, 5, 7), 0);
}

// Shewchuk's classic failure of the naive 2D test: a tiny grid near (0.5, 0.5) against the line through
// (12, 12) and (24, 24).
TEST(Orient2d, ShewchukGridAgainstReference) {
  int naive_wrong = 0;
  for (int i = 0; i < 256; ++i) {
    for (int j = 0; j < 256; ++j) {
      double x = 0.5 + i * std::ldexp(1.0, -53), y = 0.5 + j * std::ldexp(1.0, -53);
      int s = ref_orient2d(x, y, 12, 12, 24, 24);
      ASSERT_EQ(orient2d(x, y, 12, 12, 24, 24), s) << i << " " << j;
      ASSERT_EQ(orient2d(12, 12, 24, 24, x, y), s);
      ASSERT_EQ(orient2d(24, 24, 12, 12, x, y), -s);
      double naive = (12 - x) * (24 - y) - (12 - y) * (24 - x);
      naive_wrong += ((naive > 0) - (naive < 0)) != s;
    }
  }
  EXPECT_GT(naive_wrong, 1000);
}

TEST(Orient2d, RandomNearDegenerateAgainstReference) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> scale(-100, 100), ulps(-2, 2);
  for (int i = 0; i < 50000; ++i) {
    double sc = std::ldexp(1.0, scale(rng));
    float ax = float(unit(rng) * sc), ay = float(unit(rng) * sc), bx = float(unit(rng) * sc),
          by = float(unit(rng) * sc);
    double t = std::round(unit(rng) * 64) / 16;
    float cx = ulp_step(float(ax + t * (double(bx) - ax)), ulps(rng));
    float cy = ulp_step(float(ay + t * (double(by) - ay)), ulps(rng));
    int s = ref_orient2d(ax, ay, bx, by, cx, cy);
    ASSERT_EQ(orient2d(ax, ay, bx, by, cx, cy), s) << i;
    ASSERT_EQ(orient2d(bx, by, cx, cy, ax, ay), s) << i;
    ASSERT_EQ(orient2d(bx, by, ax, ay, cx, cy), -s) << i;
    // Double inputs with inexact differences.
    double dx = ax + std::ldexp(unit(rng), scale(rng)), dy = ay + std::ldexp(unit(rng), scale(rng));
    ASSERT_EQ(orient2d(dx, dy, bx, by, cx, cy), ref_orient2d(dx, dy, bx, by, cx, cy)) << i;
  }
}

TEST(Collinear3d, ExactConstructions) {
  Vec3d a = vf(1.5f, -2.25f, 1e6f), b = vf(-7.f, 3.75f, -3e5f);
  EXPECT_TRUE(collinear3d(a, a, a));
  EXPECT_TRUE(collinear3d(a, a, b));
  EXPECT_TRUE(collinear3d(a, b, b));
  for (double t : {-3.0, -0.125, 0.0, 0.5, 0.75, 1.0, 4.0}) {
    Vec3d c{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
    ASSERT_EQ(float(c.x), c.x);
    ASSERT_EQ(float(c.y), c.y);
    ASSERT_EQ(float(c.z), c.z);
    EXPECT_TRUE(collinear3d(a, b, c)) << t;
    EXPECT_TRUE(collinear3d(c, a, b)) << t;
    for (int axis = 0; axis < 3; ++axis) {
      Vec3d e = c;
      double* coord = axis == 0 ? &e.x : (axis == 1 ? &e.y : &e.z);
      *coord = ulp_step(float(*coord), 1);
      EXPECT_FALSE(collinear3d(a, b, e)) << t << " axis " << axis;
      EXPECT_EQ(collinear3d(a, b, e), ref_collinear3d(a, b, e));
    }
  }
  // Collinear in two projections but not the third.
  EXPECT_FALSE(collinear3d(Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{2, 0, 1e-30}));
  EXPECT_TRUE(collinear3d(Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{2e30, 0, 0}));
}

TEST(Collinear3d, RandomAgainstReference) {
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<int> coord(-(1 << 20), 1 << 20), ulps(-1, 1), scale(-30, 30), tq(-16, 16);
  int collinear = 0;
  for (int i = 0; i < 20000; ++i) {
    int k = scale(rng);
    auto p = [&] {
      return std::array<float, 3>{std::ldexp(float(coord(rng)), k), std::ldexp(float(coord(rng)), k),
                                  std::ldexp(float(coord(rng)), k)};
    };
    auto a = p(), b = p();
    double t = tq(rng) / 8.0;
    Vec3d va = vf(a[0], a[1], a[2]), vb = vf(b[0], b[1], b[2]);
    Vec3d vc = vf(ulp_step(float(a[0] + t * (double(b[0]) - a[0])), ulps(rng)),
                  ulp_step(float(a[1] + t * (double(b[1]) - a[1])), ulps(rng)),
                  ulp_step(float(a[2] + t * (double(b[2]) - a[2])), ulps(rng)));
    bool r = ref_collinear3d(va, vb, vc);
    ASSERT_EQ(collinear3d(va, vb, vc), r) << i;
    ASSERT_EQ(collinear3d(vc, vb, va), r) << i;
    collinear += r;
  }
  EXPECT_GT(collinear, 400);  // about 1/27 of the cases are not perturbed
  EXPECT_LT(collinear, 19000);
}

}  // namespace
}  // namespace cudahull
