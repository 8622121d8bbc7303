// Refinement (Fig. 3a) on the resident engine: every face with an external point split at its furthest point.
//
// design:
//   mark    a face refines when its furthest point lies strictly inside its cone (exact: on a side of the
//           cone a child would be flat, and the face waits)
//   split   the marked faces' children placed by the prefix sum of the marks (3 each, one decision entry
//           each); every face writes only its own links, gathered from its neighbours' marks, and an
//           unrefined face next to a refined one is stamped for the first round of swaps
#pragma once

#include "cudahull/resident/star_mesh.hpp"

namespace cudahull::resident {

// A face refines when its furthest point lies strictly inside its cone (on a side of the cone a child would
// be flat: the face waits, even if other points of it are strictly inside, and a stall ends in the exact
// finish).
template <class Point>
struct MarkRefined {
  MeshView<Point> m;
  const u64* extreme;
  u32* refine;
  CUDAHULL_HD void operator()(std::size_t fi) const {
    const u32 f = static_cast<u32>(fi);
    u32 flag = 0;
    if (extreme[f] != 0) {
      const Vec3d p = m.P(rank_key_index(extreme[f]));
      const Vec3d a = m.P(m.fv[3 * f]), b = m.P(m.fv[3 * f + 1]), d = m.P(m.fv[3 * f + 2]);
      flag = orient3d(m.c, a, b, p) > 0 && orient3d(m.c, b, d, p) > 0 && orient3d(m.c, d, a, p) > 0;
    }
    refine[f] = flag;
  }
};

// Splits each marked face into three children at first + 3 rank[f] (rank: the prefix sum of the marks);
// every face writes only its own links, gathered from the neighbours' marks.
template <class Point>
struct SplitFaces {
  MeshView<Point> m;
  const u64* extreme;
  const u32* refine;
  const u32* rank;
  u32 first_face, first_entry;
  u32* revisit;  // an unrefined face next to a refined one is revisited in the first round
  u32 first_round;
  u32* refined_total;  // optional: the last face writes how many faces refine (no wait for the scan)
  // The face across edge (a -> b) of f after the split: nb itself, or nb's child on that edge.
  CUDAHULL_HD u32 across(u32 nb, u32 a, u32 b) const {
    if (!refine[nb]) return nb;
    return first_face + 3 * rank[nb] + static_cast<u32>(m.edge_slot(nb, b, a));
  }
  CUDAHULL_HD void operator()(std::size_t fi) const {
    const u32 f = static_cast<u32>(fi);
    if (refined_total && f + 1 == first_face) *refined_total = rank[f] + refine[f];
    if (!refine[f]) {
      bool touched = false;
      for (int k = 0; k < 3; ++k) {
        const u32 a = m.fv[3 * f + k], b = m.fv[3 * f + (k + 1) % 3], nb = m.fn[3 * f + k];
        touched = touched || refine[nb];
        m.fn[3 * f + k] = across(nb, a, b);
      }
      if (touched) revisit[f] = first_round;
      return;
    }
    const u32 p = rank_key_index(extreme[f]);
    const u32 kids = first_face + 3 * rank[f], e = first_entry + rank[f];
    for (int k = 0; k < 3; ++k) {
      const u32 child = kids + static_cast<u32>(k);
      const u32 a = m.fv[3 * f + k], b = m.fv[3 * f + (k + 1) % 3];
      m.fv[3 * child] = a;
      m.fv[3 * child + 1] = b;
      m.fv[3 * child + 2] = p;
      m.fn[3 * child] = across(m.fn[3 * f + k], a, b);
      m.fn[3 * child + 1] = kids + static_cast<u32>((k + 1) % 3);
      m.fn[3 * child + 2] = kids + static_cast<u32>((k + 2) % 3);
      m.replaced_by[child] = kAlive;
      revisit[child] = 0;
    }
    m.entries[e] = Entry{kRefine, p, kNone, {kids, kids + 1, kids + 2}};
    m.replaced_by[f] = e;
  }
};

}  // namespace cudahull::resident
