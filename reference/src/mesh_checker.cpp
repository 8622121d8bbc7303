// The mesh checker's order of checks, its own numbering and adjacency, and the closed 2-manifold and
// convex-edge checks on them (items 1 and 3).
#include "mesh_checker.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "cudahull/morton.hpp"

namespace cudahull::checking {

template <class Point>
void MeshChecker<Point>::run() {
  nv_ = static_cast<std::uint32_t>(h_.vertices.size());
  nf_ = static_cast<std::uint32_t>(h_.triangles.size());
  if (nv_ < 4 || nf_ < 4) {
    rep_.fail(fmt("a hull of dimension 3 has %" PRIu32 " vertices and %" PRIu32
                  " faces (at least 4 each expected)",
                  nv_, nf_));
    return;
  }
  if (!h_.polygon.empty()) rep_.fail("a hull of dimension 3 has a polygon");
  if (!renumber()) return;
  const bool walkable = build_adjacency();
  const bool topology = check_topology() && walkable;
  bool polytope = false;
  if (walkable) {
    polytope = check_edges() && topology;
    polytope = polytope && find_interior_point();
    build_facets();
    polytope = check_vertex_fans(polytope) && polytope;
  }
  if (polytope)
    locate_points();
  else
    brute_force_points();
}

// Indices valid and faces non-degenerate; then the local numbering.  False when the faces are unusable.
template <class Point>
bool MeshChecker<Point>::renumber() {
  nv_ = static_cast<std::uint32_t>(h_.vertices.size());
  nf_ = static_cast<std::uint32_t>(h_.triangles.size());
  bool ok = true;
  for (std::uint32_t f = 0; f < nf_ && ok; ++f) {
    const Triangle& t = h_.triangles[f];
    if (t[0] >= nv_ || t[1] >= nv_ || t[2] >= nv_) {
      rep_.fail(fmt("face %" PRIu32 " has a vertex index beyond the %" PRIu32 " vertices", f, nv_));
      ok = false;
    }
  }
  if (!ok) return false;
  for (std::uint32_t f = 0; f < nf_; ++f) {
    const Triangle& t = h_.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      rep_.fail(fmt("face %" PRIu32 " repeats a vertex", f));
      ok = false;
    } else if (collinear3d_any(rep_.wide, to_vec3d(h_.vertices[t[0]]), to_vec3d(h_.vertices[t[1]]),
                               to_vec3d(h_.vertices[t[2]]))) {
      rep_.fail(fmt("face %" PRIu32 " (ids %" PRIu32 " %" PRIu32 " %" PRIu32
                    ") is degenerate: its corners are collinear",
                    f, h_.vertex_ids[t[0]], h_.vertex_ids[t[1]], h_.vertex_ids[t[2]]));
      ok = false;
    }
  }
  if (!ok) return false;

  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
    lo[k] = INFINITY, hi[k] = -INFINITY;
  for (const Point& p : h_.vertices) {
    const double c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(nv_);
  for (std::uint32_t v = 0; v < nv_; ++v) {
    const Point& p = h_.vertices[v];
    const double c[3] = {p.x, p.y, p.z};
    std::uint64_t key = 0;
    for (int k = 0; k < 3; ++k) {
      const double ext = hi[k] - lo[k];
      // An overflowing double extent (inf, NaN) goes to cell 0.
      const double t = ext > 0 ? (c[k] - lo[k]) / ext * 2097151.0 : 0;
      key |= spread3(t > 0 ? static_cast<std::uint64_t>(std::min(t, 2097151.0)) : 0) << k;
    }
    keys[v] = {key, v};
  }
  std::sort(keys.begin(), keys.end());
  lv2v_.resize(nv_);
  std::vector<std::uint32_t> v2lv(nv_);
  vp_.resize(nv_);
  for (std::uint32_t l = 0; l < nv_; ++l) {
    lv2v_[l] = keys[l].second;
    v2lv[keys[l].second] = l;
    vp_[l] = to_vec3d(h_.vertices[keys[l].second]);
  }
  // Faces by smallest local vertex (counting sort).
  std::vector<std::uint32_t> count(nv_ + 1, 0);
  auto min_vertex = [&](const Triangle& t) { return std::min({v2lv[t[0]], v2lv[t[1]], v2lv[t[2]]}); };
  for (const Triangle& t : h_.triangles)
    ++count[min_vertex(t) + 1];
  for (std::uint32_t v = 0; v < nv_; ++v)
    count[v + 1] += count[v];
  lf2f_.resize(nf_);
  tri_.resize(nf_);
  for (std::uint32_t f = 0; f < nf_; ++f) {
    const Triangle& t = h_.triangles[f];
    const std::uint32_t l = count[min_vertex(t)]++;
    lf2f_[l] = f;
    tri_[l] = {v2lv[t[0]], v2lv[t[1]], v2lv[t[2]]};
  }
  return true;
}

// Item 1, edges: every directed edge once, each with its opposite.  Fills nb_/twin_.  Returns whether the
// mesh is walkable (closed, no edge used twice in one direction).
template <class Point>
bool MeshChecker<Point>::build_adjacency() {
  start_.assign(nv_ + 1, 0);
  for (const Triangle& t : tri_)
    for (std::uint32_t v : t)
      ++start_[v + 1];
  for (std::uint32_t v = 0; v < nv_; ++v)
    start_[v + 1] += start_[v];
  he_to_.resize(3 * static_cast<std::size_t>(nf_));
  he_corner_.resize(he_to_.size());
  {
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t f = 0; f < nf_; ++f)
      for (std::uint32_t i = 0; i < 3; ++i) {
        const std::uint32_t a = tri_[f][i], pos = fill[a]++;
        he_to_[pos] = tri_[f][(i + 1) % 3];
        he_corner_[pos] = 3 * f + i;
      }
  }
  nb_.assign(3 * static_cast<std::size_t>(nf_), kNone);
  twin_.assign(nb_.size(), 0);

