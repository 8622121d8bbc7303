// merge_facets (api/src/facet_merge.hpp): Qhull-like merging of the exact hull, checked against Qhull itself
// and re-checked independently: vertex counts equal Qhull's (scipy's ConvexHull default, "Qt") on rotated
// CAD-like parts, no sliver triangles, max_outside re-verified in long double, exact convexity, coplanar
// lists, and no change on inputs without near-degeneracies.
#include "facet_merge.hpp"
#include "support/rng.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/predicates.hpp"
#include "qhull_reference.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace cudahull {
namespace {

using testing::Rng;
using Long = long double;

struct V2 {
  double x, y;
};

// A uniform double in [0, 1).
double uniform(Rng& r) {
  return static_cast<double>(r.next() >> 11) * 0x1p-53;
}

// The outline of a rectangle [-a, a] x [-b, b], counter-clockwise, with two opposite corners chamfered
// (legs `chamfer`) and two rounded (quarter circles of radius `radius` sampled as `segments`-gons).
std::vector<V2> profile(double a, double b, double chamfer, double radius, int segments) {
  std::vector<V2> out;
  const double pi = std::acos(-1.0);
  auto fillet = [&](double cx, double cy, double start) {
    for (int k = 0; k <= segments; ++k) {
      const double angle = start + (pi / 2) * k / segments;
      out.push_back({cx + radius * std::cos(angle), cy + radius * std::sin(angle)});
    }
  };
  fillet(a - radius, b - radius, 0);  // (+a, +b): rounded
  out.push_back({-a + chamfer, b});   // (-a, +b): chamfered
  out.push_back({-a, b - chamfer});
  fillet(-a + radius, -b + radius, pi);  // (-a, -b): rounded
  out.push_back({a - chamfer, -b});      // (+a, -b): chamfered
  out.push_back({a, -b + chamfer});
  return out;
}

// A CAD-like part: the profile extruded over z in [-h, h], its top and bottom edges chamfered by `c` (the
// outline inset by c at z = +-h), points sampled densely on its flat faces and along its edges, then rotated
// by a random rotation and moved, in double.  Its true vertices are the four outlines' corners.
struct Part {
  std::vector<Point3d> points;
  std::size_t true_vertices = 0;
};

Part cad_part(std::uint64_t seed, int segments) {
  Rng r(seed);
  const double a = 20 + 10 * uniform(r), b = 10 + 5 * uniform(r), h = 4 + 2 * uniform(r), c = 0.75,
               chamfer = 3, radius = 4;
  const std::vector<V2> outer = profile(a, b, chamfer, radius, segments),
                        inner = profile(a - c, b - c, chamfer - 0.5 * c, radius - c, segments);
  struct Layer {
    const std::vector<V2>* outline;
    double z;
  };
  const Layer layers[4] = {{&inner, -h}, {&outer, -h + c}, {&outer, h - c}, {&inner, h}};
  std::vector<std::array<double, 3>> p;
  auto at = [](const Layer& l, std::size_t i) {
    const V2 q = (*l.outline)[i % l.outline->size()];
    return std::array<double, 3>{q.x, q.y, l.z};
  };
  auto mix = [](const std::array<double, 3>& u, const std::array<double, 3>& v, double t) {
    return std::array<double, 3>{u[0] + t * (v[0] - u[0]), u[1] + t * (v[1] - u[1]),
                                 u[2] + t * (v[2] - u[2])};
  };
  const std::size_t n = outer.size();
  for (const Layer& l : layers)
    for (std::size_t i = 0; i < n; ++i)
      p.push_back(at(l, i));
  // Along every edge of the outlines and every edge between layers.
  for (const Layer& l : layers)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 1; k < 24; ++k)
        p.push_back(mix(at(l, i), at(l, i + 1), k / 24.0));
  for (int j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 1; k < 12; ++k)
        p.push_back(mix(at(layers[j], i), at(layers[j + 1], i), k / 12.0));
  // On every side quad (planar: its two outline edges are parallel) and on the top and bottom faces.
  for (int j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 12; ++k) {
        const double s = uniform(r), t = uniform(r);
        p.push_back(mix(mix(at(layers[j], i), at(layers[j], i + 1), s),
                        mix(at(layers[j + 1], i), at(layers[j + 1], i + 1), s), t));
      }
  for (int j : {0, 3})
    for (int k = 0; k < 400; ++k) {
      const std::size_t i = r.below(n);
      const double s = uniform(r), t = uniform(r) * (1 - s);
      const std::array<double, 3> o{0, 0, layers[j].z};
      p.push_back(mix(mix(o, at(layers[j], i), s + t), at(layers[j], i + 1), s + t > 0 ? t / (s + t) : 0));
    }
  // A random rotation (unit quaternion) and translation.
  double q[4];
  double norm = 0;
  for (double& x : q) {
    x = 2 * uniform(r) - 1;
    norm += x * x;
  }
  norm = std::sqrt(norm);
  for (double& x : q)
    x /= norm;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  const double shift[3] = {100 * uniform(r) - 50, 100 * uniform(r) - 50, 100 * uniform(r) - 50};
  Part part;
  for (const auto& v : p) {
    double out[3];
    for (int i = 0; i < 3; ++i)
      out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] + shift[i];
    part.points.push_back({out[0], out[1], out[2]});
  }
  part.true_vertices = 4 * n;
  return part;
}

