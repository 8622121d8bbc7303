// Every finite double: the wide predicates (wide_predicates.hpp) and exact_hull_any (exact_hull.hpp) on
// coordinates outside the fast exact range 2^-250..2^250 (subnormals, ~1e300, both at once), against an
// independent oracle in GMP rationals (mpq_set_d converts a finite double exactly; nothing of the code under
// test is used): the predicates' signs, and for hulls a brute force over all triples of points (a triple
// spans a supporting plane when no point is strictly on either side of it; the hull's vertices are the
// extreme points of the point sets on those planes).
#include "cudahull/wide_predicates.hpp"

#include <gmp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_checker.hpp"
#include "support/cli_runner.hpp"

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
// Inputs of mixed magnitudes.  Small integer mantissas make coincidences (shared coordinates, coplanar and
// collinear points) likely; full mantissas make near-cancellations.
double wide_value(std::mt19937_64& rng) {
  static constexpr int kExponents[] = {-1074, -1060, -1000, -700, -300, -250, -60, -1,
                                       0,     1,     60,    249,  300,  700,  960};
  const int e = kExponents[rng() % std::size(kExponents)];
  double m;
  switch (rng() % 4) {
    case 0:
      return 0.0;
    case 1:
      m = static_cast<double>(rng() % 8 + 1);
      break;
    case 2:
      m = static_cast<double>(rng() % 1000 + 1);
      break;
    default:
      m = std::ldexp(static_cast<double>(rng() >> 11), -52);  // in [0, 2048)
      break;
  }
  const double v = std::ldexp(m, e);  // may round (subnormal) or be rounded; any finite double will do
  return (rng() & 1) ? -v : v;
}

Vec3d wide_vec(std::mt19937_64& rng) {
  return {wide_value(rng), wide_value(rng), wide_value(rng)};
}

Point3d wide_point(std::mt19937_64& rng) {
  return {wide_value(rng), wide_value(rng), wide_value(rng)};
}

