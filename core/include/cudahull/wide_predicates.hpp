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

}  // namespace cudahull