template <class Point>
Vec3d at(const std::vector<Point>& p, PointIndex i) {
  return to_vec3d(p[i]);
}

// Everything about a merged hull that does not need Qhull, checked independently of facet_merge.cpp.
template <class Point>
void check_merged(const std::vector<Point>& points, const BasicHullMesh<Point>& exact,
                  const MergedHull& merged, double tolerance, const std::string& what,
                  bool check_slivers = true) {
  SCOPED_TRACE(what);
  ASSERT_EQ(merged.tolerance, tolerance);
  ASSERT_TRUE(std::is_sorted(merged.vertices.begin(), merged.vertices.end()));
  const std::size_t nf = merged.faces.size();
  ASSERT_EQ(merged.planes.size(), nf);
  ASSERT_EQ(merged.facet_of_face.size(), nf);
  ASSERT_GE(nf, 4u);

  // A closed, oriented 2-manifold on exactly the kept vertices, with V - E + F = 2.
  std::set<PointIndex> used;
  std::map<std::pair<PointIndex, PointIndex>, std::size_t> edges;
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      used.insert(merged.faces[f][k]);
      ASSERT_TRUE(edges.emplace(std::make_pair(merged.faces[f][k], merged.faces[f][(k + 1) % 3]), f).second);
    }
  for (const auto& [edge, f] : edges)
    ASSERT_TRUE(edges.count({edge.second, edge.first})) << "open edge";
  ASSERT_EQ(std::vector<PointIndex>(used.begin(), used.end()), merged.vertices);
  ASSERT_EQ(
      static_cast<long>(merged.vertices.size()) - static_cast<long>(edges.size() / 2) + static_cast<long>(nf),
      2);

  // Exactly convex: every kept vertex on or below every triangle's exact plane (outward orientation).
  for (const auto& t : merged.faces) {
    const Vec3d a = at(points, t[0]), b = at(points, t[1]), c = at(points, t[2]);
    for (PointIndex v : merged.vertices)
      ASSERT_LE(orient3d(a, b, c, at(points, v)), 0) << "vertex " << v << " above a face";
  }

  // No sliver: every triangle's smallest altitude (2 area / longest side) exceeds the tolerance.
  if (tolerance > 0 && check_slivers)
    for (const auto& t : merged.faces) {
      Long p[3][3];
      for (int k = 0; k < 3; ++k) {
        const Vec3d v = at(points, t[k]);
        p[k][0] = v.x, p[k][1] = v.y, p[k][2] = v.z;
      }
      Long u[3], w[3], longest = 0;
      for (int i = 0; i < 3; ++i)
        u[i] = p[1][i] - p[0][i], w[i] = p[2][i] - p[0][i];
      const Long cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2],
                 cz = u[0] * w[1] - u[1] * w[0];
      for (int k = 0; k < 3; ++k) {
        Long s = 0;
        for (int i = 0; i < 3; ++i)
          s += (p[(k + 1) % 3][i] - p[k][i]) * (p[(k + 1) % 3][i] - p[k][i]);
        longest = std::max(longest, std::sqrt(s));
      }
      EXPECT_GT(std::sqrt(cx * cx + cy * cy + cz * cz) / longest, tolerance) << "sliver triangle";
    }

  // Planes: unit normals, one per merged facet, pointing the triangle's way.
  std::map<std::uint32_t, std::array<double, 4>> facet_plane;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& pl = merged.planes[f];
    EXPECT_NEAR(std::sqrt(Long(pl[0]) * pl[0] + Long(pl[1]) * pl[1] + Long(pl[2]) * pl[2]), 1.0L, 1e-14L);
    const auto [it, fresh] = facet_plane.emplace(merged.facet_of_face[f], pl);
    EXPECT_TRUE(fresh || it->second == pl) << "triangles of one facet with different planes";
    const Vec3d a = at(points, merged.faces[f][0]), b = at(points, merged.faces[f][1]),
                c = at(points, merged.faces[f][2]);
    const Long nx = (Long(b.y) - a.y) * (Long(c.z) - a.z) - (Long(b.z) - a.z) * (Long(c.y) - a.y);
    const Long ny = (Long(b.z) - a.z) * (Long(c.x) - a.x) - (Long(b.x) - a.x) * (Long(c.z) - a.z);
    const Long nz = (Long(b.x) - a.x) * (Long(c.y) - a.y) - (Long(b.y) - a.y) * (Long(c.x) - a.x);
    EXPECT_GT(nx * pl[0] + ny * pl[1] + nz * pl[2], 0) << "plane against the triangle's orientation";
  }

  // max_outside, re-checked by brute force in long double over every input point and every triangle.
  Long worst = -INFINITY;
  for (const auto& [id, pl] : facet_plane)
    for (const Point& q : points)
      worst = std::max(worst, Long(pl[0]) * q.x + Long(pl[1]) * q.y + Long(pl[2]) * q.z + Long(pl[3]));
  EXPECT_LE(worst, Long(merged.max_outside)) << "max_outside does not hold";
  EXPECT_GE(merged.max_outside, 0);

  // coplanar: exactly the exact-hull vertices not kept, ascending, with a valid triangle and one of its
  // corners.
  std::vector<PointIndex> dropped;
  for (PointIndex v : exact.vertex_ids)
    if (!std::binary_search(merged.vertices.begin(), merged.vertices.end(), v)) dropped.push_back(v);
  std::sort(dropped.begin(), dropped.end());
  ASSERT_EQ(merged.coplanar.size(), dropped.size());
  for (std::size_t k = 0; k < dropped.size(); ++k) {
    const auto& row = merged.coplanar[k];
    EXPECT_EQ(row[0], dropped[k]);
    ASSERT_LT(row[1], nf);
    const auto& t = merged.faces[row[1]];
    EXPECT_TRUE(row[2] == t[0] || row[2] == t[1] || row[2] == t[2]);
  }
  // Every kept vertex is an exact-hull vertex.
  for (PointIndex v : merged.vertices)
    EXPECT_TRUE(std::binary_search(exact.vertex_ids.begin(), exact.vertex_ids.end(), v));
}

