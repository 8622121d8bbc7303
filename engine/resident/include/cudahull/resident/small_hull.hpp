// A small cloud's hull on one team, a furthest point at a time: QuickHull's own step (Barber, Dobkin and
// Huhdanpaa 1996), which CudaHull runs for every face at once (section 3).  The batch's smallest clouds take
// it on a warp each (cuda/batch_cuda.cu): a 100-point hull is some 40 such steps, and its few phases are a
// short loop that many warps run from the instruction cache at once, where the resident iteration
// (batch_hull()) is a kernel of 19,000 instructions that a warp a cloud left waiting on instruction fetch
// (ncu: half the stall samples; docs/benchmarks.md, "Batched hulls").  HostTeam runs it in the CPU tests.
//
// design:
//   tetrahedron  batch_tetrahedron() (section 3.1); each point goes to the first face it is strictly above
//                (exact), each face keeps its furthest point (rank_key: ranking only); the points above a
//                face listed (the outside list: a step's loops over points run over it, not the cloud)
//   repeat       p = the furthest point of all (the largest key over the live faces); none: done
//                seen: the faces p is above or on (orient3d >= 0, exact).  A vertex that p makes
//                non-extreme has every face around it seen, so it leaves the mesh with them, and one that
//                stays extreme keeps a face p does not see: the vertices stay the strictly extreme points
//                of the points taken so far
//                the horizon: the seen faces' edges whose other face is not seen, numbered in slot order
//                a new face on each horizon edge and p, in the seen faces' slots (slot order), then the free
//                list's, then new ones; linked across the horizon, and along it by the vertex each horizon
//                edge starts and ends at (a horizon vertex that does not start exactly one edge and end
//                exactly one sends the cloud to the single-cloud path; two disjoint cycles cannot arise:
//                the seen faces and the others are each connected); the seen faces not reused go on the
//                free list
//                the outside list again, in order, without the points found inside and p; the seen faces'
//                points among it to the first new face they are strictly above (a test a pair of point and
//                new face), else inside
//   finish       the live faces in slot order; the vertices in index order (write_batch_hull())
// Every count, slot and list is a prefix sum in index order, so every team builds the same mesh.
#pragma once

#include "cudahull/resident/batch.hpp"

