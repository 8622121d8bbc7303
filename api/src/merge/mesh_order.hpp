// The merge's views of a triangle mesh: its directed edges (EdgeIndex), an order of its vertices and
// triangles that keeps neighbours together (VisitOrder), and the mesh relabelled in that order (Relabelled);
// and a stable radix sort of (key, value) pairs, for the facets' seeds.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "box_tree.hpp"
#include "cudahull/morton.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"
#include "geometry.hpp"

namespace cudahull::merge {

// Sorts (key, value) pairs by key, stably (equal keys keep their order): a least-significant-digit radix
// sort of the keys' high halves in 11-bit digits (all three digits counted in one pass; a digit in which
// every key is the same is passed over), then each run of equal high halves by insertion on the low half.
// The keys here are doubles' bits, whose high halves (sign, exponent and 20 bits of mantissa) rarely tie:
// half the passes of a sort on all 64 bits.
inline void radix_sort_by_key(std::vector<std::pair<std::uint64_t, std::uint32_t>>& items) {
  constexpr int kDigit = 11, kDigits = 3;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  auto digit = [](std::uint64_t key, int d) { return (key >> (32 + kDigit * d)) & (kBuckets - 1); };
  std::vector<std::array<std::uint32_t, kBuckets + 1>> count(kDigits);
  for (auto& c : count)
    c.fill(0);
  for (const auto& item : items)
    for (int d = 0; d < kDigits; ++d)
      ++count[d][digit(item.first, d) + 1];
  std::vector<std::pair<std::uint64_t, std::uint32_t>> spare;
  for (int d = 0; d < kDigits; ++d) {
    std::array<std::uint32_t, kBuckets + 1>& c = count[d];
    if (items.empty() || c[digit(items[0].first, d) + 1] == items.size()) continue;
    for (std::size_t b = 0; b < kBuckets; ++b)
      c[b + 1] += c[b];
    spare.resize(items.size());
    for (const auto& item : items)
      spare[c[digit(item.first, d)]++] = item;
    items.swap(spare);
  }
  for (std::size_t k = 1; k < items.size(); ++k)
    for (std::size_t x = k;
         x > 0 && (items[x - 1].first >> 32) == (items[x].first >> 32) && items[x - 1].first > items[x].first;
         --x)
      std::swap(items[x - 1], items[x]);
}

// The triangles' largest-first order (the facets' seeds, grouping.hpp): each triangle's
// largest_first_key(), by index, then sort()ed ascending (largest first, ties by index), then each
// triangle's place in that order (rank_triangles()): two steps, run beside two passes.
struct LargestFirst {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys;
  PassVector<std::uint32_t> rank;  // per triangle, once ranked

  void sort() { radix_sort_by_key(keys); }
  void rank_triangles() {
    rank.resize(keys.size());
    for (std::uint32_t place = 0; place < keys.size(); ++place)
      rank[keys[place].second] = place;
  }
};

// The directed edges of a closed triangulated surface: per vertex a, its out-edges (b, the triangle holding
// a -> b), ascending in b.  Each neighbour of a appears once (the other triangle holds b -> a).  A counting
// sort by a on the caller (the merge's first step, taken while the workers wake: wake_workers()), then each
// vertex's few edges sorted by b on all cores, which the caller alone does if they are not yet awake (where
// two counting sorts, by b and then by a, all ran on one core).
struct EdgeIndex {
  std::vector<std::uint32_t> start;                          // per vertex, into `out`; one more at the end
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;  // (to, triangle)

