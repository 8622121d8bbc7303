// The resident engine's state: the points where the executor computes, the device buffers ResidentHull
// owns (the mesh, the kept points, the rounds' room) with their counts, and how they grow and shrink.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/mesh.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/resident/iteration.hpp"
#include "cudahull/resident/resident_ops.hpp"

namespace cudahull::resident {

// What the driver (resident_driver.hpp) and its finish (resident_finish.hpp) share.  `count` points live
// at `points`, where the executor computes; `host_points`, when given, is the same data on the host.
template <class Point, class Exec>
struct ResidentBuffers {
  template <class T>
  using Buffer = typename Exec::template Buffer<T>;

  ResidentBuffers(Exec& exec, const Point* points, std::size_t count, const std::vector<Point>* host_points)
      : exec_(exec), host_(host_points), points_(points), n_(count) {}

  // The coordinates of points `ids`: from the host copy, or gathered where the executor computes and read
  // back in one piece.
  std::vector<Point> fetch(const std::vector<PointIndex>& ids) {
    std::vector<Point> out(ids.size());
    if (host_) {
      for (std::size_t k = 0; k < ids.size(); ++k)
        out[k] = (*host_)[ids[k]];
    } else if (!ids.empty()) {
      gather(listed(ids), out);
    }
    return out;
  }
  // `ids` (point or face ids) where the executor computes, in gather_ids_ (the last list uploaded).
  const u32* listed(const std::vector<u32>& ids) {
    gather_ids_.grow(ids.size());
    exec_.upload(gather_ids_.data(), ids.data(), ids.size());
    return gather_ids_.data();
  }
  // The coordinates of the `out.size()` points listed at `ids` where the executor computes.
  void gather(const u32* ids, std::vector<Point>& out) {
    points_read_back_ += out.size();
    gathered_.grow(out.size());
    exec_.for_each(out.size(), GatherPoints<Point>{points_, ids, gathered_.data()});
    exec_.download(out.data(), gathered_.data(), out.size());
  }
  // Every point on the host: the caller's copy, or all of them read back once (section 3.1's tetrahedron
  // and lower-dimensional input only).
  const std::vector<Point>& all_points() {
    if (host_) return *host_;
    if (read_back_.size() != n_) {
      points_read_back_ += n_;
      read_back_.resize(n_);
      exec_.download(read_back_.data(), points_, n_);
    }
    return read_back_;
  }
  // The exact hull of points `ids` (ascending, no repeats; `at`: their coordinates): as exact_hull of
  // all points restricted to them, duplicates going to the lowest index.
  BasicHullMesh<Point> hull_of(const std::vector<PointIndex>& ids, const std::vector<Point>& at) const {
    if (host_) return exact_hull(*host_, ids);
    BasicHullMesh<Point> hull = exact_hull(at);
    for (PointIndex& v : hull.vertex_ids)
      v = ids[v];
    return hull;
  }

  MeshView<Point> view() {
    return MeshView<Point>{points_, c_, fv_.data(), fn_.data(), replaced_by_.data(), entries_.data()};
  }