// Qhull's own roundoff constants for a run with scipy's default options ("Qt"), read from libqhull_r.
struct QhullConstants {
  double dist_round = 0, min_outside = 0, premerge_centrum = 0;
};
QhullConstants qhull_constants(const std::vector<Point3d>& points) {
  std::vector<coordT> coords;
  for (const Point3d& p : points)
    coords.insert(coords.end(), {p.x, p.y, p.z});
  std::FILE* err = std::fopen("/dev/null", "w");
  auto storage = std::make_unique<qhT>();
  qhT* qh = storage.get();
  qh_zero(qh, err);
  char command[] = "qhull Qt";
  const int code =
      qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, command, nullptr, err);
  QhullConstants constants;
  if (code == 0) constants = {qh->DISTround, qh->MINoutside, qh->premerge_centrum};
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(err);
  return constants;
}

TEST(FacetMerge, QhullDefaultToleranceIsQhullsMinOutside) {
  // By the formula (facet_merge.cpp): maxabs per axis (3, 4, 12): MAXabs_coord 12, MAXsumcoord 19,
  // maxdistsum = min(12 sqrt 3, 19) = 19.
  const std::vector<Point3d> p = {{-3, 1, 0}, {2, -4, 12}, {1, 1, -5}, {0.5, 0.25, 0.125}};
  EXPECT_DOUBLE_EQ(qhull_default_tolerance(p), 4 * DBL_EPSILON * (3 * 19 * 1.01 + 12));
  // maxabs (10, 10, 10): maxdistsum = min(10 sqrt 3, 30) = 10 sqrt 3.
  const std::vector<Point3> f = {{10, -10, 10}, {0, 0, 0}};
  EXPECT_DOUBLE_EQ(qhull_default_tolerance(f), 4 * DBL_EPSILON * (3 * std::sqrt(3.0) * 10 * 1.01 + 10));
  EXPECT_EQ(qhull_default_tolerance(std::vector<Point3d>{}), 0);
  // And as Qhull itself computes it, on a few point sets of different magnitudes and shapes.
  EXPECT_DOUBLE_EQ(qhull_default_tolerance(p), qhull_constants(p).min_outside);
  Rng r(3);
  for (double scale : {1e-3, 1.0, 37.0, 1e6}) {
    std::vector<Point3d> q;
    for (int i = 0; i < 200; ++i)
      q.push_back(
          {scale * (uniform(r) - 0.3), 0.5 * scale * (uniform(r) - 0.9), 2 * scale * uniform(r) + scale});
    const QhullConstants c = qhull_constants(q);
    ASSERT_GT(c.dist_round, 0);
    EXPECT_DOUBLE_EQ(qhull_default_tolerance(q), c.min_outside) << scale;
    EXPECT_DOUBLE_EQ(c.min_outside, 4 * c.dist_round);
    EXPECT_DOUBLE_EQ(c.premerge_centrum, 2 * c.dist_round);
  }
}

