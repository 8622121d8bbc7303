// Qhull-like facet merging of an exact hull (design: facet_merge.hpp).
#include "facet_merge.hpp"

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "cudahull/exact_hull.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "merge/box_tree.hpp"
#include "merge/certificate.hpp"
#include "merge/geometry.hpp"
#include "merge/grouping.hpp"
#include "merge/low_vertices.hpp"
#include "merge/mesh_order.hpp"

namespace cudahull {

using namespace merge;

template <class Point>
MergedHull merge_facets(const std::vector<Point>& points, const BasicHullMesh<Point>& exact, double tolerance,
                        double angle_sine, MergedFacesWork* work) {
  if (!(tolerance >= 0) || !std::isfinite(tolerance))
    throw std::invalid_argument("merge_facets: the tolerance must be finite and >= 0, not " +
                                std::to_string(tolerance));
  if (!(angle_sine >= 0 && angle_sine <= 1))
    throw std::invalid_argument("merge_facets: the angle's sine must be in [0, 1], not " +
                                std::to_string(angle_sine));
  (void)points;  // every input point is a convex combination of exact.vertices, which hold their coordinates
  MergedHull merged;
  merged.tolerance = tolerance;
  if (exact.dimension != 3) {
    merged.vertices = exact.vertex_ids;
    std::sort(merged.vertices.begin(), merged.vertices.end());
    return merged;
  }
  // Work on the exact hull's vertices, by their position in exact.vertices.
  const std::vector<Point>& vertices = exact.vertices;
  const std::size_t m = vertices.size();
  PhaseLaps laps("merge_facets");  // CUDAHULL_PHASE_TIMES=1
  BasicHullMesh<Point> current = exact;
  std::iota(current.vertex_ids.begin(), current.vertex_ids.end(), PointIndex{0});

  VisitOrder visit;
  Relabelled graph;
  if (tolerance > 0 || angle_sine > 0)
    drop_low_vertices(vertices, current, tolerance, angle_sine, visit, graph);
  else
    index_mesh(current, visit, graph);
  laps.lap("drop");
  Facets facets = group_facets(current, graph, visit, std::move(graph.largest_first), tolerance, angle_sine);
  laps.lap("group");

  // The triangles by facet, each facet's triangles ascending (a counting sort: the stable sort's order), and
  // each triangle's place in that order; where every facet is one triangle (a ball's hull), the facets'
  // seeds and the facets themselves (the facets are numbered in the faces' order, and their planes are the
  // faces').
  const std::size_t nt = current.triangles.size();
  const bool single_triangles = facets.planes.size() == nt;
  PassVector<std::uint32_t> sorted_by_facet, sorted_position;
  if (!single_triangles) {
    sorted_by_facet.resize(nt);
    sorted_position.resize(nt);
    std::vector<std::uint32_t> facet_start(facets.planes.size() + 1, 0);
    for (std::uint32_t f : facets.facet_of)
      ++facet_start[f + 1];
    for (std::size_t f = 0; f + 1 < facet_start.size(); ++f)
      facet_start[f + 1] += facet_start[f];
    for (std::uint32_t t = 0; t < nt; ++t) {
      sorted_position[t] = facet_start[facets.facet_of[t]]++;
      sorted_by_facet[sorted_position[t]] = t;
    }
  }
  const PassVector<std::uint32_t>& by_facet = single_triangles ? facets.seeds : sorted_by_facet;
  const PassVector<std::uint32_t>& position = single_triangles ? facets.facet_of : sorted_position;
  // The kept vertices and the dropped ones, on one core beside the kept vertices' bounds (below), which do
  // not depend on them.
  std::vector<std::uint32_t> dropped;
  auto output = [&] {
    merged.vertices.reserve(current.vertex_ids.size());
    for (PointIndex id : current.vertex_ids)
      merged.vertices.push_back(exact.vertex_ids[id]);
    if (!std::is_sorted(merged.vertices.begin(), merged.vertices.end()))
      std::sort(merged.vertices.begin(), merged.vertices.end());

    // Coplanar: every exact-hull vertex that was dropped, with its nearest triangle and that one's nearest
    // corner.
    std::vector<std::uint8_t> kept(m, 0);
    for (PointIndex id : current.vertex_ids)
      kept[id] = 1;
    for (std::uint32_t i = 0; i < m; ++i)
      if (!kept[i]) dropped.push_back(i);
    std::sort(dropped.begin(), dropped.end(),
              [&](std::uint32_t a, std::uint32_t b) { return exact.vertex_ids[a] < exact.vertex_ids[b]; });
  };
  PhaseLaps::Span output_span;
  // The faces in their facets' order, in the kept bounds' pass.
  merged.faces.resize(nt);
  merged.face_positions.resize(nt);
  if (!single_triangles) merged.planes.resize(nt);
  merged.facet_of_face.resize(nt);
  merged.neighbors.resize(nt);
  auto faces = [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      const std::uint32_t t = by_facet[p];
      const Triangle& tri = current.triangles[t];
      const Triangle at = {current.vertex_ids[tri[0]], current.vertex_ids[tri[1]],
                           current.vertex_ids[tri[2]]};
      merged.face_positions[p] = at;
      merged.faces[p] = {exact.vertex_ids[at[0]], exact.vertex_ids[at[1]], exact.vertex_ids[at[2]]};
      if (!single_triangles) merged.planes[p] = facets.planes[facets.facet_of[t]];
      merged.facet_of_face[p] = facets.facet_of[t];
      for (int k = 0; k < 3; ++k) {
        // The edge opposite corner k runs from corner k + 1 to corner k + 2: across[3t + k + 1] holds it.
        const std::uint32_t u = facets.across[3 * t + (k + 1) % 3];
        if (u == kNone) throw std::logic_error("merge_facets: the mesh is not closed");
        merged.neighbors[p][k] = static_cast<std::int32_t>(position[u]);
      }
    }
    if (work) work->faces(merged, begin, end);
  };
  if (work && nt > 0) {
    const Triangle& first = current.triangles[by_facet[0]];
    work->start({current.vertex_ids[first[0]], current.vertex_ids[first[1]], current.vertex_ids[first[2]]},
                nt);
  }
  // The vertices' centroid for the thinnest depth, summed in the mesh's order.
  Vec3d centroid{0, 0, 0};
  for (const Point& p : current.vertices) {
    const Vec3d q = to_vec3d(p);
    centroid = {centroid.x + q.x, centroid.y + q.y, centroid.z + q.z};
  }
  const double vertex_count = static_cast<double>(current.vertices.size());
  centroid = {centroid.x / vertex_count, centroid.y / vertex_count, centroid.z / vertex_count};
  laps.lap("facet order and set up");
  const KeptBounds kept = kept_bounds(
      graph, facets.planes, facets.in_visit_order, facets.visit_starts, centroid, 4 * tolerance,
      [&] { output_span.time(output); }, nt, faces);
  laps.note("the kept and dropped vertices beside", output_span);
  laps.lap("kept bounds and faces");
  if (single_triangles) merged.planes = std::move(facets.planes);
  const std::vector<Plane>& facet_planes = single_triangles ? merged.planes : facets.planes;
  merged.coplanar.resize(dropped.size());
  auto face_corner = [&](std::uint32_t f, int k) {
    return to_vec3d(current.vertices[current.triangles[by_facet[f]][k]]);
  };
  std::vector<Box> face_boxes(dropped.empty() ? 0 : by_facet.size());
  for (std::uint32_t f = 0; f < face_boxes.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3d c = face_corner(f, k);
      face_boxes[f].add({{c.x, c.y, c.z}, {c.x, c.y, c.z}});
    }
  const BoxTree face_tree(std::move(face_boxes));
  parallel_chunks(
      dropped.size(), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        std::vector<std::uint32_t> stack;
        const auto& nodes = face_tree.nodes();
        auto box_distance2 = [&](const Vec3d& p, const Box& b) {
          const double q[3] = {p.x, p.y, p.z};
          double d2 = 0;
          for (int k = 0; k < 3; ++k) {
            const double d = std::max({b.lo[k] - q[k], 0.0, q[k] - b.hi[k]});
            d2 += d * d;
          }
          return d2;
        };
        for (std::size_t k = begin; k < end; ++k) {
          const Vec3d p = to_vec3d(vertices[dropped[k]]);
          // The nearest triangle, the lowest index among equals (the search order does not matter).
          double best = kInfinity;
          std::uint32_t best_face = 0;
          stack.assign(1, 0);
          while (!stack.empty()) {
            const auto& node = nodes[stack.back()];
            stack.pop_back();
            if (box_distance2(p, node.box) > best) continue;
            if (node.left == kNone) {
              for (std::uint32_t i = node.begin; i < node.end; ++i) {
                const std::uint32_t f = face_tree.item(i);
                const double d2 =
                    triangle_distance2(p, face_corner(f, 0), face_corner(f, 1), face_corner(f, 2));
                if (d2 < best || (d2 == best && f < best_face)) best = d2, best_face = f;
              }
              continue;
            }
            stack.push_back(node.left);
            stack.push_back(node.right);
          }
          const Triangle& t = current.triangles[by_facet[best_face]];
          double nearest = kInfinity;
          PointIndex corner = 0;
          for (std::uint32_t v : t) {
            const Vec3d q = sub(p, to_vec3d(current.vertices[v]));
            if (dot(q, q) < nearest) nearest = dot(q, q), corner = exact.vertex_ids[current.vertex_ids[v]];
          }
          merged.coplanar[k] = {exact.vertex_ids[dropped[k]], best_face, corner};
        }
      },
      32);

  laps.lap("coplanar");
  merged.thinnest = facet_planes.empty() ? kInfinity : kept.thinnest;
  std::vector<Vec3d> dropped_points;
  for (std::uint32_t i : dropped)
    dropped_points.push_back(to_vec3d(vertices[i]));
  // The kept vertices' bound per facet (kept_bounds() gives them in the visit order): needed only where
  // points were dropped.
  std::vector<double> kept_bound;
  if (!dropped_points.empty()) {
    kept_bound.resize(facet_planes.size());
    for (std::size_t i = 0; i < kept.bounds.size(); ++i)
      kept_bound[facets.in_visit_order[i]] = kept.bounds[i];
  }
  merged.max_outside =
      std::nextafter(dropped_bound(dropped_points, facet_planes, kept_bound, kept.largest), kInfinity);
  laps.lap("dropped bound");
  return merged;
}