  // Room for `count` faces, keeping the current ones; new claim slots hold no claim.
  // Face ids are u32 and a candidate claims with 6 f + slot (Claim): beyond kMaxFaces the ids would wrap.
  static constexpr std::size_t kMaxFaces = 0xffffffffu / 6;
  static constexpr std::size_t kDoublingFaces = std::size_t{1} << 21;
  void grow_faces(std::size_t count) {
    if (count > capacity_) grow_capacity(count);
    // The mesh's own buffers, which the compaction swaps with its spares (sized for the live faces only).
    fv_.grow(3 * capacity_, 3 * faces_);
    fn_.grow(3 * capacity_, 3 * faces_);
  }
  void grow_capacity(std::size_t count) {
    if (count > kMaxFaces)
      throw DeviceError("resident engine: the hull needs " + std::to_string(count) +
                        " face slots, more than " + std::to_string(kMaxFaces) + " (use --engine stepping)");
    const std::size_t old = capacity_;
    // Doubling while small (a regrowth is a round of allocations and copies, most of an iteration's host
    // time on a small hull), then what is asked (room_for() has the headroom; a copy of the faces is a
    // fraction of an iteration): the room follows the need (issue 26: memory).
    const std::size_t step = capacity_ < kDoublingFaces ? 2 * capacity_ : 0;
    capacity_ = std::min(std::max(count, step), kMaxFaces);
    replaced_by_.grow(capacity_, faces_);
    revisit_.grow(capacity_, faces_);
    claim_.grow(capacity_, old);
    exec_.fill(claim_.data() + old, capacity_ - old, u64{0});
    // The refinement marks and their prefix sum (one per face) and the furthest points may be in use:
    // those entries move along (in a small mesh's fused iteration the marks'
    // entries are copied before they are written: harmless, and never more than the faces in use).
    flags_.grow(capacity_ + 1, marks_in_use_);
    face_rank_.grow(capacity_ + 1, marks_in_use_);
  }
  // The compaction's spares, for `live` faces: an iteration ends with at most its faces and two more a
  // refined face (a split adds two, a swap none, a removal takes two away).  The furthest point per face
  // is kept for the live faces too (the current ones' move along).
  void grow_spares(std::size_t live) {
    fv_out_.grow(3 * live);
    fn_out_.grow(3 * live);
    extreme_.grow(live, faces_);
  }
  // The rounds' candidates, given back before the finish (which sorts the corners: the peak of a large run).
  void release_rounds() {
    cands_.release();
    work_capacity_ = 0;
  }
  // Room for the candidates of `count` work faces a round.
  void grow_work(std::size_t count) {
    if (count <= work_capacity_) return;
    work_capacity_ = std::min<std::size_t>(count, 0xffffffffu);
    cands_.grow(work_capacity_);
    work_list_.grow(work_capacity_);
  }
  void grow_entries(std::size_t count) {
    if (count > entry_capacity_) {
      // Half as much again while small, then what is asked, as the faces grow.
      entry_capacity_ =
          std::max(count, entry_capacity_ < kDoublingFaces ? entry_capacity_ + entry_capacity_ / 2 : 0);
      entries_.grow(entry_capacity_, entries_used_);
    }
  }

  // The iteration's buffers as they are now (the rounds' bits are the executor's).
  template <class Log = NoLog>
  IterationBuffers<Point, Log> iteration_buffers(const Log& log = {}) {
    IterationBuffers<Point, Log> b{};
    b.m = view();
    b.log = log;
    b.fv_spare = fv_out_.data();
    b.fn_spare = fn_out_.data();
    b.index = index_[0].data();
    b.face = face_of_[0].data();
    b.index_spare = index_[1].data();
    b.face_spare = face_of_[1].data();
    b.keep = keep_.data();
    b.point_rank = point_rank_.data();
    b.flags = flags_.data();
    b.face_rank = face_rank_.data();
    b.revisit = revisit_.data();
    b.list = work_list_.data();
    b.extreme = extreme_.data();
    b.claim = claim_.data();
    b.cands = cands_.data();
    b.st = state_.data();
    b.first_list = first_list_;
    return b;
  }

  // The first mesh's launch (section 3.1): `fv` and `fn` written where iteration_buffers() hands the
  // iterations their faces, each face live and unstamped, and the state cleared.
  FirstMesh first_mesh(const std::vector<u32>& fv, const std::vector<u32>& fn) {
    const IterationBuffers<Point, NoLog> b = iteration_buffers();
    FirstMesh first{};
    first.faces = static_cast<u32>(fv.size() / 3);
    std::copy(fv.begin(), fv.end(), first.fv);
    std::copy(fn.begin(), fn.end(), first.fn);
    first.fv_out = b.m.fv;
    first.fn_out = b.m.fn;
    first.replaced_by = b.m.replaced_by;
    first.revisit = b.revisit;
    first.extreme = b.extreme;
    first.st = b.st;
    return first;
  }

  // After a run of rounds that did not fit: the mesh as the rounds left it, and room for the next round
  // and an eighth more for those after it.
  void grow_after_overflow(const RoundsState& state, ResidentStats& stats) {
    ++stats.round_overflows;
    faces_ = state.faces;
    entries_used_ = state.entries;
    // Only what was short grows (a round short of work room needs no more face slots).
    const auto more = [](std::size_t n) { return n + n / 8 + 64; };
    // The faces' buffers at the capacity's size even when no more slots are needed: a device loop that
    // stopped after an odd number of compactions left the faces in the spares.
    grow_faces(state.needed_faces > capacity_ ? more(state.needed_faces) : 0);
    if (state.needed_entries > entry_capacity_) grow_entries(more(state.needed_entries));
    if (state.needed_work > work_capacity_) grow_work(more(state.needed_work));
  }

