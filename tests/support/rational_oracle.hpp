// An oracle in GMP rationals for every finite double (mpq_set_d converts a finite double exactly; nothing of
// the code under test is used): the predicates' signs, and for hulls a brute force over all triples of
// points (a triple spans a supporting plane when no point is strictly on either side of it; the hull's
// vertices are the extreme points of the point sets on those planes).  Link GMP::GMP.
#pragma once

#include <gmp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull {
namespace {

// ---------------------------------------------------------------------------------------------------------
// The oracle's arithmetic: GMP rationals, exact for every finite double.
class Q {
 public:
  Q() { mpq_init(v_); }
  explicit Q(double d) {
    mpq_init(v_);
    mpq_set_d(v_, d);  // exact (GMP manual: "There is no rounding, this conversion is exact.")
  }
  Q(const Q& o) {
    mpq_init(v_);
    mpq_set(v_, o.v_);
  }
  Q& operator=(const Q& o) {
    mpq_set(v_, o.v_);
    return *this;
  }
  ~Q() { mpq_clear(v_); }
  friend Q operator+(const Q& a, const Q& b) {
    Q r;
    mpq_add(r.v_, a.v_, b.v_);
    return r;
  }
  friend Q operator-(const Q& a, const Q& b) {
    Q r;
    mpq_sub(r.v_, a.v_, b.v_);
    return r;
  }
  friend Q operator*(const Q& a, const Q& b) {
    Q r;
    mpq_mul(r.v_, a.v_, b.v_);
    return r;
  }
  int sign() const { return mpq_sgn(v_); }

