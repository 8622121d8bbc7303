// The merge's planes and vectors in double: a plane's value at a point, in the order the certificate's
// error bound assumes, and a point's distance to a triangle (the coplanar points' nearest facet).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

#include "cudahull/predicates.hpp"

namespace cudahull::merge {

using Plane = std::array<double, 4>;
inline constexpr std::uint32_t kNone = 0xffffffffu;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kUnitRoundoff = 0x1p-53;

// n . p + d in double, in this order (the certificate's error bound assumes it).
inline double plane_value(const Plane& plane, const Vec3d& p) {
  return plane[0] * p.x + plane[1] * p.y + plane[2] * p.z + plane[3];
}

inline double dot3(const Plane& plane, const Vec3d& p) {
  return plane[0] * p.x + plane[1] * p.y + plane[2] * p.z;
}

inline Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Triangle t's key in the largest-first order of the facets' seeds (grouping.hpp): the bits of twice its
// area (|(b - a) x (c - a)|) inverted, which order as the areas do (none is negative or NaN), then t.
inline std::pair<std::uint64_t, std::uint32_t> largest_first_key(const Vec3d& a, const Vec3d& b,
                                                                 const Vec3d& c, std::uint32_t t) {
  const Vec3d n = cross(sub(b, a), sub(c, a));
  const double twice_area = std::sqrt(dot(n, n));
  std::uint64_t bits;
  std::memcpy(&bits, &twice_area, sizeof bits);
  return {~bits, t};
}

// Squared Euclidean distance from p to triangle abc (closest point by Voronoi regions, Ericson 5.1.5).
inline double triangle_distance2(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  auto dist2 = [&](const Vec3d& q) { return dot(sub(p, q), sub(p, q)); };
  // The squared distance to the point t of the way along `direction` from `from`.
  auto dist2_along = [&](const Vec3d& from, const Vec3d& direction, double t) {
    return dist2({from.x + t * direction.x, from.y + t * direction.y, from.z + t * direction.z});
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return dist2(a);
  const Vec3d bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dist2(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return dist2_along(a, ab, d1 / (d1 - d3));
  const Vec3d cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dist2(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return dist2_along(a, ac, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return dist2_along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return dist2({a.x + ab.x * v + ac.x * w, a.y + ab.y * v + ac.y * w, a.z + ab.z * v + ac.z * w});
}

}  // namespace cudahull::merge
