// exact_hull: vertex sets against Qhull on random inputs, exact answers on degenerate inputs (grids, flat
// facets, duplicates, lower dimensions, extreme scales) and the shared models' known extreme counts.  Every
// result must also pass the independent checker.  Double coordinates: test_exact_hull_double.cpp.
#include "cudahull/exact_hull.hpp"
#include "support/point_sets.hpp"
#include "support/rng.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "cudahull/point_io.hpp"
#include "qhull_reference.hpp"
#include "support/exact_hull_checks.hpp"

namespace cudahull {
namespace {

using testing::integer_paraboloid;
using testing::lattice;
using testing::Rng;
std::vector<Point3> ball(std::size_t n, std::uint64_t seed) {
  return testing::dyadic_ball(n, seed);
}

std::vector<Point3> cube(std::size_t n, std::uint64_t seed) {
  Rng r(seed);
  std::vector<Point3> p(n);
  for (Point3& q : p)
    q = {r.unit(), r.unit(), r.unit()};
  return p;
}

std::vector<Point3> sphere(std::size_t n, std::uint64_t seed) {
  Rng r(seed);
  std::vector<Point3> p;
  while (p.size() < n) {
    double x = r.unit(), y = r.unit(), z = r.unit();
    const double l = std::sqrt(x * x + y * y + z * z);
    if (l > 0.1 && l <= 1) p.push_back({float(x / l), float(y / l), float(z / l)});
  }
  return p;
}

std::vector<PointIndex> qhull_vertices(const std::vector<Point3>& points) {
  return run_qhull(points, "Qt").vertex_ids;
}

TEST(ExactHull, EmptyInput) {
  const HullMesh h = exact_hull({});
  EXPECT_EQ(h.dimension, -1);
  EXPECT_TRUE(h.vertex_ids.empty());
  EXPECT_TRUE(h.triangles.empty());
  EXPECT_EQ(affine_dimension({}), -1);
}

TEST(ExactHull, Tetrahedron) {
  const std::vector<Point3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1f, 0.1f, 0.1f}};
  const HullMesh h = exact_hull(p);
  EXPECT_EQ(h.dimension, 3);
  EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{0, 1, 2, 3}));
  EXPECT_EQ(h.triangles.size(), 4u);
  for (std::size_t i = 0; i < h.vertices.size(); ++i)
    EXPECT_EQ(h.vertices[i], p[h.vertex_ids[i]]);
  // Outward: the fifth (interior) point is below every face.
  for (const Triangle& t : h.triangles)
    EXPECT_LT(orient3d(to_vec3d(h.vertices[t[0]]), to_vec3d(h.vertices[t[1]]), to_vec3d(h.vertices[t[2]]),
                       to_vec3d(p[4])),
              0);
  expect_valid(p, h);
}

class RandomVsQhull : public ::testing::TestWithParam<std::size_t> {};

TEST_P(RandomVsQhull, CubeAndBall) {
  const std::size_t n = GetParam();
  for (int kind = 0; kind < 2; ++kind) {
    const std::vector<Point3> p = kind == 0 ? cube(n, 11 + n) : ball(n, 23 + n);
    const HullMesh h = exact_hull(p);
    EXPECT_EQ(h.dimension, 3);
    EXPECT_EQ(h.vertex_ids, qhull_vertices(p)) << (kind == 0 ? "cube" : "ball") << " n=" << n;
    EXPECT_TRUE(std::is_sorted(h.vertex_ids.begin(), h.vertex_ids.end()));
    // Triangulated sphere: F = 2V - 4.
    EXPECT_EQ(h.triangles.size(), 2 * h.vertex_ids.size() - 4);
    expect_valid(p, h);
  }
}
INSTANTIATE_TEST_SUITE_P(Sizes, RandomVsQhull, ::testing::Values(1000, 10000, 100000));

TEST(ExactHull, SpherePointsAreNearlyAllExtreme) {
  const std::vector<Point3> p = sphere(20000, 5);
  const HullMesh h = exact_hull(p);
  expect_valid(p, h);
  EXPECT_GT(h.vertex_ids.size(), 19000u);  // nearly all on the hull; float rounding pushes a few inside
}

std::set<std::array<float, 3>> coordinate_set(const HullMesh& h) {
  std::set<std::array<float, 3>> s;
  for (const Point3& v : h.vertices)
    s.insert({v.x, v.y, v.z});
  return s;
}

std::set<std::array<float, 3>> cube_corners(float lo, float hi) {
  std::set<std::array<float, 3>> s;
  for (float x : {lo, hi})
    for (float y : {lo, hi})
      for (float z : {lo, hi})
        s.insert({x, y, z});
  return s;
}

