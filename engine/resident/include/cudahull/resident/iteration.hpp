// One iteration of Algorithm 1 on the resident engine (section 3), written once for every executor: the
// host twin (HostTeam), one block on the device (a small mesh with few points: the device loop, whole
// iterations in one launch) and a cooperative grid (a large mesh: a launch per range of phases).  The team
// (rounds.hpp) says how a phase's work is shared; this file says what the phases are and in which order.
//
// design:
//   first     (once) each listed point to its cone of the first mesh, kept when above its face (section
//             3.1); the ones not kept stay listed until the first compaction and count for nothing
//   furthest  per face, its furthest kept point (distribution.hpp)
//   mark      a face refines when that point is strictly inside its cone; the marks' prefix sum numbers
//             the refined faces.  None: a stall (the mesh is as it was).  Too little room for the split
//             and the rounds (room_for()), or a device loop's mesh grown past its limit: stop, the marks
//             kept; the host grows and goes on from the split
//   split     every marked face into three (Fig. 3a)
//   rounds    swaps and removals until no candidate is left (Figs. 3b, 4, 5; rounds.hpp).  A round
//             short of room stops before it changes anything; the host grows and goes on from the rounds
//   route     each kept point through the decision entries to its new face (Algorithm 2, Fig. 7)
//   compact   live faces renumbered into the spares, kept points packed; the spares become current
//   A launch runs the phases from..to, and a device loop then goes on with whole iterations from
//   `furthest`; how it stopped (IterationExit) and the counts go to the state for the host's one read.
#pragma once

#include <type_traits>

#include "cudahull/resident/compaction.hpp"
#include "cudahull/resident/distribution.hpp"
#include "cudahull/resident/first_mesh.hpp"
#include "cudahull/resident/refinement.hpp"
#include "cudahull/resident/rounds.hpp"

