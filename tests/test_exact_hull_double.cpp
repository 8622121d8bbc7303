// exact_hull on double coordinates (Point3d): inputs whose answer changes when the coordinates are rounded to
// float, against a second brute-force oracle (the facet planes through triples of points), itself checked
// against the Caratheodory oracle on float sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/predicates.hpp"
#include "support/exact_hull_checks.hpp"
#include "support/rng.hpp"

namespace cudahull {
namespace {

using testing::Rng;

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

}  // namespace
}  // namespace cudahull
