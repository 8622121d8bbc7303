// exact_hull: vertex sets against Qhull on random inputs, exact answers on degenerate inputs (grids, flat
// facets, duplicates, lower dimensions, extreme scales) and the shared models' known extreme counts.  Every
// result must also pass the independent checker.
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

#include "cudahull/hull_checker.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/predicates.hpp"
#include "qhull_reference.hpp"

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

template <class Point>
void expect_valid(const std::vector<Point>& points, const BasicHullMesh<Point>& hull) {
  const CheckResult r = check_hull(points, hull);
  EXPECT_TRUE(r.ok);
  for (const std::string& f : r.failures)
    ADD_FAILURE() << f;
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

// Brute-force oracle: p is strictly extreme iff it is not in the convex hull of the other distinct points,
// i.e. (Caratheodory) not in the closed hull of any 1 to 4 of them.  Exact predicates throughout.
bool in_hull_of(const Vec3d& p, const std::vector<Vec3d>& s) {
  auto same = [](const Vec3d& a, const Vec3d& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  auto lex = [](const Vec3d& a, const Vec3d& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  if (s.size() == 1) return same(p, s[0]);
  if (s.size() == 2) {
    if (!collinear3d(s[0], s[1], p)) return false;
    const Vec3d &lo = lex(s[0], s[1]) ? s[0] : s[1], &hi = lex(s[0], s[1]) ? s[1] : s[0];
    return !lex(p, lo) && !lex(hi, p);
  }
  if (s.size() == 3) {
    const Vec3d &a = s[0], &b = s[1], &c = s[2];
    if (collinear3d(a, b, c)) return false;  // covered by the pairs
    if (orient3d(a, b, c, p) != 0) return false;
    const double A[3] = {a.x, a.y, a.z}, B[3] = {b.x, b.y, b.z}, C[3] = {c.x, c.y, c.z},
                 P[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k) {
      const int u = (k + 1) % 3, w = (k + 2) % 3;
      const int o = orient2d(A[u], A[w], B[u], B[w], C[u], C[w]);
      if (o == 0) continue;
      return orient2d(A[u], A[w], B[u], B[w], P[u], P[w]) * o >= 0 &&
             orient2d(B[u], B[w], C[u], C[w], P[u], P[w]) * o >= 0 &&
             orient2d(C[u], C[w], A[u], A[w], P[u], P[w]) * o >= 0;
    }
    return false;
  }
  const Vec3d &a = s[0], &b = s[1], &c = s[2], &d = s[3];
  const int o = orient3d(a, b, c, d);
  if (o == 0) return false;  // covered by the triangles
  return orient3d(a, b, c, p) * o >= 0 && orient3d(a, b, p, d) * o >= 0 && orient3d(a, p, c, d) * o >= 0 &&
         orient3d(p, b, c, d) * o >= 0;
}

std::vector<PointIndex> brute_force_vertices(const std::vector<Point3>& pts) {
  std::vector<PointIndex> out;
  for (PointIndex i = 0; i < pts.size(); ++i) {
    bool lowest = true;
    std::vector<Vec3d> others;
    for (PointIndex j = 0; j < pts.size(); ++j) {
      if (pts[j] == pts[i]) {
        if (j < i) lowest = false;
        continue;
      }
      bool dup = false;  // one copy of each other point is enough
      for (const Vec3d& o : others)
        dup = dup || (o.x == pts[j].x && o.y == pts[j].y && o.z == pts[j].z);
      if (!dup) others.push_back(to_vec3d(pts[j]));
    }
    if (!lowest) continue;
    const Vec3d p = to_vec3d(pts[i]);
    const std::size_t m = others.size();
    bool inside = false;
    for (std::size_t a = 0; a < m && !inside; ++a) {
      inside = in_hull_of(p, {others[a]});
      for (std::size_t b = a + 1; b < m && !inside; ++b) {
        inside = in_hull_of(p, {others[a], others[b]});
        for (std::size_t c = b + 1; c < m && !inside; ++c) {
          inside = in_hull_of(p, {others[a], others[b], others[c]});
          for (std::size_t d = c + 1; d < m && !inside; ++d)
            inside = in_hull_of(p, {others[a], others[b], others[c], others[d]});
        }
      }
    }
    if (!inside) out.push_back(i);
  }
  return out;
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

// ---------------------------------------------------------------------------------------------------------
// Double coordinates (Point3d): inputs whose answer changes when the coordinates are rounded to float.

// A double in [-1, 1) with all 53 bits random.
double unit_d(Rng& r) {
  return static_cast<double>(r.next() >> 11) * 0x1p-52 - 1;
}

std::vector<Point3> to_float(const std::vector<Point3d>& p) {
  std::vector<Point3> f;
  for (const Point3d& q : p)
    f.push_back({static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)});
  return f;
}

std::vector<PointIndex> iota_ids(std::size_t n) {
  std::vector<PointIndex> ids(n);
  std::iota(ids.begin(), ids.end(), 0u);
  return ids;
}

// A second brute-force oracle, for full-dimensional sets of either point type and independent of exact_hull:
// the facet planes are the planes through three non-collinear input points with no input point strictly on
// each side.  A point of a 3-polytope lies on no facet plane (interior), one (inside a facet), two (inside an
// edge) or at least three (a vertex).  Among identical points only the lowest index can be a vertex.
// O(n^4) exact predicates.
template <class Point>
std::vector<PointIndex> facet_oracle_vertices(const std::vector<Point>& pts) {
  const std::size_t n = pts.size();
  std::vector<Vec3d> p;
  for (const Point& q : pts)
    p.push_back(to_vec3d(q));
  std::vector<std::array<Vec3d, 3>> planes;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        if (collinear3d(p[i], p[j], p[k])) continue;
        bool pos = false, neg = false;
        for (std::size_t q = 0; q < n && !(pos && neg); ++q) {
          const int s = orient3d(p[i], p[j], p[k], p[q]);
          pos = pos || s > 0;
          neg = neg || s < 0;
        }
        if (pos && neg) continue;
        if (!pos && !neg) {
          ADD_FAILURE() << "facet_oracle_vertices needs a full-dimensional input";
          return {};
        }
        bool known = false;
        for (const auto& pl : planes)
          known =
              known || (orient3d(pl[0], pl[1], pl[2], p[i]) == 0 &&
                        orient3d(pl[0], pl[1], pl[2], p[j]) == 0 && orient3d(pl[0], pl[1], pl[2], p[k]) == 0);
        if (!known) planes.push_back({p[i], p[j], p[k]});
      }
  std::vector<PointIndex> out;
  for (PointIndex i = 0; i < n; ++i) {
    bool lowest = true;
    for (PointIndex j = 0; j < i && lowest; ++j)
      lowest = !(pts[j] == pts[i]);
    if (!lowest) continue;
    int on = 0;
    for (const auto& pl : planes)
      on += orient3d(pl[0], pl[1], pl[2], p[i]) == 0;
    if (on >= 3) out.push_back(i);
  }
  return out;
}

TEST(ExactHullDouble, FacetOracleAgreesWithTheCaratheodoryOracle) {
  // The new oracle against the one above, on float sets full of coplanar and collinear points.
  int full = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    Rng r(seed * 104729);
    std::vector<Point3> p(6 + r.below(10));
    for (Point3& q : p)
      q = {float(r.below(3)), float(r.below(3)), float(r.below(3))};
    if (affine_dimension(p) != 3) continue;
    ++full;
    EXPECT_EQ(facet_oracle_vertices(p), brute_force_vertices(p)) << "seed " << seed;
  }
  EXPECT_GT(full, 30);
}

// (a) Points 1e-12 outside (and inside) the faces of the cube [-1, 1]^3.  In double the outside points are
// vertices (three per face, alone on their plane); in float 1 + 1e-12 rounds to 1 and they lie inside the
// faces, leaving the 8 corners.
std::vector<Point3d> cube_with_points_just_off_its_faces(std::vector<PointIndex>* outside) {
  Rng r(2024);
  std::vector<Point3d> p;
  for (int c = 0; c < 8; ++c)
    p.push_back({c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0});
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    const double side = face % 2 ? 1.0 : -1.0;
    for (int k = 0; k < 5; ++k) {
      const double off = k < 3 ? 1e-12 : -1e-12;  // three just outside, two just inside
      double c[3];
      c[axis] = side * (1 + off);
      c[(axis + 1) % 3] = 0.9 * unit_d(r);
      c[(axis + 2) % 3] = 0.9 * unit_d(r);
      if (off > 0) outside->push_back(static_cast<PointIndex>(p.size()));
      p.push_back({c[0], c[1], c[2]});
    }
  }
  return p;
}

