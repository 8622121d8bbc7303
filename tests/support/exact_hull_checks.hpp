// What the exact_hull tests hold a hull to: the independent checker (hull_checker.hpp) finding nothing, and
// a brute-force oracle (Caratheodory, exact predicates) for the strictly extreme points of small float sets.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cudahull/hull_checker.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"

namespace cudahull {
namespace {

template <class Point>
void expect_valid(const std::vector<Point>& points, const BasicHullMesh<Point>& hull) {
  const CheckResult r = check_hull(points, hull);
  EXPECT_TRUE(r.ok);
  for (const std::string& f : r.failures)
    ADD_FAILURE() << f;
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

}  // namespace
}  // namespace cudahull