// The next double above / below.
double up(double x) {
  return std::nextafter(x, std::numeric_limits<double>::infinity());
}
double down(double x) {
  return std::nextafter(x, -std::numeric_limits<double>::infinity());
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

std::vector<Point3d> unit_cube() {
  std::vector<Point3d> p;
  for (int i = 0; i < 8; ++i)
    p.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  return p;
}

// ---------------------------------------------------------------------------------------------------------
TEST(FastExactRange, Bounds) {
  EXPECT_TRUE(in_fast_exact_range(0.0));
  EXPECT_TRUE(in_fast_exact_range(-0.0));
  EXPECT_TRUE(in_fast_exact_range(1.0));
  EXPECT_TRUE(in_fast_exact_range(0x1p-250));
  EXPECT_TRUE(in_fast_exact_range(-0x1p-250));
  EXPECT_TRUE(in_fast_exact_range(0x1p+250));
  EXPECT_TRUE(in_fast_exact_range(-0x1p+250));
  EXPECT_FALSE(in_fast_exact_range(down(0x1p-250)));
  EXPECT_FALSE(in_fast_exact_range(up(0x1p+250)));
  EXPECT_FALSE(in_fast_exact_range(5e-324));
  EXPECT_FALSE(in_fast_exact_range(1e300));
  EXPECT_FALSE(in_fast_exact_range(std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(in_fast_exact_range(std::numeric_limits<double>::quiet_NaN()));
}

// orient3d_wide, orient2d_wide, collinear3d_wide and the GMP stage alone against the rationals on random
// mixed-magnitude inputs, with exact degeneracies (a shared coordinate) and their one-ulp perturbations.
TEST(WidePredicates, Orient3dAgainstRationals) {
  std::mt19937_64 rng(20240611);
  int counts[3] = {0, 0, 0};
  for (int iter = 0; iter < 4000; ++iter) {
    Vec3d a = wide_vec(rng), b = wide_vec(rng), c = wide_vec(rng), d = wide_vec(rng);
    switch (iter % 4) {
      case 1:  // four points in a plane z = const: zero, then one ulp off it either way
        b.z = c.z = d.z = a.z;
        if (iter % 8 == 5) d.z = (rng() & 1) ? up(d.z) : down(d.z);
        break;
      case 2:  // shared coordinates in two axes
        c.x = a.x, d.x = b.x, c.y = b.y, d.y = a.y;
        break;
      case 3:  // a near-copy of a: d differs from a by one ulp in one coordinate
        d = a;
        if (rng() & 1) d.x = up(d.x);
        if (rng() & 1) d.y = down(d.y);
        if (rng() & 1) d.z = up(d.z);
        break;
      default:
        break;
    }
    const int want = orient3d_q(qvec(a), qvec(b), qvec(c), qvec(d));
    ++counts[want + 1];
    ASSERT_EQ(orient3d_wide(a, b, c, d), want) << iter;
    ASSERT_EQ(detail::orient3d_gmp(a, b, c, d), want) << iter;
    // The sign flips with an odd permutation.
    ASSERT_EQ(orient3d_wide(b, a, c, d), -want) << iter;
  }
  // Every sign is well represented.
  EXPECT_GT(counts[0], 400);
  EXPECT_GT(counts[1], 400);
  EXPECT_GT(counts[2], 400);
}

TEST(WidePredicates, Orient2dAndCollinearAgainstRationals) {
  std::mt19937_64 rng(77);
  int zeros = 0, collinear = 0;
  for (int iter = 0; iter < 4000; ++iter) {
    Vec3d a = wide_vec(rng), b = wide_vec(rng), c = wide_vec(rng);
    if (iter % 3 == 1) {  // collinear along an axis direction, maybe perturbed by one ulp
      b.y = a.y, b.z = a.z, c.y = a.y, c.z = a.z;
      if (iter % 6 == 4) c.z = up(c.z);
    } else if (iter % 3 == 2) {  // coincident pairs
      c = (rng() & 1) ? a : b;
    }
    const int want = orient2d_q(a.x, a.y, b.x, b.y, c.x, c.y);
    zeros += want == 0;
    ASSERT_EQ(orient2d_wide(a.x, a.y, b.x, b.y, c.x, c.y), want) << iter;
    ASSERT_EQ(detail::orient2d_gmp(a.x, a.y, b.x, b.y, c.x, c.y), want) << iter;
    const bool want_collinear = is_zero(cross(qvec(b) - qvec(a), qvec(c) - qvec(a)));
    collinear += want_collinear;
    ASSERT_EQ(collinear3d_wide(a, b, c), want_collinear) << iter;
    ASSERT_EQ(detail::collinear3d_gmp(a, b, c), want_collinear) << iter;
  }
  EXPECT_GT(zeros, 500);
  EXPECT_GT(collinear, 500);
}

// The GMP stage agrees with the fast predicates wherever those are exact.
TEST(WidePredicates, GmpStageMatchesFastInRange) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> small(-4, 4);
  for (int iter = 0; iter < 3000; ++iter) {
    auto v = [&] {
      // Small integers scaled by one of a few in-range powers: many zeros and exact degeneracies.
      const double s = std::ldexp(1.0, static_cast<int>(rng() % 200) - 100);
      return Vec3d{small(rng) * s, small(rng) * s, small(rng) * s};
    };
    const Vec3d a = v(), b = v(), c = v(), d = v();
    ASSERT_EQ(detail::orient3d_gmp(a, b, c, d), orient3d(a, b, c, d));
    ASSERT_EQ(detail::orient2d_gmp(a.x, a.y, b.x, b.y, c.x, c.y), orient2d(a.x, a.y, b.x, b.y, c.x, c.y));
    ASSERT_EQ(detail::collinear3d_gmp(a, b, c), collinear3d(a, b, c));
  }
}

// Extremes of the double range: the least subnormal, the largest finite double, both in one call.
TEST(WidePredicates, ExtremeValues) {
  const double tiny = 5e-324, huge = std::numeric_limits<double>::max();
  const Vec3d o{0, 0, 0}, x{huge, 0, 0}, y{0, huge, 0};
  EXPECT_EQ(orient3d_wide(o, x, y, {0, 0, tiny}), 1);
  EXPECT_EQ(orient3d_wide(o, x, y, {0, 0, -tiny}), -1);
  EXPECT_EQ(orient3d_wide(o, x, y, {huge, huge, 0}), 0);
  EXPECT_EQ(orient3d_wide(o, x, y, {-huge, tiny, -0.0}), 0);
  EXPECT_EQ(orient2d_wide(0, 0, huge, tiny, -huge, -tiny), 0);
  EXPECT_EQ(orient2d_wide(0, 0, huge, tiny, -huge, 0), 1);  // (huge*0 - tiny*(-huge)) > 0
  EXPECT_TRUE(collinear3d_wide({tiny, tiny, tiny}, {-huge, -huge, -huge}, {huge, huge, huge}));
  EXPECT_FALSE(collinear3d_wide({tiny, 0, tiny}, {-huge, -huge, -huge}, {huge, huge, huge}));
  // Differences that do not fit in a double: huge - (-huge) overflows, exact here.
  EXPECT_EQ(orient3d_wide({-huge, -huge, -huge}, {huge, -huge, -huge}, {-huge, huge, -huge}, {0, 0, huge}),
            1);
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

// ---------------------------------------------------------------------------------------------------------
// The checker (check_hull, `hull --verify`) on every finite double: property cases of 100 to 5,000 points
// scaled by 2^+-300 (beyond the fast range), spread over many binades, or offset by 1e9 at 2^300, with fixed
// seeds.  Each exact_hull_any() hull passes; the same hull broken (a face dropped, a point pushed out)
// fails for its reason.

std::vector<Point3d> unit_ball(std::mt19937_64& rng, std::size_t n) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3d> p;
  while (p.size() < n) {
    const double x = g(rng), y = g(rng), z = g(rng), r = std::sqrt(x * x + y * y + z * z);
    const double s = std::cbrt(u(rng)) / r;
    if (r > 0) p.push_back({x * s, y * s, z * s});
  }
  return p;
}

struct WideCase {
  const char* name;
  std::vector<Point3d> points;
};

std::vector<WideCase> wide_cases() {
  std::vector<WideCase> out;
  std::mt19937_64 rng(4321);
  auto scaled = [&](std::size_t n, int e) {
    std::vector<Point3d> p = unit_ball(rng, n);
    for (Point3d& q : p)
      q = {std::ldexp(q.x, e), std::ldexp(q.y, e), std::ldexp(q.z, e)};
    return p;
  };
  out.push_back({"ball x 2^300, 100", scaled(100, 300)});
  out.push_back({"ball x 2^-300, 1000", scaled(1000, -300)});
  out.push_back({"ball x 2^300, 5000", scaled(5000, 300)});
  // Each point scaled by its own power of two in 2^-500..2^500: the call's magnitudes span ~1000 binades.
  for (const std::size_t n : {100, 2000}) {
    std::vector<Point3d> p = unit_ball(rng, n);
    std::uniform_int_distribution<int> e(-500, 500);
    for (Point3d& q : p) {
      const int k = e(rng);
      q = {std::ldexp(q.x, k), std::ldexp(q.y, k), std::ldexp(q.z, k)};
    }
    out.push_back({n == 100 ? "binades 2^-500..2^500, 100" : "binades 2^-500..2^500, 2000", p});
  }
  // A unit ball at 1e9 (rounded there), all of it scaled by 2^300.
  {
    std::vector<Point3d> p = unit_ball(rng, 3000);
    for (Point3d& q : p)
      q = {std::ldexp(1e9 + q.x, 300), std::ldexp(1e9 + q.y, 300), std::ldexp(-1e9 + q.z, 300)};
    out.push_back({"1e9 offset x 2^300, 3000", p});
  }
  // A ball of subnormal-scale interior points and one at 2^200: the fast range on neither side.
  {
    std::vector<Point3d> p = scaled(400, -1000);
    for (const Point3d& q : scaled(400, 200))
      p.push_back(q);
    out.push_back({"2^-1000 and 2^200, 800", p});
  }
  return out;
}

TEST(WideChecker, PropertyCasesPassAndBrokenOnesFail) {
  for (const WideCase& c : wide_cases()) {
    SCOPED_TRACE(c.name);
    ASSERT_FALSE(in_fast_exact_range(c.points));
    const HullMeshd h = exact_hull_any(c.points);
    ASSERT_EQ(h.dimension, 3);
    const CheckResult ok = check_hull(c.points, h);
    EXPECT_TRUE(ok.ok) << (ok.failures.empty() ? "" : ok.failures.front());
    if (c.points.size() <= 100) expect_matches_oracle(c.points, h, c.name);

    HullMeshd open = h;
    open.triangles.pop_back();
    const CheckResult no = check_hull(c.points, open);
    ASSERT_FALSE(no.ok);
    EXPECT_NE(no.failures.front().find("not closed"), std::string::npos) << no.failures.front();

    // A point that is not a vertex pushed out along a vertex's direction, far beyond it.
    std::vector<Point3d> moved = c.points;
    std::size_t inner = 0;
    while (std::binary_search(h.vertex_ids.begin(), h.vertex_ids.end(), inner))
      ++inner;
    const Point3d& v = h.vertices[0];
    moved[inner] = {v.x * 4, v.y * 4, v.z * 4};
    const CheckResult out = check_hull(moved, h);
    ASSERT_FALSE(out.ok);
    EXPECT_NE(out.failures.front().find("point " + std::to_string(inner) + " "), std::string::npos)
        << out.failures.front();
    EXPECT_NE(out.failures.front().find("is above face"), std::string::npos) << out.failures.front();
  }
}

// `cudahull hull --verify` runs the checker on wide input too, and says so in --stats.
TEST(WideChecker, CliVerifiesWideInput) {
  TempDir dir;
  const std::vector<WideCase> all = wide_cases();
  for (const std::size_t k : {std::size_t{2}, std::size_t{4}, std::size_t{6}}) {
    const WideCase& c = all[k];
    SCOPED_TRACE(c.name);
    std::FILE* f = std::fopen((dir / "w.xyz").c_str(), "w");
    ASSERT_NE(f, nullptr);
    for (const Point3d& p : c.points)
      std::fprintf(f, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    std::fclose(f);
    const CliRun r = run_cli({"hull", (dir / "w.xyz").string(), "--backend", "cpu", "--verify", "--stats",
                              "-", "-o", (dir / "h.obj").string()});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_NE(r.err.find("verified exact"), std::string::npos) << describe(r);
    EXPECT_NE(r.out.find("\"verified\": true"), std::string::npos) << r.out;
    const CliRun chk = run_cli({"check", (dir / "w.xyz").string(), (dir / "h.obj").string()});
    EXPECT_EQ(chk.exit_code, 0) << describe(chk);
  }
}

}  // namespace
}  // namespace cudahull