  EdgeIndex() = default;
  template <class Point>
  explicit EdgeIndex(const BasicHullMesh<Point>& mesh)
      : EdgeIndex(mesh, [](const EdgeIndex&, std::size_t, std::size_t) {}) {}
  // As above, with after(*this, begin, end) run by the same worker once vertices [begin, end) have their
  // edges (index_mesh(): the relabelled mesh of a small one, in the same pass).
  template <class Point, class After>
  EdgeIndex(const BasicHullMesh<Point>& mesh, const After& after) : start(mesh.vertices.size() + 1, 0) {
    for (const Triangle& t : mesh.triangles)
      for (std::uint32_t v : t)
        ++start[v + 1];
    for (std::size_t v = 0; v + 1 < start.size(); ++v)
      start[v + 1] += start[v];
    // A vertex starts one half-edge for each triangle it is in.
    out.resize(start.back());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        out[fill[mesh.triangles[t][k]]++] = {mesh.triangles[t][(k + 1) % 3], t};
    const std::size_t n = mesh.vertices.size();
    parallel_blocks(n, workers_from(n, 1024), [&](std::size_t begin, std::size_t end, unsigned) {
      constexpr std::uint32_t kFew = 16;
      std::pair<std::uint32_t, std::uint32_t> edges[kFew];
      for (std::size_t v = begin; v < end; ++v) {
        const std::uint32_t first = start[v], degree = start[v + 1] - first;
        if (degree > kFew) {
          std::sort(out.begin() + first, out.begin() + first + degree);
          continue;
        }
        // Each edge's place is the number of edges with a smaller b (every b differs): counted by compares
        // without branches, where an insertion sort mispredicted about once an edge.
        std::copy(out.begin() + first, out.begin() + first + degree, edges);
        for (std::uint32_t i = 0; i < degree; ++i) {
          std::uint32_t place = 0;
          for (std::uint32_t j = 0; j < degree; ++j)
            place += edges[j].first < edges[i].first;
          out[first + place] = edges[i];
        }
      }
      after(*this, begin, end);
    });
  }
  std::uint32_t degree(std::uint32_t v) const { return start[v + 1] - start[v]; }
  std::uint32_t neighbour(std::uint32_t v, std::uint32_t k) const { return out[start[v] + k].first; }
};

// The vertices of `mesh` along a Morton curve of their box, and its triangles by their first corner in that
// order.  The per-vertex, per-triangle and per-facet passes take their independent items in these orders,
// so that neighbours on the hull are neighbours in time: in index order (the engine's, spatially random)
// nearly every read of a corner, a link or a plane missed the cache, most of a 100,000-vertex sphere's
// merge.  Only the order of independent items changes, never a result.  A small mesh (under 4096 vertices,
// read from the cache in any order) keeps index order, vertices and triangles.
struct VisitOrder {
  std::vector<std::uint32_t> vertices, triangles;
  std::vector<std::uint32_t> triangle_rank;  // per triangle: its place in `triangles`
  bool in_index_order = false;               // both identities (a small mesh)
};

template <class Point>
VisitOrder visit_order(const BasicHullMesh<Point>& mesh) {
  const std::size_t n = mesh.vertices.size();
  VisitOrder order;
  order.vertices.resize(n);
  std::iota(order.vertices.begin(), order.vertices.end(), 0u);
  const std::size_t nt = mesh.triangles.size();
  if (n < 4096) {  // a small mesh's passes read from the cache in any order: its triangles in index order
    order.triangles.resize(nt);
    std::iota(order.triangles.begin(), order.triangles.end(), 0u);
    order.triangle_rank = order.triangles;
    order.in_index_order = true;
    return order;
  }
  // Along the Morton curve.
  Box all;
  for (const Point& p : mesh.vertices)
    all.add({{double(p.x), double(p.y), double(p.z)}, {double(p.x), double(p.y), double(p.z)}});
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
  parallel_chunks(n, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t i = begin; i < end; ++i) {
      const double at[3] = {double(mesh.vertices[i].x), double(mesh.vertices[i].y),
                            double(mesh.vertices[i].z)};
      std::uint64_t code = 0;
      for (int k = 0; k < 3; ++k) {
        const double width = all.hi[k] - all.lo[k];
        double t = width > 0 ? (at[k] - all.lo[k]) / width : 0;
        if (!(t > 0)) t = 0;  // NaN too: the order only affects speed
        code |= spread3(static_cast<std::uint64_t>(std::min(t, 1.0) * 2097151.0)) << k;
      }
      keyed[i] = {code, static_cast<std::uint32_t>(i)};
    }
  });
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t i = 0; i < n; ++i)
    order.vertices[i] = keyed[i].second;
  // Each vertex's triangles (those it is the first corner of) in its out-edges' order (a triangle a -> b -> c
  // holds out-edge a -> b): by their second corner, then stably by their first corner's place, two counting
  // sorts.
  std::vector<std::uint32_t> rank_of(n);
  for (std::uint32_t j = 0; j < n; ++j)
    rank_of[order.vertices[j]] = j;
  std::vector<std::uint32_t> second_start(n + 1, 0), first_start(n + 1, 0);
  for (const Triangle& t : mesh.triangles)
    ++second_start[t[1] + 1], ++first_start[rank_of[t[0]] + 1];
  for (std::uint32_t j = 0; j < n; ++j)
    second_start[j + 1] += second_start[j], first_start[j + 1] += first_start[j];
  std::vector<std::uint32_t> by_second(nt);
  for (std::uint32_t t = 0; t < nt; ++t)
    by_second[second_start[mesh.triangles[t][1]]++] = t;
  order.triangles.resize(nt);
  for (std::uint32_t t : by_second)
    order.triangles[first_start[rank_of[mesh.triangles[t][0]]]++] = t;
  order.triangle_rank.resize(order.triangles.size());
  for (std::uint32_t j = 0; j < order.triangles.size(); ++j)
    order.triangle_rank[order.triangles[j]] = j;
  return order;
}

