// Exact geometric predicates on float32 (and double) coordinates.
//
// orient3d is a double-precision filter with a proven error bound (Shewchuk 1997, o3derrboundA) and an exact
// fallback in expansion arithmetic.  Every decision that changes the hull (outside/inside a face, concave
// edge, valid swap, concave vertex) goes through these; nothing else may decide those things.
//
// Both backends compile this header (CUDAHULL_HD).  TwoProduct uses fma and the sums use explicit rounding so
// that compiler contraction cannot break the error-free transformations.
#pragma once

#include "cudahull/host_device.hpp"
#if !defined(__CUDA_ARCH__)
#include <cmath>
#endif
#include "cudahull/types.hpp"

namespace cudahull {

struct Vec3d {
  double x = 0, y = 0, z = 0;
};

// Point3 (float) or Point3d (double): exact either way.
template <class Point>
CUDAHULL_HD inline Vec3d to_vec3d(const Point& p) {
  return {p.x, p.y, p.z};
}

// Sign of det[b-a, c-a, d-a] = ((b - a) x (c - a)) . (d - a):
//  +1 when d is above the plane of triangle (a, b, c), i.e. on the side its counter-clockwise normal points
//     to; 0 when the four points are coplanar; -1 when d is below.
// Exact for all finite double inputs whose products do not overflow or underflow; in particular exact for
// every float32 input and for double points such as the engine's interior reference point.
CUDAHULL_HD int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

// The same determinant in plain double arithmetic, same sign convention, NOT exact: for ranking only (e.g.
// "furthest point above a face"), never for a decision.  Bit-identical on host and device.
CUDAHULL_HD double orient3d_fast(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

// Sign of the 2D determinant det[b-a, c-a]: +1 counter-clockwise, 0 collinear, -1 clockwise.  Exact.
CUDAHULL_HD int orient2d(double ax, double ay, double bx, double by, double cx, double cy);

// Exact test: are a, b, c collinear (including coincident points)?
CUDAHULL_HD bool collinear3d(const Vec3d& a, const Vec3d& b, const Vec3d& c);

// The fast exact range: 0, or a magnitude in [2^-250, 2^250].  Where every coordinate of a call passes,
// orient3d, orient2d and collinear3d are exact: orient3d's exact stage multiplies three coordinate
// differences, and with every coordinate 0 or a multiple of 2^-302 below 2^251 in magnitude each partial
// product and each of its expansion components is a multiple of 2^-906 below 2^753, inside double's normal
// range.  False for NaN and infinities.  Every float passes.  The one statement of the rule: io's
// check_double_range(), the API, the device checks and the wide predicates ask it.
inline constexpr double kMinExactMagnitude = 0x1p-250;
inline constexpr double kMaxExactMagnitude = 0x1p+250;
CUDAHULL_HD inline bool in_fast_exact_range(double coordinate) {
  // fabs, not a branch on the sign: random signs mispredicted half the time, most of a small cloud's check.
#if defined(__CUDA_ARCH__)
  const double a = fabs(coordinate);
#else
  const double a = std::fabs(coordinate);
#endif
  return (a == 0.0) | ((a >= kMinExactMagnitude) & (a <= kMaxExactMagnitude));
}

// Counters for tests and statistics: how often the filter fell back to exact arithmetic (host only).
struct PredicateStats {
  unsigned long long orient3d_calls = 0;
  unsigned long long orient3d_exact = 0;
};
PredicateStats predicate_stats();
void reset_predicate_stats();

}  // namespace cudahull

#include "cudahull/detail/predicates_impl.hpp"
