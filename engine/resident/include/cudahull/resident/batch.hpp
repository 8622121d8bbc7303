// Batched hulls (issue 27): one small cloud's whole hull on one team, the same iteration as every other run
// of the resident engine (iteration.hpp), so that a batch is many device loops at once.  The team is a block
// on the device (cuda/batch_cuda.cu: a block takes cloud after cloud) and HostTeam in the CPU tests; the
// smallest clouds take small_hull.hpp's hull on a warp, which shares the tetrahedron and the output here.
//
// design:
//   room         a team owns a slot of face room (batch_room()), sized for the largest hull the pass
//                expects (batch_vertices(): a few times a ball's); a cloud that asks for more stops (room,
//                overflow), and the next pass gives it room for every point a vertex
//   tetrahedron  section 3.1 by the team's maxima: the least and greatest x, the point furthest from their
//                line, the point furthest from their plane (rank keys: ties to the lowest index).  Exactly
//                non-degenerate, with its centroid strictly inside every face, else the cloud goes to the
//                single-cloud path (a flat cloud, or picks that rounding spoiled)
//   iterations   resident_iterations from the first distribution, every phase, until no point is outside;
//                a stall goes to the single-cloud path (its exact finish)
//   finish       the defects counted (CountConcave, CountThin: flat edges inside coplanar facets are none);
//                with none, the vertices listed in index order (a flag per point and a prefix sum) and the
//                corners renumbered to them, written where the batch's output has room (one atomic a
//                cloud; a cloud past it goes to the next pass, which has room for all); with some, the
//                single-cloud path (its local repair); a mesh off Euler's F = 2V - 4 too (write_batch_hull())
#pragma once

#include "cudahull/resident/finish.hpp"
#include "cudahull/resident/iteration.hpp"

