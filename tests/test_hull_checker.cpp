// The independent checker: accepts correct hulls (hand-made and from exact_hull) and rejects each kind of
// corruption with a message that names the problem.
#include "cudahull/hull_checker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "support/point_sets.hpp"
#include "support/rng.hpp"

namespace cudahull {
namespace {

using testing::Rng;
std::vector<Point3> ball(std::size_t n, std::uint64_t seed) {
  return testing::dyadic_ball(n, seed);
}

// A mesh whose vertices are the given input points, in the given order.
HullMesh mesh(const std::vector<Point3>& pts, const std::vector<PointIndex>& ids, std::vector<Triangle> tris,
              int dim = 3) {
  HullMesh h;
  h.dimension = dim;
  h.vertex_ids = ids;
  for (PointIndex i : ids)
    h.vertices.push_back(pts[i]);
  h.triangles = std::move(tris);
  return h;
}

std::string joined(const CheckResult& r) {
  std::string s;
  for (const std::string& f : r.failures)
    s += f + "\n";
  return s;
}

// Expects a rejection with at least one line containing `needle`.
template <class Point>
void expect_rejected(const std::vector<Point>& pts, const BasicHullMesh<Point>& h,
                     const std::string& needle) {
  const CheckResult r = check_hull(pts, h);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.failures.empty());
  EXPECT_NE(joined(r).find(needle), std::string::npos) << "expected \"" << needle << "\" in:\n" << joined(r);
}

template <class Point>
void expect_accepted(const std::vector<Point>& pts, const BasicHullMesh<Point>& h) {
  const CheckResult r = check_hull(pts, h);
  EXPECT_TRUE(r.ok) << joined(r);
}

// Unit cube corners 0..7 (bit 0: x, bit 1: y, bit 2: z) and its 12 outward triangles.
std::vector<Point3> cube_points() {
  std::vector<Point3> p;
  for (int i = 0; i < 8; ++i)
    p.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
  return p;
}
std::vector<Triangle> cube_triangles() {
  return {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},   // z = 0, z = 1
          {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},   // y = 0, y = 1
          {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};  // x = 0, x = 1
}

const std::vector<Point3> kTetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.2f, 0.2f, 0.2f}};
const std::vector<Triangle> kTetraFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

TEST(HullChecker, AcceptsHandMadeTetrahedronAndCube) {
  expect_accepted(kTetra, mesh(kTetra, {0, 1, 2, 3}, kTetraFaces));
  std::vector<Point3> cube = cube_points();
  cube.push_back({0.5f, 0.5f, 0.5f});
  cube.push_back({0.5f, 0.5f, 1});  // on the top facet
  cube.push_back({1, 1, 0.25f});    // on an edge
  expect_accepted(cube, mesh(cube, {0, 1, 2, 3, 4, 5, 6, 7}, cube_triangles()));
}

TEST(HullChecker, AcceptsExactHulls) {
  for (std::size_t n : {100, 5000, 100000}) {
    const std::vector<Point3> p = ball(n, n);
    expect_accepted(p, exact_hull(p));
  }
}

TEST(HullChecker, RejectsFlippedFace) {
  std::vector<Triangle> t = kTetraFaces;
  std::swap(t[3][0], t[3][1]);
  expect_rejected(kTetra, mesh(kTetra, {0, 1, 2, 3}, t), "same direction");
  // Every face flipped: closed and consistently oriented, but inside out.
  t = kTetraFaces;
  for (Triangle& f : t)
    std::swap(f[0], f[1]);
  expect_rejected(kTetra, mesh(kTetra, {0, 1, 2, 3}, t), "concave");
}

TEST(HullChecker, RejectsMissingVertex) {
  const std::vector<Point3> p = ball(2000, 5);
  const HullMesh full = exact_hull(p);
  const PointIndex dropped = full.vertex_ids[full.vertex_ids.size() / 2];
  std::vector<PointIndex> rest;
  for (PointIndex i = 0; i < p.size(); ++i)
    if (i != dropped) rest.push_back(i);
  const HullMesh h = exact_hull(p, rest);
  expect_rejected(p, h, "point " + std::to_string(dropped) + " (");
  expect_rejected(p, h, "is above face");
}