TEST(ExactHullDouble, PointsOneTrillionthOutsideCubeFacesAreVertices) {
  std::vector<PointIndex> outside;
  const std::vector<Point3d> p = cube_with_points_just_off_its_faces(&outside);
  const std::vector<Point3> pf = to_float(p);
  for (std::size_t i = 8; i < p.size(); ++i) {  // the premise: float puts every point onto its face
    const Point3& q = pf[i];
    ASSERT_EQ(std::max({std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)}), 1.0f) << "point " << i;
  }
  std::vector<PointIndex> expected = iota_ids(8);
  expected.insert(expected.end(), outside.begin(), outside.end());

  const HullMeshd hd = exact_hull(p);
  EXPECT_EQ(hd.dimension, 3);
  EXPECT_EQ(hd.vertex_ids, facet_oracle_vertices(p));
  EXPECT_EQ(hd.vertex_ids, expected);
  for (std::size_t k = 0; k < hd.vertices.size(); ++k)  // the double coordinates, not a float rounding
    EXPECT_EQ(hd.vertices[k], p[hd.vertex_ids[k]]);
  expect_valid(p, hd);

  const HullMesh hf = exact_hull(pf);
  EXPECT_EQ(hf.vertex_ids, facet_oracle_vertices(pf));
  EXPECT_EQ(hf.vertex_ids, iota_ids(8));
  EXPECT_NE(hf.vertex_ids, hd.vertex_ids);
  expect_valid(pf, hf);
}

