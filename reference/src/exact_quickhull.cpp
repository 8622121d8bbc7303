// The exact hull's QuickHull (exact_quickhull.hpp): building the hull point by point from a tetrahedron,
// and polishing it into facets of strict corners.
#include "exact_quickhull.hpp"

#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"
#include "cudahull/wide_predicates.hpp"
#include "exact_vector.hpp"

namespace cudahull::exact {

template <class Pred>
std::uint32_t QuickHull<Pred>::new_face(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  std::uint32_t f;
  if (!free_.empty()) {
    f = free_.back();
    free_.pop_back();
  } else {
    f = static_cast<std::uint32_t>(faces_.size());
    faces_.emplace_back();
  }
  Face& face = faces_[f];
  face = Face{};
  face.v = {a, b, c};
  face.nb = {kNone, kNone, kNone};
  face.normal = cross(sub(p_[b], p_[a]), sub(p_[c], p_[a]));
  face.far_dist = -std::numeric_limits<double>::infinity();
  face.alive = true;
  return f;
}

template <class Pred>
void QuickHull<Pred>::distribute(const std::vector<std::uint32_t>& pts,
                                 const std::vector<std::uint32_t>& cands) {
  const std::size_t nc = cands.size();
  which_.resize(pts.size());
  counts_.assign(nc, 0);
  std::size_t hint = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    which_[i] = kNone;
    for (std::size_t t = 0; t < nc; ++t) {
      const std::size_t k = (hint + t) % nc;  // neighbouring points tend to see the same face
      Face& F = faces_[cands[k]];
      if (side(F, pts[i]) > 0) {
        which_[i] = static_cast<std::uint32_t>(k);
        ++counts_[k];
        const double d = dot(F.normal, sub(p_[pts[i]], p_[F.v[0]]));
        if (F.far == kNone || d > F.far_dist) F.far_dist = d, F.far = pts[i];
        hint = k;
        break;
      }
    }
  }
  // Slices in the arena, then scatter.
  std::size_t pos = arena_.size(), total = 0;
  for (std::size_t k = 0; k < nc; ++k) {
    Face& F = faces_[cands[k]];
    F.out_begin = static_cast<std::uint32_t>(pos + total);
    F.out_count = 0;
    total += counts_[k];
    if (counts_[k] > 0) stack_.push_back(cands[k]);
  }
  arena_.resize(pos + total);
  live_ += total;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (which_[i] != kNone) {
      Face& F = faces_[cands[which_[i]]];
      arena_[F.out_begin + F.out_count++] = pts[i];
    }
}

template <class Pred>
void QuickHull<Pred>::compact_arena() {
  std::vector<std::uint32_t> fresh;
  fresh.reserve(live_ + live_ / 2);
  for (Face& F : faces_) {
    if (!F.alive || F.out_count == 0) continue;
    const std::uint32_t b = static_cast<std::uint32_t>(fresh.size());
    fresh.insert(fresh.end(), arena_.begin() + F.out_begin, arena_.begin() + F.out_begin + F.out_count);
    F.out_begin = b;
  }
  arena_.swap(fresh);
}

template <class Pred>
void QuickHull<Pred>::build(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  faces_.reserve(2 * p_.size() + 8);
  if (Pred::orient3d(p_[a], p_[b], p_[c], p_[d]) > 0) std::swap(b, c);  // now d is below (a, b, c)
  const std::uint32_t f0 = new_face(a, b, c), f1 = new_face(b, a, d), f2 = new_face(c, b, d),
                      f3 = new_face(a, c, d);
  // Link the tetrahedron by matching opposite edges.
  const std::uint32_t fs[4] = {f0, f1, f2, f3};
  for (std::uint32_t f : fs)
    for (int i = 0; i < 3; ++i)
      for (std::uint32_t g : fs) {
        if (g == f) continue;
        const Face& F = faces_[f];
        for (int j = 0; j < 3; ++j)
          if (faces_[g].v[j] == F.v[(i + 1) % 3] && faces_[g].v[(j + 1) % 3] == F.v[i]) faces_[f].nb[i] = g;
      }

  pending_.clear();
  for (std::uint32_t q = 0; q < p_.size(); ++q)
    if (q != a && q != b && q != c && q != d) pending_.push_back(q);
  distribute(pending_, {f0, f1, f2, f3});

  while (!stack_.empty()) {
    const std::uint32_t f = stack_.back();
    stack_.pop_back();
    if (faces_[f].alive && faces_[f].out_count != 0) add_point(f);
    if (arena_.size() > 2 * live_ + (1u << 20)) compact_arena();
  }
}