// The case that asked for merging: rotated parts whose exact hulls keep 1e-16-high slivers.
TEST(FacetMerge, RotatedCadPartsMatchQhullsVertexCount) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const Part part = cad_part(seed, 2 + static_cast<int>(seed % 4));
    const std::string what = "seed " + std::to_string(seed);
    const HullMeshd exact = exact_hull(part.points);
    ASSERT_EQ(exact.dimension, 3);
    const double tolerance = qhull_default_tolerance(part.points);
    const MergedHull merged = merge_facets(part.points, exact, tolerance);
    const QhullResult qhull = run_qhull(part.points, "Qt");  // scipy's ConvexHull default in 3-D
    std::printf(
        "[ part %llu ] points %zu  exact vertices %zu  merged %zu  qhull %zu  true %zu  facets %u  "
        "tolerance %.3g  max_outside %.3g\n",
        static_cast<unsigned long long>(seed), part.points.size(), exact.vertex_ids.size(),
        merged.vertices.size(), qhull.vertex_ids.size(), part.true_vertices,
        merged.facet_of_face.empty()
            ? 0u
            : *std::max_element(merged.facet_of_face.begin(), merged.facet_of_face.end()) + 1,
        tolerance, merged.max_outside);
    EXPECT_GT(exact.vertex_ids.size(), merged.vertices.size()) << what << ": nothing to merge?";
    EXPECT_EQ(merged.vertices.size(), qhull.vertex_ids.size()) << what;
    EXPECT_EQ(merged.vertices, qhull.vertex_ids) << what;  // the very same points
    EXPECT_EQ(merged.vertices.size(), part.true_vertices) << what;
    check_merged(part.points, exact, merged, tolerance, what);
    // The certificate stays a few tolerances: merging only dropped near-coplanar points.
    EXPECT_LT(merged.max_outside, 10 * tolerance) << what;
  }
}

