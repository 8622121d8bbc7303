// exact_hull_any (exact_hull.hpp) on every finite double: subnormal offsets, coordinates ~1e300, magnitudes
// from 1e-300 to 1e300 in one input, lower-dimensional wide input, against the GMP rationals' brute force
// (support/rational_oracle.hpp); in the fast exact range it is exact_hull.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/wide_predicates.hpp"
#include "support/rational_oracle.hpp"
#include "support/wide_inputs.hpp"

namespace cudahull {
namespace {

std::vector<Point3d> unit_cube() {
  std::vector<Point3d> p;
  for (int i = 0; i < 8; ++i)
    p.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  return p;
}

// ---------------------------------------------------------------------------------------------------------
// The case refused before: a unit cube with subnormal offsets.
TEST(ExactHullAny, CubeWithSubnormalOffsets) {
  std::vector<Point3d> p = unit_cube();
  const double t = 1e-310;            // subnormal
  p.push_back({0.5, 0.5, t});         // 8: just inside, above the bottom face: not a vertex
  p.push_back({0.5, 0.5, 0});         // 9: on the bottom face: not a vertex
  p.push_back({t, t, 0});             // 10: on the bottom face by corner 0: not a vertex
  p.push_back({0.5, 0.5, -t});        // 11: just below the bottom face: a vertex
  p.push_back({0.25, 0.5, up(1.0)});  // 12: one ulp above the top face: a vertex
  p.push_back({0.75, -t, 0.25});      // 13: just outside the face y = 0: a vertex
  p.push_back({-5e-324, 0.5, 0.5});   // 14: the least subnormal outside the face x = 0: a vertex
  p.push_back({1, 1, -0.0});          // 15: a copy of corner 3 (-0 == +0): not a vertex
  p.push_back({0, 0, -4e-320});       // 16: below corner 0, which is then inside the segment from 16 to
                                      //     corner 4: corner 0 is no vertex any more, 16 is
  const HullMeshd h = exact_hull_any(p);
  EXPECT_EQ(h.dimension, 3);
  EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{1, 2, 3, 4, 5, 6, 7, 11, 12, 13, 14, 16}));
  expect_matches_oracle(p, h, "cube with subnormal offsets");
}

TEST(ExactHullAny, BentFaceWithSubnormals) {
  // The top face of the cube bent by lifting corner 7 one ulp: its upper surface is the flat triangle
  // 4, 5, 6 at z = 1 and the triangle 5, 7, 6 rising to 7.  Subnormal coordinates elsewhere force the wide
  // predicates.
  std::vector<Point3d> p = unit_cube();
  p[7].z = up(1.0);
  p.push_back({0.5, 0.5, 1});          // 8: on the diagonal 5-6: on the hull, not a vertex
  p.push_back({0.75, 0.75, up(1.0)});  // 9: above the triangle 5, 7, 6 (z = 1 + ulp/2 there): a vertex
  p.push_back({0.75, 0.75, 1});        // 10: below that triangle: inside
  p.push_back({1e-300, 1e-300, 1});    // 11: on the flat triangle by corner 4: not a vertex
  p.push_back({0.5, 0.5, 1e-320});     // 12: inside, by the bottom face
  p.push_back({1e-320, 0.5, 0.5});     // 13: inside, by the face x = 0
  const HullMeshd h = exact_hull_any(p);
  EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{0, 1, 2, 3, 4, 5, 6, 7, 9}));
  expect_matches_oracle(p, h, "bent top face");
}

// Products of two or three tiny differences underflow in double (the fast predicates would see the
// tetrahedron q1, q2, q3, q5 below as flat): a cluster of size 2^-400 beyond corner 0 of the unit cube,
// once with magnitudes one scale fits (2^-400..1), once with a subnormal point too (the wide predicates).
TEST(ExactHullAny, TinyClusterBeyondACorner) {
  for (const bool with_subnormal : {false, true}) {
    SCOPED_TRACE(with_subnormal ? "with a subnormal" : "scaled");
    const double s = 0x1p-400;
    std::vector<Point3d> p = unit_cube();
    p.push_back({-s, 0, 0});                // 8: a vertex (the least x)
    p.push_back({0, -s, 0});                // 9: a vertex
    p.push_back({0, 0, -s});                // 10: a vertex
    p.push_back({-s / 4, -s / 4, -s / 4});  // 11: x + y + z = -3s/4 > -s: inside
    p.push_back({-s / 2, -s / 2, -s / 2});  // 12: x + y + z = -3s/2 < -s: a vertex; corner 0 lies on the
                                            //     segment from 12 to corner 7, so it is not
    p.push_back({-s / 3, -s / 3, -s / 3});  // 13: x + y + z = -s (rounded): on or near the plane of 8-10
    if (with_subnormal) p.push_back({0.5, 1e-310, 0.5});  // 14: inside
    const HullMeshd h = exact_hull_any(p);
    EXPECT_EQ(h.dimension, 3);
    EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12}));
    expect_matches_oracle(p, h, "tiny cluster");
  }
}