TEST(ExactHull, IntegerGridHasOnlyCorners) {
  std::vector<Point3> p = lattice(6, 6, 6);
  Rng r(3);
  for (std::size_t i = p.size(); i > 1; --i)
    std::swap(p[i - 1], p[r.below(i)]);
  const HullMesh h = exact_hull(p);
  EXPECT_EQ(h.dimension, 3);
  EXPECT_EQ(h.vertex_ids.size(), 8u);
  EXPECT_EQ(coordinate_set(h), cube_corners(0, 5));
  EXPECT_EQ(h.triangles.size(), 12u);
  expect_valid(p, h);
}

TEST(ExactHull, CubeSurfaceGridHasOnlyCorners) {
  std::vector<Point3> p;
  for (const Point3& q : lattice(11, 11, 11))
    if (q.x == 0 || q.x == 10 || q.y == 0 || q.y == 10 || q.z == 0 || q.z == 10) p.push_back(q);
  const HullMesh h = exact_hull(p);
  EXPECT_EQ(h.vertex_ids.size(), 8u);
  EXPECT_EQ(coordinate_set(h), cube_corners(0, 10));
  expect_valid(p, h);
}

TEST(ExactHull, TripledPointsKeepLowestIndex) {
  const std::vector<Point3> base = ball(3000, 77);
  const HullMesh h1 = exact_hull(base);
  // Block order: copies at i, i + n, i + 2n; the lowest index is the original.
  std::vector<Point3> tripled;
  for (int k = 0; k < 3; ++k)
    tripled.insert(tripled.end(), base.begin(), base.end());
  const HullMesh h3 = exact_hull(tripled);
  EXPECT_EQ(h3.vertex_ids, h1.vertex_ids);
  expect_valid(tripled, h3);
  // Shuffled copies: the vertex must be the lowest index among each point's three copies.
  Rng r(9);
  std::vector<std::size_t> perm(tripled.size());
  std::iota(perm.begin(), perm.end(), 0);
  for (std::size_t i = perm.size(); i > 1; --i)
    std::swap(perm[i - 1], perm[r.below(i)]);
  std::vector<Point3> shuffled(tripled.size());
  std::vector<PointIndex> lowest(base.size(), ~0u);
  for (std::size_t j = 0; j < perm.size(); ++j) {
    shuffled[j] = tripled[perm[j]];
    PointIndex& l = lowest[perm[j] % base.size()];
    l = std::min<PointIndex>(l, static_cast<PointIndex>(j));
  }
  std::vector<PointIndex> expected;
  for (PointIndex v : h1.vertex_ids)
    expected.push_back(lowest[v]);
  std::sort(expected.begin(), expected.end());
  const HullMesh hs = exact_hull(shuffled);
  EXPECT_EQ(hs.vertex_ids, expected);
  expect_valid(shuffled, hs);
}

TEST(ExactHull, ParaboloidPointsAreAllExtreme) {
  const std::vector<Point3> p = integer_paraboloid(12);
  const HullMesh h = exact_hull(p);
  EXPECT_EQ(h.vertex_ids.size(), p.size());
  expect_valid(p, h);
}

TEST(ExactHull, IdsSelectASubset) {
  const std::vector<Point3> p = cube(5000, 31);
  std::vector<PointIndex> ids;
  for (PointIndex i = 0; i < p.size(); i += 3)
    ids.push_back(i);
  std::vector<Point3> sub;
  for (PointIndex i : ids)
    sub.push_back(p[i]);
  const HullMesh hs = exact_hull(sub);
  const HullMesh h = exact_hull(p, ids);
  std::vector<PointIndex> expected;
  for (PointIndex v : hs.vertex_ids)
    expected.push_back(ids[v]);
  EXPECT_EQ(h.vertex_ids, expected);
  for (std::size_t i = 0; i < h.vertices.size(); ++i)
    EXPECT_EQ(h.vertices[i], p[h.vertex_ids[i]]);
  EXPECT_EQ(h.triangles.size(), hs.triangles.size());
  // Duplicated ids are one point.
  std::vector<PointIndex> twice = ids;
  twice.insert(twice.end(), ids.begin(), ids.end());
  EXPECT_EQ(exact_hull(p, twice).vertex_ids, expected);
}