TEST(HullChecker, RejectsNonStrictVertices) {
  // The centre of the top facet as a vertex: the facet z = 1 fanned around it.
  std::vector<Point3> p = cube_points();
  p.push_back({0.5f, 0.5f, 1});  // 8
  std::vector<Triangle> t = cube_triangles();
  t[2] = {4, 5, 8};
  t[3] = {5, 7, 8};
  t.push_back({7, 6, 8});
  t.push_back({6, 4, 8});
  expect_rejected(p, mesh(p, {0, 1, 2, 3, 4, 5, 6, 7, 8}, t),
                  "vertex 8 (0.5 0.5 1) is not strictly extreme: it lies inside");

  // The midpoint of the edge (1,1,0)-(1,1,1) as a vertex, splitting the two faces on that edge.
  p = cube_points();
  p.push_back({1, 1, 0.5f});  // 8
  t = cube_triangles();
  // y = 1 facet: {2,6,7},{2,7,3} -> the edge 7-3 gets 8 in between.
  t[6] = {2, 6, 7};
  t[7] = {2, 7, 8};
  t.push_back({2, 8, 3});
  // x = 1 facet: {1,3,7},{1,7,5} -> the edge 3-7 gets 8 in between.
  t[10] = {1, 3, 8};
  t.push_back({1, 8, 7});
  expect_rejected(p, mesh(p, {0, 1, 2, 3, 4, 5, 6, 7, 8}, t), "lies on the segment between vertices");
}

TEST(HullChecker, RejectsHigherIndexDuplicate) {
  std::vector<Point3> p = cube_points();
  p.push_back(p[5]);  // index 8 duplicates vertex 5
  HullMesh h = mesh(p, {0, 1, 2, 3, 4, 5, 6, 7}, cube_triangles());
  expect_accepted(p, h);
  h.vertex_ids[5] = 8;
  expect_rejected(p, h,
                  "vertex 5 (id 8) is not the lowest index with its coordinates: input point 5 is identical");
  // Two vertices at the same place.
  HullMesh d = mesh(p, {0, 1, 2, 3, 4, 5, 6, 7}, cube_triangles());
  d.vertex_ids.push_back(8);
  d.vertices.push_back(p[8]);
  expect_rejected(p, d, "identical coordinates");
}

TEST(HullChecker, RejectsConcaveEdge) {
  // Corner 7 pushed inside, past the plane of its three neighbours; the mesh is kept.
  std::vector<Point3> p = cube_points();
  p[7] = {0.3f, 0.3f, 0.3f};
  expect_rejected(p, mesh(p, {0, 1, 2, 3, 4, 5, 6, 7}, cube_triangles()), "is concave");
}

TEST(HullChecker, RejectsOpenAndNonManifoldMeshes) {
  const std::vector<Point3> cube = cube_points();
  std::vector<Triangle> t = cube_triangles();
  t.pop_back();
  expect_rejected(cube, mesh(cube, {0, 1, 2, 3, 4, 5, 6, 7}, t), "not closed");

  // Two tetrahedra sharing vertex 0: every edge has its twin, but the vertex is pinched and V-E+F = 3.
  std::vector<Point3> p = kTetra;
  p.resize(4);
  for (int i = 1; i <= 3; ++i)
    p.push_back({-p[i].x, -p[i].y, -p[i].z});
  std::vector<Triangle> two = kTetraFaces;
  // Second tetrahedron (0, 4, 5, 6): the first reflected through the origin, which reverses orientation.
  for (const Triangle& f : kTetraFaces) {
    auto m = [](std::uint32_t v) { return v == 0 ? 0u : v + 3; };
    two.push_back({m(f[0]), m(f[2]), m(f[1])});
  }
  HullMesh h = mesh(p, {0, 1, 2, 3, 4, 5, 6}, two);
  expect_rejected(p, h, "V - E + F = 3");
  expect_rejected(p, h, "not a manifold point");
}

