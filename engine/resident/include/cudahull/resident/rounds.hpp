// The swap and removal rounds of one iteration (section 3.2, Figs. 3b, 4, 5), written once for every
// executor, as the iteration around them is (iteration.hpp): the host twin (HostTeam, one thread), one block
// on the device (a small mesh) and a cooperative grid (cuda/resident_cuda.cu's BlockTeam and GridTeam).  A
// team is what runs the body: for_range() splits a range among its threads, barrier() waits for all of them,
// list_if() appends the indices that pass a test (in any order), exclusive_scan() numbers in index order and
// gives every thread the total, max_per_segment() keeps the largest key per segment, leader() is the one
// thread that writes the state, and start_timing() and time() profile the rounds' phases (device teams).
//
// design:
//   repeat
//     list the work faces: new since the round began, or touched by the last round's edits (MarkWork)
//     none: the rounds are over.  More than the room for their candidates: the host grows it
//     recording (the stepper): no room in the log for the round's rejections: the host grows it
//     each work face points its links at the faces that replaced the ones it knew (FixLinks)
//     each finds its first candidate, a concave edge to swap or a degree-3 vertex to remove, kept only if
//       no foldover (Fig. 5), and claims the faces it would change with (round, ~id) (Claim)
//     a candidate that holds every claim wins (Won): a bit per face
//     the winners are numbered in face order (a prefix sum over the bits' words), so that every team
//       numbers them alike and the mesh is the same on every executor
//     no winner: the rounds are over
//     no room for the winners' faces and decision entries: the work goes back to this round and the host
//       grows the buffers (RoundsState::overflow); the rerun claims with the same keys
//     each winner applies (Apply): two new faces (a removal: one, and a slot left dead), one decision entry
#pragma once

#include <type_traits>

#include "cudahull/resident/swaps.hpp"

