// Exact geometric predicates for EVERY finite double, host only.
//
// The predicates of predicates.hpp are exact as long as no product of coordinate differences overflows or
// underflows, which holds when every nonzero coordinate magnitude lies in 2^-250..2^250
// (in_fast_exact_range).  The *_wide predicates below take any finite doubles (subnormals, 1e308, both at
// once) and are exact for all of them, in three stages chosen per call:
//   1. every coordinate of the call in the fast range: the fast predicate itself;
//   2. the call's nonzero magnitudes span few enough binades (floor(log2 |c|) within 499 of each other):
//      the fast predicate on the coordinates scaled by one power of two into the fast range (exact, and
//      the sign of a determinant of differences does not change under a positive scale);
//   3. otherwise a double filter whose error bound also covers underflow (and the rounding of a scaling
//      that keeps every product finite) decides whenever the determinant is clearly away from zero, and
//      exact integer arithmetic (GMP mpz) decides the rest: a finite double is m * 2^e with an integer m and
//      e >= -1074, so scaling every coordinate of the call by 2^-(the call's least e) gives integers, and the
//      determinant is evaluated on those exactly.
// Same signatures and sign conventions as orient3d, orient2d and collinear3d.  NaN or infinite coordinates
// are not finite doubles: the result is then unspecified.  This header does not include gmp.h.
#pragma once

#include <cmath>

#include "cudahull/predicates.hpp"

namespace cudahull {

// in_fast_exact_range() (predicates.hpp): where every coordinate of a call passes, the fast predicates
// are exact, and the wide ones below are them.

// Sign of det[b-a, c-a, d-a] as orient3d: +1 when d is above the counter-clockwise triangle (a, b, c).
int orient3d_wide(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

// Sign of det[b-a, c-a] as orient2d: +1 counter-clockwise, 0 collinear, -1 clockwise.
int orient2d_wide(double ax, double ay, double bx, double by, double cx, double cy);

// Whether a, b, c are collinear (including coincident points), as collinear3d.
bool collinear3d_wide(const Vec3d& a, const Vec3d& b, const Vec3d& c);

namespace detail {
// The exact integer evaluation of stage 3 alone (GMP, no filter), whatever the magnitudes: for tests, which
// compare it with the other stages.
int orient3d_gmp(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);
int orient2d_gmp(double ax, double ay, double bx, double by, double cx, double cy);
bool collinear3d_gmp(const Vec3d& a, const Vec3d& b, const Vec3d& c);
}  // namespace detail

// A set of the predicates as a policy of static functions, for code templated on which set decides.  The
// functions are template arguments, so calls through the policy are direct calls (the inline predicates
// inline as if called themselves).
template <int (*Orient3d)(const Vec3d&, const Vec3d&, const Vec3d&, const Vec3d&),
          int (*Orient2d)(double, double, double, double, double, double),
          bool (*Collinear3d)(const Vec3d&, const Vec3d&, const Vec3d&)>
struct PredicatePolicy {
  static int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
    return Orient3d(a, b, c, d);
  }
  static int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
    return Orient2d(ax, ay, bx, by, cx, cy);
  }
  static bool collinear3d(const Vec3d& a, const Vec3d& b, const Vec3d& c) { return Collinear3d(a, b, c); }
};
// predicates.hpp's: exact where in_fast_exact_range() holds.
using FastPredicates = PredicatePolicy<orient3d, orient2d, collinear3d>;
// The *_wide ones: exact for every finite double, slower.
using WidePredicates = PredicatePolicy<orient3d_wide, orient2d_wide, collinear3d_wide>;
// Stage 3 alone (GMP, no filter): for tests.
using GmpPredicates = PredicatePolicy<detail::orient3d_gmp, detail::orient2d_gmp, detail::collinear3d_gmp>;

}  // namespace cudahull
