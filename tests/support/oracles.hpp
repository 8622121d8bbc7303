// Independent oracles for the tests: brute-force exact extreme-point finders for small sets (they share
// nothing with the engines or exact_hull but the exact predicates), in 3-D, 2-D and any affine dimension.
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"
#include "cudahull/wide_predicates.hpp"

namespace cudahull::testing {

// The oracles' exact predicates (policies of wide_predicates.hpp).  FilteredExact: the engines' (a
// floating-point filter, then expansions), exact on floats and on doubles whose products neither overflow nor
// underflow.  GmpExact: integer arithmetic on the doubles' exact values, any finite double, no filter (slow:
// small sets only).
using FilteredExact = FastPredicates;
using GmpExact = GmpPredicates;

// Strictly extreme points of a 3D-full set by brute force, O(n^4): a point is extreme iff it is a strict
// corner of the coplanar set on some supporting plane through three of the points.  Among duplicates the
// lowest index.  Only for n up to ~60.
template <class Point, class Exact = FilteredExact>
std::vector<PointIndex> brute_force_extreme(const std::vector<Point>& p) {
  const std::size_t n = p.size();
  auto V = [&](std::size_t i) { return to_vec3d(p[i]); };
  std::vector<bool> extreme(n, false);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        if (Exact::collinear3d(V(i), V(j), V(k))) continue;
        int side = 0;
        bool supporting = true;
        std::vector<std::size_t> on;
        for (std::size_t m = 0; m < n && supporting; ++m) {
          const int s = Exact::orient3d(V(i), V(j), V(k), V(m));
          if (s == 0) {
            on.push_back(m);
          } else if (side == 0) {
            side = s;
          } else if (s != side) {
            supporting = false;
          }
        }
        if (!supporting) continue;
        // The facet: the coplanar points on this supporting plane.  A point q of it is a strict corner iff
        // no other facet points a, b, c (possibly equal to each other) contain q in their closed triangle /
        // segment; test in a projection that drops an axis along which the plane projects one to one (the
        // triangle i, j, k stays non-degenerate: decided exactly, so that it holds at any magnitude).
        const Vec3d a = V(i), b = V(j), c = V(k);
        auto uv = [](const Vec3d& q, int drop, double& u, double& v) {
          u = drop == 0 ? q.y : q.x;
          v = drop == 2 ? q.y : q.z;
        };
        int drop = 0;
        for (; drop < 2; ++drop) {
          double au, av, bu, bv, cu, cv;
          uv(a, drop, au, av);
          uv(b, drop, bu, bv);
          uv(c, drop, cu, cv);
          if (Exact::orient2d(au, av, bu, bv, cu, cv) != 0) break;
        }
        auto proj = [&](std::size_t m, double& u, double& v) { uv(V(m), drop, u, v); };
        for (std::size_t q : on) {
          bool corner = true;
          double qu, qv;
          proj(q, qu, qv);
          // q is not a corner if it equals a lower-index point, or lies in the closed triangle of three
          // others.
          for (std::size_t r : on) {
            if (r != q && p[r] == p[q] && r < q) corner = false;
          }
          for (std::size_t r1 = 0; r1 < on.size() && corner; ++r1)
            for (std::size_t r2 = r1; r2 < on.size() && corner; ++r2)
              for (std::size_t r3 = r2; r3 < on.size() && corner; ++r3) {
                const std::size_t A = on[r1], B = on[r2], C = on[r3];
                if (p[A] == p[q] || p[B] == p[q] || p[C] == p[q]) continue;
                double au, av, bu, bv, cu, cv;
                proj(A, au, av);
                proj(B, bu, bv);
                proj(C, cu, cv);
                const int s1 = Exact::orient2d(au, av, bu, bv, qu, qv),
                          s2 = Exact::orient2d(bu, bv, cu, cv, qu, qv),
                          s3 = Exact::orient2d(cu, cv, au, av, qu, qv);
                const int o = Exact::orient2d(au, av, bu, bv, cu, cv);
                if (o != 0) {
                  if (s1 * o >= 0 && s2 * o >= 0 && s3 * o >= 0) corner = false;
                } else {
                  // Degenerate triple: q on a segment between two of them?
                  auto between = [&](double xu, double xv, double yu, double yv) {
                    return Exact::orient2d(xu, xv, yu, yv, qu, qv) == 0 && std::min(xu, yu) <= qu &&
                           qu <= std::max(xu, yu) && std::min(xv, yv) <= qv && qv <= std::max(xv, yv);
                  };
                  if (between(au, av, bu, bv) || between(bu, bv, cu, cv) || between(au, av, cu, cv))
                    corner = false;
                }
              }
          if (corner) extreme[q] = true;
        }
      }
  std::vector<PointIndex> out;
  for (std::size_t i = 0; i < n; ++i)
    if (extreme[i]) out.push_back(static_cast<PointIndex>(i));
  return out;
}