  // Sort each vertex's half-edges by target, then report same-direction duplicates.
  const std::size_t dups = parallel_failures(nv_, 8, rep_, [&](std::size_t v, auto& sink, std::size_t) {
    const std::uint32_t b = start_[v], e = start_[v + 1];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> list(e - b);
    for (std::uint32_t k = b; k < e; ++k)
      list[k - b] = {he_to_[k], he_corner_[k]};
    std::sort(list.begin(), list.end());
    for (std::uint32_t k = b; k < e; ++k)
      he_to_[k] = list[k - b].first, he_corner_[k] = list[k - b].second;
    for (std::uint32_t k = b + 1; k < e; ++k)
      if (he_to_[k] == he_to_[k - 1]) {
        const std::uint32_t f1 = he_corner_[k - 1] / 3, f2 = he_corner_[k] / 3;
        sink(std::min(lf2f_[f1], lf2f_[f2]),
             fmt("edge (%" PRIu32 ", %" PRIu32 ") is used in the same direction by face %" PRIu32
                 " and face %" PRIu32 ": not an oriented 2-manifold",
                 id(static_cast<std::uint32_t>(v)), id(he_to_[k]), std::min(lf2f_[f1], lf2f_[f2]),
                 std::max(lf2f_[f1], lf2f_[f2])));
      }
  });
  const std::size_t open = parallel_failures(nv_, 8, rep_, [&](std::size_t a, auto& sink, std::size_t) {
    for (std::uint32_t k = start_[a]; k < start_[a + 1]; ++k) {
      const std::uint32_t b = he_to_[k];
      const auto first = he_to_.begin() + start_[b], last = he_to_.begin() + start_[b + 1];
      const auto it = std::lower_bound(first, last, static_cast<std::uint32_t>(a));
      const std::uint32_t corner = he_corner_[k];
      if (it == last || *it != a) {
        sink(lf2f_[corner / 3], fmt("edge (%" PRIu32 ", %" PRIu32 ") of face %" PRIu32
                                    " has no opposite edge in another face: the mesh is not closed",
                                    id(static_cast<std::uint32_t>(a)), id(b), lf2f_[corner / 3]));
        continue;
      }
      const std::uint32_t other = he_corner_[it - he_to_.begin()];
      nb_[corner] = other / 3;
      twin_[corner] = static_cast<std::uint8_t>(other % 3);
    }
  });
  return dups == 0 && open == 0;
}

