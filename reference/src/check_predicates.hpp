// The checker's exact tests: the fast predicates inside their range, else the wide ones; the input's
// affine dimension; the lexicographic order; finite and out-of-range coordinates.  Internal to reference/.
#pragma once

#include <cmath>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"
#include "cudahull/wide_predicates.hpp"

namespace cudahull::checking {

template <class Point>
bool lex_less(const Point& a, const Point& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// The predicates, exact for the coordinates at hand: the fast ones inside their range, else the wide ones.
inline int orient3d_any(bool wide, const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return wide ? orient3d_wide(a, b, c, d) : orient3d(a, b, c, d);
}
inline bool collinear3d_any(bool wide, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return wide ? collinear3d_wide(a, b, c) : collinear3d(a, b, c);
}
inline int orient2d_any(bool wide, double ax, double ay, double bx, double by, double cx, double cy) {
  return wide ? orient2d_wide(ax, ay, bx, by, cx, cy) : orient2d(ax, ay, bx, by, cx, cy);
}

// Affine dimension of the input, exactly (its own small scan: the checker shares no code with exact_hull).
template <class Point>
int input_dimension(const std::vector<Point>& pts, bool wide) {
  if (pts.empty()) return -1;
  const Vec3d a = to_vec3d(pts[0]);
  std::size_t i = 1;
  while (i < pts.size() && pts[i] == pts[0])
    ++i;
  if (i == pts.size()) return 0;
  const Vec3d b = to_vec3d(pts[i]);
  while (i < pts.size() && collinear3d_any(wide, a, b, to_vec3d(pts[i])))
    ++i;
  if (i == pts.size()) return 1;
  const Vec3d c = to_vec3d(pts[i]);
  while (i < pts.size() && orient3d_any(wide, a, b, c, to_vec3d(pts[i])) == 0)
    ++i;
  return i == pts.size() ? 2 : 3;
}

// Whether a coordinate of p is outside the fast predicates' range; false for every float.
inline bool outside_fast_range(const Point3&) {
  return false;
}
inline bool outside_fast_range(const Point3d& p) {
  return !in_fast_exact_range(p.x) || !in_fast_exact_range(p.y) || !in_fast_exact_range(p.z);
}
template <class Point>
bool finite(const Point& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace cudahull::checking