// A scan-like box: points sampled on a rotated box's faces and edges (none at its corners).
TEST(FacetMerge, RotatedScannedBoxMatchesQhull) {
  Rng r(21);
  double q[4], norm = 0;
  for (double& x : q) {
    x = 2 * uniform(r) - 1;
    norm += x * x;
  }
  for (double& x : q)
    x /= std::sqrt(norm);
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  const double half[3] = {3, 2, 1};
  std::vector<Point3d> points;
  for (int i = 0; i < 20000; ++i) {
    double v[3];
    for (int k = 0; k < 3; ++k)
      v[k] = (2 * uniform(r) - 1) * half[k];
    const int face = i % 6, axis = face / 2;
    v[axis] = (face % 2 ? 1 : -1) * half[axis];
    if (i % 7 == 0) v[(axis + 1) % 3] = (i % 2 ? 1 : -1) * half[(axis + 1) % 3];  // on an edge
    points.push_back({m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2] + 5,
                      m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2] - 3,
                      m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2] + 1});
  }
  const HullMeshd exact = exact_hull(points);
  const double tolerance = qhull_default_tolerance(points);
  const MergedHull merged = merge_facets(points, exact, tolerance);
  const QhullResult qhull = run_qhull(points, "Qt");
  std::printf("[ scanned box ] points %zu  exact vertices %zu  merged %zu  qhull %zu  max_outside %.3g\n",
              points.size(), exact.vertex_ids.size(), merged.vertices.size(), qhull.vertex_ids.size(),
              merged.max_outside);
  EXPECT_LT(merged.vertices.size(), exact.vertex_ids.size());
  EXPECT_EQ(merged.vertices, qhull.vertex_ids);
  check_merged(points, exact, merged, tolerance, "scanned box");
}

// Explicit tolerances: a larger one merges at least as much, and every result is still certified.
TEST(FacetMerge, ExplicitTolerancesAreCertified) {
  const Part part = cad_part(11, 3);
  const HullMeshd exact = exact_hull(part.points);
  std::size_t previous = exact.vertex_ids.size() + 1;
  for (double tolerance : {0.0, 1e-12, 1e-9, 1e-3, 0.2}) {
    const MergedHull merged = merge_facets(part.points, exact, tolerance);
    std::printf("[ tolerance %g ] vertices %zu (exact %zu)  coplanar %zu  max_outside %.3g\n", tolerance,
                merged.vertices.size(), exact.vertex_ids.size(), merged.coplanar.size(), merged.max_outside);
    check_merged(part.points, exact, merged, tolerance, "tolerance " + std::to_string(tolerance));
    EXPECT_LE(merged.vertices.size(), previous);
    previous = merged.vertices.size();
  }
  // 0 merges only exactly coplanar triangles: every vertex stays.
  EXPECT_EQ(merge_facets(part.points, exact, 0.0).vertices, exact.vertex_ids);
  EXPECT_THROW(merge_facets(part.points, exact, -1.0), std::invalid_argument);
  EXPECT_THROW(merge_facets(part.points, exact, NAN), std::invalid_argument);
}

// Without near-degeneracies a tiny tolerance changes nothing: random points in a ball (float) and on a
// sphere (double).
TEST(FacetMerge, TinyToleranceChangesNothingOnBallsAndSpheres) {
  Rng r(5);
  std::vector<Point3> ball;
  while (ball.size() < 4000) {
    const Point3 q{r.unit(), r.unit(), r.unit()};
    if (double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z <= 1) ball.push_back(q);
  }
  std::vector<Point3d> sphere;
  for (int i = 0; i < 2000; ++i) {
    const double z = 2 * uniform(r) - 1, phi = 2 * std::acos(-1.0) * uniform(r), s = std::sqrt(1 - z * z);
    sphere.push_back({7 * s * std::cos(phi), 7 * s * std::sin(phi), 7 * z});
  }
  const HullMesh exact_ball = exact_hull(ball);
  const HullMeshd exact_sphere = exact_hull(sphere);
  for (double scale : {0.0, 1.0}) {
    const double tb = scale * qhull_default_tolerance(ball), ts = scale * qhull_default_tolerance(sphere);
    const MergedHull mb = merge_facets(ball, exact_ball, tb), ms = merge_facets(sphere, exact_sphere, ts);
    EXPECT_EQ(mb.vertices, exact_ball.vertex_ids);
    EXPECT_EQ(mb.faces.size(), exact_ball.triangles.size());
    EXPECT_TRUE(mb.coplanar.empty());
    EXPECT_EQ(ms.vertices, exact_sphere.vertex_ids);
    EXPECT_EQ(ms.faces.size(), exact_sphere.triangles.size());
    check_merged(ball, exact_ball, mb, tb, "ball");
    check_merged(sphere, exact_sphere, ms, ts, "sphere");
    // Qhull agrees on these.
    EXPECT_EQ(run_qhull(ball).vertex_ids, mb.vertices);
    EXPECT_EQ(run_qhull(sphere).vertex_ids, ms.vertices);
  }
}