namespace cudahull::resident {

// How a cloud's team ended: its hull is in the output (done), it needs more room (in its slot or in the
// output: the next pass), or the single-cloud path takes it (flat, stalled, a defect).
enum BatchStatus : u32 { kBatchDone = 0, kBatchRoom = 1, kBatchSingle = 2 };

// Per cloud: how it ended, its hull's size, and where its words (3 corners a face, then the vertex list) and
// its vertices' coordinates are in the output.
struct BatchResult {
  u32 status, faces, vertices, word_at, point_at;
};

// The hull vertices a pass makes room for, for a cloud of n points: a uniform ball's hull has about
// 4.5 sqrt(n) (scipy, n = 16 .. 100,000); a block's first pass allows some 1.5 to 2 times that, the second
// every point (as a warp's first, cuda/batch_cuda.cu).
CUDAHULL_HD inline u32 batch_vertices(u32 n, bool every_point) {
  if (every_point) return n;
  u32 root = 0;
  while ((root + 1) * (root + 1) <= n)
    ++root;
  const u32 guess = 16 + 8 * root;
  return guess < n ? guess : n;
}

// A team's room for a hull of up to v vertices: room_for() never asks for more on a mesh of at most v
// vertices (F + 2 r <= 2 v, every refined face adds a vertex: F + 7.5 r <= 7.5 v), so only the rounds'
// own needs can overflow.
struct BatchRoom {
  u32 faces, entries, work;
};
CUDAHULL_HD inline BatchRoom batch_room(u32 v) {
  return BatchRoom{15 * v / 2 + 64, 13 * v / 4 + 64, 4 * v + 64};
}

// A team's slot: the face room (the mesh, its spares, the marks and the rounds' own) and its state.
struct BatchSlot {
  u32 *fv, *fn, *fv_spare, *fn_spare;  // 3 a face
  u32 *replaced_by, *revisit, *flags, *face_rank;
  u32 *win_mask, *word_rank;  // faces / 32 + 1 words each
  u64 *extreme, *claim;
  Entry* entries;
  u32* list;
  Candidate* cands;
  RoundsState* st;
  BatchRoom room;
};

// A cloud: its points, and per point the iteration's own (the kept points and their faces, twice; the marks
// and their ranks), where the batch's packed points are.
template <class Point>
struct BatchCloud {
  const Point* points;
  u32 n;
  u32 *index, *face, *index_spare, *face_spare, *keep, *point_rank;
};

// Where finished hulls go: words (corners, then the vertex list) and vertex coordinates, each taken by one
// atomic a cloud from a counter; a cloud past the room asks for the next pass (kBatchRoom).
template <class Point>
struct BatchOutput {
  u32* words;
  Point* coordinates;
  u32* used;  // [0]: words taken, [1]: coordinates taken
  u32 word_capacity, coordinate_capacity;
};

// Section 3.1's ranking keys for the team's maxima: the least and greatest x (segments 0 and 1 over 2n
// indices), the squared distance from line (a, b), the distance from plane (a, b, d).
template <class Point>
struct TetrahedronKeys {
  const Point* points;
  u32 n;
  int what;  // 0: x both ways, 1: from the line, 2: from the plane
  Vec3d a, b, d;
  u64* extreme;
  CUDAHULL_HD u32 segment(u32 j) const { return what == 0 ? (j >= n ? 1u : 0u) : static_cast<u32>(what + 1); }
  CUDAHULL_HD u64 key(u32 j) const {
    const u32 i = j >= n ? j - n : j;
    const Vec3d p = to_vec3d(points[i]);
    if (what == 0) return rank_key(j >= n ? p.x : -p.x, i);
    if (what == 1) {
      const Vec3d u{b.x - a.x, b.y - a.y, b.z - a.z}, w{p.x - a.x, p.y - a.y, p.z - a.z};
      const Vec3d c{u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x};
      return rank_key(c.x * c.x + c.y * c.y + c.z * c.z, i);
    }
    const double h = orient3d_fast(a, b, d, p);
    return rank_key(h < 0 ? -h : h, i);
  }
};

// The cloud ends here (every thread together) with `status` and no hull in the output.
template <class Team>
CUDAHULL_HD void end_batch_cloud(const Team& team, BatchResult* result, u32 status) {
  if (team.leader()) *result = BatchResult{status, 0, 0, 0, 0};
  team.barrier();
}

// Section 3.1's tetrahedron (see the design note) as the first mesh in the slot: faces 0-3 live, outward,
// linked, with no furthest point; its centroid into *centroid.  False (every thread) where it is flat or
// rounding spoiled the picks: the cloud takes the single-cloud path.
template <class Team, class Point>
CUDAHULL_HD bool batch_tetrahedron(const Team& team, const BatchSlot& slot, const BatchCloud<Point>& cloud,
                                   Vec3d* centroid) {
  const u32 n = cloud.n;
  if (team.leader()) {
    for (int k = 0; k < 4; ++k)
      slot.extreme[k] = 0;
  }
  team.barrier();
  TetrahedronKeys<Point> keys{cloud.points, n, 0, {}, {}, {}, slot.extreme};
  team.max_per_segment(2 * n, keys);
  team.barrier();
  u32 corner[4] = {rank_key_index(slot.extreme[0]), rank_key_index(slot.extreme[1]), 0, 0};
  keys.a = to_vec3d(cloud.points[corner[0]]);
  keys.b = to_vec3d(cloud.points[corner[1]]);
  keys.what = 1;
  team.max_per_segment(n, keys);
  team.barrier();
  corner[2] = rank_key_index(slot.extreme[2]);
  keys.d = to_vec3d(cloud.points[corner[2]]);
  keys.what = 2;
  team.max_per_segment(n, keys);
  team.barrier();
  corner[3] = rank_key_index(slot.extreme[3]);
  Vec3d p[4];
  for (int k = 0; k < 4; ++k)
    p[k] = to_vec3d(cloud.points[corner[k]]);
  const int sign = orient3d(p[0], p[1], p[2], p[3]);
  if (sign == 0) return false;
  if (sign > 0) {  // p3 above (p0, p1, p2): that face would point at it; (p0, p2, p1) points away
    const u32 t = corner[1];
    corner[1] = corner[2];
    corner[2] = t;
    const Vec3d q = p[1];
    p[1] = p[2];
    p[2] = q;
  }
  // With orient3d(p0, p1, p2, p3) < 0 these four faces (even permutations of it) face outward.
  constexpr int kFaces[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  const Vec3d c{(p[0].x + p[1].x + p[2].x + p[3].x) / 4, (p[0].y + p[1].y + p[2].y + p[3].y) / 4,
                (p[0].z + p[1].z + p[2].z + p[3].z) / 4};
  for (const auto& f : kFaces) {
    if (orient3d(p[f[0]], p[f[1]], p[f[2]], c) >= 0) return false;
  }
  *centroid = c;
  team.barrier();  // every thread has read the maxima before the first mesh overwrites them
  if (team.leader()) {
    for (u32 f = 0; f < 4; ++f) {
      for (int i = 0; i < 3; ++i) {
        slot.fv[3 * f + i] = corner[kFaces[f][i]];
        // The face across directed edge a -> b holds b -> a.
        const int a = kFaces[f][i], b = kFaces[f][(i + 1) % 3];
        for (u32 g = 0; g < 4; ++g) {
          for (int j = 0; j < 3; ++j) {
            if (kFaces[g][j] == b && kFaces[g][(j + 1) % 3] == a) slot.fn[3 * f + i] = g;
          }
        }
      }
      slot.replaced_by[f] = kAlive;
      slot.revisit[f] = 0;
      slot.extreme[f] = 0;
    }
  }
  return true;
}

// The finish's output: the hull of `faces` faces (`corners`, 3 a face, on the cloud's indices) and the
// points `used` marks (1 a vertex) written where the batch's output has room, the vertices in index order
// (a prefix sum into `rank`, listed in `list`) and the corners renumbered to them (one atomic a cloud; a
// cloud past the room asks for the next pass).
// The cloud's points may be wider than the output's (a warp's float cloud staged in double): each vertex
// goes out as it came in.
template <class Team, class Point, class OutPoint>
CUDAHULL_HD void write_batch_hull(const Team& team, const BatchCloud<Point>& cloud, const u32* corners,
                                  u32 faces, const u32* used, u32* rank, u32* list,
                                  const BatchOutput<OutPoint>& out, BatchResult* result) {
  const u32 n = cloud.n;
  const u32 vertices = team.exclusive_scan(
      n, [&](u32 i) { return used[i]; }, rank);
  team.for_range(n, [&](u32 i) {
    if (used[i]) list[rank[i]] = i;
  });
  if (team.leader()) {
    // A closed triangulated sphere has F = 2 V - 4 (Euler): anything else goes to the single-cloud path,
    // taking no output.
    if (faces + 4 != 2 * vertices) {
      *result = BatchResult{kBatchSingle, 0, 0, 0, 0};
    } else {
      const u32 words = 3 * faces + vertices;
      const u32 word_at = atomic_add_u32(&out.used[0], words);
      const u32 point_at = atomic_add_u32(&out.used[1], vertices);
      const bool fits =
          word_at + words <= out.word_capacity && point_at + vertices <= out.coordinate_capacity;
      *result = BatchResult{fits ? kBatchDone : kBatchRoom, faces, vertices, word_at, point_at};
    }
  }
  team.barrier();
  if (result->status != kBatchDone) return;
  const BatchResult at = *result;
  const RenumberCorners renumber{corners, rank, out.words + at.word_at};
  team.for_range(3 * faces, [&](u32 k) { renumber(k); });
  team.for_range(vertices, [&](u32 k) {
    out.words[at.word_at + 3 * faces + k] = list[k];
    const Point& p = cloud.points[list[k]];
    out.coordinates[at.point_at + k] =
        OutPoint{static_cast<decltype(OutPoint::x)>(p.x), static_cast<decltype(OutPoint::y)>(p.y),
                 static_cast<decltype(OutPoint::z)>(p.z)};
  });
  team.barrier();
}

// One cloud's hull on `team` in `slot`: the status into *result (and, when done, the hull into `out`).
template <class Team, class Point>
CUDAHULL_HD void batch_hull(const Team& team, const BatchSlot& slot, const BatchCloud<Point>& cloud,
                            const BatchOutput<Point>& out, BatchResult* result) {
  const u32 n = cloud.n;
  RoundsState* st = slot.st;
  const auto end_with = [&](u32 status) { end_batch_cloud(team, result, status); };
  Vec3d c;
  if (!batch_tetrahedron(team, slot, cloud, &c)) return end_with(kBatchSingle);
  if (team.leader()) *st = RoundsState{};
  // No claim is left from the slot's last cloud (a claim is a round and a candidate: stale ones would win).
  team.for_range(slot.room.faces, [&](u32 f) { slot.claim[f] = 0; });
  team.barrier();

  IterationBuffers<Point> b{};
  b.m = MeshView<Point>{cloud.points, c, slot.fv, slot.fn, slot.replaced_by, slot.entries};
  b.fv_spare = slot.fv_spare;
  b.fn_spare = slot.fn_spare;
  b.index = cloud.index;
  b.face = cloud.face;
  b.index_spare = cloud.index_spare;
  b.face_spare = cloud.face_spare;
  b.keep = cloud.keep;
  b.point_rank = cloud.point_rank;
  b.flags = slot.flags;
  b.face_rank = slot.face_rank;
  b.revisit = slot.revisit;
  b.list = slot.list;
  b.win_mask = slot.win_mask;
  b.word_rank = slot.word_rank;
  b.extreme = slot.extreme;
  b.claim = slot.claim;
  b.cands = slot.cands;
  b.st = st;
  b.first_list = nullptr;
  const IterationLaunch launch{
      kFirst,         kCompact,        0xffffffffu, 4,           n, 0, slot.room.faces, slot.room.entries,
      slot.room.work, slot.room.faces, 0xffffffffu, 0xffffffffu, 0};
  resident_iterations(team, b, launch);
  team.barrier();
  // Every thread reads the exit before the relaunch's leader writes the state again.
  const bool first_stalled = st->loop_exit == kExitStall && st->loop_iterations == 0;
  team.barrier();
  if (first_stalled) {
    // No face refined in the first iteration: the points the first distribution did not keep are still
    // listed.  Compacted, none may be left (every point inside the tetrahedron: the hull is done).
    const IterationLaunch compact{
        kCompact,       kCompact,        1,           4,           n, 1, slot.room.faces, slot.room.entries,
        slot.room.work, slot.room.faces, 0xffffffffu, 0xffffffffu, 0};
    resident_iterations(team, b, compact);
    team.barrier();
    if (team.leader() && st->kept_points != 0) st->loop_exit = kExitStall;
    team.barrier();
  }
  const u32 exit = st->loop_exit;
  if (exit == kExitRoom || exit == kExitOverflow) return end_with(kBatchRoom);
  if (exit != kExitDone || st->kept_points != 0) return end_with(kBatchSingle);

  // The finish: the mesh is in the spares after an odd number of compactions.
  MeshView<Point> m = b.m;
  if (st->loop_iterations % 2 == 1) {
    m.fv = slot.fv_spare;
    m.fn = slot.fn_spare;
  }
  const u32 faces = st->live_faces;
  u32 *creases = cloud.keep, *used = cloud.point_rank, *rank = cloud.index, *list = cloud.index_spare;
  team.for_range(n, [&](u32 i) { creases[i] = used[i] = 0; });
  team.for_range(faces, [&](u32 f) { slot.revisit[f] = 0; });
  if (team.leader()) st->defects = 0;
  team.barrier();
  const CountConcave<Point> concave{m, creases, used, &st->defects, slot.revisit};
  team.for_range(faces, [&](u32 f) { concave(f); });
  team.barrier();
  const CountThin thin{creases, used, &st->defects};
  team.for_range(n, [&](u32 i) { thin(i); });
  team.barrier();
  if (st->defects != 0) return end_with(kBatchSingle);
  write_batch_hull(team, cloud, m.fv, faces, used, rank, list, out, result);
}

}  // namespace cudahull::resident