 private:
  mpq_t v_;
};

using QVec = std::array<Q, 3>;

QVec qvec(const Vec3d& p) {
  return {Q(p.x), Q(p.y), Q(p.z)};
}
QVec qvec(const Point3d& p) {
  return {Q(p.x), Q(p.y), Q(p.z)};
}
QVec operator-(const QVec& a, const QVec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
QVec cross(const QVec& a, const QVec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Q dot(const QVec& a, const QVec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
bool is_zero(const QVec& a) {
  return a[0].sign() == 0 && a[1].sign() == 0 && a[2].sign() == 0;
}

// Sign of ((b - a) x (c - a)) . (d - a), orient3d's convention.
int orient3d_q(const QVec& a, const QVec& b, const QVec& c, const QVec& d) {
  return dot(cross(b - a, c - a), d - a).sign();
}
int orient2d_q(double ax, double ay, double bx, double by, double cx, double cy) {
  const Q a(ax), b(ay), c(bx), d(by), e(cx), f(cy);
  return ((c - a) * (f - b) - (d - b) * (e - a)).sign();
}

// ---------------------------------------------------------------------------------------------------------
// The oracle hull.
struct Oracle {
  int dimension = -1;
  std::vector<PointIndex> vertices;  // ascending
};

// Is q in the convex hull of the (coplanar, spanning a plane) points `others`?  By Caratheodory q lies in a
// triangle of them, which can be taken non-degenerate when the others span the plane.  `axis` is a
// coordinate axis the plane's normal has a nonzero component along (the projection dropping it keeps
// containment).
bool in_planar_hull(const QVec& q, const std::vector<const QVec*>& others, int axis) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  auto orient = [&](const QVec& a, const QVec& b, const QVec& c) {
    return ((b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u])).sign();
  };
  const std::size_t m = others.size();
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = i + 1; j < m; ++j)
      for (std::size_t k = j + 1; k < m; ++k) {
        const QVec &a = *others[i], &b = *others[j], &c = *others[k];
        const int s = orient(a, b, c);
        if (s == 0) continue;
        if (orient(a, b, q) * s >= 0 && orient(b, c, q) * s >= 0 && orient(c, a, q) * s >= 0) return true;
      }
  return false;
}

// The members of `set` (coplanar, spanning the plane with normal `normal`) that are extreme among them.
std::vector<std::size_t> planar_extremes(const std::vector<QVec>& p, const std::vector<std::size_t>& set,
                                         const QVec& normal) {
  const int axis = normal[0].sign() != 0 ? 0 : normal[1].sign() != 0 ? 1 : 2;
  std::vector<std::size_t> out;
  for (std::size_t q : set) {
    std::vector<const QVec*> others;
    for (std::size_t r : set)
      if (r != q) others.push_back(&p[r]);
    if (!in_planar_hull(p[q], others, axis)) out.push_back(q);
  }
  return out;
}

bool lex_less(const Point3d& a, const Point3d& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

Oracle oracle_hull(const std::vector<Point3d>& points) {
  // Distinct points, each the lowest index of its coordinates (+0 == -0).
  std::vector<PointIndex> reps;
  for (PointIndex i = 0; i < points.size(); ++i) {
    bool dup = false;
    for (PointIndex j : reps)
      dup = dup || points[j] == points[i];
    if (!dup) reps.push_back(i);
  }
  Oracle o;
  const std::size_t m = reps.size();
  if (m == 0) return o;
  std::vector<QVec> p;
  for (PointIndex i : reps)
    p.push_back(qvec(points[i]));
  o.dimension = 0;
  if (m == 1) {
    o.vertices = {reps[0]};
    return o;
  }
  // Affine dimension: a non-collinear third point, then a non-coplanar fourth.
  std::size_t c = m, d = m;
  for (std::size_t k = 2; k < m && c == m; ++k)
    if (!is_zero(cross(p[1] - p[0], p[k] - p[0]))) c = k;
  if (c == m) {  // collinear: the ends are the lexicographic extremes
    o.dimension = 1;
    std::size_t lo = 0, hi = 0;
    for (std::size_t k = 1; k < m; ++k) {
      if (lex_less(points[reps[k]], points[reps[lo]])) lo = k;
      if (lex_less(points[reps[hi]], points[reps[k]])) hi = k;
    }
    o.vertices = {reps[lo], reps[hi]};
    std::sort(o.vertices.begin(), o.vertices.end());
    return o;
  }
  for (std::size_t k = 2; k < m && d == m; ++k)
    if (orient3d_q(p[0], p[1], p[c], p[k]) != 0) d = k;
  std::set<std::size_t> extreme;
  if (d == m) {
    o.dimension = 2;
    std::vector<std::size_t> all(m);
    for (std::size_t k = 0; k < m; ++k)
      all[k] = k;
    for (std::size_t k : planar_extremes(p, all, cross(p[1] - p[0], p[c] - p[0])))
      extreme.insert(k);
  } else {
    o.dimension = 3;
    std::set<std::vector<std::size_t>> facets;
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = i + 1; j < m; ++j)
        for (std::size_t k = j + 1; k < m; ++k) {
          const QVec n = cross(p[j] - p[i], p[k] - p[i]);
          if (is_zero(n)) continue;
          bool pos = false, neg = false;
          std::vector<std::size_t> on;
          for (std::size_t l = 0; l < m && !(pos && neg); ++l) {
            const int s = dot(n, p[l] - p[i]).sign();
            pos = pos || s > 0, neg = neg || s < 0;
            if (s == 0) on.push_back(l);
          }
          if (pos && neg) continue;
          if (!facets.insert(on).second) continue;
          for (std::size_t v : planar_extremes(p, on, n))
            extreme.insert(v);
        }
  }
  for (std::size_t k : extreme)
    o.vertices.push_back(reps[k]);
  std::sort(o.vertices.begin(), o.vertices.end());
  return o;
}

// The hull against the oracle: dimension, vertex set, coordinates; in 3-D every triangle non-degenerate
// with every point on or below its plane and the triangles a closed oriented surface of Euler
// characteristic 2; in 2-D the polygon convex, counter-clockwise about the canonical normal.
void expect_matches_oracle(const std::vector<Point3d>& points, const HullMeshd& hull, const char* what) {
  SCOPED_TRACE(what);
  const Oracle o = oracle_hull(points);
  ASSERT_EQ(hull.dimension, o.dimension);
  ASSERT_EQ(hull.vertex_ids, o.vertices);
  ASSERT_EQ(hull.vertices.size(), hull.vertex_ids.size());
  for (std::size_t v = 0; v < hull.vertices.size(); ++v) {
    const Point3d& got = hull.vertices[v];
    const Point3d& want = points[hull.vertex_ids[v]];
    // Bit for bit (the sign of a zero included): the input's own coordinates.
    EXPECT_EQ(std::signbit(got.x), std::signbit(want.x));
    EXPECT_EQ(std::signbit(got.y), std::signbit(want.y));
    EXPECT_EQ(std::signbit(got.z), std::signbit(want.z));
    EXPECT_EQ(got, want);
  }
  std::vector<QVec> vq;
  for (const Point3d& v : hull.vertices)
    vq.push_back(qvec(v));
  if (hull.dimension == 3) {
    std::vector<QVec> pq;
    for (const Point3d& p : points)
      pq.push_back(qvec(p));
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (const Triangle& t : hull.triangles) {
      ASSERT_LT(std::max({t[0], t[1], t[2]}), hull.vertices.size());
      const QVec n = cross(vq[t[1]] - vq[t[0]], vq[t[2]] - vq[t[0]]);
      EXPECT_FALSE(is_zero(n)) << "degenerate triangle";
      for (const QVec& p : pq)
        EXPECT_LE(dot(n, p - vq[t[0]]).sign(), 0) << "a point above a hull triangle";
      for (int i = 0; i < 3; ++i)
        ++edges[{t[i], t[(i + 1) % 3]}];
    }
    for (const auto& [e, count] : edges) {
      EXPECT_EQ(count, 1) << "directed edge used twice";
      EXPECT_EQ(edges.count({e.second, e.first}), 1u) << "edge without its twin";
    }
    EXPECT_EQ(static_cast<long>(hull.vertices.size()) - static_cast<long>(edges.size() / 2) +
                  static_cast<long>(hull.triangles.size()),
              2);
  } else {
    EXPECT_TRUE(hull.triangles.empty());
  }
  if (hull.dimension == 2) {
    const std::size_t k = hull.polygon.size();
    ASSERT_EQ(k, hull.vertices.size());
    ASSERT_GE(k, 3u);
    const QVec n =
        cross(vq[hull.polygon[1]] - vq[hull.polygon[0]], vq[hull.polygon[2]] - vq[hull.polygon[0]]);
    const int canonical = n[0].sign() != 0 ? n[0].sign() : n[1].sign() != 0 ? n[1].sign() : n[2].sign();
    EXPECT_GT(canonical, 0) << "polygon not counter-clockwise about the canonical normal";
    for (std::size_t i = 0; i < k; ++i) {
      const QVec& a = vq[hull.polygon[i]];
      const QVec& b = vq[hull.polygon[(i + 1) % k]];
      const QVec& c = vq[hull.polygon[(i + 2) % k]];
      EXPECT_GT(dot(cross(b - a, c - a), n).sign(), 0) << "polygon not strictly convex at corner " << i;
    }
  }
}

}  // namespace
}  // namespace cudahull