// Large merges (above 4096 vertices: the spatial visit order and the relabelled mesh of facet_merge.cpp)
// give what the merge gave before those (pinned: the same vertices, triangles, planes, coplanar rows,
// max_outside and thinnest, digested), and each triangle's neighbours are the triangles across its edges.
std::uint64_t digest(const MergedHull& m) {
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&](const void* data, std::size_t bytes) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i)
      h = (h ^ c[i]) * 1099511628211ull;
  };
  mix(m.vertices.data(), m.vertices.size() * sizeof m.vertices[0]);
  mix(m.faces.data(), m.faces.size() * sizeof m.faces[0]);
  mix(m.planes.data(), m.planes.size() * sizeof m.planes[0]);
  mix(m.facet_of_face.data(), m.facet_of_face.size() * sizeof m.facet_of_face[0]);
  mix(m.coplanar.data(), m.coplanar.size() * sizeof m.coplanar[0]);
  mix(&m.max_outside, sizeof m.max_outside);
  mix(&m.thinnest, sizeof m.thinnest);
  return h;
}

TEST(FacetMerge, LargeMergesKeepTheirResults) {
  Rng r(17);
  std::vector<Point3d> sphere, box;
  for (int i = 0; i < 20000; ++i) {
    const double z = 2 * uniform(r) - 1, phi = 2 * std::acos(-1.0) * uniform(r), s = std::sqrt(1 - z * z);
    sphere.push_back({3 * s * std::cos(phi), 3 * s * std::sin(phi), 3 * z});
  }
  // A 1500-sided prism's corners and points on its sides, with noise of the order of Qhull's roundoff:
  // thousands of vertices, and merging drops thousands.
  const int sides = 1500;
  for (int i = 0; i < sides; ++i)
    for (double z : {-1.0, 1.0})
      box.push_back(
          {std::cos(2 * std::acos(-1.0) * i / sides), std::sin(2 * std::acos(-1.0) * i / sides), z});
  for (int i = 0; i < 40000; ++i) {
    const Point3d a = box[2 * (i % sides)], b = box[2 * ((i + 1) % sides)];
    const double t = uniform(r), z = 2 * uniform(r) - 1;
    box.push_back({(1 - t) * a.x + t * b.x + 2e-16 * (uniform(r) - 0.5),
                   (1 - t) * a.y + t * b.y + 2e-16 * (uniform(r) - 0.5), z});
  }
  struct Expected {
    const std::vector<Point3d>* points;
    std::size_t vertices;
    std::uint64_t digest;
  };
  // Pinned at d99821d (before the visit order).
  for (const Expected& e :
       {Expected{&sphere, 20000, 0x1a02239e440b4a27ull}, Expected{&box, 3000, 0x5196ac18ec9e7045ull}}) {
    const HullMeshd exact = exact_hull(*e.points);
    const MergedHull merged = merge_facets(*e.points, exact, qhull_default_tolerance(*e.points));
    std::printf("[ large ] exact %zu  merged %zu  coplanar %zu  digest %016llx\n", exact.vertex_ids.size(),
                merged.vertices.size(), merged.coplanar.size(),
                static_cast<unsigned long long>(digest(merged)));
    EXPECT_EQ(merged.vertices.size(), e.vertices);
    EXPECT_EQ(digest(merged), e.digest);
    std::map<std::pair<PointIndex, PointIndex>, std::int32_t> holding;  // directed edge -> triangle
    for (std::size_t f = 0; f < merged.faces.size(); ++f)
      for (int k = 0; k < 3; ++k)
        holding[{merged.faces[f][k], merged.faces[f][(k + 1) % 3]}] = static_cast<std::int32_t>(f);
    ASSERT_EQ(merged.neighbors.size(), merged.faces.size());
    for (std::size_t f = 0; f < merged.faces.size(); ++f)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(merged.neighbors[f][k],
                  (holding[{merged.faces[f][(k + 2) % 3], merged.faces[f][(k + 1) % 3]}]));
  }
}