TEST(HullChecker, RejectsWrongEulerCharacteristic) {
  // Two disjoint tetrahedra: closed and manifold, V - E + F = 4.
  std::vector<Point3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 4; ++i)
    p.push_back({p[i].x + 5, p[i].y, p[i].z});
  std::vector<Triangle> t = kTetraFaces;
  for (const Triangle& f : kTetraFaces)
    t.push_back({f[0] + 4, f[1] + 4, f[2] + 4});
  expect_rejected(p, mesh(p, {0, 1, 2, 3, 4, 5, 6, 7}, t), "V - E + F = 4");
}

TEST(HullChecker, RejectsWrongDimension) {
  // Coplanar points claimed as a 3D hull (a doubled triangle).
  const std::vector<Point3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2f, 0.2f, 0}};
  expect_rejected(flat, mesh(flat, {0, 1, 2}, {{0, 1, 2}, {0, 2, 1}}), "dimension mismatch");
  // A 3D input claimed as a polygon.
  HullMesh poly = mesh(kTetra, {0, 1, 2}, {}, 2);
  poly.polygon = {0, 1, 2};
  expect_rejected(kTetra, poly, "dimension mismatch");
  // Invalid dimension value.
  expect_rejected(kTetra, mesh(kTetra, {0, 1, 2, 3}, kTetraFaces, 4), "invalid dimension");
}

TEST(HullChecker, RejectsWrongCoordinates) {
  HullMesh h = mesh(kTetra, {0, 1, 2, 3}, kTetraFaces);
  h.vertices[2].y = 2;
  expect_rejected(kTetra, h, "but input point 2 is");
  h = mesh(kTetra, {0, 1, 2, 3}, kTetraFaces);
  h.vertex_ids[3] = 99;
  expect_rejected(kTetra, h, "beyond the 5 input points");
}

TEST(HullChecker, LowerDimensions) {
  // Dimension 2: the square z = 0 with an interior point and an edge point.
  const std::vector<Point3> sq = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 0}, {1, 0, 0}};
  HullMesh h = mesh(sq, {0, 1, 2, 3}, {}, 2);
  h.polygon = {0, 1, 2, 3};
  expect_accepted(sq, h);
  h.polygon = {3, 2, 1, 0};  // either orientation
  expect_accepted(sq, h);
  h.polygon = {0, 2, 1, 3};  // not convex (self-intersecting)
  expect_rejected(sq, h, "polygon");
  HullMesh tri = mesh(sq, {0, 1, 2}, {}, 2);  // corner 3 missing
  tri.polygon = {0, 1, 2};
  expect_rejected(sq, tri, "point 3 (0 2 0) is outside the polygon");
  HullMesh edge = mesh(sq, {0, 1, 2, 3, 5}, {}, 2);  // the edge point as a corner
  edge.polygon = {0, 4, 1, 2, 3};
  expect_rejected(sq, edge, "collinear with its neighbours");
  expect_accepted(sq, exact_hull(sq));

  // Dimension 1.
  const std::vector<Point3> line = {{1, 1, 1}, {0, 0, 0}, {3, 3, 3}, {2, 2, 2}};
  expect_accepted(line, mesh(line, {1, 2}, {}, 1));
  expect_rejected(line, mesh(line, {0, 2}, {}, 1), "point 1 (0 0 0) lies on the line beyond");
  expect_rejected(line, mesh(line, {1}, {}, 1), "has 1 vertices");

  // Dimension 0 and empty.
  const std::vector<Point3> same(3, Point3{1, 2, 3});
  expect_accepted(same, mesh(same, {0}, {}, 0));
  expect_rejected(same, mesh(same, {2}, {}, 0), "not the lowest index");
  expect_accepted({}, mesh({}, {}, {}, -1));
  expect_rejected({}, mesh({}, {}, {}, 3), "dimension mismatch");
}

TEST(HullChecker, LimitsTheNumberOfReports) {
  std::vector<Point3> p = ball(3000, 17);
  const HullMesh h = exact_hull(p);
  for (Point3& q : p)
    q = {q.x * 2, q.y * 2, q.z * 2};  // nearly every point outside now
  HullMesh moved = h;  // keep the small hull's coordinates: vertices no longer match their points
  const CheckResult r = check_hull(p, moved, 5);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.failures.size(), 5u);
}