// Adds the furthest outside point of face f: removes every face it is strictly above (a connected set
// bounded by one simple horizon cycle, by convexity), and connects the horizon to it.
template <class Pred>
void QuickHull<Pred>::add_point(std::uint32_t f0) {
  const std::uint32_t eye = faces_[f0].far;
  const std::uint32_t stamp = ++stamp_;

  visible_.assign(1, f0);
  horizon_.clear();
  faces_[f0].stamp = stamp;
  faces_[f0].visible = true;
  for (std::size_t k = 0; k < visible_.size(); ++k) {
    const std::uint32_t f = visible_[k];
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = faces_[f].nb[i];
      Face& G = faces_[g];
      if (G.stamp != stamp) {
        G.stamp = stamp;
        G.visible = side(G, eye) > 0;
        if (G.visible) visible_.push_back(g);
      }
      if (!G.visible) horizon_.push_back({faces_[f].v[i], faces_[f].v[(i + 1) % 3], g});
    }
  }

  pending_.clear();
  for (std::uint32_t f : visible_) {
    Face& F = faces_[f];
    for (std::uint32_t k = F.out_begin, e = F.out_begin + F.out_count; k < e; ++k)
      if (arena_[k] != eye) pending_.push_back(arena_[k]);
    live_ -= F.out_count;
    F.out_count = 0;
    F.alive = false;
    free_.push_back(f);
  }

  // Cone of new faces (a, b, eye) over the horizon edges a -> b; the old face across keeps edge b -> a.
  created_.clear();
  for (const HorizonEdge& h : horizon_) {
    if (start_face_[h.a] != kNone) throw std::logic_error("exact_hull: horizon is not a simple cycle");
    const std::uint32_t nf = new_face(h.a, h.b, eye);
    faces_[nf].nb[0] = h.other;
    Face& other = faces_[h.other];
    other.nb[edge_index(other, h.b, h.a)] = nf;
    start_face_[h.a] = nf;
    created_.push_back(nf);
  }
  for (std::uint32_t nf : created_) {
    const std::uint32_t g = start_face_[faces_[nf].v[1]];
    if (g == kNone) throw std::logic_error("exact_hull: horizon is not a closed cycle");
    faces_[nf].nb[1] = g;  // edge b -> eye
    faces_[g].nb[2] = nf;  // edge eye -> b of the face starting at b
  }
  for (std::uint32_t nf : created_)
    start_face_[faces_[nf].v[0]] = kNone;

  // A pending point strictly above no new face is inside the new hull (it was above a removed face only).
  distribute(pending_, created_);
}

template <class Pred>
std::vector<Triangle> QuickHull<Pred>::polish() const {
  const std::uint32_t nf = static_cast<std::uint32_t>(faces_.size());
  // Union-find over faces: adjacent faces with exactly coplanar planes belong to one facet.
  std::vector<std::uint32_t> parent(nf);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::uint32_t f = 0; f < nf; ++f) {
    const Face& F = faces_[f];
    if (!F.alive) continue;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = F.nb[i];
      if (g < f) continue;  // each edge once
      const Face& G = faces_[g];
      const int j = edge_index(G, F.v[(i + 1) % 3], F.v[i]);
      if (side(F, G.v[(j + 2) % 3]) == 0) {
        const std::uint32_t rf = find(f), rg = find(g);
        if (rf != rg) parent[rf] = rg;
      }
    }
  }
  auto boundary = [&](std::uint32_t f, int i) { return find(f) != find(faces_[f].nb[i]); };

  // Each facet is a convex polygon (a disk): walk its boundary cycle counter-clockwise (seen from outside),
  // keep the strict corners and fan-triangulate over them.
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(nf) * 3, 0);
  std::vector<Triangle> tris;
  std::vector<std::uint32_t> cycle, corners;
  for (std::uint32_t f0 = 0; f0 < nf; ++f0) {
    if (!faces_[f0].alive) continue;
    for (int i0 = 0; i0 < 3; ++i0) {
      if (seen[f0 * 3 + i0] || !boundary(f0, i0)) continue;
      cycle.clear();
      std::uint32_t f = f0;
      int i = i0;
      do {
        seen[f * 3 + i] = 1;
        cycle.push_back(faces_[f].v[i]);
        // Rotate around the edge's end vertex through the facet to the next boundary edge leaving it.
        int k = (i + 1) % 3;
        while (!boundary(f, k)) {
          const std::uint32_t g = faces_[f].nb[k];
          const int j = edge_index(faces_[g], faces_[f].v[(k + 1) % 3], faces_[f].v[k]);
          f = g;
          k = (j + 1) % 3;
        }
        i = k;
      } while (f != f0 || i != i0);

      const std::size_t len = cycle.size();
      corners.clear();
      for (std::size_t t = 0; t < len; ++t) {
        const std::uint32_t prev = cycle[(t + len - 1) % len], cur = cycle[t], next = cycle[(t + 1) % len];
        if (!Pred::collinear3d(p_[prev], p_[cur], p_[next])) corners.push_back(cur);
      }
      if (corners.size() < 3) throw std::logic_error("exact_hull: degenerate facet");
      for (std::size_t t = 1; t + 1 < corners.size(); ++t)
        tris.push_back({corners[0], corners[t], corners[t + 1]});
    }
  }
  return tris;
}

// The two predicate policies; one implementation.
template class QuickHull<FastPredicates>;
template class QuickHull<WidePredicates>;

}  // namespace cudahull::exact
