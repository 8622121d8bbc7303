// The recording of iterations (ResidentHull::step(), for the viewer's stepping and --trace): the rounds'
// log of what they turned down, and what an iteration did, read back (RecordedIteration).  The iteration
// calls its recording's hooks (ResidentHull::iterate()): a plain run's are Unrecorded's and empty, so that
// the loop is written once and has no branch on whether it records.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/resident/iteration.hpp"
#include "cudahull/resident/resident_ops.hpp"

namespace cudahull::resident {

// What a recorded iteration did, read back for the records (resident_stepping.hpp makes the IterationRecord
// of it).  Face ids are the iteration's own: 0 .. faces_before - 1 the mesh it began with, then the
// refinement's children, then each round's new faces, in order.
struct RecordedIteration {
  std::size_t faces_before = 0, refined = 0;
  u32 first_round = 0;                 // the number of its first round (Rejection::round counts on)
  std::vector<u32> fv;                 // corners of every face id (killed faces keep theirs)
  std::vector<u32> replaced_by;        // per face id: kAlive, kDeadSlot, or the entry that killed it
  std::vector<Entry> entries;          // the decision entries (Fig. 7): refinements first, then the edits
  std::vector<u32> round_first_entry;  // per round: its first entry
  std::vector<Rejection> rejections;   // what the rounds turned down, by round and candidate (repeats kept)
  std::vector<u32> new_id;             // per face id: its id after the compaction (live faces only)
};

// A plain run's iteration (ResidentHull::run()): nothing is recorded, and every hook is empty.
struct Unrecorded {
  static constexpr bool kRecords = false;
  template <class Exec>
  void begin(Exec&, std::size_t) {}
  NoLog log() const { return {}; }
  template <class Exec>
  void grow_log(Exec&, const RoundsState&) {}
  void refined(std::size_t, u32) {}
  template <class Exec, class View>
  void read_rounds(Exec&, const View&, std::size_t, std::size_t, u32) {}
  template <class Exec>
  void end(Exec&, const u32*, std::size_t) {}
};

// A recorded iteration (ResidentHull::step(), which the stepper calls with its recorder): the rounds' log
// where the executor computes, and what the iteration did read back into `out`.  The hooks are
// Unrecorded's, in the order ResidentHull::iterate() calls them.
template <class Point, class Exec>
class IterationRecorder {
  template <class T>
  using Buffer = typename Exec::template Buffer<T>;

 public:
  static constexpr bool kRecords =
      true;  // the iteration waits for the refined count and stops after the rounds

  explicit IterationRecorder(RecordedIteration& out) : out_(&out) {}

  // A recorded iteration begins, on a mesh of `faces` faces.
  void begin(Exec& exec, std::size_t faces) {
    RecordedIteration& out = *out_;
    out = RecordedIteration{};
    out.faces_before = faces;
    // The rounds' rejections (a face may meet the same one in several rounds: all are kept here, in order,
    // and the records keep the first), with each round's first entry; a log without room for a round
    // stops it before it begins, and the host grows the log.
    rejection_capacity_ = static_cast<u32>(std::max<std::size_t>(4096, 2 * faces));
    rejections_.grow(rejection_capacity_);
    rejection_count_.grow(1);
    exec.fill(rejection_count_.data(), 1, u32{0});
    round_capacity_ = 64;
    round_first_entry_.grow(round_capacity_);
  }

  // The log the rounds write, their numbers counted from the iteration's first round.
  RejectionLog log() {
    return RejectionLog{rejections_.data(),        rejection_count_.data(), rejection_capacity_, 0,
                        round_first_entry_.data(), out_->first_round,       round_capacity_};
  }

  // After a run of rounds that did not fit: the log grows too, where it was short, keeping the rejections
  // logged so far (not the unwritten rest of the log, which compute-sanitizer's initcheck would see read).
  void grow_log(Exec& exec, const RoundsState& state) {
    if (state.needed_rejections > rejection_capacity_) {
      const std::size_t room = 2 * std::size_t{state.needed_rejections};
      if (room > 0xffffffffu) throw DeviceError("resident engine: too many rejections to record");
      u32 logged = 0;
      exec.download(&logged, rejection_count_.data(), 1);
      rejections_.grow(room, std::min<std::size_t>(logged, rejection_capacity_));
      rejection_capacity_ = static_cast<u32>(room);
    }
    if (state.needed_rounds > round_capacity_) {
      round_first_entry_.grow(2 * std::size_t{state.needed_rounds}, round_capacity_);
      round_capacity_ = 2 * state.needed_rounds;
    }
  }

  // The marks are made: `refined` faces refine, and the rounds are numbered from `first_round`.
  void refined(std::size_t refined, u32 first_round) {
    out_->refined = refined;
    out_->first_round = first_round;
  }

  // After the rounds, before the routing: the iteration's `faces` faces and `entries` entries (in `m`) and
  // the log of its rounds up to `last_round`, read back.
  void read_rounds(Exec& exec, const MeshView<Point>& m, std::size_t faces, std::size_t entries,
                   u32 last_round) {
    RecordedIteration& out = *out_;
    out.fv.resize(3 * faces);
    out.replaced_by.resize(faces);
    out.entries.resize(entries);
    exec.download(out.fv.data(), m.fv, out.fv.size());
    exec.download(out.replaced_by.data(), m.replaced_by, out.replaced_by.size());
    exec.download(out.entries.data(), m.entries, out.entries.size());
    out.round_first_entry.resize(last_round + 1 - out.first_round);
    exec.download(out.round_first_entry.data(), round_first_entry_.data(), out.round_first_entry.size());
    u32 rejected = 0;
    exec.download(&rejected, rejection_count_.data(), 1);
    out.rejections.resize(rejected);  // all of them: every round had room
    exec.download(out.rejections.data(), rejections_.data(), out.rejections.size());
    // The log is filled by atomics in any order: by round, then candidate, the same on every executor.
    std::sort(out.rejections.begin(), out.rejections.end(), [](const Rejection& a, const Rejection& b) {
      return a.round != b.round ? a.round < b.round : a.id != b.id ? a.id < b.id : a.kind < b.kind;
    });
  }

  // After the compaction: each of the iteration's `face_ids` face ids' id after it (`face_rank`).
  void end(Exec& exec, const u32* face_rank, std::size_t face_ids) {
    out_->new_id.resize(face_ids);
    exec.download(out_->new_id.data(), face_rank, face_ids);
  }

 private:
  RecordedIteration* out_;
  // step()'s log of the rounds: the candidates turned down, and each round's first entry.
  Buffer<Rejection> rejections_;
  Buffer<u32> rejection_count_, round_first_entry_;
  u32 rejection_capacity_ = 0, round_capacity_ = 0;
};

}  // namespace cudahull::resident
