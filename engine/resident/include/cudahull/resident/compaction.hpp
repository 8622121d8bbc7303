// Compaction between the resident engine's iterations: the live faces renumbered 0..F-1 and the kept points
// packed, both by a prefix sum of their marks (section 4).
//
// design:
//   faces    MarkLive: 1 on a face no edit killed; the marks' prefix sum is each live face's new id;
//            MoveLive writes it into the spares, each link renumbered by the same ranks (after the rounds
//            every link is to a live face: the refinement's and the rounds' gathers relink them, Figs. 3-5)
//   points   the routing's keep marks (Algorithm 2) prefix-summed; MovePoints packs each kept point with its
//            face renumbered the same way
//   reset    ResetFaces: the live faces unstamped, with no furthest point, for the next iteration
#pragma once

#include <cstddef>

#include "cudahull/resident/star_mesh.hpp"

namespace cudahull::resident {

// Run over a bound of the face ids in use; `count` (optional, where the executor computes) is the number.
template <class Point>
struct MarkLive {
  MeshView<Point> m;
  u32* live;
  const u32* count;
  CUDAHULL_HD void operator()(std::size_t f) const {
    live[f] = (!count || f < *count) && m.replaced_by[f] == kAlive ? 1u : 0u;
  }
};

// Live face f moves to rank[f] in (fv_out, fn_out), its links renumbered.
template <class Point>
struct MoveLive {
  MeshView<Point> m;
  const u32* live;
  const u32* rank;
  u32* fv_out;
  u32* fn_out;
  std::size_t last;  // the last face id it runs over: that thread writes the number of live faces
  u32* total;
  CUDAHULL_HD void operator()(std::size_t fi) const {
    if (fi == last) *total = rank[fi] + live[fi];
    if (!live[fi]) return;
    const u32 to = rank[fi];
    for (int k = 0; k < 3; ++k) {
      fv_out[3 * to + k] = m.fv[3 * fi + k];
      fn_out[3 * to + k] = rank[m.fn[3 * fi + k]];
    }
  }
};

// Kept point j moves to rank[j], its face renumbered.
struct MovePoints {
  const u32* keep;
  const u32* rank;
  const u32* face_rank;
  const u32* index_in;
  const u32* face_in;
  u32* index_out;
  u32* face_out;
  std::size_t last;  // the last point it runs over: that thread writes the number of kept points
  u32* total;
  CUDAHULL_HD void operator()(std::size_t j) const {
    if (j == last) *total = rank[j] + keep[j];
    if (!keep[j]) return;
    index_out[rank[j]] = index_in[j];
    face_out[rank[j]] = face_rank[face_in[j]];
  }
};

// Between iterations: the compacted faces live, unstamped, with no furthest point yet.
struct ResetFaces {
  u32* replaced_by;
  u32* revisit;
  u64* extreme;
  CUDAHULL_HD void operator()(std::size_t f) const {
    replaced_by[f] = kAlive;
    revisit[f] = 0;
    extreme[f] = 0;
  }
};

}  // namespace cudahull::resident
