// Synthetic distributions: determinism, counts, and the geometric promise of each distribution.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "cudahull/generators.hpp"

namespace cudahull {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const Distribution kAll[] = {Distribution::kCube,  Distribution::kBall,       Distribution::kSphere,
                             Distribution::kGauss, Distribution::kParaboloid, Distribution::kCylinder,
                             Distribution::kGrid};

double norm(const Point3& p) {
  return std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
}

class EveryDistribution : public ::testing::TestWithParam<Distribution> {};

TEST_P(EveryDistribution, ExactCountsAndFiniteCoordinates) {
  for (std::size_t n : {0u, 1u, 2u, 3u, 7u, 1000u, 4097u}) {
    const auto p = generate_points(GetParam(), n, 1);
    ASSERT_EQ(p.size(), n);
    for (const Point3& q : p) {
      ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
    }
  }
}

TEST_P(EveryDistribution, SameSeedSamePoints) {
  EXPECT_EQ(generate_points(GetParam(), 5000, 42), generate_points(GetParam(), 5000, 42));
}

TEST_P(EveryDistribution, DifferentSeedDifferentPoints) {
  // The integer lattice has nothing random in it: the same for every seed.
  if (GetParam() == Distribution::kGrid) {
    EXPECT_EQ(generate_points(GetParam(), 100, 1), generate_points(GetParam(), 100, 2));
  } else {
    EXPECT_NE(generate_points(GetParam(), 100, 1), generate_points(GetParam(), 100, 2));
  }
}

TEST_P(EveryDistribution, NameRoundTrips) {
  EXPECT_EQ(distribution_from_name(distribution_name(GetParam())), GetParam());
}

INSTANTIATE_TEST_SUITE_P(All, EveryDistribution, ::testing::ValuesIn(kAll),
                         [](const auto& info) { return distribution_name(info.param); });

TEST(Generators, PinnedOutputGuardsDeterminismAcrossVersions) {
  // A change to the generator, the seeding or the transforms changes every stored benchmark input; this
  // fails then.  The cube uses only exact arithmetic: pinned bit for bit.
  const auto cube = generate_points(Distribution::kCube, 2, 42);
  EXPECT_EQ(cube[0], (Point3{-0x1.aa1fd4p-1f, -0x1.efb268p-3f, 0x1.70ba9ap-2f}));
  // The normals go through log/sin/cos, which C libraries may round differently in the last bit.
  const auto gauss = generate_points(Distribution::kGauss, 2, 42);
  EXPECT_NEAR(gauss[0].x, -0.303263068, 1e-6);
  EXPECT_NEAR(gauss[0].y, 0.288461745, 1e-6);
  EXPECT_NEAR(gauss[0].z, 1.34381175, 1e-6);
}

TEST(Generators, CubeFillsTheCube) {
  const auto p = generate_points(Distribution::kCube, 100000, 3);
  float lo = 2, hi = -2;
  for (const Point3& q : p) {
    for (float v : {q.x, q.y, q.z}) {
      ASSERT_GE(v, -1.0f);
      ASSERT_LE(v, 1.0f);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  EXPECT_LT(lo, -0.999f);
  EXPECT_GT(hi, 0.999f);
}

TEST(Generators, BallIsInsideTheUnitBallAndFillsIt) {
  const auto p = generate_points(Distribution::kBall, 100000, 4);
  double outer = 0;
  std::size_t inner_half = 0;
  for (const Point3& q : p) {
    const double r = norm(q);
    ASSERT_LE(r, 1.0 + 1e-7);  // float rounding of the coordinates only
    outer = std::max(outer, r);
    if (r < 0.5) ++inner_half;
  }
  EXPECT_GT(outer, 0.99);
  // Uniform in volume: an eighth of the points lie within radius 1/2.
  EXPECT_NEAR(double(inner_half) / p.size(), 0.125, 0.01);
}

TEST(Generators, SphereIsOnTheUnitSphere) {
  const auto p = generate_points(Distribution::kSphere, 100000, 5);
  double mean[3] = {0, 0, 0};
  for (const Point3& q : p) {
    ASSERT_LT(std::fabs(norm(q) - 1.0), 1e-6);
    mean[0] += q.x;
    mean[1] += q.y;
    mean[2] += q.z;
  }
  // Uniform directions: the mean is near the centre.
  for (double m : mean)
    EXPECT_NEAR(m / p.size(), 0.0, 0.01);
}

TEST(Generators, GaussHasZeroMeanUnitVariance) {
  const auto p = generate_points(Distribution::kGauss, 200000, 6);
  for (int axis = 0; axis < 3; ++axis) {
    double sum = 0, sum2 = 0;
    for (const Point3& q : p) {
      const double v = axis == 0 ? q.x : axis == 1 ? q.y : q.z;
      sum += v;
      sum2 += v * v;
    }
    const double mean = sum / p.size();
    EXPECT_NEAR(mean, 0.0, 0.01) << "axis " << axis;
    EXPECT_NEAR(sum2 / p.size() - mean * mean, 1.0, 0.02) << "axis " << axis;
  }
}

TEST(Generators, ParaboloidLiesOnTheParaboloidOverTheDisc) {
  const auto p = generate_points(Distribution::kParaboloid, 100000, 7);
  for (const Point3& q : p) {
    const double r2 = double(q.x) * q.x + double(q.y) * q.y;
    ASSERT_LE(r2, 1.0);
    // z is x^2 + y^2 of the stored x and y, rounded once to float.
    ASSERT_EQ(q.z, static_cast<float>(r2));
  }
}

TEST(Generators, CylinderIsRingsOfPointsOnTheSurface) {
  const std::size_t n = 1000;
  const auto p = generate_points(Distribution::kCylinder, n, 8);
  std::set<float> heights;
  std::set<std::pair<float, float>> columns;
  for (const Point3& q : p) {
    ASSERT_NEAR(std::hypot(double(q.x), double(q.y)), 1.0, 1e-6);
    ASSERT_GE(q.z, -1.0f);
    ASSERT_LE(q.z, 1.0f);
    heights.insert(q.z);
    columns.insert({q.x, q.y});
  }
  // Degenerate by design: few distinct heights (coplanar rings) and few distinct (x, y) (collinear columns).
  EXPECT_GE(heights.size(), 2u);
  EXPECT_LE(heights.size() * columns.size(), 2 * n);
  EXPECT_LT(columns.size(), n / 10);
}

TEST(Generators, GridIsTheFirstNPointsOfAnIntegerLattice) {
  for (std::size_t n : {1u, 8u, 27u, 28u, 1000u, 1001u}) {
    const auto p = generate_points(Distribution::kGrid, n, 9);
    std::size_t side = 1;
    while (side * side * side < n)
      ++side;
    std::set<std::tuple<float, float, float>> seen;
    for (std::size_t i = 0; i < n; ++i) {
      const Point3& q = p[i];
      // x fastest, then y, then z.
      ASSERT_EQ(q, (Point3{float(i % side), float((i / side) % side), float(i / (side * side))}))
          << n << " " << i;
      seen.insert({q.x, q.y, q.z});
    }
    EXPECT_EQ(seen.size(), n);
  }
  const auto g = generate_points(Distribution::kGrid, 28, 0);
  EXPECT_EQ(g[4], (Point3{0, 1, 0}));  // side 4 for 28 points
  EXPECT_EQ(g[27], (Point3{3, 2, 1}));
}

TEST(Names, KnownAndUnknown) {
  EXPECT_THAT(distribution_names(),
              ElementsAre("cube", "ball", "sphere", "gauss", "paraboloid", "cylinder", "grid"));
  EXPECT_EQ(distribution_from_name("paraboloid"), Distribution::kParaboloid);
  try {
    distribution_from_name("torus");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("'torus'"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("cube, ball, sphere, gauss, paraboloid, cylinder, grid"));
  }
  EXPECT_THROW(distribution_from_name("Cube"), std::invalid_argument);
  EXPECT_THROW(distribution_from_name(""), std::invalid_argument);
}

}  // namespace
}  // namespace cudahull