  // Room for a run of rounds: `faces` face slots, `entries` entries and `work` work faces a round.
  void grow_for_rounds(std::size_t faces, std::size_t entries, std::size_t work) {
    grow_faces(faces);
    grow_entries(entries);
    grow_work(work);
  }
  // Everything grows before the split (the marks are kept), by the refined count (room_for()).  A small
  // mesh (`small`: sized as if every face refined) has work room for every face slot, as the first round's
  // work may be six a refined face (the children and the stamped faces beside them), and on a device loop
  // spares for them too, as its faces go back and forth between the two (a loop is sized for twice its
  // faces refining: its later iterations grow the mesh, and each stop for room costs a launch and a wait).
  void grow_for_iteration(std::size_t refined, bool small = false, bool loop = false) {
    IterationRoom room = room_for(faces_, refined);
    if (small) room.work = std::max<u64>(room.work, room.faces);
    if (loop) room.spares = std::max<u64>(room.spares, room.faces);
    marks_in_use_ = faces_;
    // What holds nothing between iterations and must grow goes first, so that its old blocks are not
    // held while the faces' buffers copy into their new ones.
    if (room.work > work_capacity_) release_rounds();
    // The spares are the last iteration's faces, swapped out at the capacity's size: back to the live
    // faces' size (their contents are dead), before the faces' buffers copy into bigger ones.  A small
    // mesh keeps both at the capacity's size instead, so that the swaps need no new blocks and copies.
    if (!small &&
        (3 * room.spares > fv_out_.capacity() || 3 * (room.spares + room.spares / 4) < fv_out_.capacity())) {
      fv_out_.release();
      fn_out_.release();
    }
    grow_for_rounds(room.faces, room.entries, room.work);
    grow_spares(small ? std::max<std::size_t>(room.spares, capacity_) : room.spares);
    marks_in_use_ = 0;
  }

  // The points' buffers follow the kept points down (issue 26: memory): those that hold nothing between
  // iterations (the compaction's spares, the kept marks and their ranks) are made afresh once the kept
  // points are fewer than half their room; the current ones follow when they become the spares.
  void shrink_points() {
    for (Buffer<u32>* b : {&index_[1], &face_of_[1], &keep_, &point_rank_}) {
      if (active_ >= b->capacity() / 2) continue;
      b->release();
      b->grow(active_);
    }
  }

  // The compaction's outputs become the current faces and points.
  void swap_spares() {
    fv_.swap(fv_out_);
    fn_.swap(fn_out_);
    index_[0].swap(index_[1]);
    face_of_[0].swap(face_of_[1]);
  }

  Exec& exec_;
  const std::vector<Point>* host_;  // null: the points are only where the executor computes
  const Point* points_;
  std::size_t n_;
  std::vector<Point> read_back_;  // all_points() without a host copy
  std::uint64_t points_read_back_ = 0;
  Buffer<u32> gather_ids_;
  Buffer<Point> gathered_;
  Vec3d c_{};
  const u32* first_list_ = nullptr;  // the points kFirst distributes (NotInsideP), or null for all
  std::size_t marks_in_use_ = 0;     // entries of flags_ and face_rank_ that grow_faces() keeps
  std::size_t faces_ = 0, capacity_ = 0, entries_used_ = 0, entry_capacity_ = 0, active_ = 0;
  std::size_t work_capacity_ = 0;  // work faces a round has room for (cands_, work_list_)
  Buffer<u32> fv_, fn_, fv_out_, fn_out_, replaced_by_, revisit_, flags_, face_rank_;
  Buffer<u64> claim_, extreme_;
  Buffer<RoundsState> state_;  // the counts where the executor computes (see RoundsState)
  Buffer<Entry> entries_;
  Buffer<u32> work_list_;        // the rounds' work faces (and the repair's stamped faces)
  Buffer<FaceRow> repair_rows_;  // the repair's rows, read back and written (repair_faults())
  Buffer<Candidate> cands_;      // the rounds' candidates, per work item
  Buffer<u32> index_[2], face_of_[2], keep_, point_rank_;
};

}  // namespace cudahull::resident
