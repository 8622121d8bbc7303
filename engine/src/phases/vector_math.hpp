// Double-precision vector arithmetic for the geometry that only routes or views (separating planes, the
// foldover test's viewpoints).  Never for a decision: those go through the exact predicates.
#pragma once

#include <algorithm>
#include <cmath>

#include "cudahull/predicates.hpp"

namespace cudahull::phases {

inline Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3d add(const Vec3d& a, const Vec3d& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3d normalized(const Vec3d& a) {
  // Scale first so that huge or tiny coordinates (1e30, 1e-30) neither overflow nor underflow.
  const double m = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)});
  if (m == 0) return {0, 0, 0};
  const double inverse = 1 / m;  // two divisions in all instead of six: this runs ~10 times a refinement
  const Vec3d s{a.x * inverse, a.y * inverse, a.z * inverse};
  const double k = 1 / std::sqrt(dot(s, s));
  return {s.x * k, s.y * k, s.z * k};
}

}  // namespace cudahull::phases
