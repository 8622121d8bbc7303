// Exact 3D convex hull: exact QuickHull with outside sets (conflict lists) on the exact predicates, then a
// polish pass that merges coplanar faces into facets and keeps only strict corners.  Lower-dimensional
// inputs get an exact segment or an exact 2D hull (Andrew's monotone chain).
//
// Every combinatorial decision is an exact predicate (orient3d, orient2d, collinear3d) on the input's own
// coordinates, float (Point3) or double (Point3d): one implementation, instantiated for both.  Other
// arithmetic appears only to rank candidates (furthest point), which needs no exactness: a wrong ranking
// costs time, never correctness, because every choice is re-checked exactly.  (Ranking may overflow to
// infinity or NaN, or underflow to zero, on huge or tiny doubles; every such pick is re-checked too.)
//
// The predicates are a policy (FastPredicates, WidePredicates): exact_hull() is the fast one;
// exact_hull_any() takes every finite double, scaling the input by a power of two where that is enough, else
// on the wide predicates.
//
// This file holds the entry points and exact_hull() on a predicate policy (hull_with); the parts live in
// exact_vector.hpp (vector helpers), exact_sites.hpp (sorting and deduplication), exact_lower_dimension.hpp
// (the affine basis and the 2D hull) and exact_quickhull.hpp (QuickHull).
#include "cudahull/exact_hull.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/wide_predicates.hpp"
#include "exact_lower_dimension.hpp"
#include "exact_quickhull.hpp"
#include "exact_sites.hpp"
#include "exact_vector.hpp"