namespace cudahull::resident {

// What a run of rounds works on: the claims and stamps per face, the candidates per work item, the work
// list, a bit per face for the wins with the wins before each word, and the state.
template <class Point, class Log = NoLog>
struct RoundsBuffers {
  FindCandidate<Point, Log> find;  // the mesh, and the log of rejections (the recording driver's)
  u64* claim;
  u32* revisit;
  Candidate* cands;  // per work item
  u32* list;         // the work faces
  u32* win_mask;     // a bit per face: (faces + 31) / 32 words
  u32* word_rank;    // the wins in the words before each
  RoundsState* st;
};

// The end of a round (the team's leader): its counts into the state, for the next round and the stats.
CUDAHULL_HD inline void end_round(RoundsState* st, u32 faces, u32 entries, u32 round, u32 work, u32 winners) {
  if (winners != 0) {
    st->fresh_from = faces;
    st->faces = faces + 2 * winners;
    st->entries = entries + winners;
    st->edits += winners;
  }
  st->round = round;
  ++st->rounds;
  st->work_items += work;
  st->round_work = 0;
}

// Rounds until no candidate is left, or until a round's winners do not fit (st->overflow).  Every thread
// of the team calls it; start_rounds() has set the state up.
template <class Team, class Point, class Log>
CUDAHULL_HD void swap_and_removal_rounds(const Team& team, const RoundsBuffers<Point, Log>& b) {
  RoundsState* st = b.st;
  team.start_timing();
  while (true) {
    const u32 faces = st->faces, fresh = st->fresh_from, entries = st->entries, round = st->round + 1;
    const u32 words = (faces + 31) / 32;
    const MarkWork<Point> rule{b.find.m, b.revisit, fresh, round};
    const auto is_work = [&](u32 f) { return rule.is_work(f); };
    team.list_if(faces, is_work, b.list, &st->round_work, st->work_capacity);
    team.for_range(words, [&](u32 w) { b.win_mask[w] = 0; });
    team.barrier();
    const u32 work = st->round_work;
    if (work == 0) return;
    // Room for the round before it changes anything: its work's candidates (the list kept only what fit)
    // and, recording, the log's (six rejections a work face at most, and the round's first entry).
    // Otherwise the host grows what is short and the round runs afresh.
    constexpr bool kRecording = !std::is_same_v<Log, NoLog>;
    bool short_of_room = work > st->work_capacity;
    [[maybe_unused]] u32 logged_before = 0, at = 0;  // recording: the log's length, the round's slot
    if constexpr (kRecording) {
      logged_before = *b.find.log.count;
      at = round - b.find.log.first_round;
      short_of_room =
          short_of_room || logged_before + 6 * work > b.find.log.capacity || at >= b.find.log.round_capacity;
    }
    if (short_of_room) {
      if (team.leader()) {
        st->overflow = 1;
        st->needed_faces = faces;
        st->needed_entries = entries;
        st->needed_work = work;
        if constexpr (kRecording) {
          st->needed_rejections = logged_before + 6 * work;
          st->needed_rounds = at + 1;
        }
      }
      return;
    }
    if constexpr (kRecording) {
      if (team.leader()) b.find.log.round_first_entry[at] = entries;
    }

    const FixLinks<Point> fixer{b.find.m};
    team.for_range(work, [&](u32 i) { fixer.fix(b.list[i]); });
    team.barrier();
    FindCandidate<Point, Log> find = b.find;
    if constexpr (kRecording) find.log.round = round;
    const Claim<Point, FindCandidate<Point, Log>, Team::kCompactCode> claimer{find, round, b.claim,
                                                                              b.revisit};
    team.for_range(work, [&](u32 i) { claimer.claim_for(b.list[i], b.cands[i]); });
    team.barrier();
    team.time(0);

    const Won judge{round, b.claim};
    team.for_range(work, [&](u32 i) {
      const u32 f = b.list[i];
      if (judge.holds(b.cands[i])) atomic_or_u32(&b.win_mask[f / 32], 1u << (f % 32));
    });
    team.barrier();
    team.time(1);
    const u32 winners = team.exclusive_scan(
        words, [&](u32 w) { return popcount_u32(b.win_mask[w]); }, b.word_rank);
    team.time(2);
    if (winners == 0) {
      if (team.leader()) end_round(st, faces, entries, round, work, 0);
      return;
    }
    if (faces + 2 * winners > st->face_capacity || entries + winners > st->entry_capacity) {
      // So far the round changed links (FixLinks, which a rerun repeats), claims (a rerun claims with the
      // same keys) and the stamps of the faces with a candidate, which go back to this round.
      team.for_range(work, [&](u32 i) { b.revisit[b.list[i]] = round; });
      if (team.leader()) {
        // The rerun logs the round's rejections again: this run's go (every claim is done).
        if constexpr (kRecording) *b.find.log.count = logged_before;
        st->overflow = 1;
        st->needed_faces = faces + 2 * winners;
        st->needed_entries = entries + winners;
      }
      return;
    }

    const Apply<Point> applier{b.find.m, faces, entries, b.revisit, round};
    team.for_range(work, [&](u32 i) {
      const u32 f = b.list[i], word = b.win_mask[f / 32], bit = 1u << (f % 32);
      if (word & bit) applier.apply(b.cands[i], b.word_rank[f / 32] + popcount_u32(word & (bit - 1)));
    });
    team.barrier();
    team.time(3);
    if (team.leader()) end_round(st, faces, entries, round, work, winners);
    team.barrier();
  }
}

// The lengths of list_two()'s lists (HostTeam, WarpTeam).
struct TwoCounts {
  u32 first, second;
};

// The host's team: one thread, in index order.
struct HostTeam {
  static constexpr bool kCompactCode = false;
  template <class F>
  CUDAHULL_HD void for_range(u32 n, const F& f) const {
    for (u32 i = 0; i < n; ++i)
      f(i);
  }
  CUDAHULL_HD void barrier() const {}
  CUDAHULL_HD bool leader() const { return true; }
  CUDAHULL_HD void start_timing() const {}
  CUDAHULL_HD void time(int) const {}
  // Per segment, the largest key of the indices below n (op.segment(j), op.key(j), into op.extreme).
  template <class Op>
  CUDAHULL_HD void max_per_segment(u32 n, const Op& op) const {
    for (u32 j = 0; j < n; ++j)
      atomic_max_u64(&op.extreme[op.segment(j)], op.key(j));
  }
  // The indices below n that pass, appended at *count (those past `capacity` counted, not written).
  template <class Pred>
  CUDAHULL_HD void list_if(u32 n, const Pred& pred, u32* list, u32* count, u32 capacity) const {
    for (u32 i = 0; i < n; ++i) {
      if (!pred(i)) continue;
      if (*count < capacity) list[*count] = i;
      ++*count;
    }
  }
  template <class Value>
  CUDAHULL_HD u32 exclusive_scan(u32 n, const Value& value, u32* out) const {
    u32 sum = 0;
    for (u32 i = 0; i < n; ++i) {
      const u32 v = value(i);
      out[i] = sum;
      sum += v;
    }
    return sum;
  }
  // small_hull()'s (and WarpTeam's): the largest key(i) over i < n (0 where there is none), the exclusive
  // count of the indices below n that pass, and the lists of them.
  template <class Key>
  CUDAHULL_HD u64 max_of(u32 n, const Key& key) const {
    u64 best = 0;
    for (u32 i = 0; i < n; ++i) {
      const u64 k = key(i);
      best = k > best ? k : best;
    }
    return best;
  }
  template <class Pred>
  CUDAHULL_HD u32 count_scan(u32 n, const Pred& pred, u32* out) const {
    return exclusive_scan(
        n, [&](u32 i) { return pred(i) ? 1u : 0u; }, out);
  }
  // The indices below n that pass (pred(i), once each), in index order, each told its rank among them
  // (emit(i, rank)); their count: list_two()'s first list alone.
  template <class Pred, class Emit>
  CUDAHULL_HD u32 list(u32 n, const Pred& pred, const Emit& emit) const {
    return list_two(
               n, [&](u32 i) { return pred(i) ? 1u : 0u; }, emit, [](u32, u32) {})
        .first;
  }
  // Two such lists in one pass: kind(i) (once each) puts i in the first (bit 0), the second (bit 1), both
  // or neither; first(i, rank) and second(i, rank) as emit().
  template <class Kind, class First, class Second>
  CUDAHULL_HD TwoCounts list_two(u32 n, const Kind& kind, const First& first, const Second& second) const {
    TwoCounts counts{0, 0};
    for (u32 i = 0; i < n; ++i) {
      const u32 k = kind(i);
      if (k & 1u) first(i, counts.first++);
      if (k & 2u) second(i, counts.second++);
    }
    return counts;
  }
};

}  // namespace cudahull::resident