// All coordinates ~1e300: one power of two brings the input into the fast range; the answer equals
// exact_hull of the unscaled points (the scaling changes no decision and no ranking).
TEST(ExactHullAny, HugeCoordinatesByExponentScaling) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> grid(-(1 << 20), 1 << 20);
  std::vector<Point3d> unit;
  for (int i = 0; i < 3000; ++i)
    unit.push_back({std::ldexp(grid(rng), -20), std::ldexp(grid(rng), -20), std::ldexp(grid(rng), -20)});
  const HullMeshd want = exact_hull(unit);
  for (const int e : {900, 1000, -1000, -1030}) {  // up to ~1e301 and down to subnormals (exact: 21 bits)
    std::vector<Point3d> scaled;
    for (const Point3d& q : unit)
      scaled.push_back({std::ldexp(q.x, e), std::ldexp(q.y, e), std::ldexp(q.z, e)});
    bool outside = false;
    for (const Point3d& q : scaled)
      outside =
          outside || !in_fast_exact_range(q.x) || !in_fast_exact_range(q.y) || !in_fast_exact_range(q.z);
    ASSERT_TRUE(outside);
    const HullMeshd got = exact_hull_any(scaled);
    EXPECT_EQ(got.dimension, want.dimension) << e;
    EXPECT_EQ(got.vertex_ids, want.vertex_ids) << e;
    EXPECT_EQ(got.triangles, want.triangles) << e;
    for (std::size_t v = 0; v < got.vertices.size(); ++v)
      ASSERT_EQ(got.vertices[v], scaled[got.vertex_ids[v]]) << e;
  }
}

TEST(ExactHullAny, HugeCoordinatesAgainstOracle) {
  std::mt19937_64 rng(12);
  for (int set = 0; set < 6; ++set) {
    std::vector<Point3d> p;
    for (int i = 0; i < 18; ++i) {
      auto c = [&] {
        return std::ldexp(static_cast<double>(rng() >> 11), 940 + static_cast<int>(rng() % 30));
      };
      p.push_back({(rng() & 1) ? c() : -c(), (rng() & 1) ? c() : -c(), (rng() & 1) ? c() : -c()});
    }
    expect_matches_oracle(p, exact_hull_any(p), "~1e300");
  }
}

// Magnitudes from 1e-300 to 1e300 in one input: no single scale fits, the wide predicates decide.
TEST(ExactHullAny, MixedMagnitudesAgainstOracle) {
  std::mt19937_64 rng(13);
  for (int set = 0; set < 40; ++set) {
    std::vector<Point3d> p;
    const int n = 6 + static_cast<int>(rng() % 14);
    for (int i = 0; i < n; ++i) {
      if (i > 0 &&
          rng() % 6 == 0) {  // a copy, or a copy with one coordinate replaced: duplicates and alignments
        Point3d q = p[rng() % p.size()];
        if (rng() & 1) (rng() & 1 ? q.x : q.z) = wide_value(rng);
        p.push_back(q);
      } else {
        p.push_back(wide_point(rng));
      }
    }
    expect_matches_oracle(p, exact_hull_any(p), "mixed magnitudes");
  }
}

TEST(ExactHullAny, LogUniformMagnitudesAgainstOracle) {
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> exponent(-300, 300);
  for (int set = 0; set < 12; ++set) {
    std::vector<Point3d> p;
    for (int i = 0; i < 20; ++i) {
      auto c = [&] { return ((rng() & 1) ? 1 : -1) * std::pow(10.0, exponent(rng)); };
      p.push_back({c(), c(), c()});
    }
    expect_matches_oracle(p, exact_hull_any(p), "log-uniform 1e-300..1e300");
  }
}

// A hull whose facets mix scales: a unit-scale box sheared by subnormal offsets, and a far apex.
TEST(ExactHullAny, MixedScalesWithStructure) {
  std::vector<Point3d> p;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      p.push_back({double(i), double(j), std::ldexp(double((i * 7 + j * 3) % 5), -1074)});  // a bumpy floor
  p.push_back({1.5, 1.5, 1e300});                                                           // a far apex
  p.push_back({1.5, 1.5, -1e-300});                                                         // below the floor
  expect_matches_oracle(p, exact_hull_any(p), "bumpy subnormal floor, far apex");
}