TEST(ExactHull, CoplanarPointsGiveAPolygon) {
  // On the plane z = x + 2y (exact for these small integers): a 10 x 10 square of points with collinear
  // points on its edges and interior points.
  std::vector<Point3> p;
  for (int x = 0; x <= 10; ++x)
    for (int y = 0; y <= 10; ++y)
      p.push_back({float(x), float(y), float(x + 2 * y)});
  Rng r(4);
  for (std::size_t i = p.size(); i > 1; --i)
    std::swap(p[i - 1], p[r.below(i)]);
  EXPECT_EQ(affine_dimension(p), 2);
  const HullMesh h = exact_hull(p);
  ASSERT_EQ(h.dimension, 2);
  EXPECT_TRUE(h.triangles.empty());
  ASSERT_EQ(h.polygon.size(), 4u);
  EXPECT_EQ(h.vertex_ids.size(), 4u);
  std::set<std::array<float, 3>> expected = {{0, 0, 0}, {10, 0, 10}, {0, 10, 20}, {10, 10, 30}};
  EXPECT_EQ(coordinate_set(h), expected);
  // Counter-clockwise about the canonical normal (first non-zero component positive): here (1, 2, -1)
  // up to scale, so the x component decides: positive orientation in the (y, z) projection.
  for (std::size_t i = 0; i < 4; ++i) {
    const Point3 &a = h.vertices[h.polygon[i]], &b = h.vertices[h.polygon[(i + 1) % 4]],
                 &c = h.vertices[h.polygon[(i + 2) % 4]];
    EXPECT_EQ(orient2d(a.y, a.z, b.y, b.z, c.y, c.z), 1);
  }
  // Starts at the lexicographically smallest corner.
  EXPECT_EQ(h.vertices[h.polygon[0]], (Point3{0, 0, 0}));
  expect_valid(p, h);
}

TEST(ExactHull, CoplanarAxisAlignedAndDuplicates) {
  // A flat disc of random points in z = 3, every point doubled.
  std::vector<Point3> p;
  for (const Point3& q : ball(2000, 8))
    p.push_back({q.x, q.y, 3});
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    p.push_back(p[i]);
  const HullMesh h = exact_hull(p);
  ASSERT_EQ(h.dimension, 2);
  for (PointIndex v : h.vertex_ids)
    EXPECT_LT(v, n);
  expect_valid(p, h);
  // Normal (0, 0, +1): counter-clockwise in (x, y).
  const std::size_t k = h.polygon.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Point3 &a = h.vertices[h.polygon[i]], &b = h.vertices[h.polygon[(i + 1) % k]],
                 &c = h.vertices[h.polygon[(i + 2) % k]];
    EXPECT_EQ(orient2d(a.x, a.y, b.x, b.y, c.x, c.y), 1);
  }
}

TEST(ExactHull, CollinearPointsGiveASegment) {
  std::vector<Point3> p;
  for (int t = -20; t <= 30; ++t)
    p.push_back({float(3 * t), float(-2 * t), float(t)});
  std::swap(p[0], p[25]);
  p.push_back(p[3]);  // a duplicate of the end at index 3 (t = -17)
  EXPECT_EQ(affine_dimension(p), 1);
  const HullMesh h = exact_hull(p);
  ASSERT_EQ(h.dimension, 1);
  ASSERT_EQ(h.vertex_ids.size(), 2u);
  // Ends: t = -20 (now at index 25) and t = 30 (index 50).
  EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{25, 50}));
  EXPECT_TRUE(h.triangles.empty());
  expect_valid(p, h);
}

TEST(ExactHull, RepeatedPointGivesDimensionZero) {
  const std::vector<Point3> p(10, Point3{1.5f, -2, 7});
  EXPECT_EQ(affine_dimension(p), 0);
  const HullMesh h = exact_hull(p);
  ASSERT_EQ(h.dimension, 0);
  EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{0}));
  expect_valid(p, h);
  EXPECT_EQ(exact_hull(p, {7, 4, 9}).vertex_ids, (std::vector<PointIndex>{4}));
  // +0 and -0 are the same coordinate.
  const std::vector<Point3> z = {{-0.0f, 0, 0}, {0, 0, 0}};
  EXPECT_EQ(exact_hull(z).dimension, 0);
  EXPECT_EQ(exact_hull(z).vertex_ids, (std::vector<PointIndex>{0}));
}

TEST(ExactHull, AffineDimension) {
  EXPECT_EQ(affine_dimension({{1, 2, 3}}), 0);
  EXPECT_EQ(affine_dimension({{1, 2, 3}, {1, 2, 3}, {2, 2, 3}}), 1);
  EXPECT_EQ(affine_dimension({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {1, 0, 0}}), 2);
  EXPECT_EQ(affine_dimension({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {1, 0, 0}, {0, 0, 1}}), 3);
  // Nearly but not exactly collinear (float spacing): exact predicates must see it.
  const float e = std::nextafter(1.0f, 2.0f);
  EXPECT_EQ(affine_dimension({{0, 0, 0}, {1, 1, 1}, {2, 2, 2 * e}}), 2);
}