TEST(HullChecker, MillionPointsIsFast) {
  const std::vector<Point3> p = ball(1000000, 3);
  const HullMesh h = exact_hull(p);
  const auto t0 = std::chrono::steady_clock::now();
  const CheckResult r = check_hull(p, h);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  RecordProperty("milliseconds", std::to_string(ms));
  EXPECT_TRUE(r.ok) << joined(r);
  EXPECT_LT(ms, 10000);
}

// ---------------------------------------------------------------------------------------------------------
// Double coordinates (Point3d): every test is exact on the doubles, nothing is rounded to float.

std::vector<Point3> to_float(const std::vector<Point3d>& p) {
  std::vector<Point3> f;
  for (const Point3d& q : p)
    f.push_back({static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)});
  return f;
}

// The cube [-1, 1]^3 (points 0..7) and, on each face, two points 1e-12 outside and one 1e-12 inside.  In
// double the outside points are vertices; in float they round onto the faces.
std::vector<Point3d> cube_with_points_just_off_its_faces() {
  Rng r(31);
  std::vector<Point3d> p;
  for (int c = 0; c < 8; ++c)
    p.push_back({c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0});
  for (int face = 0; face < 6; ++face)
    for (int k = 0; k < 3; ++k) {
      const int axis = face / 2;
      double c[3];
      c[axis] = (face % 2 ? 1.0 : -1.0) * (k < 2 ? 1 + 1e-12 : 1 - 1e-12);
      c[(axis + 1) % 3] = 0.8 * r.unit() + 1e-3 / 3;  // not float-exact
      c[(axis + 2) % 3] = 0.8 * r.unit() - 1e-3 / 7;
      p.push_back({c[0], c[1], c[2]});
    }
  return p;
}

TEST(HullCheckerDouble, AcceptsTheDoubleHullAndRejectsOneMissingAPointOneTrillionthOutside) {
  const std::vector<Point3d> p = cube_with_points_just_off_its_faces();
  const HullMeshd full = exact_hull(p);
  ASSERT_EQ(full.vertex_ids.size(), 8u + 12u);  // the corners and the points just outside
  expect_accepted(p, full);

  // Point 9 is 1e-12 outside the face x = -1: leave it out of the hull.
  const PointIndex missing = 9;
  ASSERT_EQ(p[missing].x, -(1 + 1e-12));
  std::vector<PointIndex> rest;
  for (PointIndex i = 0; i < p.size(); ++i)
    if (i != missing) rest.push_back(i);
  const HullMeshd h = exact_hull(p, rest);
  const CheckResult r = check_hull(p, h);
  EXPECT_FALSE(r.ok);
  // Named with its coordinates in full (17 significant digits: 9 would print -1).
  EXPECT_NE(joined(r).find("point 9 (-1.000000000001"), std::string::npos) << joined(r);
  EXPECT_NE(joined(r).find("is above"), std::string::npos) << joined(r);

  // The same hulls in float: the point rounds onto the face and both hulls are the cube, accepted.
  const std::vector<Point3> pf = to_float(p);
  EXPECT_EQ(exact_hull(pf, rest).vertex_ids.size(), 8u);
  expect_accepted(pf, exact_hull(pf, rest));
}

