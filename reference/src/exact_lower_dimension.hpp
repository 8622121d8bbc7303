// The exact hull's lower dimensions: the affine basis of the sites (find_basis), which decides the input's
// dimension, and the exact 2D hull of a planar input on that basis (hull_2d, exact_lower_dimension.cpp).
// Internal to reference/.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cudahull/predicates.hpp"
#include "exact_vector.hpp"

namespace cudahull::exact {

// Up to four affinely independent points, found exactly.  a/b are the lexicographic extremes; c and d are
// picked by approximate distance (for a fat initial simplex) and confirmed (or replaced) exactly.
struct Basis {
  int dim = -1;
  std::uint32_t a = kNone, b = kNone, c = kNone, d = kNone;
};

template <class Pred, class Get>
Basis find_basis(std::size_t n, const Get& get) {
  Basis r;
  if (n == 0) return r;
  std::uint32_t lo = 0, hi = 0;
  for (std::uint32_t i = 1; i < n; ++i) {
    if (lex_less(get(i), get(lo))) lo = i;
    if (lex_less(get(hi), get(i))) hi = i;
  }
  r.a = lo;
  r.dim = 0;
  const Vec3d a = get(lo), b = get(hi);
  if (same(a, b)) return r;  // lexicographic min == max: all points identical
  r.b = hi;
  r.dim = 1;

  const Vec3d ab = sub(b, a);
  std::uint32_t best = kNone;
  double best_d = -1;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Vec3d w = cross(sub(get(i), a), ab);
    const double d = dot(w, w);
    if (d > best_d) best_d = d, best = i;
  }
  // The approximate pick may be exactly collinear (or missing, when a huge double input overflows the
  // ranking to NaN): scan exactly.
  if (best == kNone || Pred::collinear3d(a, b, get(best))) {
    best = kNone;
    for (std::uint32_t i = 0; i < n && best == kNone; ++i)
      if (!Pred::collinear3d(a, b, get(i))) best = i;
    if (best == kNone) return r;
  }
  r.c = best;
  r.dim = 2;

  const Vec3d c = get(best);
  const Vec3d nrm = cross(ab, sub(c, a));
  best = kNone;
  best_d = -1;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double d = std::fabs(dot(nrm, sub(get(i), a)));
    if (d > best_d) best_d = d, best = i;
  }
  if (best == kNone || Pred::orient3d(a, b, c, get(best)) == 0) {
    best = kNone;
    for (std::uint32_t i = 0; i < n && best == kNone; ++i)
      if (Pred::orient3d(a, b, c, get(i)) != 0) best = i;
    if (best == kNone) return r;
  }
  r.d = best;
  r.dim = 3;
  return r;
}

// 2D hull of coplanar distinct points: Andrew's monotone chain on the projection that drops one axis of the
// plane's normal N = (b - a) x (c - a) (the basis points), with exact orient2d.  The projection keeps the
// axes in cyclic order ((y,z), (z,x), (x,y)), so its orientation is sign(N_k) for the dropped axis k.
//
// Output: the strict corners, counter-clockwise seen from the side of the plane's canonical normal n, which
// is the normal whose first non-zero component (x, then y, then z) is positive; the polygon starts at its
// lexicographically smallest corner.
template <class Pred>
std::vector<std::uint32_t> hull_2d(const std::vector<Vec3d>& p, const Basis& bs);

}  // namespace cudahull::exact