namespace cudahull::resident {

inline constexpr u32 kNoFace = 0xffffffffu;

// Whether a team runs its ranges one index after another, in order (HostTeam): then a point's tests against
// the new faces stop at the first it is above, the least, which a team of threads finds with atomic_min().
template <class Team>
struct RunsInOrder {
  static constexpr bool value = false;
};
template <>
struct RunsInOrder<HostTeam> {
  static constexpr bool value = true;
};

// The slot's arrays as this hull uses them (a face: 3 corners, 3 links, a live flag, a seen flag, its
// furthest key; a horizon edge: its start, end and outer edge; the seen faces and the free slots listed;
// seen_rank and edge_rank: the finish's ranks and corners, edge_rank a step's first new faces until then).
struct SmallHullArrays {
  u32 *fv, *fn, *live, *seen, *seen_rank, *seen_list, *edge_rank, *horizon, *free_list;
  u64* furthest;
  u32 faces, free_room;  // face slots; free-list entries
};
CUDAHULL_HD inline SmallHullArrays small_hull_arrays(const BatchSlot& s) {
  return SmallHullArrays{s.fv,       s.fn,       s.replaced_by, s.flags,   s.face_rank,  s.revisit,
                         s.fv_spare, s.fn_spare, s.list,        s.extreme, s.room.faces, s.room.work};
}

// A team's room for a hull of up to v vertices: a mesh of at most 2 v - 4 live faces, and no more slots in
// use than it ever had live (the free ones are taken first); the free list in `list`.
CUDAHULL_HD inline BatchRoom small_hull_room(u32 v) {
  return BatchRoom{2 * v + 64, 1, 2 * v + 64};
}

// One cloud's hull on `team` in `slot`, as batch_hull()'s: the status into *result (and, when done, the
// hull into `out`).  Per point it uses the cloud's face (the face it is above), index and index_spare (the
// horizon edge starting and ending there), keep and point_rank (the points still outside a face, listed:
// this step's list and the next's; the finish's marks and ranks) and face_spare (a step's points to place;
// the finish's list).  The cloud's points may be wider than the output's: a warp stages a float cloud in
// double, converted once, not at each of its tests.
template <class Team, class Point, class OutPoint>
CUDAHULL_HD void small_hull(const Team& team, const BatchSlot& slot, const BatchCloud<Point>& cloud,
                            const BatchOutput<OutPoint>& out, BatchResult* result) {
  const u32 n = cloud.n;
  const SmallHullArrays h = small_hull_arrays(slot);
  u32 *face_of = cloud.face, *starts = cloud.index, *ends = cloud.index_spare;
  // The points above a face, listed (a step reads one list and writes the other: each step's loops over
  // points are as long as the points still outside, not the cloud); a step's points to place and the first
  // new face each is above (the horizon's edge ranks are a list's emits now: their array is free).
  u32 *outside = cloud.keep, *outside_next = cloud.point_rank, *mover = cloud.face_spare,
      *first_above = h.edge_rank;
  u32* failed = &slot.st->defects;
  const auto end_with = [&](u32 status) { end_batch_cloud(team, result, status); };
  // A step's points to place are at most the cloud's: first_above's room (3 words a face slot) holds them.
  if (n > 3 * h.faces) return end_with(kBatchRoom);
  Vec3d centroid;
  if (!batch_tetrahedron(team, slot, cloud, &centroid)) return end_with(kBatchSingle);
  const auto at = [&](u32 i) { return to_vec3d(cloud.points[i]); };
  // Where q is against face f's plane: the exact sign (every decision), or the rounded height (ranking).
  const auto side = [&](u32 f, const Vec3d& q) {
    return orient3d(at(h.fv[3 * f]), at(h.fv[3 * f + 1]), at(h.fv[3 * f + 2]), q);
  };
  const auto height = [&](u32 f, const Vec3d& q) {
    return orient3d_fast(at(h.fv[3 * f]), at(h.fv[3 * f + 1]), at(h.fv[3 * f + 2]), q);
  };
  // Point i to face f, which it is strictly above: the face's furthest point kept.
  const auto place = [&](u32 i, u32 f) {
    face_of[i] = f;
    atomic_max_u64(&h.furthest[f], rank_key(height(f, at(i)), i));
  };
  if (team.leader()) *failed = 0;
  team.barrier();
  u32 outside_count = team.list(
      n,
      [&](u32 i) {
        u32 f = 0;
        while (f < 4 && side(f, at(i)) <= 0)
          ++f;
        if (f == 4) return false;  // inside the tetrahedron, or on it
        place(i, f);
        return true;
      },
      [&](u32 i, u32 rank) { outside[rank] = i; });
  u32 faces = 4, free_count = 0;  // the slots in use (live or free), the free list's length: every thread's
  // In-order teams' walk to the seen faces (below): the last step's seen faces, the slots whose seen flag and
  // visit stamp (seen_rank, unused until the finish) are known clear, and this step's stamp.
  u32 last_seen = 0, clear_slots = 0, step = 0;
  while (true) {
    team.barrier();
    const u64 best = team.max_of(faces, [&](u32 f) { return h.furthest[f]; });  // a free slot's: 0
    if (best == 0) break;
    const u32 p = rank_key_index(best);
    const Vec3d pp = at(p);
    u32 seen = 0;
    if constexpr (RunsInOrder<Team>::value) {
      // The faces p is above or on are connected (those it is strictly above are, and a face whose plane
      // holds p shares an edge with one of them or with another such face), and p is strictly above its
      // own: a walk from there tests the seen faces and their neighbours, not every face.  Listed in slot
      // order, the team's list below, so the mesh is the same face for face.
      for (u32 k = 0; k < last_seen; ++k)
        h.seen[h.seen_list[k]] = 0;
      for (; clear_slots < faces; ++clear_slots)
        h.seen[clear_slots] = 0, h.seen_rank[clear_slots] = 0;
      ++step;
      const u32 start = face_of[p];
      h.seen[start] = 1;
      h.seen_rank[start] = step;
      h.seen_list[seen++] = start;
      for (u32 k = 0; k < seen; ++k) {
        const u32 f = h.seen_list[k];
        for (int j = 0; j < 3; ++j) {
          const u32 g = h.fn[3 * f + j];
          if (h.seen_rank[g] == step) continue;
          h.seen_rank[g] = step;
          if (side(g, pp) < 0) continue;
          h.seen[g] = 1;
          h.seen_list[seen++] = g;
        }
      }
      for (u32 k = 1; k < seen; ++k)  // insertion sort: a handful of faces
        for (u32 x = k; x > 0 && h.seen_list[x - 1] > h.seen_list[x]; --x) {
          const u32 t = h.seen_list[x];
          h.seen_list[x] = h.seen_list[x - 1];
          h.seen_list[x - 1] = t;
        }
      last_seen = seen;
    } else {
      seen = team.list(
          faces,
          [&](u32 f) {
            h.seen[f] = h.live[f] && side(f, pp) >= 0;
            return h.seen[f] != 0;
          },
          [&](u32 f, u32 rank) { h.seen_list[rank] = f; });
    }
    // The seen faces' edges (3 a seen face, in slot order) on the horizon, read before any face is
    // rewritten: each one's start, end and outer edge, and the horizon edge each vertex starts and ends.
    const auto edge_of = [&](u32 x) { return 3 * h.seen_list[x / 3] + x % 3; };
    const u32 edges = team.list(
        3 * seen, [&](u32 x) { return !h.seen[h.fn[edge_of(x)]]; },
        [&](u32 x, u32 k) {
          if (k >= h.faces) return;  // beyond the horizon's room: the check below ends the cloud
          const u32 e = edge_of(x), f = e / 3, g = h.fn[e];
          u32 outer = 3 * g;
          while (outer < 3 * g + 2 && h.fn[outer] != f)
            ++outer;
          const u32 a = h.fv[e], b = h.fv[3 * f + (e % 3 + 1) % 3];
          h.horizon[3 * k] = a;
          h.horizon[3 * k + 1] = b;
          h.horizon[3 * k + 2] = outer;
          starts[a] = k;
          ends[b] = k;
        });
    const u32 fresh = edges > seen + free_count ? edges - seen - free_count : 0;
    if (faces + fresh > h.faces || edges > h.faces ||
        (seen > edges && free_count + seen - edges > h.free_room))
      return end_with(kBatchRoom);
    const auto slot_of = [&](u32 k) {
      if (k < seen) return h.seen_list[k];
      k -= seen;
      return k < free_count ? h.free_list[free_count - 1 - k] : faces + (k - free_count);
    };
    // The new faces (a, b, p), each in the seen face's orientation of its horizon edge.
    team.for_range(edges, [&](u32 k) {
      const u32 s = slot_of(k), a = h.horizon[3 * k], b = h.horizon[3 * k + 1], outer = h.horizon[3 * k + 2];
      const u32 next = starts[b], before = ends[a];
      if (starts[a] != k || ends[b] != k || next >= edges || h.horizon[3 * next] != b || before >= edges ||
          h.horizon[3 * before + 1] != a)
        *failed = 1;  // a vertex that starts or ends more than one horizon edge, or none
      h.fv[3 * s] = a;
      h.fv[3 * s + 1] = b;
      h.fv[3 * s + 2] = p;
      h.fn[3 * s] = outer / 3;
      h.fn[outer] = s;
      h.fn[3 * s + 1] = next < edges ? slot_of(next) : s;
      h.fn[3 * s + 2] = before < edges ? slot_of(before) : s;
      h.live[s] = 1;
      h.furthest[s] = 0;
    });
    team.for_range(seen > edges ? seen - edges : 0, [&](u32 d) {
      const u32 s = h.seen_list[edges + d];
      h.live[s] = 0;
      h.furthest[s] = 0;
      h.free_list[free_count + d] = s;
    });
    team.barrier();
    if (*failed) return end_with(kBatchSingle);
    // The points still outside (the last step's placed inside leave the list, and p), and among them the
    // seen faces' (seen flags as before this step: a seen face's slot may hold a new face now).
    const TwoCounts listed = team.list_two(
        outside_count,
        [&](u32 x) {
          const u32 i = outside[x], f = face_of[i];
          if (f == kNoFace || i == p) return 0u;
          return h.seen[f] ? 3u : 1u;
        },
        [&](u32 x, u32 rank) { outside_next[rank] = outside[x]; },
        [&](u32 x, u32 rank) {
          mover[rank] = outside[x];
          first_above[rank] = edges;
        });
    const u32 movers = listed.second;
    outside_count = listed.first;
    u32* const swap = outside;
    outside = outside_next;
    outside_next = swap;
    // Each to the first new face it is strictly above: a test a (point, new face) pair, the least new face
    // kept, so that no lane waits on another's long search.  New face k is (a, b, p) of horizon edge k: its
    // corners read from the horizon, not through its slot.
    team.for_range(movers * edges, [&](u32 t) {
      const u32 x = t / edges, k = t % edges;
      if constexpr (RunsInOrder<Team>::value) {
        if (first_above[x] < k) return;  // a lesser new face already found: this one cannot be the least
      }
      if (orient3d(at(h.horizon[3 * k]), at(h.horizon[3 * k + 1]), pp, at(mover[x])) > 0)
        atomic_min_u32(&first_above[x], k);
    });
    team.barrier();
    team.for_range(movers, [&](u32 x) {
      const u32 i = mover[x], k = first_above[x];
      if (k == edges) {
        face_of[i] = kNoFace;  // inside: it leaves the list at the next step
        return;
      }
      place(i, slot_of(k));
    });
    faces += fresh;
    free_count = seen > edges ? free_count + (seen - edges) : free_count - (edges - seen - fresh);
  }
  // The finish: the live faces in slot order, their corners marking the vertices.
  u32 *used = cloud.keep, *rank = cloud.point_rank, *list = cloud.face_spare, *corners = h.edge_rank;
  team.for_range(n, [&](u32 i) { used[i] = 0; });
  const u32 live = team.count_scan(
      faces, [&](u32 f) { return h.live[f] != 0; }, h.seen_rank);  // the tetrahedron's: kAlive
  team.for_range(faces, [&](u32 f) {
    if (!h.live[f]) return;
    for (int j = 0; j < 3; ++j) {
      corners[3 * h.seen_rank[f] + j] = h.fv[3 * f + j];
      used[h.fv[3 * f + j]] = 1;
    }
  });
  team.barrier();
  write_batch_hull(team, cloud, corners, live, used, rank, list, out, result);
}

}  // namespace cudahull::resident