TEST(HullCheckerDouble, RejectsVertexCoordinatesRoundedToFloat) {
  const std::vector<Point3d> p = cube_with_points_just_off_its_faces();
  HullMeshd h = exact_hull(p);
  const std::size_t k = h.vertices.size() - 1;  // one of the points just outside
  ASSERT_GE(h.vertex_ids[k], 8u);
  Point3d& v = h.vertices[k];
  v = {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
  ASSERT_NE(v, p[h.vertex_ids[k]]);
  expect_rejected(p, h, "has coordinates");
}

TEST(HullCheckerDouble, PointsEqualOnlyInFloatAreNotDuplicates) {
  // A cube and, beyond its face x = 1, two points alone on the plane x = 2 that are equal in float.
  std::vector<Point3d> p;
  for (int c = 0; c < 8; ++c)
    p.push_back({c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0});
  p.push_back({2, 0.375, -0.625});
  p.push_back({2, 0.375 + 1e-9, -0.625});
  const std::vector<Point3> pf = to_float(p);
  ASSERT_EQ(pf[8], pf[9]);
  const HullMeshd h = exact_hull(p);
  ASSERT_EQ(h.vertex_ids.size(), 10u);
  expect_accepted(p, h);
  // The same mesh on the float points: two vertices with identical coordinates.
  HullMesh hf;
  hf.vertex_ids = h.vertex_ids;
  for (PointIndex i : hf.vertex_ids)
    hf.vertices.push_back(pf[i]);
  hf.triangles = h.triangles;
  expect_rejected(pf, hf, "identical coordinates");
  // And a double hull that leaves out point 9 (it is outside the rest's hull).
  std::vector<PointIndex> rest(9);
  std::iota(rest.begin(), rest.end(), 0u);
  expect_rejected(p, exact_hull(p, rest), "point 9 (2 0.37500000100000003 -0.625)");
}

TEST(HullCheckerDouble, LowerDimensionsInDouble) {
  // A segment whose ends differ from interior points only beyond float precision.
  const std::vector<Point3d> seg = {{1e6, 0, 0}, {1e6 + 1e-9, 0, 0}, {1e6 + 2e-9, 0, 0}};
  HullMeshd h = exact_hull(seg);
  EXPECT_EQ(h.dimension, 1);
  EXPECT_EQ(h.vertex_ids, (std::vector<PointIndex>{0, 2}));
  expect_accepted(seg, h);
  HullMeshd short_seg = h;
  short_seg.vertex_ids = {0, 1};
  short_seg.vertices = {seg[0], seg[1]};
  expect_rejected(seg, short_seg, "beyond the segment's ends");
  // A triangle in the plane z = 1 with a point 1e-12 outside one edge: a corner in double.
  const std::vector<Point3d> tri = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0.5 + 1e-12, 0.5, 1}};
  const HullMeshd ht = exact_hull(tri);
  EXPECT_EQ(ht.dimension, 2);
  EXPECT_EQ(ht.vertex_ids.size(), 4u);
  expect_accepted(tri, ht);
  const std::vector<PointIndex> three = {0, 1, 2};
  expect_rejected(tri, exact_hull(tri, three), "is outside the polygon");
}

// Beyond the fast predicates' range the checker takes the wide ones.  On a tetrahedron of side 2^-400 the
// fast orient3d's products underflow (alone they would find the input flat and reject the valid hull); with
// the wide ones the hull passes, and a point 2^-453 outside a face is caught.  NaN is reported, not judged.
TEST(HullCheckerDouble, WideCoordinatesAreCheckedExactly) {
  std::vector<Point3d> cube = cube_with_points_just_off_its_faces();
  for (Point3d& q : cube)
    q = {std::ldexp(q.x, -400), std::ldexp(q.y, -400), std::ldexp(q.z, -400)};
  expect_accepted(cube, exact_hull_any(cube));

  const double s = std::ldexp(1.0, -400);
  const std::vector<Point3d> p{
      {0, 0, 0}, {s, 0, 0}, {0, s, 0}, {0, 0, s}, {s / 4, s / 4, s / 2 * (1 + 0x1p-52)}};
  const HullMeshd full = exact_hull_any(p);
  EXPECT_EQ(full.vertex_ids.size(), 5u);
  expect_accepted(p, full);
  const CheckResult r = check_hull(p, exact_hull_any(p, {0, 1, 2, 3}));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(joined(r).find("point 4 ("), std::string::npos) << joined(r);
  EXPECT_NE(joined(r).find("is above"), std::string::npos) << joined(r);

  std::vector<Point3d> bad = p;
  bad[3].y = std::nan("");
  const CheckResult n = check_hull(bad, full);
  EXPECT_FALSE(n.ok);
  EXPECT_NE(joined(n).find("point 3 ("), std::string::npos) << joined(n);
  EXPECT_NE(joined(n).find("is not finite"), std::string::npos) << joined(n);
}
}  // namespace
}  // namespace cudahull
