// Steps 1-2 of the merge (design: facet_merge.hpp): each vertex's height over the hull of its link, and
// the rounds that drop the vertices within the tolerance.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cudahull/detail/plane_impl.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/plane.hpp"
#include "cudahull/predicates.hpp"
#include "geometry.hpp"
#include "mesh_order.hpp"

namespace cudahull::merge {

// Step 1: how far above hull(link) the vertex v stands (see facet_merge.hpp); `link` indexes `points`.
template <class Point>
double vertex_height(const std::vector<Point>& points, const Vec3d& v, const std::vector<PointIndex>& link) {
  const BasicHullMesh<Point> hull = exact_hull(points, link);
  if (hull.dimension == 3) {
    double height = -kInfinity;
    for (const Triangle& t : hull.triangles) {
      const Vec3d a = to_vec3d(hull.vertices[t[0]]), b = to_vec3d(hull.vertices[t[1]]),
                  c = to_vec3d(hull.vertices[t[2]]);
      if (orient3d(a, b, c, v) > 0) height = std::max(height, plane_value(plane_through(a, b, c), v));
    }
    // None above: v is not strictly extreme, which a vertex of an exact hull always is.
    return height == -kInfinity ? kInfinity : height;
  }
  if (hull.dimension == 2) {
    // Strict corners of a convex polygon: any three are affinely independent.
    const Plane plane =
        plane_through(to_vec3d(hull.vertices[hull.polygon[0]]), to_vec3d(hull.vertices[hull.polygon[1]]),
                      to_vec3d(hull.vertices[hull.polygon[2]]));
    return std::fabs(plane_value(plane, v));
  }
  return kInfinity;
}

// Whether v's height over hull(link) (vertex_height()) is certainly above `limit`, found without that hull
// (which, with its planes, was most of a merge: almost every vertex stands far above its link).  A plane
// through three link points with every link point on or below it (exact orient3d) and v strictly above is
// the plane of a facet of hull(link) that v is above, so v's distance to it is at most the height; a lower
// bound on that distance (the determinant's error by Shewchuk's orient3d bound, the edges' lengths rounded
// up) beyond the limit plus a margin for the height's own rounding (under 2^-46 of the largest coordinate)
// decides.  False where no triple shows it: the exact height then decides, as it always did.
inline constexpr std::size_t kMaxLink = 12;  // C(12, 3) triples at most; a larger link takes the exact height

inline bool clearly_above(const Vec3d& v, const Vec3d* link, std::size_t k, double limit) {
  if (k < 3 || k > kMaxLink) return false;
  Vec3d q[kMaxLink];
  double scale = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  for (std::size_t j = 0; j < k; ++j) {
    q[j] = link[j];
    scale = std::max({scale, std::fabs(q[j].x), std::fabs(q[j].y), std::fabs(q[j].z)});
  }
  // The facets of hull(link) that v stands above face about the way from the link's centroid to v, and hold
  // the link points furthest that way: the points sorted that way first, so that the triples of the highest
  // come first (about two triples a vertex on a ball's hull, where the furthest point alone first took five).
  // Only the order of the tries changes: the answer is whether any triple shows it.
  Vec3d centre{0, 0, 0};
  for (std::size_t j = 0; j < k; ++j)
    centre = {centre.x + q[j].x, centre.y + q[j].y, centre.z + q[j].z};
  const Vec3d way = sub(v, {centre.x / k, centre.y / k, centre.z / k});
  double along[kMaxLink];
  for (std::size_t j = 0; j < k; ++j) {
    along[j] = dot(way, q[j]);
    for (std::size_t x = j; x > 0 && along[x - 1] < along[x]; --x) {
      std::swap(along[x - 1], along[x]);
      std::swap(q[x - 1], q[x]);
    }
  }
  const double needed = limit + 0x1p-40 * scale;
  auto length_up = [](const Vec3d& a, const Vec3d& b) {
    const Vec3d d = sub(b, a);
    return std::sqrt(dot(d, d)) * (1 + 0x1p-40);
  };
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b)
      for (std::size_t c = b + 1; c < k; ++c) {
        // v's side of a, b, c: the filter below where it decides (as exact as orient3d), else orient3d.
        const detail::DoubleCross abc = detail::double_cross(q[a], q[b], q[c]);
        int side;
        {
          const Vec3d w = sub(v, q[a]);
          const double det = w.x * abc.n[0] + w.y * abc.n[1] + w.z * abc.n[2];
          const double error =
              detail::kO3dErrBoundA * (1 + 0x1p-40) *
              (std::fabs(w.x) * abc.p[0] + std::fabs(w.y) * abc.p[1] + std::fabs(w.z) * abc.p[2]);
          side = det > error ? 1 : det < -error ? -1 : orient3d(q[a], q[b], q[c], v);
        }
        if (side == 0) continue;
        const Vec3d &pa = q[a], &pb = side > 0 ? q[b] : q[c], &pc = side > 0 ? q[c] : q[b];
        const detail::DoubleCross cross = side > 0 ? abc : detail::double_cross(pa, pb, pc);
        // A link point certainly below by the same filter as v's test below needs no orient3d.
        auto certainly_below = [&](const Vec3d& p) {
          const Vec3d w = sub(p, pa);
          const double det = w.x * cross.n[0] + w.y * cross.n[1] + w.z * cross.n[2];
          const double permanent =
              std::fabs(w.x) * cross.p[0] + std::fabs(w.y) * cross.p[1] + std::fabs(w.z) * cross.p[2];
          return det + detail::kO3dErrBoundA * permanent * (1 + 0x1p-40) < 0;
        };
        bool supports = true;
        for (std::size_t j = 0; j < k && supports; ++j)
          supports = j == a || j == b || j == c || certainly_below(q[j]) || orient3d(pa, pb, pc, q[j]) <= 0;
        if (!supports) continue;
        const Vec3d w = sub(v, pa);
        const double det = w.x * cross.n[0] + w.y * cross.n[1] + w.z * cross.n[2];
        const double permanent =
            std::fabs(w.x) * cross.p[0] + std::fabs(w.y) * cross.p[1] + std::fabs(w.z) * cross.p[2];
        const double low = det - detail::kO3dErrBoundA * permanent * (1 + 0x1p-40);
        if (low > 0 && low / (length_up(pa, pb) * length_up(pa, pc)) * (1 - 0x1p-40) > needed) return true;
      }
  return false;
}

