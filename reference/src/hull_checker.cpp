// The independent hull checker (`cudahull hull --verify`).  It shares no code with exact_hull: every
// decision is an exact predicate on the input coordinates (and, for containment, on one double interior
// point), and it never builds a hull itself.
#include "cudahull/hull_checker.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstddef>
#include <vector>

#include "check_predicates.hpp"
#include "check_report.hpp"
#include "checker.hpp"
#include "mesh_checker.hpp"

namespace cudahull::checking {

template <class Point>
void Checker<Point>::run() {
  if (!check_vertices()) return;
  check_lowest_index();
  const int d = h_.dimension;
  if (d < -1 || d > 3) {
    rep_.fail(fmt("invalid dimension %d", d));
    return;
  }
  const int din = input_dimension(pts_, rep_.wide);
  if (din != d) {
    rep_.fail(
        fmt("dimension mismatch: the hull has dimension %d but the input points have affine dimension %d", d,
            din));
    return;
  }
  if (d != 3 && !h_.triangles.empty())
    rep_.fail(fmt("a hull of dimension %d has %zu triangles (expected none)", d, h_.triangles.size()));
  if (d != 2 && !h_.polygon.empty())
    rep_.fail(
        fmt("a hull of dimension %d has a polygon of %zu corners (expected none)", d, h_.polygon.size()));
  const std::size_t expect_v[] = {0, 1, 2};
  if (d <= 1 && h_.vertex_ids.size() != expect_v[d + 1]) {
    rep_.fail(fmt("a hull of dimension %d has %zu vertices (expected %zu)", d, h_.vertex_ids.size(),
                  expect_v[d + 1]));
    return;
  }
  // Dimension 0: the input is one repeated point and the vertex is an input point; the lowest-index rule
  // was checked above, so nothing is left.
  if (d == 1) check_segment();
  if (d == 2) check_polygon();
  if (d == 3) MeshChecker<Point>(pts_, h_, rep_).run();
}

}  // namespace cudahull::checking

namespace cudahull {

template <class Point>
CheckResult check_hull(const std::vector<Point>& points, const BasicHullMesh<Point>& hull,
                       std::size_t max_failures) {
  CheckResult result;
  checking::Report rep{result, max_failures};
  // The wide predicates take every finite double; NaN and infinity are no coordinates at all.
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!checking::finite(points[i])) {
      rep.fail(checking::fmt("point %zu %s is not finite", i, checking::coords(points[i]).c_str()));
      return result;
    }
  for (std::size_t v = 0; v < hull.vertices.size(); ++v)
    if (!checking::finite(hull.vertices[v])) {
      rep.fail(checking::fmt("vertex %zu %s is not finite", v, checking::coords(hull.vertices[v]).c_str()));
      return result;
    }
  rep.wide = std::any_of(points.begin(), points.end(),
                         [](const Point& p) { return checking::outside_fast_range(p); }) ||
             std::any_of(hull.vertices.begin(), hull.vertices.end(),
                         [](const Point& p) { return checking::outside_fast_range(p); });
  checking::Checker<Point>(points, hull, rep).run();
  return result;
}

// The two point types; one implementation.
template CheckResult check_hull(const std::vector<Point3>&, const HullMesh&, std::size_t);
template CheckResult check_hull(const std::vector<Point3d>&, const HullMeshd&, std::size_t);

}  // namespace cudahull