namespace cudahull {
namespace exact {
namespace {

// The exact predicates behind every combinatorial decision are a policy (wide_predicates.hpp):
// FastPredicates (exact_hull) calls the inline predicates themselves, so its instantiations compile to the
// same code as direct calls; WidePredicates (exact_hull_any, when no power-of-two scale brings the input
// into the fast range) is exact for every finite double, slower.

// exact_hull() deciding with the predicates of Pred.
template <class Pred, class Point>
BasicHullMesh<Point> hull_with(const std::vector<Point>& points, const std::vector<PointIndex>& ids) {
  const std::size_t n = ids.empty() ? points.size() : ids.size();
  if (n >= kNone) throw std::length_error("exact_hull: too many points");

  // Distinct points, each carrying the lowest input index of its coordinates: only that index may become a
  // vertex.
  std::vector<Site<Point>> sites(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PointIndex id = ids.empty() ? static_cast<PointIndex>(i) : ids[i];
    if (id >= points.size())
      throw std::out_of_range("exact_hull: id " + std::to_string(id) + " out of range");
    const Point& q = points[id];
    sites[i] = {q.x, q.y, q.z, id};
  }
  sort_and_dedupe(sites);
  const std::size_t m = sites.size();
  // The vertex coordinates are those of the vertex's own input point (+0 and -0 compared equal above).
  for (Site<Point>& s : sites) {
    const Point& q = points[s.id];
    s.x = q.x, s.y = q.y, s.z = q.z;
  }

  std::vector<Vec3d> p(m);
  for (std::size_t i = 0; i < m; ++i)
    p[i] = {sites[i].x, sites[i].y, sites[i].z};
  const Basis bs = find_basis<Pred>(m, [&](std::uint32_t i) { return p[i]; });

  std::vector<std::uint32_t> out_index;
  switch (bs.dim) {
    case -1: {
      BasicHullMesh<Point> empty;
      empty.dimension = -1;
      return empty;
    }
    case 0:
      return make_mesh<Point>(sites, {bs.a}, 0, out_index);
    case 1:
      return make_mesh<Point>(sites, {bs.a, bs.b}, 1, out_index);
    case 2: {
      const std::vector<std::uint32_t> poly = hull_2d<Pred>(p, bs);
      BasicHullMesh<Point> mesh = make_mesh(sites, poly, 2, out_index);
      for (std::uint32_t s : poly)
        mesh.polygon.push_back(out_index[s]);
      return mesh;
    }
    default:
      break;
  }

  QuickHull<Pred> qh(p);
  qh.build(bs.a, bs.b, bs.c, bs.d);
  std::vector<Triangle> tris = qh.polish();
  std::vector<std::uint8_t> used(m, 0);
  for (const Triangle& t : tris)
    for (std::uint32_t v : t)
      used[v] = 1;
  std::vector<std::uint32_t> keep;
  for (std::uint32_t i = 0; i < m; ++i)
    if (used[i]) keep.push_back(i);
  BasicHullMesh<Point> mesh = make_mesh(sites, std::move(keep), 3, out_index);
  mesh.triangles.reserve(tris.size());
  for (const Triangle& t : tris)
    mesh.triangles.push_back({out_index[t[0]], out_index[t[1]], out_index[t[2]]});
  return mesh;
}

}  // namespace
}  // namespace exact

// ---------------------------------------------------------------------------------------------------------

using exact::find_basis;
using exact::hull_with;

template <class Point>
int affine_dimension(const std::vector<Point>& points) {
  return find_basis<FastPredicates>(points.size(), [&](std::uint32_t i) { return to_vec3d(points[i]); }).dim;
}

template <class Point>
BasicHullMesh<Point> exact_hull(const std::vector<Point>& points, const std::vector<PointIndex>& ids) {
  return hull_with<FastPredicates>(points, ids);
}

bool in_fast_exact_range(const Point3d* points, std::size_t count) {
  // Every point tested, without a branch a coordinate: a small cloud's check costs a few comparisons.
  bool in_range = true;
  for (std::size_t i = 0; i < count; ++i)
    in_range &= in_fast_exact_range(points[i].x) & in_fast_exact_range(points[i].y) &
                in_fast_exact_range(points[i].z);
  return in_range;
}

bool in_fast_exact_range(const std::vector<Point3d>& points) {
  return in_fast_exact_range(points.data(), points.size());
}

HullMeshd exact_hull_any(const std::vector<Point3d>& points, const std::vector<PointIndex>& ids) {
  const std::size_t n = ids.empty() ? points.size() : ids.size();
  // The binades (floor(log2 |c|)) of the nonzero coordinates that take part; ids out of range are left to
  // exact_hull(), which reports them.
  bool fast = true;
  int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
  for (std::size_t i = 0; i < n; ++i) {
    const PointIndex id = ids.empty() ? static_cast<PointIndex>(i) : ids[i];
    if (id >= points.size()) continue;
    for (const double c : {points[id].x, points[id].y, points[id].z}) {
      if (!std::isfinite(c))
        throw std::invalid_argument("exact_hull_any: point " + std::to_string(id) +
                                    " has a coordinate that is not finite");
      fast = fast && in_fast_exact_range(c);
      if (c == 0.0) continue;
      const int b = std::ilogb(c);  // exact for subnormals too
      lo = std::min(lo, b), hi = std::max(hi, b);
    }
  }
  if (fast) return hull_with<FastPredicates>(points, ids);

  // One power of two 2^k that moves every binade into -250..249 (the fast range) exists when
  // -250 - lo <= 249 - hi; the scaled coordinates are normal doubles, so the scaling is exact, keeps
  // equality and order (dedupe, tie-breaks, the lexicographic extremes) and the sign of every predicate.
  const int k_min = -250 - lo, k_max = 249 - hi;
  if (k_min <= k_max) {
    const int k = k_min + (k_max - k_min) / 2;   // centred: leaves the ranking arithmetic room both ways
    std::vector<Point3d> scaled(points.size());  // only the points taking part are read
    for (std::size_t i = 0; i < n; ++i) {
      const PointIndex id = ids.empty() ? static_cast<PointIndex>(i) : ids[i];
      if (id >= points.size()) continue;
      const Point3d& q = points[id];
      scaled[id] = {std::ldexp(q.x, k), std::ldexp(q.y, k), std::ldexp(q.z, k)};
    }
    HullMeshd mesh = hull_with<FastPredicates>(scaled, ids);
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      mesh.vertices[v] = points[mesh.vertex_ids[v]];  // the input's own coordinates, -0 included
    return mesh;
  }
  return hull_with<WidePredicates>(points, ids);
}

// The two point types; one implementation.
template HullMesh exact_hull(const std::vector<Point3>&, const std::vector<PointIndex>&);
template HullMeshd exact_hull(const std::vector<Point3d>&, const std::vector<PointIndex>&);
template int affine_dimension(const std::vector<Point3>&);
template int affine_dimension(const std::vector<Point3d>&);

}  // namespace cudahull
