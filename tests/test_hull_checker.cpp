// The independent checker: accepts correct hulls (hand-made and from exact_hull) and rejects each kind of
// corruption with a message that names the problem.
#include "cudahull/hull_checker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
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
void expect_rejected(const std::vector<Point3>& pts, const HullMesh& h, const std::string& needle) {
  const CheckResult r = check_hull(pts, h);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.failures.empty());
  EXPECT_NE(joined(r).find(needle), std::string::npos) << "expected \"" << needle << "\" in:\n" << joined(r);
}

void expect_accepted(const std::vector<Point3>& pts, const HullMesh& h) {
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

}  // namespace
}  // namespace cudahull
