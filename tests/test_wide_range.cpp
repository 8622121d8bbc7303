// Every finite double: the wide predicates (wide_predicates.hpp) on coordinates outside the fast exact range
// 2^-250..2^250 (subnormals, ~1e300, both at once) against an independent oracle in GMP rationals
// (support/rational_oracle.hpp).  exact_hull_any on such input: test_exact_hull_any.cpp; the checker:
// test_wide_checker.cpp.
#include "cudahull/wide_predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "cudahull/predicates.hpp"
#include "support/rational_oracle.hpp"
#include "support/wide_inputs.hpp"

namespace cudahull {
namespace {

// ---------------------------------------------------------------------------------------------------------
TEST(FastExactRange, Bounds) {
  EXPECT_TRUE(in_fast_exact_range(0.0));
  EXPECT_TRUE(in_fast_exact_range(-0.0));
  EXPECT_TRUE(in_fast_exact_range(1.0));
  EXPECT_TRUE(in_fast_exact_range(0x1p-250));
  EXPECT_TRUE(in_fast_exact_range(-0x1p-250));
  EXPECT_TRUE(in_fast_exact_range(0x1p+250));
  EXPECT_TRUE(in_fast_exact_range(-0x1p+250));
  EXPECT_FALSE(in_fast_exact_range(down(0x1p-250)));
  EXPECT_FALSE(in_fast_exact_range(up(0x1p+250)));
  EXPECT_FALSE(in_fast_exact_range(5e-324));
  EXPECT_FALSE(in_fast_exact_range(1e300));
  EXPECT_FALSE(in_fast_exact_range(std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(in_fast_exact_range(std::numeric_limits<double>::quiet_NaN()));
}

// orient3d_wide, orient2d_wide, collinear3d_wide and the GMP stage alone against the rationals on random
// mixed-magnitude inputs, with exact degeneracies (a shared coordinate) and their one-ulp perturbations.
TEST(WidePredicates, Orient3dAgainstRationals) {
  std::mt19937_64 rng(20240611);
  int counts[3] = {0, 0, 0};
  for (int iter = 0; iter < 4000; ++iter) {
    Vec3d a = wide_vec(rng), b = wide_vec(rng), c = wide_vec(rng), d = wide_vec(rng);
    switch (iter % 4) {
      case 1:  // four points in a plane z = const: zero, then one ulp off it either way
        b.z = c.z = d.z = a.z;
        if (iter % 8 == 5) d.z = (rng() & 1) ? up(d.z) : down(d.z);
        break;
      case 2:  // shared coordinates in two axes
        c.x = a.x, d.x = b.x, c.y = b.y, d.y = a.y;
        break;
      case 3:  // a near-copy of a: d differs from a by one ulp in one coordinate
        d = a;
        if (rng() & 1) d.x = up(d.x);
        if (rng() & 1) d.y = down(d.y);
        if (rng() & 1) d.z = up(d.z);
        break;
      default:
        break;
    }
    const int want = orient3d_q(qvec(a), qvec(b), qvec(c), qvec(d));
    ++counts[want + 1];
    ASSERT_EQ(orient3d_wide(a, b, c, d), want) << iter;
    ASSERT_EQ(detail::orient3d_gmp(a, b, c, d), want) << iter;
    // The sign flips with an odd permutation.
    ASSERT_EQ(orient3d_wide(b, a, c, d), -want) << iter;
  }
  // Every sign is well represented.
  EXPECT_GT(counts[0], 400);
  EXPECT_GT(counts[1], 400);
  EXPECT_GT(counts[2], 400);
}

TEST(WidePredicates, Orient2dAndCollinearAgainstRationals) {
  std::mt19937_64 rng(77);
  int zeros = 0, collinear = 0;
  for (int iter = 0; iter < 4000; ++iter) {
    Vec3d a = wide_vec(rng), b = wide_vec(rng), c = wide_vec(rng);
    if (iter % 3 == 1) {  // collinear along an axis direction, maybe perturbed by one ulp
      b.y = a.y, b.z = a.z, c.y = a.y, c.z = a.z;
      if (iter % 6 == 4) c.z = up(c.z);
    } else if (iter % 3 == 2) {  // coincident pairs
      c = (rng() & 1) ? a : b;
    }
    const int want = orient2d_q(a.x, a.y, b.x, b.y, c.x, c.y);
    zeros += want == 0;
    ASSERT_EQ(orient2d_wide(a.x, a.y, b.x, b.y, c.x, c.y), want) << iter;
    ASSERT_EQ(detail::orient2d_gmp(a.x, a.y, b.x, b.y, c.x, c.y), want) << iter;
    const bool want_collinear = is_zero(cross(qvec(b) - qvec(a), qvec(c) - qvec(a)));
    collinear += want_collinear;
    ASSERT_EQ(collinear3d_wide(a, b, c), want_collinear) << iter;
    ASSERT_EQ(detail::collinear3d_gmp(a, b, c), want_collinear) << iter;
  }
  EXPECT_GT(zeros, 500);
  EXPECT_GT(collinear, 500);
}

// The GMP stage agrees with the fast predicates wherever those are exact.
TEST(WidePredicates, GmpStageMatchesFastInRange) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> small(-4, 4);
  for (int iter = 0; iter < 3000; ++iter) {
    auto v = [&] {
      // Small integers scaled by one of a few in-range powers: many zeros and exact degeneracies.
      const double s = std::ldexp(1.0, static_cast<int>(rng() % 200) - 100);
      return Vec3d{small(rng) * s, small(rng) * s, small(rng) * s};
    };
    const Vec3d a = v(), b = v(), c = v(), d = v();
    ASSERT_EQ(detail::orient3d_gmp(a, b, c, d), orient3d(a, b, c, d));
    ASSERT_EQ(detail::orient2d_gmp(a.x, a.y, b.x, b.y, c.x, c.y), orient2d(a.x, a.y, b.x, b.y, c.x, c.y));
    ASSERT_EQ(detail::collinear3d_gmp(a, b, c), collinear3d(a, b, c));
  }
}

// Extremes of the double range: the least subnormal, the largest finite double, both in one call.
TEST(WidePredicates, ExtremeValues) {
  const double tiny = 5e-324, huge = std::numeric_limits<double>::max();
  const Vec3d o{0, 0, 0}, x{huge, 0, 0}, y{0, huge, 0};
  EXPECT_EQ(orient3d_wide(o, x, y, {0, 0, tiny}), 1);
  EXPECT_EQ(orient3d_wide(o, x, y, {0, 0, -tiny}), -1);
  EXPECT_EQ(orient3d_wide(o, x, y, {huge, huge, 0}), 0);
  EXPECT_EQ(orient3d_wide(o, x, y, {-huge, tiny, -0.0}), 0);
  EXPECT_EQ(orient2d_wide(0, 0, huge, tiny, -huge, -tiny), 0);
  EXPECT_EQ(orient2d_wide(0, 0, huge, tiny, -huge, 0), 1);  // (huge*0 - tiny*(-huge)) > 0
  EXPECT_TRUE(collinear3d_wide({tiny, tiny, tiny}, {-huge, -huge, -huge}, {huge, huge, huge}));
  EXPECT_FALSE(collinear3d_wide({tiny, 0, tiny}, {-huge, -huge, -huge}, {huge, huge, huge}));
  // Differences that do not fit in a double: huge - (-huge) overflows, exact here.
  EXPECT_EQ(orient3d_wide({-huge, -huge, -huge}, {huge, -huge, -huge}, {-huge, huge, -huge}, {0, 0, huge}),
            1);
}

}  // namespace
}  // namespace cudahull
