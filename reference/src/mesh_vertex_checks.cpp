// The mesh checker's interior point, its coplanar facets, and each vertex's fan: strictly extreme (item 4)
// and winding once around the ray from the interior point.
#include "mesh_checker.hpp"

#include <algorithm>
#include <atomic>
#include <cinttypes>
#include <cstdint>
#include <numeric>
#include <vector>

namespace cudahull::checking {

// The interior reference point c: the vertex centroid, or else the centroid of face 0 and the vertex
// furthest below it.  Either is strictly inside a valid hull up to rounding; the exact test decides.
template <class Point>
bool MeshChecker<Point>::find_interior_point() {
  auto strictly_inside = [&](const Vec3d& c) {
    // A candidate only; the fast predicates need its coordinates in their range too (or 0).
    auto snap = [&](double x) { return rep_.wide || in_fast_exact_range(x) ? x : 0.0; };
    c_ = {snap(c.x), snap(c.y), snap(c.z)};
    std::atomic<bool> inside{true};
    parallel_failures(nf_, 1, rep_, [&](std::size_t f, auto&, std::size_t) {
      if (inside.load(std::memory_order_relaxed) && above(static_cast<std::uint32_t>(f), c) >= 0)
        inside = false;
    });
    return inside.load();
  };
  long double s[3] = {0, 0, 0};
  for (const Vec3d& p : vp_)
    s[0] += p.x, s[1] += p.y, s[2] += p.z;
  if (strictly_inside({static_cast<double>(s[0] / nv_), static_cast<double>(s[1] / nv_),
                       static_cast<double>(s[2] / nv_)}))
    return true;
  // Long double: its range holds every product of three doubles, so wide coordinates neither overflow nor
  // underflow here.
  using L = long double;
  const Triangle& t = tri_[0];
  const Vec3d &a = P(t[0]), &b = P(t[1]), &c = P(t[2]);
  const L ux = L(b.x) - a.x, uy = L(b.y) - a.y, uz = L(b.z) - a.z;
  const L wx = L(c.x) - a.x, wy = L(c.y) - a.y, wz = L(c.z) - a.z;
  const L nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
  std::uint32_t best = 0;
  L best_d = 0;
  for (std::uint32_t v = 0; v < nv_; ++v) {
    const L d = nx * (L(P(v).x) - a.x) + ny * (L(P(v).y) - a.y) + nz * (L(P(v).z) - a.z);
    if (d < best_d) best_d = d, best = v;
  }
  const Vec3d& d = P(best);
  return strictly_inside({static_cast<double>((L(a.x) + b.x + c.x + d.x) / 4),
                          static_cast<double>((L(a.y) + b.y + c.y + d.y) / 4),
                          static_cast<double>((L(a.z) + b.z + c.z + d.z) / 4)});
}

// Facets: maximal sets of faces joined by flat edges.
template <class Point>
void MeshChecker<Point>::build_facets() {
  facet_.resize(nf_);
  std::iota(facet_.begin(), facet_.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (facet_[x] != x)
      x = facet_[x] = facet_[facet_[x]];
    return x;
  };
  for (std::uint32_t f = 0; f < nf_; ++f)
    for (int i = 0; i < 3; ++i)
      if (flat_[3 * f + i]) {
        const std::uint32_t a = find(f), b = find(nb_[3 * f + i]);
        if (a != b) facet_[std::max(a, b)] = std::min(a, b);
      }
  for (std::uint32_t f = 0; f < nf_; ++f)
    facet_[f] = find(f);
}

// Item 4 and the winding condition, one fan walk per vertex.
//  - Strictly extreme iff a strict corner of every facet it belongs to: around the vertex the faces of one
//    facet form a contiguous run whose first and last edges are the facet's boundary edges at the vertex.
//  - Winding (only when `polytope`): each face (v, a, b) turns by an angle in (0, pi) around the axis from
//    c through v, since c is strictly below it; the fan must cross the half-plane of its first neighbour
//    exactly once.  With the rest, this makes the radial projection from c a homeomorphism, so the cones
//    over the faces tile space exactly once.
template <class Point>
bool MeshChecker<Point>::check_vertex_fans(bool polytope) {
  std::atomic<bool> winding_ok{true};
  parallel_failures(nv_, 8, rep_, [&](std::size_t vi, auto& sink, std::size_t) {
    const std::uint32_t v = static_cast<std::uint32_t>(vi);
    const std::uint32_t c0 = he_corner_[start_[v]];
    // Fan order: corner j is face (v, next_j, prev_j); the next face around v shares the edge (v, prev_j).
    thread_local std::vector<std::uint32_t> fan;
    fan.clear();
    std::uint32_t c = c0;
    do {
      fan.push_back(c);
      c = next_corner(c);
    } while (c != c0);
    const std::size_t n = fan.size();
    auto nxt = [&](std::size_t j) { return tri_[fan[j] / 3][(fan[j] % 3 + 1) % 3]; };
    auto prv = [&](std::size_t j) { return tri_[fan[j] / 3][(fan[j] % 3 + 2) % 3]; };
    auto fct = [&](std::size_t j) { return facet_[fan[j] / 3]; };

    std::size_t start = n;
    for (std::size_t j = 0; j < n && start == n; ++j)
      if (fct(j) != fct((j + n - 1) % n)) start = j;
    if (start == n) {
      sink(lv2v_[v], "vertex " + vname(v) + " is not strictly extreme: it lies inside the facet of " +
                         fname(fan[0] / 3) + " (all its faces are coplanar)");
    } else {
      for (std::size_t r = 0; r < n; ++r) {
        const std::size_t j = (start + r) % n;
        if (fct(j) == fct((j + n - 1) % n)) continue;  // not the first face of a run
        std::size_t e = j;
        while (fct((e + 1) % n) == fct(j))
          e = (e + 1) % n;
        const std::uint32_t a = nxt(j), b = prv(e);
        if (collinear3d_any(rep_.wide, P(a), P(v), P(b))) {
          sink(lv2v_[v],
               fmt("vertex %s is not strictly extreme: it lies on the segment between vertices %" PRIu32
                   " and %" PRIu32 " on the boundary of a facet",
                   vname(v).c_str(), id(a), id(b)));
          break;
        }
      }
    }
    if (!polytope) return;
    // Upper half: angle in [0, pi) from w0 = next_0; lower: [pi, 2 pi).  r = prev_0 is at an angle in
    // (0, pi); a point on the plane (c, v, w0) is at angle 0 iff it is on w0's side of the plane (c, v, r).
    const Vec3d &pv = P(v), &w0 = P(nxt(0)), &r = P(prv(0));
    const int ref = orient3d_any(rep_.wide, c_, pv, r, w0);
    auto upper = [&](const Vec3d& w) {
      const int s = orient3d_any(rep_.wide, c_, pv, w0, w);
      return s > 0 || (s == 0 && orient3d_any(rep_.wide, c_, pv, r, w) == ref);
    };
    int crossings = 0;
    bool up = true;
    for (std::size_t j = 0; j < n; ++j) {
      const bool next_up = upper(P(prv(j)));
      if (!up && next_up) ++crossings;
      up = next_up;
    }
    if (crossings != 1) {
      winding_ok = false;
      sink(lv2v_[v], fmt("vertex %s: its faces wind %d times around it (not a convex vertex)",
                         vname(v).c_str(), crossings));
    }
  });
  return winding_ok;
}

// The two point types; the callers are in other files.
template bool MeshChecker<Point3>::find_interior_point();
template void MeshChecker<Point3>::build_facets();
template bool MeshChecker<Point3>::check_vertex_fans(bool);
template bool MeshChecker<Point3d>::find_interior_point();
template void MeshChecker<Point3d>::build_facets();
template bool MeshChecker<Point3d>::check_vertex_fans(bool);

}  // namespace cudahull::checking
