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
// Compiled with -ffp-contract=off, like predicates.cpp: the error-free transformations need every
// operation rounded on its own.
#include "cudahull/plane.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace cudahull {
namespace {

using detail::Pair;

constexpr int kMaxComponents = 16;  // pair_cross's output
constexpr int kMaxSteps = 4;        // rounding corrections; Compress's guess needs at most two

// Shewchuk 1997, fig. 15 and Theorem 23: `e` (nonoverlapping, increasing magnitude, length >= 1) rewritten
// as a nonadjacent expansion whose largest component, returned, differs from the sum by less than one of
// its ulps.  Only used as a first guess, so its accuracy affects the number of correction steps, not the
// result.
double compress_largest(int len, const double* e) {
  double h[kMaxComponents];
  int bottom = len - 1;
  double q = e[bottom];
  for (int i = len - 2; i >= 0; --i) {
    double qnew, tail;
    detail::fast_two_sum(q, e[i], qnew, tail);
    if (tail != 0.0) {
      h[bottom--] = qnew;
      q = tail;
    } else {
      q = qnew;
    }
  }
  for (int i = bottom + 1; i < len; ++i) {
    double qnew, tail;
    detail::fast_two_sum(h[i], q, qnew, tail);
    q = qnew;
  }
  return q;
}

// The double nearest to the exact sum of `e` (as produced by expansion_sum: nonoverlapping, increasing
// magnitude, no zero components except a lone zero), ties to even.
double round_expansion(int len, const double* e) {
  double r = compress_largest(len, e);
  // The remainder e - r, exactly.  Each correction step appends at most one component.
  double rem[kMaxComponents + kMaxSteps + 1], next_rem[kMaxComponents + kMaxSteps + 1];
  double twice[kMaxComponents + kMaxSteps + 1];
  double minus_r = -r;
  int rlen = detail::expansion_sum(len, e, 1, &minus_r, rem);
  for (int step = 0; step < kMaxSteps; ++step) {
    const double top = rem[rlen - 1];  // carries the remainder's sign
    if (top == 0.0) return r;          // r is the exact value
    const double neighbour = std::nextafter(
        r, top > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity());
    if (!std::isfinite(neighbour)) return r;  // beyond the largest double: out of contract
    // Adjacent doubles: the gap is a power of two and the subtraction exact.  Compare 2 * rem with it
    // rather than rem with half of it, which could underflow.
    double minus_gap = r - neighbour;
    for (int i = 0; i < rlen; ++i)
      twice[i] = 2.0 * rem[i];
    const int side = detail::expansion_sum_sign(rlen, twice, 1, &minus_gap);  // sign of 2 rem - gap
    const int direction = top > 0 ? 1 : -1;
    if (side == -direction) return r;  // less than half way to the neighbour
    if (side == 0) {                   // exactly half way: the even one
      return (std::bit_cast<std::uint64_t>(r) & 1) == 0 ? r : neighbour;
    }
    // Past half way: the neighbour is nearer; the remainder from it is rem - gap.
    rlen = detail::expansion_sum(rlen, rem, 1, &minus_gap, next_rem);
    std::copy(next_rem, next_rem + rlen, rem);
    r = neighbour;
  }
  return r;  // not reached: Compress's guess is within one ulp, so two steps suffice
}

// u_j v_k - u_k v_j, rounded to nearest.
double rounded_minor(const Pair& uj, const Pair& vk, const Pair& uk, const Pair& vj) {
  if (uj.len == 1 && vk.len == 1 && uk.len == 1 && vj.len == 1) {
    // Shortcut, common for float32 input: when both products are exact in double, their rounded difference
    // is the exact minor rounded to nearest.
    double p, p_err, q, q_err;
    detail::two_product(uj.v[0], vk.v[0], p, p_err);
    detail::two_product(uk.v[0], vj.v[0], q, q_err);
    if (p_err == 0.0 && q_err == 0.0) return detail::sub_rn(p, q) + 0.0;
  }
  double h[kMaxComponents];
  const int len = detail::pair_cross(uj, vk, uk, vj, h);
  return round_expansion(len, h) + 0.0;  // + 0.0: a zero component is +0, never -0
}

}  // namespace

std::array<double, 3> cross_rounded(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  using detail::exact_diff;
  const Pair ux = exact_diff(b.x, a.x), uy = exact_diff(b.y, a.y), uz = exact_diff(b.z, a.z);
  const Pair vx = exact_diff(c.x, a.x), vy = exact_diff(c.y, a.y), vz = exact_diff(c.z, a.z);
  return {rounded_minor(uy, vz, uz, vy), rounded_minor(uz, vx, ux, vz), rounded_minor(ux, vy, uy, vx)};
}

std::array<double, 4> plane_through(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const std::array<double, 3> n = cross_rounded(a, b, c);
  const double largest = std::max({std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])});
  if (largest == 0.0) return {0.0, 0.0, 0.0, 0.0};  // collinear or coincident: no plane
  // Scale by a power of two (exact) so that the largest component lies in [1, 2): the squares can neither
  // overflow nor underflow whatever the input's magnitude.
  const int exponent = std::ilogb(largest);
  const double x = std::ldexp(n[0], -exponent), y = std::ldexp(n[1], -exponent),
               z = std::ldexp(n[2], -exponent);
  const double length = std::sqrt(x * x + y * y + z * z);
  const double nx = x / length, ny = y / length, nz = z / length;
  const auto height = [&](const Vec3d& p) { return nx * p.x + ny * p.y + nz * p.z; };
  return {nx, ny, nz, -std::max({height(a), height(b), height(c)})};
}

}  // namespace cudahull