// MergedHull::thinnest (Qhull's flatness test, QH6154) against the brute force, max over the merged hull's
// vertices of -(n . p + d) per facet, min over facets: within rounding of it on slabs a few ulps to a few
// tolerances thick; on a ball, above 4 x the tolerance and at most the brute force (a lower bound there).
TEST(FacetMerge, ThinnestIsTheLeastDepthBelowAFacet) {
  Rng r(17);
  const auto brute_force = [](const std::vector<Point3d>& points, const MergedHull& merged) {
    double least = INFINITY;
    for (const auto& plane : merged.planes) {
      double depth = -INFINITY;
      for (PointIndex v : merged.vertices) {
        const Point3d& p = points[v];
        depth = std::max(depth, -(plane[0] * p.x + plane[1] * p.y + plane[2] * p.z + plane[3]));
      }
      least = std::min(least, depth);
    }
    return least;
  };
  int thin = 0, thick = 0;
  for (const double thickness : {1e-16, 1e-15, 3e-15, 2e-14, 1e-13}) {
    SCOPED_TRACE("thickness " + std::to_string(thickness));
    // A tilted slab of 300 points: z = x / 3 - y / 5 + thickness times a number in [0, 1].
    std::vector<Point3d> slab;
    for (int i = 0; i < 300; ++i) {
      const double x = r.unit(), y = r.unit();
      slab.push_back({x, y, x / 3 - y / 5 + thickness * uniform(r)});
    }
    const HullMeshd exact = exact_hull(slab);
    ASSERT_EQ(exact.dimension, 3);
    const double tolerance = qhull_default_tolerance(slab);
    const MergedHull merged = merge_facets(slab, exact, tolerance);
    const double expected = brute_force(slab, merged);
    if (expected <= 4 * tolerance) {
      ++thin;
      EXPECT_NEAR(merged.thinnest, expected, 1e-16);
    } else {
      ++thick;
      EXPECT_GT(merged.thinnest, 4 * tolerance);
      EXPECT_LE(merged.thinnest, expected + 1e-16);
    }
  }
  EXPECT_GE(thin, 2);  // both branches met
  EXPECT_GE(thick, 1);
  std::vector<Point3d> ball;
  while (ball.size() < 2000) {
    const Point3d q{r.unit(), r.unit(), r.unit()};
    if (q.x * q.x + q.y * q.y + q.z * q.z <= 1) ball.push_back(q);
  }
  const HullMeshd exact = exact_hull(ball);
  const double tolerance = qhull_default_tolerance(ball);
  const MergedHull merged = merge_facets(ball, exact, tolerance);
  EXPECT_GT(merged.thinnest, 4 * tolerance);
  EXPECT_LE(merged.thinnest, brute_force(ball, merged) + 1e-15);
  EXPECT_GT(merged.thinnest, 0.5);  // the centroid lies deep inside a ball of radius about 1
}

// A tolerance beyond the part's thickness: merging stops before the hull turns flat.
TEST(FacetMerge, NeverMergesDownToFlat) {
  Rng r(9);
  std::vector<Point3d> slab;
  for (int i = 0; i < 300; ++i)
    slab.push_back({uniform(r), uniform(r), 1e-9 * uniform(r)});
  const HullMeshd exact = exact_hull(slab);
  ASSERT_EQ(exact.dimension, 3);
  const MergedHull merged = merge_facets(slab, exact, 1e-6);
  EXPECT_GE(merged.vertices.size(), 4u);
  EXPECT_LT(merged.vertices.size(), exact.vertex_ids.size());
  // Its triangles are slivers by construction (thinner than the tolerance): every other check holds.
  check_merged(slab, exact, merged, 1e-6, "slab", false);
}

// A hull of lower dimension comes back as is.
TEST(FacetMerge, FlatInputIsReturnedAsIs) {
  const std::vector<Point3d> square = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 1}};
  const HullMeshd exact = exact_hull(square);
  ASSERT_EQ(exact.dimension, 2);
  const MergedHull merged = merge_facets(square, exact, 1e-9);
  EXPECT_EQ(merged.vertices, (std::vector<PointIndex>{0, 1, 2, 3}));
  EXPECT_TRUE(merged.faces.empty());
}

}  // namespace
}  // namespace cudahull
