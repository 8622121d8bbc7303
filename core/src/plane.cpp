// Facet planes from exact cross products (design: cudahull/plane.hpp).
//
// Each component of (b - a) x (c - a) is a 2x2 determinant of coordinate differences.  The differences are
// exact as one- or two-component expansions (two_diff), their products and the difference of the products
// exact as an expansion of at most 16 components (pair_cross, the same code as orient3d's exact stage).  The
// expansion is then rounded to the nearest double: Shewchuk's Compress gives a first guess within one ulp,
// and an exact comparison of the remainder with half the gap to the neighbouring double settles the
// rounding.  There is no floating-point filter, whose error bound could only promise a few ulps: the
// shortcut taken first is exact too (differences and products exact in double, as for most float32
// facets, so that one subtraction rounds the exact minor), so every path returns the same correctly rounded
// components, and a facet gives the same plane whichever corner it is listed from.
//
// Error of the plane (u = 2^-53): each component within u of its exact value relatively; the power-of-two
// scaling is exact (but for a component that turns subnormal, off by under 2^-1075); the squares, their sum
// and the square root add under 3u to the length, the division u/2 to each component: |n - N| < 5u for the
// exact unit normal N.  Then for p on or below the exact plane and any corner c (they all lie on the exact
// plane), n . p - n . c = (n - N) . (p - c) + N . (p - c), where N . (p - c) <= 0 and |p - c| <= 2 sqrt(3)
// scale (scale: the largest coordinate magnitude); each of the two dot products rounds by at most about 3u
// sqrt(3) scale.  So n . p + d <= (5u 2 sqrt(3) + 2 x 3u sqrt(3)) x scale = 16 sqrt(3) u x scale < 28u x
// scale (3.1e-15 x scale), the final addition's rounding aside (it is monotone).
//
// The code is in cudahull/detail/plane_impl.hpp, which the batch kernel's device describe shares.
#include "cudahull/plane.hpp"

#include "cudahull/detail/plane_impl.hpp"

namespace cudahull {

std::array<double, 3> cross_rounded(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  std::array<double, 3> n;
  detail::cross_rounded(a, b, c, n.data());
  return n;
}

std::array<double, 4> plane_through(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  std::array<double, 4> plane;
  detail::plane_through(a, b, c, plane.data());
  return plane;
}

}  // namespace cudahull