// Qhull 2020.2 (github.com/qhull/qhull, src/libqhull_r/geom2_r.c: qh_maxmin, qh_distround, qh_detroundoff;
// global_r.c: qh_initqhull_globals), default options in 3-D (no 'Cn', 'An' or 'QJ': pre-merge with 'C-0'):
//   qh_maxmin:      per axis k, maxabs_k = max(max_k, -min_k) over the points;
//                   qh.MAXabs_coord = max_k maxabs_k, qh.MAXsumcoord = sum_k maxabs_k
//   qh_distround:   maxdistsum = min(sqrt(3) x MAXabs_coord, MAXsumcoord)
//                   qh.DISTround = REALepsilon x (3 x maxdistsum x 1.01 + MAXabs_coord),  REALepsilon =
//                   DBL_EPSILON
//   qh_detroundoff: qh.premerge_centrum = 0 ('C-0') + 2 x DISTround ("2 for centrum and distplane()"), the
//                   centrum radius of Qhull's coplanar-facet test; qh.MINvisible = premerge_centrum (3-D);
//                   qh.MINoutside = 2 x MINvisible = 4 x DISTround.
//   qh_findbest / qh_partitionpoint (geom_r.c, libqhull_r.c): a point is outside a facet, so that it can
//   become a vertex, only if its distance is at least qh.MINoutside; otherwise it stays a coplanar point.
// The tolerance returned is qh.MINoutside: merge_facets() drops a vertex when it stands within the tolerance
// of the hull of the others, which is that test (4 x DISTround, not 2, matches Qhull's vertex counts:
// docs/benchmarks.md, "The measurements behind the code's constants").
// Qhull's options 'Qbb' (scale the last coordinate, Delaunay only) and 'Qt' do not change it.
template <class Point>
double qhull_default_tolerance(const std::vector<Point>& points) {
  if (points.empty()) return 0;
  double maxabs[3] = {0, 0, 0};
  for (const Point& p : points) {
    maxabs[0] = std::max(maxabs[0], std::fabs(static_cast<double>(p.x)));
    maxabs[1] = std::max(maxabs[1], std::fabs(static_cast<double>(p.y)));
    maxabs[2] = std::max(maxabs[2], std::fabs(static_cast<double>(p.z)));
  }
  const double max_abs_coord = std::max({maxabs[0], maxabs[1], maxabs[2]});
  const double max_sum_coord = maxabs[0] + maxabs[1] + maxabs[2];
  const double max_dist_sum = std::min(std::sqrt(3.0) * max_abs_coord, max_sum_coord);
  const double dist_round = DBL_EPSILON * (3 * max_dist_sum * 1.01 + max_abs_coord);
  return 4 * dist_round;
}

template MergedHull merge_facets(const std::vector<Point3>&, const HullMesh&, double, double,
                                 MergedFacesWork*);
template MergedHull merge_facets(const std::vector<Point3d>&, const HullMeshd&, double, double,
                                 MergedFacesWork*);
template double qhull_default_tolerance(const std::vector<Point3>&);
template double qhull_default_tolerance(const std::vector<Point3d>&);

}  // namespace cudahull
