// The exact hull's small vector helpers on Vec3d (lexicographic order, equality, difference, cross and dot
// product) and its "no index" marker.  The arithmetic ones only rank candidates: every decision is an exact
// predicate.  Internal to reference/.
#pragma once

#include <cstdint>

#include "cudahull/predicates.hpp"

namespace cudahull::exact {

inline constexpr std::uint32_t kNone = 0xffffffffu;

inline bool lex_less(const Vec3d& a, const Vec3d& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

inline bool same(const Vec3d& a, const Vec3d& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

inline Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

}  // namespace cudahull::exact