// (b) Pairs of points that are equal in float but distinct in double.  Each pair sits alone on the plane
// x_axis = +-2 beyond a cube, so in double both are vertices (the ends of a segment); in float they are one
// point and only the lower index is a vertex.  Pairs inside the cube are vertices in neither.
TEST(ExactHullDouble, PairsEqualInFloatAreDistinctVerticesInDouble) {
  std::vector<Point3d> p;
  for (int c = 0; c < 8; ++c)
    p.push_back({c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0});
  const double tweak[6][2] = {{0x1p-30, 0},    {1e-9, -3e-9},    {0, 0x1p-31},
                              {-2e-10, 5e-10}, {0x1p-28, 1e-10}, {7e-9, 0}};
  std::vector<std::pair<PointIndex, PointIndex>> pairs;
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    double a[3], b[3];
    a[axis] = b[axis] = face % 2 ? 2.0 : -2.0;
    a[(axis + 1) % 3] = 0.375, a[(axis + 2) % 3] = -0.625;
    b[(axis + 1) % 3] = 0.375 + tweak[face][0], b[(axis + 2) % 3] = -0.625 + tweak[face][1];
    const PointIndex first = static_cast<PointIndex>(p.size());
    if (face % 2) {  // the perturbed twin first: the float vertex is whichever comes first
      p.push_back({b[0], b[1], b[2]});
      p.push_back({a[0], a[1], a[2]});
    } else {
      p.push_back({a[0], a[1], a[2]});
      p.push_back({b[0], b[1], b[2]});
    }
    pairs.push_back({first, first + 1});
  }
  p.push_back({0.1, 0.2, 0.3});  // an interior pair
  p.push_back({0.1 + 1e-10, 0.2, 0.3 - 1e-10});
  const std::vector<Point3> pf = to_float(p);
  for (const auto& [i, j] : pairs) {  // the premise
    ASSERT_NE(p[i], p[j]);
    ASSERT_EQ(pf[i], pf[j]);
  }
  ASSERT_EQ(pf[p.size() - 2], pf[p.size() - 1]);

  std::vector<PointIndex> expected_d = iota_ids(8), expected_f = iota_ids(8);
  for (const auto& [i, j] : pairs) {
    expected_d.push_back(i), expected_d.push_back(j);
    expected_f.push_back(i);
  }

  const HullMeshd hd = exact_hull(p);
  EXPECT_EQ(hd.vertex_ids, facet_oracle_vertices(p));
  EXPECT_EQ(hd.vertex_ids, expected_d);
  expect_valid(p, hd);

  const HullMesh hf = exact_hull(pf);
  EXPECT_EQ(hf.vertex_ids, facet_oracle_vertices(pf));
  EXPECT_EQ(hf.vertex_ids, expected_f);
  expect_valid(pf, hf);
}

