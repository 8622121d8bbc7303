// Issue 14: the hull is exact for the coordinates as given, in float and in double.  Inputs whose answer
// changes under rounding to float, run through the engine in both precisions and checked against
// independent answers: a brute-force oracle (a point is a vertex unless it lies in a closed tetrahedron,
// triangle or segment of other points, or repeats an earlier point) on small sets, exact_hull on larger ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cudahull/cpu_backend.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/predicates.hpp"
#include "support/rng.hpp"

namespace cudahull {
namespace {

using testing::Rng;

// Is p in the closed convex hull of the points `others` (indices into `pts`)?  Exact, O(k^4).
template <class Point>
bool in_hull_of(const std::vector<Point>& pts, const std::vector<std::size_t>& others, const Point& p) {
  const Vec3d x = to_vec3d(p);
  auto P = [&](std::size_t i) { return to_vec3d(pts[others[i]]); };
  const std::size_t k = others.size();
  for (std::size_t a = 0; a < k; ++a) {
    if (P(a).x == x.x && P(a).y == x.y && P(a).z == x.z) return true;
    for (std::size_t b = a + 1; b < k; ++b) {
      // On the segment ab: collinear and between on every axis.
      if (collinear3d(P(a), P(b), x) && std::min(P(a).x, P(b).x) <= x.x && x.x <= std::max(P(a).x, P(b).x) &&
          std::min(P(a).y, P(b).y) <= x.y && x.y <= std::max(P(a).y, P(b).y) &&
          std::min(P(a).z, P(b).z) <= x.z && x.z <= std::max(P(a).z, P(b).z))
        return true;
      for (std::size_t c = b + 1; c < k; ++c) {
        if (collinear3d(P(a), P(b), P(c))) continue;
        if (orient3d(P(a), P(b), P(c), x) == 0) {
          // In the triangle: seen from any point q off its plane, x is in the cone over abc.
          Vec3d q = P(a);
          for (const Vec3d& step : {Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1}}) {
            const double scale = 1 + std::fabs(q.x) + std::fabs(q.y) + std::fabs(q.z);
            const Vec3d t{P(a).x + step.x * scale, P(a).y + step.y * scale, P(a).z + step.z * scale};
            if (orient3d(P(a), P(b), P(c), t) != 0) {
              q = t;
              break;
            }
          }
          const int s = orient3d(q, P(a), P(b), P(c));
          if (orient3d(q, P(a), P(b), x) * s >= 0 && orient3d(q, P(b), P(c), x) * s >= 0 &&
              orient3d(q, P(c), P(a), x) * s >= 0)
            return true;
        }
        for (std::size_t d = c + 1; d < k; ++d) {
          const int s = orient3d(P(a), P(b), P(c), P(d));
          if (s == 0) continue;
          if (orient3d(x, P(b), P(c), P(d)) * s >= 0 && orient3d(P(a), x, P(c), P(d)) * s >= 0 &&
              orient3d(P(a), P(b), x, P(d)) * s >= 0 && orient3d(P(a), P(b), P(c), x) * s >= 0)
            return true;
        }
      }
    }
  }
  return false;
}

// The strictly extreme points, lowest index among duplicates, by brute force.
template <class Point>
std::vector<PointIndex> brute_force_vertices(const std::vector<Point>& pts) {
  std::vector<PointIndex> out;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    std::vector<std::size_t> others;
    bool repeated = false;
    for (std::size_t j = 0; j < pts.size(); ++j) {
      if (j == i) continue;
      if (pts[j] == pts[i]) {
        if (j < i) repeated = true;
        continue;  // a later copy of i is not another point
      }
      others.push_back(j);
    }
    if (!repeated && !in_hull_of(pts, others, pts[i])) out.push_back(static_cast<PointIndex>(i));
  }
  return out;
}

template <class Point>
std::vector<PointIndex> engine_vertices(const std::vector<Point>& pts) {
  BasicEngine<Point> engine(pts, make_cpu_backend<Point>(2));
  engine.run();
  const CheckResult check = check_hull(pts, engine.result());
  EXPECT_TRUE(check.ok) << (check.failures.empty() ? "" : check.failures.front());
  return engine.result().vertex_ids;
}