// Lower-dimensional inputs with wide coordinates.
TEST(ExactHullAny, FlatWideInput) {
  std::mt19937_64 rng(15);
  std::vector<Point3d> p;
  for (int i = 0; i < 16; ++i) {  // the plane z = 2^-1000 x, with y from 1e-300 to 1e300
    const double x = std::ldexp(static_cast<double>(static_cast<int>(rng() % 2049) - 1024), -10);
    const double y = wide_value(rng);
    p.push_back({x, y, std::ldexp(x, -1000)});
  }
  const HullMeshd h = exact_hull_any(p);
  EXPECT_EQ(h.dimension, 2);
  expect_matches_oracle(p, h, "tilted plane");

  std::vector<Point3d> q;  // the plane z = the least subnormal, x and y of all magnitudes
  for (int i = 0; i < 16; ++i)
    q.push_back({wide_value(rng), wide_value(rng), 5e-324});
  q.push_back({1e300, 1e-300, 5e-324});
  q.push_back({-1e300, 1e-300, 5e-324});
  q.push_back({0, -1e300, 5e-324});
  const HullMeshd hq = exact_hull_any(q);
  EXPECT_EQ(hq.dimension, 2);
  expect_matches_oracle(q, hq, "plane z = 5e-324");
}

TEST(ExactHullAny, CollinearAndCoincidentWideInput) {
  std::vector<Point3d> p;
  const Point3d dir{0x1p900, 0x1p-900, 0x1p-1070};
  for (const int t : {3, -7, 0, 12, -7, 5, 15, -16, 1})
    p.push_back({t * dir.x, t * dir.y, t * dir.z});  // exact: t * 2^-1070 is a multiple of 2^-1074
  const HullMeshd h = exact_hull_any(p);
  EXPECT_EQ(h.dimension, 1);
  EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{6, 7}));
  expect_matches_oracle(p, h, "collinear");

  const std::vector<Point3d> same = {{1e-310, -1e300, 0.0}, {1e-310, -1e300, -0.0}, {1e-310, -1e300, 0.0}};
  const HullMeshd hs = exact_hull_any(same);
  EXPECT_EQ(hs.dimension, 0);
  EXPECT_EQ(hs.vertex_ids, (std::vector<PointIndex>{0}));
  expect_matches_oracle(same, hs, "coincident");

  EXPECT_EQ(exact_hull_any({}).dimension, -1);
}

// In the fast range exact_hull_any is exact_hull; ids select points and skip the rest (even non-finite
// ones); a non-finite coordinate taking part throws; an id out of range throws as exact_hull's does.
TEST(ExactHullAny, ContractAndIds) {
  std::mt19937_64 rng(16);
  std::vector<Point3d> p;
  for (int i = 0; i < 200; ++i)
    p.push_back({std::ldexp(double(rng() >> 11), -53), std::ldexp(double(rng() >> 11), -53),
                 std::ldexp(double(rng() >> 11), -53)});
  const HullMeshd a = exact_hull_any(p), b = exact_hull(p);
  EXPECT_EQ(a.vertex_ids, b.vertex_ids);
  EXPECT_EQ(a.triangles, b.triangles);

  std::vector<Point3d> q = unit_cube();
  q.push_back({std::numeric_limits<double>::quiet_NaN(), 0, 0});  // 8: not taking part
  q.push_back({0.5, 0.5, -1e-310});                               // 9
  q.push_back({1e300, 0, 0});                                     // 10: not taking part
  const std::vector<PointIndex> ids = {9, 0, 1, 2, 3, 4, 5, 6, 7};
  const HullMeshd h = exact_hull_any(q, ids);
  EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{0, 1, 2, 3, 4, 5, 6, 7, 9}));
  EXPECT_THROW(exact_hull_any(q), std::invalid_argument);
  EXPECT_THROW(exact_hull_any(q, {0, 1, 2, 3, 11}), std::out_of_range);
  q[8].x = std::numeric_limits<double>::infinity();
  EXPECT_THROW(exact_hull_any(q, {0, 1, 2, 8}), std::invalid_argument);
}

// A larger input on the wide predicates (a ball plus interior points with subnormal coordinates): the same
// vertices as the ball alone, in reasonable time.
TEST(ExactHullAny, LargerInputOnWidePredicates) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> g;
  std::vector<Point3d> p;
  while (p.size() < 5000) {
    const double x = g(rng), y = g(rng), z = g(rng), r = std::sqrt(x * x + y * y + z * z);
    if (r > 0) p.push_back({x / r, y / r, z / r});
  }
  const HullMeshd ball = exact_hull(p);
  for (int i = 0; i < 50; ++i)
    p.push_back({std::ldexp(double(rng() % 1000), -1074), -std::ldexp(double(rng() % 1000), -1074),
                 (rng() & 1) ? 1e-310 : 0.25});
  const HullMeshd h = exact_hull_any(p);
  EXPECT_EQ(h.dimension, 3);
  EXPECT_EQ(h.vertex_ids, ball.vertex_ids);
}

}  // namespace
}  // namespace cudahull