namespace cudahull::resident {

enum IterationPhase : u32 { kFirst = 0, kFurthest = 1, kSplit = 2, kRounds = 3, kRoute = 4, kCompact = 5 };

// Why a launch stopped: it ran its phases (done; or no point is left outside), no face could refine (a
// stall: the mesh is as it was), too little room for the split (room: the marks kept, st->refined set), or
// a round did not fit (overflow: mid-iteration, the state as the rounds left it).
enum IterationExit : u32 { kExitDone = 0, kExitStall = 1, kExitRoom = 2, kExitOverflow = 3 };

// The room an iteration of `faces` faces that refines `refined` asks for before its split: the children and
// about two edits a refined face (1.5 to 2.1 on dense spheres), two new slots and one entry each (and an
// entry a refined face); a round's
// work (the children and the faces beside the refined ones); the compaction's spares (a split adds two live
// faces, a swap none, a removal takes two away).  Past these a round stops and the host grows the room.
struct IterationRoom {
  u64 faces, entries, work, spares;
};
CUDAHULL_HD inline IterationRoom room_for(u64 faces, u64 refined) {
  return IterationRoom{faces + 3 * refined + 9 * refined / 2 + 64, refined + 9 * refined / 4 + 64,
                       4 * refined + 64, faces + 2 * refined + 64};
}

// The buffers an iteration works on: the current faces and points and the spares the compaction writes
// (swapped after it), the marks and ranks, the rounds' own, and the state.
template <class Point, class Log = NoLog>
struct IterationBuffers {
  MeshView<Point> m;  // fv, fn: the current faces
  Log log;            // the rounds' rejections (the recording driver's)
  u32 *fv_spare, *fn_spare;
  u32 *index, *face, *index_spare, *face_spare;  // the kept points and their faces
  u32 *keep, *point_rank, *flags, *face_rank, *revisit, *list;
  u32 *win_mask, *word_rank;  // the executor's: a bit per face, the wins before each word (rounds.hpp)
  u64 *extreme, *claim;
  Candidate* cands;
  RoundsState* st;
  const u32* first_list;  // kFirst: the listed points (NotInsideP), or null for all
};

// What the host gives a launch.  `faces` and `active`: the mesh and points it begins with (a launch that
// resumes after the split takes the rest from the state).  `after`: it follows a launch of the same
// iteration with no wait between them, and does nothing if that one stopped.
struct IterationLaunch {
  u32 from, to;               // the phases run, in order
  u32 iterations;             // then whole iterations from kFurthest until this many have ended
  u32 faces, active, unkept;  // unkept: the listed points not kept are still listed (after kFirst)
  u32 face_capacity, entry_capacity, work_capacity, spare_capacity;
  // A device loop goes on to another iteration only on a mesh of at most face_limit faces, or of at most
  // few_points_face_limit with no more points left than faces (loop_goes_on()).
  u32 face_limit, few_points_face_limit;
  u32 after;
};

// Whether a device loop (one block) runs an iteration on a mesh of `faces` faces with `active` points left:
// on a small mesh, or on a larger one with few points (little work an iteration, where the grid's launches
// cost more than they share out; on ball 1M, thousands of points on a few thousand faces, the grid is
// faster: docs/benchmarks.md, "The device loop's face limit").
CUDAHULL_HD inline bool loop_goes_on(u32 faces, u32 active, u32 face_limit, u32 few_points_face_limit) {
  return faces <= face_limit || (faces <= few_points_face_limit && active <= faces);
}

// The phases a kernel is compiled with (a cooperative grid runs a range a launch: each kernel keeps the
// registers of its own phases).
template <u32 First, u32 Last>
struct PhaseRange {
  CUDAHULL_HD static constexpr bool has(u32 phase) { return phase - First <= Last - First; }
};
using AllPhases = PhaseRange<kFirst, kCompact>;

// The face slots an iteration has: after an odd number of compactions in one launch the faces are in what
// were the spares.
CUDAHULL_HD inline u32 face_room(const IterationLaunch& launch, u32 iterations) {
  return iterations % 2 == 1 && launch.spare_capacity < launch.face_capacity ? launch.spare_capacity
                                                                             : launch.face_capacity;
}

// The ranges of phases a launch covers, one kernel each on a grid (marks | split and rounds | routing and
// compaction): run(Range{}, launch) for each in order, every one after the first marked `after`.
using MarkPhases = PhaseRange<kFirst, kFurthest>;
using RoundPhases = PhaseRange<kSplit, kRounds>;
using CompactPhases = PhaseRange<kRoute, kCompact>;
template <class Run>
void for_each_phase_range(IterationLaunch launch, Run&& run) {
  const u32 from = launch.from, to = launch.to;
  if (from <= kFurthest) {
    run(MarkPhases{}, launch);
    launch.after = 1;
  }
  if (from <= kRounds && to >= kSplit) {
    run(RoundPhases{}, launch);
    launch.after = 1;
  }
  if (to >= kRoute) run(CompactPhases{}, launch);
}

template <class Team, class Point, class Log, class Range = AllPhases>
CUDAHULL_HD void resident_iterations(const Team& team, IterationBuffers<Point, Log> b,
                                     const IterationLaunch& launch, Range = {}) {
  RoundsState* st = b.st;
  if (launch.after) {
    if (st->loop_exit != kExitDone) return;
  } else if (team.leader()) {
    st->loop_exit = kExitDone;
    st->loop_iterations = st->loop_refined = 0;
  }
  u32 faces = launch.faces, active = launch.active, phase = launch.from;
  bool unkept = launch.unkept != 0;
  u32 iterations = 0, refined_total = 0, exit = kExitDone;
  const auto runs = [&](u32 p) { return Range::has(p) && phase <= p && p <= launch.to; };
  while (true) {
    MeshView<Point>& m = b.m;
    if (runs(kFirst)) {
      const AssignFirst<Point> assign{m, faces, b.first_list, b.index, b.face, b.keep};
      team.for_range(active, [&](u32 j) { assign(j); });
      team.barrier();
      unkept = true;
    }
    if (runs(kFurthest)) {
      if (active == 0) break;
      team.max_per_segment(active,
                           FurthestPerFace<Point>{m, b.index, b.face, b.extreme, unkept ? b.keep : nullptr});
      team.barrier();
      const MarkRefined<Point> mark{m, b.extreme, b.flags};
      team.for_range(faces, [&](u32 f) { mark(f); });
      team.barrier();
      const u32 refined = team.exclusive_scan(
          faces, [&](u32 f) { return b.flags[f]; }, b.face_rank);
      if (team.leader()) st->refined = refined;
      if (refined == 0) {
        exit = kExitStall;
        break;
      }
      const IterationRoom room = room_for(faces, refined);
      if (room.faces > face_room(launch, iterations) || room.entries > launch.entry_capacity ||
          room.work > launch.work_capacity || room.spares > launch.spare_capacity ||
          (iterations > 0 && !loop_goes_on(faces, active, launch.face_limit, launch.few_points_face_limit))) {
        exit = kExitRoom;
        break;
      }
      team.barrier();
    }
    if (runs(kSplit)) {
      const SplitFaces<Point> split{m, b.extreme, b.flags,       b.face_rank, faces,
                                    0, b.revisit, st->round + 1, nullptr};
      team.for_range(faces, [&](u32 f) { split(f); });
      refined_total += st->refined;
    }
    if (runs(kRounds)) {
      // From the split: the iteration's faces and entries from the refined count; else (after an
      // overflow) the rounds go on from where they stopped.
      if (team.leader())
        start_rounds(st, RoundsLaunch{runs(kSplit) ? 1u : 0u, faces, face_room(launch, iterations),
                                      launch.entry_capacity, launch.work_capacity});
      team.barrier();
      swap_and_removal_rounds(
          team, RoundsBuffers<Point, Log>{FindCandidate<Point, Log>{m, b.log}, b.claim, b.revisit, b.cands,
                                          b.list, b.win_mask, b.word_rank, st});
      team.barrier();
      if (st->overflow) {
        exit = kExitOverflow;
        break;
      }
    } else if (runs(kSplit)) {
      team.barrier();
    }
    // After the rounds the faces in use are the state's; a compaction alone (after the first distribution,
    // or when no face refined) runs over the faces as they are.
    const u32 bound = phase <= kRoute ? st->faces : faces;
    if (runs(kRoute)) {
      const RoutePoints<Point> route{m, b.index, b.face, b.keep};
      team.for_range(active, [&](u32 j) { route(j); });
    }
    if (!runs(kCompact)) break;
    const MarkLive<Point> mark_live{m, b.flags, nullptr};
    team.for_range(bound, [&](u32 f) { mark_live(f); });
    team.barrier();
    const u32 live = team.exclusive_scan(
        bound, [&](u32 f) { return b.flags[f]; }, b.face_rank);
    const MoveLive<Point> move_live{m,          b.flags,         b.face_rank, b.fv_spare,
                                    b.fn_spare, ~std::size_t{0}, nullptr};
    team.for_range(bound, [&](u32 f) { move_live(f); });
    const u32 kept = team.exclusive_scan(
        active, [&](u32 j) { return b.keep[j]; }, b.point_rank);
    const MovePoints move_points{b.keep,        b.point_rank, b.face_rank,     b.index, b.face,
                                 b.index_spare, b.face_spare, ~std::size_t{0}, nullptr};
    team.for_range(active, [&](u32 j) { move_points(j); });
    team.barrier();
    swap_pointers(m.fv, b.fv_spare);
    swap_pointers(m.fn, b.fn_spare);
    swap_pointers(b.index, b.index_spare);
    swap_pointers(b.face, b.face_spare);
    faces = live;
    active = kept;
    unkept = false;
    const ResetFaces reset{m.replaced_by, b.revisit, b.extreme};
    team.for_range(faces, [&](u32 f) { reset(f); });
    team.barrier();
    ++iterations;
    if (iterations >= launch.iterations) break;
    phase = kFurthest;
  }
  if (team.leader()) {
    st->live_faces = faces;
    st->kept_points = active;
    st->loop_iterations += iterations;
    st->loop_refined += refined_total;
    st->loop_exit = exit;
  }
}

}  // namespace cudahull::resident
