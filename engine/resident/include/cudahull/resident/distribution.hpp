// Algorithm 2 on the resident engine: each kept point routed through the decision entries (Fig. 7) to the
// live face whose cone holds it, and the furthest point of each face (the next refinement's apex).
//
// design:
//   route     from the point's face, while the face was killed this iteration: its entry says which new
//             face holds the point, by one (a swap) or three (a refinement) exact orient3d with c, or the
//             one face a removal made; the point is kept when strictly above its last face (else it is
//             inside the tetrahedron of c and that face, so inside the hull, and dropped)
//   furthest  per face, the kept point of largest height (rank_key: rounded for the ranking, ties to the
//             lowest index; the refinement confirms it exactly)
#pragma once

#include "cudahull/resident/star_mesh.hpp"

namespace cudahull::resident {

// Follows the entries from a point's face to the live face whose cone holds it; kept when above.
template <class Point>
struct RoutePoints {
  MeshView<Point> m;
  const u32* point_index;
  u32* point_face;
  u32* keep;
  CUDAHULL_HD void operator()(std::size_t j) const {
    const Vec3d q = m.P(point_index[j]);
    u32 f = point_face[j];
    for (u32 e = m.replaced_by[f]; e != kAlive; e = m.replaced_by[f]) {
      const Entry& entry = m.entries[e];
      if (entry.kind == kRefine) {
        // Child k = (v_k, v_k+1, p) holds q when q is left of p -> v_k+1 and right of p -> v_k.
        const Vec3d p = m.P(entry.p);
        int s[3];
        for (int k = 0; k < 3; ++k)
          s[k] = orient3d(m.c, m.P(m.fv[3 * f + k]), p, q);
        const int k = (s[1] >= 0 && s[0] <= 0) ? 0 : (s[2] >= 0 && s[1] <= 0) ? 1 : 2;
        f = entry.out[k];
      } else if (entry.kind == kSwap) {
        f = orient3d(m.c, m.P(entry.p), m.P(entry.q), q) >= 0 ? entry.out[1] : entry.out[0];
      } else {
        f = entry.out[0];
      }
    }
    point_face[j] = f;
    keep[j] = m.above(f, q) > 0 ? 1u : 0u;
  }
};

// Per face, the furthest external point (rank_key: largest height, ties to the lowest index).  `extreme`
// is zeroed first; a face with no external point keeps 0.
template <class Point>
struct FurthestPerFace {
  MeshView<Point> m;
  const u32* point_index;
  const u32* point_face;
  u64* extreme;
  const u32* keep = nullptr;  // optional: the points listed but not kept count for nothing (key 0)
  CUDAHULL_HD u32 segment(std::size_t j) const { return point_face[j]; }
  CUDAHULL_HD u64 key(std::size_t j) const {
    if (keep && !keep[j]) return 0;
    const u32 f = point_face[j], i = point_index[j];
    const double h = orient3d_fast(m.P(m.fv[3 * f]), m.P(m.fv[3 * f + 1]), m.P(m.fv[3 * f + 2]), m.P(i));
    return rank_key(h > 0 ? h : 0, i);
  }
  CUDAHULL_HD void operator()(std::size_t j) const { atomic_max_u64(&extreme[segment(j)], key(j)); }
};

}  // namespace cudahull::resident