// Steps 1-2: drops the vertices of `current` (its vertex_ids index `points`) whose height is within
// `limit`, in rounds of independent sets, until a round drops nothing or only the flat remains, and
// leaves the final mesh's visit order and relabelled mesh in `visit` and `graph`.
// With an angle (`angle_sine` > 0, Qhull's An), a vertex's limit grows by angle_sine times half its
// distance r to its farthest neighbour in the exact hull (taken once, so that the drops do not compound: a
// later, wider link would let the angle grow): a vertex h above its link makes facets that meet at about
// 2h / r, so the dropped ones are those whose facets' normals differ by less than about the angle, Qhull's
// test for a pair of facets.
template <class Point>
void drop_low_vertices(const std::vector<Point>& points, BasicHullMesh<Point>& current, double limit,
                       double angle_sine, VisitOrder& visit, Relabelled& graph) {
  // Per vertex of `points`: its link (ascending) when its height was computed, and that height; a vertex
  // whose link did not change keeps its height (it depends on nothing else).  The links lie in one pool,
  // each vertex's latest at link_at[id] (link_size[id] of them; a vertex a round did not touch keeps its
  // place): no allocation a vertex.
  std::vector<PointIndex> link_pool;
  std::vector<std::size_t> link_at(points.size(), 0);
  std::vector<std::uint32_t> link_size(points.size(), kNone);  // kNone: no height yet
  std::vector<double> cached_height(points.size(), kInfinity), first_reach(points.size(), -1);
  PhaseLaps laps("drop_low_vertices");  // CUDAHULL_PHASE_TIMES=1
  for (;;) {
    const std::size_t n = current.vertices.size();
    const EdgeIndex edges = index_mesh(current, visit, graph);
    laps.lap("edges and relabelled");
    const Relabelled& g = graph;
    std::vector<PointIndex> ids(n);  // by position
    for (std::uint32_t j = 0; j < n; ++j)
      ids[j] = current.vertex_ids[visit.vertices[j]];
    // By position, turned back into vertex order below.
    std::vector<double> heights_at(n, kInfinity), reach_at(n, 0);
    std::vector<std::uint8_t> relinked_at(n, 0);
    parallel_blocks(
        n, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          std::vector<PointIndex> link;
          std::vector<Vec3d> link_at_points;
          for (std::size_t j = begin; j < end; ++j) {
            const PointIndex id = ids[j];
            const Vec3d v = g.at[j];
            link.clear();
            link_at_points.clear();
            for (std::uint32_t k = g.start[j]; k < g.start[j + 1]; ++k) {
              link.push_back(ids[g.to[k]]);
              link_at_points.push_back(g.at[g.to[k]]);
            }
            if (angle_sine > 0 && first_reach[id] < 0) {
              first_reach[id] = 0;
              for (const Vec3d& w : link_at_points) {
                const Vec3d d = sub(w, v);
                first_reach[id] = std::max(first_reach[id], std::sqrt(dot(d, d)));
              }
            }
            if (angle_sine > 0) reach_at[j] = first_reach[id];
            if (link_size[id] != link.size() ||
                !std::equal(link.begin(), link.end(), link_pool.begin() + link_at[id])) {
              // Above its limit: never dropped, whatever its exact height (infinity stands for it).
              cached_height[id] = clearly_above(v, link_at_points.data(), link_at_points.size(),
                                                limit + angle_sine * reach_at[j] / 2)
                                      ? kInfinity
                                      : vertex_height(points, v, link);
              relinked_at[j] = 1;  // each entry is only this chunk's
            }
            heights_at[j] = cached_height[id];
          }
        },
        256);  // blocks of some hundreds of microseconds: a worker woken for less costs more
    laps.lap("heights");
    // Nothing low enough (most hulls' first round): done, with no bookkeeping for a next round.
    bool any_low = false;
    for (std::uint32_t j = 0; j < n && !any_low; ++j)
      any_low = heights_at[j] <= limit + angle_sine * reach_at[j] / 2;
    if (!any_low) {
      laps.lap("round");
      return;
    }
    std::vector<double> heights(n), reach(n);
    std::vector<std::uint8_t> relinked(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t j = g.rank[i];
      heights[i] = heights_at[j], reach[i] = reach_at[j], relinked[i] = relinked_at[j];
    }
    for (std::uint32_t i = 0; i < n; ++i) {
      if (!relinked[i]) continue;
      const PointIndex id = current.vertex_ids[i];
      link_at[id] = link_pool.size();
      link_size[id] = edges.degree(i);
      for (std::uint32_t k = 0; k < edges.degree(i); ++k)
        link_pool.push_back(current.vertex_ids[edges.neighbour(i, k)]);
    }
    // Lowest first, no two adjacent: their stars are disjoint, so each one's height stays what it was.
    std::vector<std::uint32_t> order;
    for (std::uint32_t i = 0; i < n; ++i)
      if (heights[i] <= limit + angle_sine * reach[i] / 2) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return heights[a] < heights[b] || (heights[a] == heights[b] && a < b);
    });
    std::vector<std::uint8_t> blocked(n, 0), drop(n, 0);
    std::vector<std::uint32_t> dropped;
    for (std::uint32_t i : order) {
      if (blocked[i]) continue;
      dropped.push_back(i);
      blocked[i] = 1;
      for (std::uint32_t k = 0; k < edges.degree(i); ++k)
        blocked[edges.neighbour(i, k)] = 1;
    }
    // Never flat: halve the round's drops (the highest go first) until the rest stays three-dimensional.
    while (!dropped.empty()) {
      std::fill(drop.begin(), drop.end(), 0);
      for (std::uint32_t i : dropped)
        drop[i] = 1;
      std::vector<PointIndex> keep;
      for (std::uint32_t i = 0; i < n; ++i)
        if (!drop[i]) keep.push_back(current.vertex_ids[i]);
      BasicHullMesh<Point> next = exact_hull(points, keep);
      if (next.dimension == 3) {
        current = std::move(next);
        break;
      }
      dropped.resize(dropped.size() / 2);
    }
    laps.lap("round");
    if (dropped.empty()) return;  // the mesh unchanged by this round
  }
}

}  // namespace cudahull::merge