TEST(ExactHull, PowerOfTwoScalingKeepsCombinatorics) {
  const std::vector<Point3> p = ball(20000, 99);
  const HullMesh h = exact_hull(p);
  for (float s : {std::ldexp(1.0f, 100), std::ldexp(1.0f, -100)}) {
    std::vector<Point3> q = p;
    for (Point3& v : q)
      v = {v.x * s, v.y * s, v.z * s};
    const HullMesh hq = exact_hull(q);
    EXPECT_EQ(hq.vertex_ids, h.vertex_ids);
    EXPECT_EQ(hq.triangles, h.triangles);
    expect_valid(q, hq);
  }
  // Also for a degenerate input: the scaled grid still has only its corners.
  std::vector<Point3> g = lattice(5, 5, 5);
  for (Point3& v : g)
    v = {std::ldexp(v.x, -100), std::ldexp(v.y, -100), std::ldexp(v.z, -100)};
  EXPECT_EQ(exact_hull(g).vertex_ids.size(), 8u);
}

TEST(ExactHull, ThinSlab) {
  Rng r(12);
  std::vector<Point3> p(20000);
  for (Point3& q : p)
    q = {r.unit(), r.unit(), (r.unit() + 1) * 0.5e-6f};
  const HullMesh h = exact_hull(p);
  EXPECT_EQ(h.dimension, 3);
  expect_valid(p, h);
}

TEST(ExactHull, SmallIntegerCloudsWithManyDegeneracies) {
  // Coordinates in {0..3}: many coplanar facets, collinear boundary points and duplicates.
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    Rng r(seed);
    std::vector<Point3> p(5 + r.below(200));
    for (Point3& q : p)
      q = {float(r.below(4)), float(r.below(4)), float(r.below(4))};
    const HullMesh h = exact_hull(p);
    EXPECT_EQ(h.dimension, affine_dimension(p));
    expect_valid(p, h);
  }
}

TEST(ExactHull, MatchesBruteForceOnTinyDegenerateSets) {
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    Rng r(seed * 7919);
    const int side = 2 + static_cast<int>(seed % 3);
    std::vector<Point3> p(4 + r.below(11));
    for (Point3& q : p)
      q = {float(r.below(side)), float(r.below(side)), float(r.below(side))};
    if (seed % 5 == 0)
      for (Point3& q : p)
        q.z = q.x + q.y;  // coplanar
    if (seed % 7 == 0)
      for (Point3& q : p)
        q = {q.x, 2 * q.x, -q.x};  // collinear
    const HullMesh h = exact_hull(p);
    const int dim = affine_dimension(p);
    EXPECT_EQ(h.dimension, dim) << "seed " << seed;
    // In 1D and 0D the oracle's "not in the hull of the others" is exactly the ends / the single point.
    EXPECT_EQ(h.vertex_ids, brute_force_vertices(p)) << "seed " << seed;
    expect_valid(p, h);
  }
}

TEST(ExactHull, CylinderRings) {
  // Rings of a cylinder: the top and bottom discs are large coplanar facets.
  std::vector<Point3> p;
  for (int ring = 0; ring <= 4; ++ring)
    for (int k = 0; k < 64; ++k) {
      const double a = 2 * M_PI * k / 64;
      p.push_back({float(std::cos(a)), float(std::sin(a)), float(ring)});
    }
  const HullMesh h = exact_hull(p);
  expect_valid(p, h);
}

struct Model {
  const char* file;
  std::size_t extreme;
};

TEST(ExactHull, SharedModelsHaveKnownExtremeCounts) {
  const std::filesystem::path dir = CUDAHULL_MODELS_DIR;
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "models folder " << dir << " is absent";
  const Model models[] = {
      {"bun_zipper.ply", 1564},  {"stanford-bunny.obj", 1562}, {"dragonStandRight_0.ply", 439},
      {"dragon_scans.ply", 207}, {"teapot.obj", 878},          {"spot.obj", 305}};
  for (const Model& m : models) {
    SCOPED_TRACE(m.file);
    const std::vector<Point3> p = read_points((dir / m.file).string());
    const HullMesh h = exact_hull(p);
    EXPECT_EQ(h.vertex_ids.size(), m.extreme);
    expect_valid(p, h);
  }
}

TEST(ExactHull, LargeBallIsFast) {
  const std::vector<Point3> p = ball(100000, 1234);
  const auto t0 = std::chrono::steady_clock::now();
  const HullMesh h = exact_hull(p);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  RecordProperty("milliseconds", std::to_string(ms));
  EXPECT_LT(ms, 5000);  // generous: debug and sanitizer builds
  EXPECT_GT(h.vertex_ids.size(), 1000u);
}

}  // namespace
}  // namespace cudahull