// Item 1, the rest: no unused vertex, V - E + F = 2, one component, every vertex's faces one fan.
template <class Point>
bool MeshChecker<Point>::check_topology() {
  bool ok = true;
  std::size_t edges = 0;
  for (std::uint32_t a = 0; a < nv_; ++a)
    for (std::uint32_t k = start_[a]; k < start_[a + 1]; ++k)
      if (a < he_to_[k] || nb_[he_corner_[k]] == kNone) ++edges;  // unmatched edges count once too
  for (std::uint32_t v = 0; v < nv_; ++v)
    if (start_[v] == start_[v + 1]) {
      rep_.fail("vertex " + vname(v) + " is not used by any face");
      ok = false;
    }
  const long long euler =
      static_cast<long long>(nv_) - static_cast<long long>(edges) + static_cast<long long>(nf_);
  if (euler != 2) {
    rep_.fail(fmt("V - E + F = %lld (V = %" PRIu32 ", E = %zu, F = %" PRIu32 "), expected 2", euler, nv_,
                  edges, nf_));
    ok = false;
  }
  return ok;
}

// Needs a walkable mesh.
template <class Point>
bool MeshChecker<Point>::check_edges() {
  bool ok = true;
  // One connected component.
  std::vector<std::uint8_t> seen(nf_, 0);
  std::vector<std::uint32_t> stack = {0};
  seen[0] = 1;
  std::size_t reached = 1;
  while (!stack.empty()) {
    const std::uint32_t f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = nb_[3 * f + i];
      if (!seen[g]) seen[g] = 1, ++reached, stack.push_back(g);
    }
  }
  if (reached != nf_) {
    rep_.fail(fmt("the mesh is not connected: face %" PRIu32 " reaches %zu of %" PRIu32 " faces", lf2f_[0],
                  reached, nf_));
    ok = false;
  }
  // Every vertex's faces form one fan (a vertex where two fans touch is not a manifold point).  Each corner
  // belongs to one vertex, so the marks of different vertices never collide between threads.
  std::vector<std::uint8_t> done(3 * static_cast<std::size_t>(nf_), 0);
  if (parallel_failures(nv_, 8, rep_, [&](std::size_t v, auto& sink, std::size_t) {
        std::uint32_t fans = 0;
        for (std::uint32_t k = start_[v]; k < start_[v + 1]; ++k) {
          if (done[he_corner_[k]]) continue;
          ++fans;
          std::uint32_t c = he_corner_[k];
          do {
            done[c] = 1;
            c = next_corner(c);
          } while (c != he_corner_[k]);
        }
        if (fans > 1)
          sink(lv2v_[v], fmt("vertex %s is not a manifold point: its faces form %" PRIu32 " separate fans",
                             vname(static_cast<std::uint32_t>(v)).c_str(), fans));
      }) != 0)
    ok = false;

  // Item 3: convex or flat edges (each edge once, from its face with the smaller local index), and whether
  // the interior point is strictly below every face.
  flat_.assign(3 * static_cast<std::size_t>(nf_), 0);
  if (parallel_failures(nf_, 16, rep_, [&](std::size_t fi, auto& sink, std::size_t) {
        const std::uint32_t f = static_cast<std::uint32_t>(fi);
        for (int i = 0; i < 3; ++i) {
          const std::uint32_t g = nb_[3 * f + i];
          if (g < f) continue;
          const int j = twin_[3 * f + i];
          const std::uint32_t y = tri_[g][(j + 2) % 3];
          const int s = above(f, P(y));
          flat_[3 * f + i] = flat_[3 * g + j] = s == 0;  // slot 3g+j is written only here
          if (s > 0)
            sink(lf2f_[f],
                 fmt("edge (%" PRIu32 ", %" PRIu32 ") between face %" PRIu32 " and face %" PRIu32
                     " is concave: vertex %" PRIu32 " is above face %" PRIu32,
                     id(tri_[f][i]), id(tri_[f][(i + 1) % 3]), lf2f_[f], lf2f_[g], id(y), lf2f_[f]));
        }
      }) != 0)
    ok = false;
  return ok;
}

// The two point types; the callers are in other files.
template void MeshChecker<Point3>::run();
template void MeshChecker<Point3d>::run();

}  // namespace cudahull::checking