// Strictly extreme points of a 2-D set by brute force, O(n^3): point i is one iff a line through two other
// points has every other point on one closed side and i strictly on the other, or the others are collinear
// (or one point) and i lies off their closed segment.  Among duplicates the lowest index.
template <class Exact = FilteredExact>
std::vector<PointIndex> brute_force_extreme_2d(const std::vector<std::array<double, 2>>& p) {
  std::vector<PointIndex> out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::vector<std::array<double, 2>> others;  // a copy of p[i] with a higher index is not a rival
    for (std::size_t j = 0; j < p.size(); ++j)
      if (j != i && (p[j] != p[i] || j < i)) others.push_back(p[j]);
    const auto& q = p[i];
    bool extreme = others.empty();
    bool others_collinear = true;
    for (std::size_t a = 0; a < others.size() && !extreme; ++a)
      for (std::size_t b = a + 1; b < others.size() && !extreme; ++b) {
        if (others[a] == others[b]) continue;
        for (const auto& o : others)
          if (Exact::orient2d(others[a][0], others[a][1], others[b][0], others[b][1], o[0], o[1]) != 0)
            others_collinear = false;
        const int side = Exact::orient2d(others[a][0], others[a][1], others[b][0], others[b][1], q[0], q[1]);
        if (side == 0) continue;
        extreme = std::none_of(others.begin(), others.end(), [&](const std::array<double, 2>& o) {
          return Exact::orient2d(others[a][0], others[a][1], others[b][0], others[b][1], o[0], o[1]) == side;
        });
      }
    if (!extreme && others_collinear) {
      // All others on one line (or one point): i is extreme unless it lies on their closed segment, whose
      // ends are the lexicographic least and greatest of them.
      const auto [lo, hi] = std::minmax_element(others.begin(), others.end());
      const bool on_line =
          lo == hi || *lo == *hi || Exact::orient2d((*lo)[0], (*lo)[1], (*hi)[0], (*hi)[1], q[0], q[1]) == 0;
      extreme = !on_line || q < *lo || *hi < q;
    }
    if (extreme) out.push_back(static_cast<PointIndex>(i));
  }
  return out;
}

// Strictly extreme points of any small 3-D set, with its affine dimension (-1 for none): the 3-D brute force
// for a solid set; a flat one's in a projection that keeps it one to one (the 2-D brute force); on a line
// the lexicographic ends; one point (with copies) the lowest index.
template <class Point, class Exact = FilteredExact>
std::vector<PointIndex> brute_force_extreme_any(const std::vector<Point>& p, int* dimension = nullptr) {
  auto V = [&](std::size_t i) { return to_vec3d(p[i]); };
  const std::size_t n = p.size();
  std::size_t b = 0, c = 0, d = 0;
  while (b < n && p[b] == p[0])
    ++b;
  if (b < n) {
    c = b + 1;
    while (c < n && Exact::collinear3d(V(0), V(b), V(c)))
      ++c;
  }
  if (b < n && c < n) {
    d = c + 1;
    while (d < n && Exact::orient3d(V(0), V(b), V(c), V(d)) == 0)
      ++d;
  }
  const int dim = n == 0 ? -1 : b >= n ? 0 : c >= n ? 1 : d >= n ? 2 : 3;
  if (dimension) *dimension = dim;
  if (dim <= 0) return dim < 0 ? std::vector<PointIndex>{} : std::vector<PointIndex>{0};
  if (dim == 3) return brute_force_extreme<Point, Exact>(p);
  if (dim == 1) {
    auto key = [&](std::size_t i) { return std::array<double, 3>{V(i).x, V(i).y, V(i).z}; };
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 1; i < n; ++i) {
      if (key(i) < key(lo)) lo = i;
      if (key(hi) < key(i)) hi = i;
    }
    return {static_cast<PointIndex>(std::min(lo, hi)), static_cast<PointIndex>(std::max(lo, hi))};
  }
  for (int drop = 0; drop < 3; ++drop) {
    auto uv = [&](std::size_t i) {
      const Vec3d q = V(i);
      return std::array<double, 2>{drop == 0 ? q.y : q.x, drop == 2 ? q.y : q.z};
    };
    const auto A = uv(0), B = uv(b), C = uv(c);
    if (Exact::orient2d(A[0], A[1], B[0], B[1], C[0], C[1]) == 0) continue;
    std::vector<std::array<double, 2>> flat(n);
    for (std::size_t i = 0; i < n; ++i)
      flat[i] = uv(i);
    return brute_force_extreme_2d<Exact>(flat);
  }
  return {};  // unreachable: a plane projects one to one along some axis
}

}  // namespace cudahull::testing
