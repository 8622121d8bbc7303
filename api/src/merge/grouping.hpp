// Step 3 of the merge (design: facet_merge.hpp): the triangles grouped into merged facets, largest first.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/plane.hpp"
#include "cudahull/predicates.hpp"
#include "geometry.hpp"
#include "mesh_order.hpp"

namespace cudahull::merge {

struct Facets {
  PassVector<std::uint32_t> facet_of;  // per triangle of the mesh
  std::vector<Plane> planes;           // per facet
  PassVector<std::uint32_t> seeds;     // per facet: its largest triangle
  PassVector<std::uint32_t> across;    // per triangle t and edge k: the triangle holding its reverse
  // The facets by their seeds' places in the visit order, and each one's seed corners as positions of the
  // relabelled mesh: kept_bounds() takes the facets in this order, so that neighbours' planes are read
  // together.
  PassVector<std::uint32_t> in_visit_order;
  PassVector<std::array<std::uint32_t, 3>> visit_starts;
};

// Step 3: groups the triangles of `mesh` into merged facets.
// With an angle (`angle_sine` > 0), a corner also fits where it lies within angle_sine times its distance
// from the seed's nearest corner of the seed's plane (a tilt of at most about that angle).
//
// Each triangle's plane, its neighbours across its edges, which of them would join it as a seed and, for a
// group of it alone, the plane's offset are found first, on all cores: the seeds come largest first,
// scattered over the mesh, and most of them stay alone (every one on a ball), so that the sequential
// grouping then reads four words for such a seed, where it read both triangles' corners and planes for each
// of its edges (a cache miss each, most of the grouping's time on a large hull).  All of it works on the
// triangles renumbered by their visit order (position j for visit.triangles[j]) and the relabelled mesh
// `g`, so that neighbours' data lies together; the seeds' order (largest first, ties by the mesh's index)
// and every test are the mesh's, so the facets are too.
template <class Point>
Facets group_facets(const BasicHullMesh<Point>& mesh, const Relabelled& g, const VisitOrder& visit,
                    LargestFirst largest_first, double tolerance, double angle_sine) {
  PhaseLaps laps("group_facets");  // CUDAHULL_PHASE_TIMES=1
  const std::size_t nt = mesh.triangles.size();
  const std::vector<std::uint32_t>& jrank = visit.triangle_rank;  // per mesh triangle: its position
  PassVector<std::array<std::uint32_t, 3>> tri(nt);               // per position: its corners' positions
  auto corner = [&](std::uint32_t j, int k) { return g.at[tri[j][k]]; };
  // The triangle holding the directed edge a -> b (positions), kNone if none.
  auto holder = [&](std::uint32_t a, std::uint32_t b) {
    for (std::uint32_t e = g.start[a]; e < g.start[a + 1]; ++e)
      if (g.to[e] == b) return g.face[e];
    return kNone;
  };
  PassVector<Plane> plane(nt);
  // The seeds' order, largest first, ties by the mesh's index (Relabelled::largest_first): sorted beside
  // the planes' pass, ranked beside the joining pass.
  const auto& keyed = largest_first.keys;
  PassVector<std::uint32_t> across(3 * nt);  // the triangle across edge k of j: the one holding its reverse
  PhaseLaps::Span sort;
  parallel_blocks_beside(
      nt, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t j = begin; j < end; ++j) {
          const Triangle& corners = mesh.triangles[visit.triangles[j]];
          tri[j] = {g.rank[corners[0]], g.rank[corners[1]], g.rank[corners[2]]};
          const Vec3d a = corner(j, 0), b = corner(j, 1), c = corner(j, 2);
          plane[j] = plane_through(a, b, c);
          for (int k = 0; k < 3; ++k)
            across[3 * j + k] = holder(tri[j][(k + 1) % 3], tri[j][k]);
        }
      },
      [&] { sort.time([&] { largest_first.sort(); }); }, 1024);
  laps.note("the seeds' order beside", sort);
  laps.lap("planes");
  // Whether `vertex` (a position) fits the group of `seed`: within the tolerance of the seed's plane, or
  // exactly on it (a point exactly on it evaluates to within a few ulps of the coordinates' scale, under 28u
  // by plane.cpp's analysis; the exact orient3d decides).
  auto fits = [&](std::uint32_t seed, std::uint32_t vertex) {
    const Vec3d sa = corner(seed, 0), sb = corner(seed, 1), sc = corner(seed, 2);
    const Vec3d p = g.at[vertex];
    const double value = std::fabs(plane_value(plane[seed], p));
    if (value <= tolerance) return true;
    if (angle_sine > 0) {
      double nearest = kInfinity;
      for (const Vec3d& s : {sa, sb, sc}) {
        const Vec3d d = sub(p, s);
        nearest = std::min(nearest, std::sqrt(dot(d, d)));
      }
      if (value <= tolerance + angle_sine * nearest) return true;
    }
    const double scale = std::max({std::fabs(sa.x), std::fabs(sa.y), std::fabs(sa.z), std::fabs(sb.x),
                                   std::fabs(sb.y), std::fabs(sb.z), std::fabs(sc.x), std::fabs(sc.y),
                                   std::fabs(sc.z), std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    return value <= 64 * kUnitRoundoff * scale && orient3d(sa, sb, sc, p) == 0;
  };
  // Whether triangle u joins the group of `seed` across an edge: facing the group's way too (across a body
  // thinner than the tolerance, the far side's triangles fit the plane but face away from it), every corner
  // fitting.
  // Corner `first` is tested first: across an edge, the far corner, which alone usually fails.
  auto joins = [&](std::uint32_t seed, std::uint32_t u, int first = 0) {
    if (dot3(plane[seed], {plane[u][0], plane[u][1], plane[u][2]}) <= 0) return false;
    return fits(seed, tri[u][first]) && fits(seed, tri[u][(first + 1) % 3]) &&
           fits(seed, tri[u][(first + 2) % 3]);
  };
  // Per triangle as a seed: which neighbours would join (bit k: across edge k), and the offset of its plane
  // were it alone (the top of its corners).
  PassVector<std::uint8_t> joining(nt);
  PhaseLaps::Span ranks;
  PassVector<double> alone_top(nt);
  parallel_blocks_beside(
      nt, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t j = begin; j < end; ++j) {
          std::uint8_t bits = 0;
          for (int k = 0; k < 3; ++k) {
            const std::uint32_t u = across[3 * j + k];
            if (u == kNone) continue;
            // u holds the edge's reverse, tri[j][k + 1] -> tri[j][k]: its corner after that is the far one.
            const std::uint32_t back = tri[j][(k + 1) % 3];
            const int far = tri[u][0] == back ? 2 : tri[u][1] == back ? 0 : 1;
            if (joins(j, u, far)) bits |= 1u << k;
          }
          joining[j] = bits;
          alone_top[j] = std::max(
              {dot3(plane[j], corner(j, 0)), dot3(plane[j], corner(j, 1)), dot3(plane[j], corner(j, 2))});
        }
      },
      [&] { ranks.time([&] { largest_first.rank_triangles(); }); }, 1024);
  laps.note("the seeds' ranks beside", ranks);
  laps.lap("joining");
  Facets facets;
  // Mesh triangle t's neighbours (position j's, in positions) as mesh triangles, into facets.across.
  auto across_in_mesh = [&](std::uint32_t t, std::uint32_t j) {
    for (int k = 0; k < 3; ++k)
      facets.across[3 * t + k] = across[3 * j + k] == kNone ? kNone : visit.triangles[across[3 * j + k]];
  };
  if (std::none_of(joining.begin(), joining.end(), [](std::uint8_t bits) { return bits != 0; })) {
    // No triangle joins another (a ball's hull): every seed is a facet alone, numbered in the seeds' order,
    // placed on all cores, where the grouping below would take them one by one.
    // Each block's writes together (written scattered, the workers' lines moved between the cores): its
    // range taken as facets (seeds and planes), as positions (the visit order) and as triangles (the
    // neighbours).  In index order (a small mesh), position j is triangle j: the neighbours are already the
    // mesh's, and the facets' visit order is facet_of.
    facets.facet_of = std::move(largest_first.rank);
    facets.seeds.resize(nt);
    facets.planes.resize(nt);
    const bool in_index_order = visit.in_index_order;
    if (!in_index_order) facets.across.resize(3 * nt), facets.in_visit_order.resize(nt);
    parallel_blocks(nt, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
      for (std::size_t id = begin; id < end; ++id) {
        const std::uint32_t t = keyed[id].second, j = in_index_order ? t : jrank[t];
        facets.seeds[id] = t;
        facets.planes[id] = {plane[j][0], plane[j][1], plane[j][2], -alone_top[j]};
      }
      if (in_index_order) return;
      for (std::size_t j = begin; j < end; ++j)
        facets.in_visit_order[j] = facets.facet_of[visit.triangles[j]];
      for (std::size_t t = begin; t < end; ++t)
        across_in_mesh(static_cast<std::uint32_t>(t), jrank[t]);
    });
    if (in_index_order) facets.across = std::move(across), facets.in_visit_order = facets.facet_of;
    facets.visit_starts = std::move(tri);  // every position is a seed
    laps.lap("alone");
    return facets;
  }
  std::vector<std::uint32_t> facet_of(nt, kNone), seeds;  // by position
  seeds.reserve(nt);
  facets.planes.reserve(nt);
  std::vector<std::uint32_t> queue, vertices;
  std::vector<std::uint8_t> in_group(g.at.size(), 0);
  for (const auto& key : keyed) {
    const std::uint32_t seed = jrank[key.second];
    if (facet_of[seed] != kNone) continue;
    const std::uint32_t id = static_cast<std::uint32_t>(facets.planes.size());
    const Plane& seed_plane = plane[seed];
    facet_of[seed] = id;
    seeds.push_back(seed);
    if (joining[seed] == 0) {  // alone: no neighbour fits, whichever are free
      facets.planes.push_back({seed_plane[0], seed_plane[1], seed_plane[2], -alone_top[seed]});
      continue;
    }
    queue.assign(1, seed);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = across[3 * queue[q] + k];
        if (u == kNone || facet_of[u] != kNone) continue;
        if (queue[q] == seed ? !(joining[seed] >> k & 1u) : !joins(seed, u)) continue;
        facet_of[u] = id;
        queue.push_back(u);
      }
    }
    // The offset: every group vertex on or below the plane, as evaluated (fl(x - max) <= 0 for x <= max).
    vertices.clear();
    for (std::uint32_t t : queue)
      for (std::uint32_t v : tri[t])
        if (!in_group[v]) {
          in_group[v] = 1;
          vertices.push_back(v);
        }
    double top = -kInfinity;
    for (std::uint32_t v : vertices) {
      top = std::max(top, dot3(seed_plane, g.at[v]));
      in_group[v] = 0;
    }
    facets.planes.push_back({seed_plane[0], seed_plane[1], seed_plane[2], -top});
  }
  laps.lap("grouping");
  // Back to the mesh's triangles.
  facets.facet_of.resize(nt);
  facets.across.resize(3 * nt);
  parallel_blocks(nt, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t t = begin; t < end; ++t) {
      const std::uint32_t j = jrank[t];
      facets.facet_of[t] = facet_of[j];
      across_in_mesh(t, j);
    }
  });
  facets.seeds.reserve(seeds.size());
  for (std::uint32_t j : seeds)
    facets.seeds.push_back(visit.triangles[j]);
  facets.in_visit_order.reserve(seeds.size());
  facets.visit_starts.reserve(seeds.size());
  for (std::uint32_t j = 0; j < nt; ++j)
    if (seeds[facet_of[j]] == j) {
      facets.in_visit_order.push_back(facet_of[j]);
      facets.visit_starts.push_back(tri[j]);
    }
  return facets;
}

}  // namespace cudahull::merge