// A mesh's vertices and edges relabelled by a VisitOrder: position j is vertex visit.vertices[j], at[j] its
// coordinates, to[start[j]..start[j + 1]) its neighbours' positions in EdgeIndex's order (ascending original
// index, so that every loop over them takes the same steps).  Built in one pass of scattered reads that
// overlap; the passes then read their neighbours' data from the cache.
struct Relabelled {
  std::vector<std::uint32_t> rank, start;
  PassVector<std::uint32_t> to;
  PassVector<std::uint32_t> face;  // per out-edge: the place in VisitOrder::triangles of its triangle
  std::vector<Vec3d> at;
  bool coordinates_safe = true;  // every coordinate in compare_along()'s exact range
  // The triangles' keys, found in the relabelling's pass (group_facets() sorts them beside its planes).
  LargestFirst largest_first;
};

// Whether every coordinate of p is in compare_along()'s exact range (Relabelled::coordinates_safe).
inline bool coordinates_safe(const Vec3d& p) {
  return in_fast_exact_range(p.x) && in_fast_exact_range(p.y) && in_fast_exact_range(p.z);
}

// The keys of the triangles in vertices [begin, end)'s share of [0, nt), into `order`: over the blocks of a
// pass over the vertices, every triangle once, each block's written together.
template <class Point>
void key_triangles(const BasicHullMesh<Point>& mesh, std::size_t begin, std::size_t end,
                   LargestFirst& order) {
  const std::size_t n = mesh.vertices.size(), nt = mesh.triangles.size();
  for (std::size_t t = begin * nt / n; t < end * nt / n; ++t) {
    const Triangle& corners = mesh.triangles[t];
    order.keys[t] =
        largest_first_key(to_vec3d(mesh.vertices[corners[0]]), to_vec3d(mesh.vertices[corners[1]]),
                          to_vec3d(mesh.vertices[corners[2]]), static_cast<std::uint32_t>(t));
  }
}

template <class Point>
Relabelled relabelled(const BasicHullMesh<Point>& mesh, const EdgeIndex& edges, const VisitOrder& visit) {
  const std::size_t n = mesh.vertices.size();
  Relabelled g;
  g.rank.resize(n);
  g.start.assign(n + 1, 0);
  g.to.resize(edges.out.size());
  g.face.resize(edges.out.size());
  g.at.resize(n);
  g.largest_first.keys.resize(mesh.triangles.size());
  for (std::uint32_t j = 0; j < n; ++j) {
    const std::uint32_t v = visit.vertices[j];
    g.rank[v] = j;
    g.start[j + 1] = g.start[j] + edges.degree(v);
  }
  std::atomic<bool> safe{true};
  parallel_blocks(n, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
    bool block_safe = true;
    for (std::size_t j = begin; j < end; ++j) {
      const std::uint32_t v = visit.vertices[j];
      g.at[j] = to_vec3d(mesh.vertices[v]);
      block_safe = block_safe && coordinates_safe(g.at[j]);
      for (std::uint32_t k = 0; k < edges.degree(v); ++k) {
        g.to[g.start[j] + k] = g.rank[edges.neighbour(v, k)];
        g.face[g.start[j] + k] = visit.triangle_rank[edges.out[edges.start[v] + k].second];
      }
    }
    key_triangles(mesh, begin, end, g.largest_first);
    if (!block_safe) safe.store(false, std::memory_order_relaxed);
  });
  g.coordinates_safe = safe.load();
  return g;
}

// The three views of `mesh`: its EdgeIndex, its VisitOrder into `visit` and its Relabelled into `g`.  A
// small mesh (in index order) is its own relabelling (ranks and orders identities), so its relabelled
// arrays, and its triangles' keys, are filled in the edge index's pass: one pass, not two.
template <class Point>
EdgeIndex index_mesh(const BasicHullMesh<Point>& mesh, VisitOrder& visit, Relabelled& g) {
  visit = visit_order(mesh);
  if (!visit.in_index_order) {
    EdgeIndex edges(mesh);
    g = relabelled(mesh, edges, visit);
    return edges;
  }
  const std::size_t n = mesh.vertices.size(), nt = mesh.triangles.size();
  g = Relabelled{};
  g.rank.resize(n);
  std::iota(g.rank.begin(), g.rank.end(), 0u);
  g.to.resize(3 * nt);  // a half-edge for each corner
  g.face.resize(3 * nt);
  g.at.resize(n);
  g.largest_first.keys.resize(nt);
  std::atomic<bool> safe{true};
  EdgeIndex edges(mesh, [&](const EdgeIndex& index, std::size_t begin, std::size_t end) {
    bool block_safe = true;
    for (std::size_t v = begin; v < end; ++v) {
      g.at[v] = to_vec3d(mesh.vertices[v]);
      block_safe = block_safe && coordinates_safe(g.at[v]);
      for (std::uint32_t k = index.start[v]; k < index.start[v + 1]; ++k) {
        g.to[k] = index.out[k].first;
        g.face[k] = index.out[k].second;
      }
    }
    if (!block_safe) safe.store(false, std::memory_order_relaxed);
    key_triangles(mesh, begin, end, g.largest_first);
  });
  g.start = edges.start;
  g.coordinates_safe = safe.load();
  return edges;
}

}  // namespace cudahull::merge
