// Hulls of dimension 1 and 2: a segment whose ends hold every input point, and a strictly convex simple
// polygon in the input's plane that holds every input point.
#include "checker.hpp"

#include <algorithm>
#include <array>
#include <cinttypes>
#include <cstdint>
#include <utility>
#include <vector>

#include "check_predicates.hpp"

namespace cudahull::checking {

// Dimension 1: the input is collinear (checked), so a point is inside the segment iff it lies between the
// ends in lexicographic order, which is monotone along a line.
template <class Point>
void Checker<Point>::check_segment() {
  Point lo = h_.vertices[0], hi = h_.vertices[1];
  if (lo == hi) return;  // reported as coincident vertices
  if (lex_less(hi, lo)) std::swap(lo, hi);
  std::size_t reported = 0;
  for (std::size_t i = 0; i < pts_.size() && reported < rep_.max; ++i)
    if (lex_less(pts_[i], lo) || lex_less(hi, pts_[i])) {
      rep_.fail(pname(i) + " lies on the line beyond the segment's ends");
      ++reported;
    }
}

// Dimension 2: the input is coplanar (checked) and the corners are input points, so the polygon lies in the
// input's plane.  Checks strict convexity, simplicity, and that every point is inside or on the polygon.
template <class Point>
void Checker<Point>::check_polygon() {
  const std::vector<std::uint32_t>& poly = h_.polygon;
  const std::size_t k = poly.size(), nv = h_.vertex_ids.size();
  if (k < 3) {
    rep_.fail(fmt("a hull of dimension 2 has a polygon of %zu corners", k));
    return;
  }
  std::vector<int> uses(nv, 0);
  for (std::uint32_t v : poly) {
    if (v >= nv) {
      rep_.fail(fmt("polygon corner index %" PRIu32 " is beyond the %zu vertices", v, nv));
      return;
    }
    ++uses[v];
  }
  bool ok = true;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (uses[v] != 1) {
      rep_.fail(fmt("vertex %" PRIu32 " (id %" PRIu32 ") appears %d times in the polygon (expected once)", v,
                    h_.vertex_ids[v], uses[v]));
      ok = false;
    }
  if (!ok) return;

  // Project by dropping an axis along which the plane's normal has an exactly non-zero component.  Any three
  // consecutive corners of a strictly convex polygon give that normal's direction; find a non-collinear
  // triple.
  auto coord = [](const Point& p, int a) -> double { return a == 0 ? p.x : a == 1 ? p.y : p.z; };
  int axis = -1;
  for (std::size_t i = 0; i < k && axis < 0; ++i) {
    const Point &a = h_.vertices[poly[i]], &b = h_.vertices[poly[(i + 1) % k]],
                &c = h_.vertices[poly[(i + 2) % k]];
    for (int t = 0; t < 3 && axis < 0; ++t) {
      const int u = (t + 1) % 3, w = (t + 2) % 3;
      if (orient2d_any(rep_.wide, coord(a, u), coord(a, w), coord(b, u), coord(b, w), coord(c, u),
                       coord(c, w)) != 0)
        axis = t;
    }
  }
  if (axis < 0) {
    rep_.fail("the polygon's corners are collinear");
    return;
  }
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  std::vector<std::array<double, 2>> q(k);
  for (std::size_t i = 0; i < k; ++i)
    q[i] = {coord(h_.vertices[poly[i]], u), coord(h_.vertices[poly[i]], w)};
  auto turn = [&](const std::array<double, 2>& a, const std::array<double, 2>& b,
                  const std::array<double, 2>& c) {
    return orient2d_any(rep_.wide, a[0], a[1], b[0], b[1], c[0], c[1]);
  };
  // Orientation from the first strictly turning corner; every corner must turn the same way.
  int sign = 0;
  for (std::size_t i = 0; i < k && sign == 0; ++i)
    sign = turn(q[i], q[(i + 1) % k], q[(i + 2) % k]);
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t j = (i + 1) % k;
    const int s = turn(q[i], q[j], q[(i + 2) % k]);
    if (s == 0) {
      rep_.fail(
          fmt("polygon corner %zu, vertex %s, is not strictly extreme: it is collinear with its neighbours",
              j, vname(poly[j]).c_str()));
      ok = false;
    } else if (s != sign) {
      rep_.fail(fmt("polygon corner %zu, vertex %s, is reflex: the polygon is not convex", j,
                    vname(poly[j]).c_str()));
      ok = false;
    }
  }
  if (!ok) return;
  // Same turn everywhere and one lexicographic maximum along the cycle: total turning 2*pi, a simple convex
  // polygon (a star polygon turns the same way everywhere too, but has several maxima).
  auto lexq = [](const std::array<double, 2>& a, const std::array<double, 2>& b) { return a < b; };
  std::size_t maxima = 0;
  for (std::size_t i = 0; i < k; ++i)
    if (lexq(q[(i + k - 1) % k], q[i]) && lexq(q[(i + 1) % k], q[i])) ++maxima;
  if (maxima != 1) {
    rep_.fail(fmt("the polygon winds %zu times around its interior (not simple)", maxima));
    return;
  }
  if (sign < 0) std::reverse(q.begin(), q.end());  // counter-clockwise in the projection from here on

  // Point in convex polygon: binary search for the wedge at q[0], then the edge test.  O(log k) per point.
  parallel_failures(pts_.size(), 2, rep_, [&](std::size_t i, auto& sink, std::size_t) {
    const std::array<double, 2> x = {coord(pts_[i], u), coord(pts_[i], w)};
    bool in = turn(q[0], q[1], x) >= 0 && turn(q[0], q[k - 1], x) <= 0;
    if (in) {
      std::size_t lo = 1, hi = k - 1;
      while (hi - lo > 1) {
        const std::size_t mid = (lo + hi) / 2;
        (turn(q[0], q[mid], x) >= 0 ? lo : hi) = mid;
      }
      in = turn(q[lo], q[hi], x) >= 0;
    }
    if (!in) sink(i, pname(i) + " is outside the polygon");
  });
}

// The two point types; the callers are in other files.
template void Checker<Point3>::check_segment();
template void Checker<Point3>::check_polygon();
template void Checker<Point3d>::check_segment();
template void Checker<Point3d>::check_polygon();

}  // namespace cudahull::checking