// (c) A ball of radius 1e-3 about 1e6 from the origin: float spacing there is 1/32 or 1/16, so in float every
// point rounds to the centre (dimension 0); in double the ball has a proper 3D hull.
TEST(ExactHullDouble, SmallBallFarFromTheOrigin) {
  const Point3d centre = {400000, -400000, 824621.125};  // |centre| = 1e6 to 7 digits; float-exact
  Rng r(77);
  std::vector<Point3d> p;
  while (p.size() < 60) {
    const double x = unit_d(r), y = unit_d(r), z = unit_d(r), l = std::sqrt(x * x + y * y + z * z);
    if (l < 0.1 || l > 1) continue;
    const double radius = p.size() < 40 ? 1e-3 / l : 0.5e-3;  // 40 on the sphere, 20 inside
    p.push_back({centre.x + x * radius, centre.y + y * radius, centre.z + z * radius});
  }
  const std::vector<Point3> pf = to_float(p);
  for (const Point3& q : pf)  // the premise
    ASSERT_EQ(q, (Point3{400000.0f, -400000.0f, 824621.125f}));

  const HullMeshd hd = exact_hull(p);
  EXPECT_EQ(hd.dimension, 3);
  EXPECT_EQ(hd.vertex_ids, facet_oracle_vertices(p));
  EXPECT_GE(hd.vertex_ids.size(), 20u);
  expect_valid(p, hd);

  const HullMesh hf = exact_hull(pf);
  EXPECT_EQ(hf.dimension, 0);
  EXPECT_EQ(hf.vertex_ids, (std::vector<PointIndex>{0}));
  expect_valid(pf, hf);
}

// (d) Near-coplanar rings about the plane z = 1: an outer ring whose points alternate 1e-12 above and below
// it, an inner ring 2e-12 above and a smaller one 2e-12 below.  In double this is a thin lens with every
// point a vertex (each ring is alone on its plane or a strict corner of the projection); in float every z
// rounds to 1, leaving a polygon of the outer ring.
TEST(ExactHullDouble, NearCoplanarRings) {
  std::vector<Point3d> p;
  auto ring = [&](int count, double radius, double phase, auto height) {
    for (int k = 0; k < count; ++k) {
      const double a = 2 * M_PI * (k + phase) / count;
      p.push_back({radius * std::cos(a), radius * std::sin(a), height(k)});
    }
  };
  ring(24, 1.0, 0, [](int k) { return k % 2 ? 1 + 1e-12 : 1 - 1e-12; });
  ring(12, 0.5, 0.25, [](int) { return 1 + 2e-12; });
  ring(12, 0.25, 0.5, [](int) { return 1 - 2e-12; });
  const std::vector<Point3> pf = to_float(p);
  for (const Point3& q : pf)  // the premise
    ASSERT_EQ(q.z, 1.0f);

  const HullMeshd hd = exact_hull(p);
  EXPECT_EQ(hd.dimension, 3);
  EXPECT_EQ(hd.vertex_ids, facet_oracle_vertices(p));
  EXPECT_EQ(hd.vertex_ids, iota_ids(p.size()));
  expect_valid(p, hd);

  const HullMesh hf = exact_hull(pf);
  EXPECT_EQ(hf.dimension, 2);
  EXPECT_EQ(hf.vertex_ids, iota_ids(24));
  expect_valid(pf, hf);
}

TEST(ExactHullDouble, AffineDimension) {
  EXPECT_EQ(affine_dimension(std::vector<Point3d>{}), -1);
  // Collinear in float, a plane in double.
  const std::vector<Point3d> p = {
      {1e6, 1e6, 1e6}, {1e6 + 1, 1e6 + 1, 1e6 + 1 + 1e-9}, {1e6 + 2, 1e6 + 2, 1e6 + 2}};
  EXPECT_EQ(affine_dimension(p), 2);
  EXPECT_EQ(affine_dimension(to_float(p)), 1);
  // Coplanar in float (two points merge), a solid in double.
  const std::vector<Point3d> q = {{1e6, 0, 0}, {1e6 + 1e-9, 1e-9, 0}, {1e6, 1e-9, 0}, {1e6, 0, 1e-9}};
  EXPECT_EQ(affine_dimension(q), 3);
  EXPECT_EQ(affine_dimension(to_float(q)), 2);
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