std::vector<Point3> to_float(const std::vector<Point3d>& pts) {
  std::vector<Point3> out;
  for (const Point3d& p : pts)
    out.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  return out;
}

// Both precisions against the brute force, and the answers differ (the input really needs double).
void expect_exact_in_both(const std::vector<Point3d>& pts) {
  const std::vector<Point3> narrow = to_float(pts);
  const std::vector<PointIndex> wide_answer = brute_force_vertices(pts),
                                narrow_answer = brute_force_vertices(narrow);
  EXPECT_EQ(engine_vertices(pts), wide_answer);
  EXPECT_EQ(engine_vertices(narrow), narrow_answer);
  EXPECT_NE(wide_answer, narrow_answer) << "the set does not depend on the precision: a weak test";
}

TEST(Precision, PointsJustOutsideACubesFacesAreVerticesOnlyInDouble) {
  Rng r(1);
  std::vector<Point3d> pts;
  for (int c = 0; c < 8; ++c)
    pts.push_back({c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0});
  for (int k = 0; k < 18; ++k) {  // 1e-12 outside a face: on the face once rounded to float
    const int axis = k % 3;
    const double side = (k / 3) % 2 ? 1 : -1;
    double q[3] = {0.9 * r.unit(), 0.9 * r.unit(), 0.9 * r.unit()};
    q[axis] = side * (1 + 1e-12 * (1 + k));
    pts.push_back({q[0], q[1], q[2]});
  }
  expect_exact_in_both(pts);
}

TEST(Precision, PointsEqualInFloatButDistinctInDoubleAreTwoVertices) {
  Rng r(2);
  std::vector<Point3d> pts;
  for (int k = 0; k < 12; ++k) {
    const Point3d p{r.unit(), r.unit(), r.unit()};
    const double n = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z) + 1e-3;
    const Point3d s{p.x / n, p.y / n, p.z / n};  // on a sphere: every point extreme
    pts.push_back(s);
    pts.push_back({s.x * (1 + 1e-10), s.y * (1 + 1e-10), s.z * (1 + 1e-10)});  // the same float
  }
  expect_exact_in_both(pts);
}

TEST(Precision, NearCoplanarRingsKeepTheirSmallHeights) {
  // A ring in the plane z = 1, an inner ring 1e-12 above it (in that plane once rounded to float, and then
  // inside the outer ring's polygon), and an apex below.
  Rng r(3);
  std::vector<Point3d> pts{{0, 0, -1}};
  for (int k = 0; k < 9; ++k) {
    const double a = 2 * M_PI * k / 9, b = 2 * M_PI * (k + 0.5) / 9;
    pts.push_back({std::cos(a), std::sin(a), 1});
    pts.push_back({0.5 * std::cos(b), 0.5 * std::sin(b), 1 + 1e-12 * (1.5 + r.unit())});
  }
  expect_exact_in_both(pts);
}

TEST(Precision, BallAMillionFromTheOriginAgainstExactHull) {
  Rng r(4);
  std::vector<Point3d> pts;
  while (pts.size() < 20000) {
    const Point3d d{r.unit(), r.unit(), r.unit()};
    if (d.x * d.x + d.y * d.y + d.z * d.z > 1) continue;
    pts.push_back({1e6 + d.x, 1e6 + d.y, -1e6 + d.z});
  }
  const std::vector<Point3> narrow = to_float(pts);
  const std::vector<PointIndex> wide = engine_vertices(pts), flat = engine_vertices(narrow);
  EXPECT_EQ(wide, exact_hull(pts).vertex_ids);
  EXPECT_EQ(flat, exact_hull(narrow).vertex_ids);
  // float's spacing there is 0.0625: the rounded ball is a coarse lattice with far fewer hull vertices.
  EXPECT_GT(wide.size(), 2 * flat.size());
}

}  // namespace
}  // namespace cudahull
