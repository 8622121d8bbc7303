// The resident engine's driver: Algorithm 1 with every phase on one executor, the host hearing O(1) bytes
// per iteration (a small state) until the result.  `Exec` is HostExec (host_exec.hpp: loops on the host,
// for the CPU tests and as the reference; DevicePathHostExec takes the GPU's paths) or CudaExec
// (cuda/resident_cuda.cu: kernels on the device); all run the same operations (resident_ops.hpp) in the
// same order and give the same mesh.
//
// design:
//   P                  one pass: the points extreme along 14 directions; P is their exact hull (host)
//   drop test          the points proven strictly inside P (DropFilter) are dropped; the rest listed
//   first mesh         P with c its centre (else section 3.1's tetrahedron, confirmed exactly)
//   iterations         iteration.hpp, written once for every executor: the first distribution, then per
//                      iteration the furthest point per face, the split (Fig. 3a), swap and removal rounds
//                      (Figs. 3b, 4, 5), the routing (Algorithm 2) and the compaction.  The host reads the
//                      state after each launch and grows the room when a launch stopped short of it: one
//                      wait an iteration (two on a large mesh, which waits for the refined count to stay
//                      tight in memory), and with few points left whole iterations in one launch (the
//                      device loop)
//   finish             no external point left: the edges that are not strictly convex counted; none, or
//                      only flat ones with every vertex on three strictly convex edges, and the mesh is
//                      the exact hull.  Defects (concave edges, thin vertices) are repaired where they
//                      are (fault_repair.hpp), with 2, 4 and 8 rings around them.  Otherwise (flat input
//                      whose facets are wider than a patch), or on a stall, the exact reference hull of the
//                      mesh's vertices and the points still outside: every other point was dropped inside
//                      P or inside a tetrahedron of c and mesh vertices, so these hold every extreme point.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/mesh.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/resident/fault_repair.hpp"
#include "cudahull/resident/first_mesh.hpp"
#include "cudahull/resident/iteration.hpp"
#include "cudahull/resident/resident_ops.hpp"
#include "cudahull/resident/shared_phases.hpp"

namespace cudahull::resident {

// What a recorded iteration did, read back for the records (resident_stepping.hpp makes the IterationRecord
// of it).  Face ids are the iteration's own: 0 .. faces_before - 1 the mesh it began with, then the
// refinement's children, then each round's new faces, in order.
struct RecordedIteration {
  std::size_t faces_before = 0, refined = 0;
  u32 first_round = 0;                 // the number of its first round (Rejection::round counts on)
  std::vector<u32> fv;                 // corners of every face id (killed faces keep theirs)
  std::vector<u32> killer;             // per face id: kAlive, kDeadSlot, or the entry that killed it
  std::vector<Entry> entries;          // the decision entries (Fig. 7): refinements first, then the edits
  std::vector<u32> round_first_entry;  // per round: its first entry
  std::vector<Rejection> rejections;   // what the rounds turned down, by round and candidate (repeats kept)
  std::vector<u32> new_id;             // per face id: its id after the compaction (live faces only)
};

template <class Point, class Exec>
class ResidentHull {
 public:
  template <class T>
  using Buffer = typename Exec::template Buffer<T>;

  // `count` points live at `points`, where the executor computes (the host vector itself for HostExec, a
  // device copy or the caller's device array for CudaExec).  `host_points`, when given, is the same data on
  // the host, where the exact checks read.  Without it (points only the executor holds, e.g. a CuPy array)
  // the driver reads back the few coordinates it checks: P's 14 points, the result's vertices, the exact
  // finish's candidates; every point only for section 3.1's tetrahedron or lower-dimensional input.
  ResidentHull(Exec& exec, const Point* points, std::size_t count, const std::vector<Point>* host_points)
      : exec_(exec), host_(host_points), points_(points), n_(count) {}

  BasicHullMesh<Point> run(ResidentStats& stats) {
    BasicHullMesh<Point> hull = run_all(stats);
    stats.points_read_back = points_read_back_;
    return hull;
  }

  // Stepping with records (resident_stepping.hpp: the viewer, --trace, --table).  The same iterations as
  // run(), one per step(), the rounds stepped by the host (the mesh is the fused rounds' own, which the tests
  // check edit for edit), and what each did read back (RecordedIteration): O(faces) bytes a step, asked for.
  // begin(): P, the first mesh and the first distribution; false when that is already the answer (no points,
  // lower-dimensional input), then in `done`.
  bool begin(ResidentStats& stats, BasicHullMesh<Point>& done) {
    start_laps(stats);
    if (setup(stats, done, true)) return true;
    close_laps(stats);
    return false;
  }
  // One iteration, recorded; false when no face could refine (a stall: end(stats, true) finishes exactly).
  bool step(ResidentStats& stats, RecordedIteration& out) { return iterate(stats, &out); }
  // After the last step: the exact check and the result (the exact finish after a stall).
  BasicHullMesh<Point> end(ResidentStats& stats, bool stalled) {
    lap(stats, ResidentPhase::kHost);
    BasicHullMesh<Point> out = stalled ? exact_finish(stats, "stalled: no face could refine") : finish(stats);
    stats.finish_ms = lap(stats, ResidentPhase::kFinish, mesh_bytes());
    close_laps(stats);
    stats.points_read_back = points_read_back_;
    return out;
  }
  std::size_t active_points() const { return active_; }
  Vec3d interior() const { return c_; }
  // The current (compacted) mesh: corners and links, 3 per face.
  void read_mesh(std::vector<u32>& fv, std::vector<u32>& fn) {
    fv.resize(3 * faces_);
    fn.resize(3 * faces_);
    exec_.download(fv.data(), fv_.data(), fv.size());
    exec_.download(fn.data(), fn_.data(), fn.size());
  }
  // Per point: its face while it is kept (outside), else -1.
  void read_point_faces(std::vector<std::int32_t>& out) {
    out.assign(n_, -1);
    std::vector<u32> index(active_), face(active_);
    exec_.download(index.data(), index_[0].data(), active_);
    exec_.download(face.data(), face_of_[0].data(), active_);
    for (std::size_t j = 0; j < active_; ++j)
      out[index[j]] = static_cast<std::int32_t>(face[j]);
  }
  // Per face: how many kept points it holds and the furthest (the next refinement's apex), or 0 and none.
  void read_face_extremes(std::vector<FaceExtreme>& out) {
    std::vector<u64> furthest(faces_);
    std::vector<u32> counts(faces_);
    flags_.grow(faces_ + 1);
    exec_.fill(flags_.data(), faces_, u32{0});
    exec_.for_each(active_, CountPerFace{face_of_[0].data(), flags_.data()});
    exec_.segmented_max(
        active_, FurthestPerFace<Point>{view(), index_[0].data(), face_of_[0].data(), extreme_.data()});
    exec_.download(counts.data(), flags_.data(), faces_);
    exec_.download(furthest.data(), extreme_.data(), faces_);
    out.resize(faces_);
    for (std::size_t f = 0; f < faces_; ++f)
      out[f] = FaceExtreme{counts[f], counts[f] ? rank_key_index(furthest[f]) : kNoPoint};
  }
  // Backend::write_point_states_on_device's states, written where the executor computes.
  void write_point_states(std::int32_t* out, const std::vector<PointIndex>& vertices) {
    exec_.fill(out, n_, kPointStateInternal);
    exec_.for_each(active_, ScatterPointStates{index_[0].data(), face_of_[0].data(), out});
    if (vertices.empty()) return;
    exec_.for_each(vertices.size(), MarkPoints{listed(vertices), kPointStateVertex, out});
  }

 private:
  BasicHullMesh<Point> run_all(ResidentStats& stats) {
    start_laps(stats);
    BasicHullMesh<Point> done;
    if (!setup(stats, done, false)) {
      close_laps(stats);
      return done;
    }
    bool stalled = false;
    while (active_ > 0 && !stalled) {
      if (!iterate(stats)) {
        if (active_ == 0) break;  // no point was left outside (only after setup() left them uncompacted)
        stalled = true;
      }
    }
    lap(stats, ResidentPhase::kHost);
    if (!stalled) release_rounds();
    BasicHullMesh<Point> out = stalled ? exact_finish(stats, "stalled: no face could refine") : finish(stats);
    stats.finish_ms = lap(stats, ResidentPhase::kFinish, mesh_bytes());
    close_laps(stats);
    return out;
  }

  // P, the first mesh, and the points not proven inside P listed for the first distribution (section 3.1),
  // which the first iteration's launch does (kFirst).  `recording`: the points are distributed and
  // compacted here, for the states the first step shows.  False when `done` is already the answer.
  bool setup(ResidentStats& stats, BasicHullMesh<Point>& done, bool recording) {
    const std::size_t n = n_;
    if (n == 0) {
      done = exact_hull(std::vector<Point>{});
      stats.setup_ms = lap(stats, ResidentPhase::kSetup);
      return false;
    }
    // P, the drop filter, and the first mesh: P itself where its centre is strictly inside every face
    // (its cones tile space from there: the star shape holds from the start, and the first iterations
    // need not find P's vertices again); else section 3.1's tetrahedron, over all points when P is flat
    // (then the input may be too).
    const BasicHullMesh<Point> polytope = directional_polytope();
    const DropFilter filter = drop_filter(polytope, max_coordinate_);
    std::vector<u32> fv, fn;
    stats.polytope_first = polytope_mesh(polytope, fv, fn, c_);
    if (!stats.polytope_first) {
      const std::vector<Point>& host = all_points();
      TetrahedronQueries<Point, Exec> queries(exec_, host, points_);
      const std::string flat = first_tetrahedron(host, queries, fv, fn, c_);
      if (!flat.empty()) {
        done = lower_dimensional(stats, flat);
        stats.setup_ms = lap(stats, ResidentPhase::kSetup, n * sizeof(Point));
        return false;
      }
    }

    // The first mesh, and the first distribution (section 3.1), in the room reserve_first() made.
    static_assert(static_cast<std::size_t>(kMaxFirstFaces) <= kInitialFaces, "the first mesh fits");
    faces_ = fv.size() / 3;
    const u32 first_faces = static_cast<u32>(faces_);
    FirstMesh first{};
    first.faces = first_faces;
    std::copy(fv.begin(), fv.end(), first.fv);
    std::copy(fn.begin(), fn.end(), first.fn);
    first.fv_out = fv_.data();
    first.fn_out = fn_.data();
    first.killer = killer_.data();
    first.look = look_.data();
    first.extreme = extreme_.data();
    first.st = state_.data();
    exec_.for_each(fv.size(), first);
    // The points not proven inside P (all, without P), listed in index order (one wait for the count).
    first_list_ = nullptr;
    active_ = n;
    if (filter.planes != 0) {
      index_[1].grow(n);
      active_ = exec_.select_if(n, NotInsideP<Point>{points_, filter}, index_[1].data());
      first_list_ = index_[1].data();
    }
    stats.dropped_by_polytope = n - active_;
    for (auto* b : {&index_[0], &index_[1], &face_of_[0], &face_of_[1], &keep_, &point_rank_})
      b->grow(active_, b == &index_[1] ? active_ : 0);
    first_pending_ = true;
    if (recording) {
      run_phases(kFirst, kFirst, false);
      compact_only();
    }
    stats.setup_ms = lap(stats, ResidentPhase::kSetup, n * sizeof(Point));  // every point read once
    return true;
  }

  // P (see DirectionKeys): the exact hull of the points extreme along kDirections, found in one pass.
  BasicHullMesh<Point> directional_polytope() {
    const std::array<u64, kDirections> keys = exec_.template reduce_max_many<kDirections>(
        n_, DirectionKeys<Point>{points_}, [&] { reserve_first(); });
    std::vector<PointIndex> ids;
    for (const u64 key : keys)
      ids.push_back(rank_key_index(key));
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    const std::vector<Point> at = fetch(ids);
    // Every coordinate is at most M in size: the axis extremes, widened for the float-rounded ranking of
    // double coordinates (rank_key) by more than its relative error.
    max_coordinate_ = 0;
    for (int k = 0; k < 6; ++k) {
      const auto slot = std::lower_bound(ids.begin(), ids.end(), rank_key_index(keys[k])) - ids.begin();
      const Vec3d p = to_vec3d(at[static_cast<std::size_t>(slot)]);
      const double v = k < 2 ? p.x : k < 4 ? p.y : p.z;
      max_coordinate_ = std::max(max_coordinate_, std::fabs(v));
    }
    max_coordinate_ *= 1 + 0x1p-20;
    return hull_of(ids, at);
  }

  // Room for the first mesh and its first iterations (a hull of a few thousand faces: growing is a round of
  // allocations and copies, most of an iteration's host time on a small hull) and for the points not
  // proven inside P, made while the device finds P's points: none of it needs P, and on the GPU each
  // allocation costs the host microseconds.
  void reserve_first() {
    grow_faces(kInitialFaces);
    grow_entries(kInitialFaces);
    state_.grow(1);
    grow_work(capacity_);
    grow_spares(capacity_);
    index_[1].grow(n_);
  }

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

  // Milliseconds since the last lap, charged to `phase` with the executor's launches and waits since then
  // and `bytes`, the least the phase moved (ResidentStats::phases).
  double lap(ResidentStats& stats, ResidentPhase phase, std::uint64_t bytes = 0) {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - lap_start_).count();
    lap_start_ = now;
    PhaseStat& p = stats.phases[static_cast<int>(phase)];
    p.ms += ms;
    p.bytes += bytes;
    p.launches += exec_.launches - lap_launches_;
    p.host_waits += exec_.host_syncs - lap_waits_;
    lap_launches_ = exec_.launches;
    lap_waits_ = exec_.host_syncs;
    return ms;
  }
  void start_laps(ResidentStats& stats) {
    stats = ResidentStats{};
    lap_start_ = std::chrono::steady_clock::now();
    lap_launches_ = exec_.launches;
    lap_waits_ = exec_.host_syncs;
  }
  // Once the run is over: its total, which its phases add up to (fill_floors() adds the floors).
  void close_laps(ResidentStats& stats) {
    stats.total_ms = 0;
    for (const PhaseStat& p : stats.phases)
      stats.total_ms += p.ms;
  }
  // The mesh's corners and links, read once (refinement, rounds and finish each read at least that).
  std::uint64_t mesh_bytes() const { return std::uint64_t{faces_} * 6 * sizeof(u32); }
  // A routing's least traffic: the kept points' coordinates read, and their index and face read and written.
  std::uint64_t routing_bytes(std::size_t kept) const { return kept * (sizeof(Point) + 4 * sizeof(u32)); }

  MeshView<Point> view() {
    return MeshView<Point>{points_, c_, fv_.data(), fn_.data(), killer_.data(), entries_.data()};
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
    killer_.grow(capacity_, faces_);
    look_.grow(capacity_, faces_);
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

  // One iteration (iteration.hpp), or on a device loop as many as it can run, the host reading the state
  // after each launch; false when no face could refine.  With `out`, every candidate the rounds turn down
  // is logged and what the iteration did is read back into it.
  bool iterate(ResidentStats& stats, RecordedIteration* out = nullptr);

  // A small mesh is sized for every face refining, so that the host need not wait for the refined count
  // between the marks and the split; a larger one waits for it and stays tight in memory.
  static constexpr std::size_t kInitialFaces = std::size_t{1} << 13;
  static constexpr std::size_t kSpeculateFaces = std::size_t{1} << 16;

  // The largest mesh a device loop runs on (one block: past it the grid's launches are faster).
  std::size_t loop_faces() const {
    if constexpr (Exec::kDeviceLoop) {
      return exec_.tuning.loop_faces;
    } else {
      return 0;
    }
  }
  // The largest mesh it runs on with no more points left than faces (loop_goes_on()).
  std::size_t loop_few_points_faces() const {
    if constexpr (Exec::kDeviceLoop) {
      return exec_.tuning.loop_few_points_faces;
    } else {
      return 0;
    }
  }
  // A count as the device's 32 bits, held at the largest (a capacity past it is never reached).
  static u32 u32_of(std::size_t n) { return static_cast<u32>(std::min<std::size_t>(n, 0xffffffffu)); }
  bool loop_goes_on_here() const {
    return loop_goes_on(u32_of(faces_), u32_of(active_), u32_of(loop_faces()),
                        u32_of(loop_few_points_faces()));
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
    b.look = look_.data();
    b.list = work_list_.data();
    b.extreme = extreme_.data();
    b.claim = claim_.data();
    b.cands = cands_.data();
    b.st = state_.data();
    b.first_list = first_list_;
    return b;
  }

  // The phases from..to of the iteration on the executor (`loop`: then whole iterations, in one launch of
  // one block), and one read of the state after them.  The spares are swapped once per compaction, as the
  // launch swapped them; the counters go to the stats.
  template <class Log = NoLog>
  RoundsState run_phases(u32 from, u32 to, bool loop, const Log& log = {}) {
    const IterationLaunch launch{from,
                                 to,
                                 loop ? 0xffffffffu : 1u,
                                 u32_of(faces_),
                                 u32_of(active_),
                                 unkept_listed_ ? 1u : 0u,
                                 u32_of(capacity_),
                                 u32_of(entry_capacity_),
                                 u32_of(work_capacity_),
                                 u32_of(std::min(fv_out_.capacity() / 3, extreme_.capacity())),
                                 u32_of(loop_faces()),
                                 u32_of(loop_few_points_faces()),
                                 0};
    exec_.iterations(iteration_buffers(log), launch, loop);
    RoundsState state{};
    exec_.download(&state, state_.data(), 1);
    if (state.loop_iterations % 2 == 1) swap_spares();
    if (from == kFirst) {
      first_pending_ = false;
      unkept_listed_ = true;
    }
    if (state.loop_iterations > 0) unkept_listed_ = false;
    round_ = state.round;
    return state;
  }
  // A compaction alone: the points the first distribution did not keep, dropped.
  void compact_only() {
    grow_spares(faces_);
    const RoundsState state = run_phases(kCompact, kCompact, false);
    faces_ = state.live_faces;
    active_ = state.kept_points;
  }
  // An iteration that refines no face: the points setup() left in uncompacted are compacted now (all of
  // them may be inside: then the hull is done, not stalled).  False.
  bool no_face_refined() {
    if (unkept_listed_) compact_only();
    return false;
  }

  // The state's counters, which add up over the run, into the stats.
  void take_counters(const RoundsState& state, ResidentStats& stats) {
    stats.rounds = state.rounds;
    stats.edits = state.edits;
    stats.work_items = state.work_items;
    for (int k = 0; k < 4; ++k)
      stats.round_phase_ms[k] = static_cast<double>(state.phase_ns[k]) * 1e-6;
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

  BasicHullMesh<Point> lower_dimensional(ResidentStats& stats, const std::string& why) {
    stats.note = why;
    return exact_hull(all_points());
  }

  // The mesh's faces, read back once.
  std::vector<u32> corners() {
    std::vector<u32> fv(3 * faces_);
    exec_.download(fv.data(), fv_.data(), fv.size());
    return fv;
  }

  // No point left outside: the result, the defects the rounds left repaired where they are first
  // (fault_repair.hpp), with more rings around them while some remain; the exact finish after the last.
  static constexpr std::array<u32, 3> kRepairRings{2, 4, 8};
  BasicHullMesh<Point> finish(ResidentStats& stats) {
    u32 faults = 0;
    bool checked = false;
    for (std::size_t attempt = 0;; ++attempt) {
      std::optional<BasicHullMesh<Point>> out = finish_once(faults, checked);
      if (out) return std::move(*out);
      if (attempt == 0) stats.faults = faults;
      if (active_ != 0 || attempt == kRepairRings.size()) break;
      stats.repaired_patches += repair_faults(kRepairRings[attempt], checked, stats.repair_vertices);
    }
    return exact_finish(
        stats, std::to_string(stats.faults) + " concave edges or vertices not strictly extreme" +
                   (stats.repaired_patches ? ", " + std::to_string(faults) + " left after repair" : ""));
  }

  // The result when no edge is concave and every vertex is strictly extreme (flat edges only triangulate
  // coplanar facets); otherwise nothing, and the defects in `faults`.
  // `checked`: the mesh is known to have none (a repair checked its faces), and is not counted again.
  std::optional<BasicHullMesh<Point>> finish_once(u32& faults, bool checked) {
    if constexpr (Exec::kFinishFaces > 0) {
      if (faces_ <= Exec::kFinishFaces) return finish_small(faults, checked);
    }
    // The edges that are not strictly convex, counted into the state; then the vertices in index order
    // (ascending, as exact_hull gives them) with the corners renumbered to their ranks, where they are.
    // Fewer corners than points (most hulls): the corners sorted without repeats, each corner found there
    // by bisection, and both counts read at once.  Otherwise each vertex flagged among the points and the
    // flags prefix-summed (no sort of a corner list larger than the points).  Only the result comes back.
    RoundsState* st = state_.data();
    exec_.fill(&st->faults, 2, u32{0});
    if (!checked) exec_.for_each(faces_, CountFaults<Point>{view(), &st->faults});
    const std::size_t n = n_, corners = 3 * faces_;
    u32 counts[2] = {0, 0};  // faults, vertices
    const bool sorted = corners < n;
    if (sorted) {
      // The vertex list right after the renumbered corners, so that both come back in one read: fv_out_
      // grown for it (a spare: nothing in it is kept), as the face capacity may be only a little above
      // the faces in use.
      index_[1].grow(corners);
      fv_out_.grow(corners + std::min(corners, n));
      u32* list = fv_out_.data() + corners;
      exec_.sort_unique_to(fv_.data(), corners, list, index_[1].data(), n, &st->vertices);
      exec_.for_each(corners, FindCorners{fv_.data(), list, &st->vertices, fv_out_.data()});
    }
    exec_.download(counts, &st->faults, sorted ? 2 : 1);
    faults = counts[0] == 0 ? 0 : defects();
    if (faults != 0) return std::nullopt;
    if (sorted) {
      std::vector<u32> both(corners + counts[1]);
      exec_.download(both.data(), fv_out_.data(), both.size());
      return result_mesh(both.data(), counts[1], fv_out_.data() + corners);
    }
    keep_.grow(n);
    point_rank_.grow(n);
    index_[1].grow(n);
    exec_.fill(keep_.data(), n, u32{0});
    exec_.for_each(corners, FlagCorners{fv_.data(), keep_.data()});
    counts[1] = exec_.select(keep_.data(), point_rank_.data(), index_[1].data(), n);
    fv_out_.grow(corners);
    exec_.for_each(corners, RenumberCorners{fv_.data(), point_rank_.data(), fv_out_.data()});
    const u32* vertex_list = index_[1].data();
    const u32 vertices = counts[1];
    BasicHullMesh<Point> out;
    out.vertex_ids.resize(vertices);
    exec_.download(out.vertex_ids.data(), vertex_list, vertices);
    out.triangles.resize(faces_);
    static_assert(sizeof(Triangle) == 3 * sizeof(u32));
    exec_.download(reinterpret_cast<u32*>(out.triangles.data()), fv_out_.data(), 3 * faces_);
    out.vertices = vertex_coordinates(out.vertex_ids, vertex_list);
    return out;
  }

  // finish() of a small mesh in one launch and, as a rule, one read (the executor's finish_small): the
  // counts, the renumbered corners and the vertex list lie one after another in fv_out_, and the host reads
  // as many vertices as a closed mesh of genus 0 has (F / 2 + 2, Euler's formula), the rest only if there
  // are more.
  std::optional<BasicHullMesh<Point>> finish_small(u32& faults, bool checked) {
    const std::size_t corners = 3 * faces_, at = 2 + corners;
    // A spare (nothing in it is kept), whose size follows the live faces: room for the counts, the corners
    // and a list of up to as many vertices as corners.
    fv_out_.grow(at + corners);
    u32* out = fv_out_.data();
    exec_.finish_small(view(), faces_, n_, out);
    // (Words past the list, when there are faults or fewer vertices, are read and not used.)
    std::vector<u32> got(at + faces_ / 2 + 2);
    exec_.download(got.data(), out, got.size());
    const u32 vertices = got[1];
    faults = got[0] == 0 || checked ? 0 : defects();
    if (faults != 0) return std::nullopt;
    if (at + vertices > got.size()) {
      const std::size_t had = got.size();
      got.resize(at + vertices);
      exec_.download(got.data() + had, out + had, got.size() - had);
    }
    return result_mesh(got.data() + 2, vertices, out + at);
  }

  // The result from what the finish read back: the renumbered corners (3 a face), then `vertices` vertex
  // ids; the coordinates from the host copy, or gathered from the vertex list at `list` where it is.
  BasicHullMesh<Point> result_mesh(const u32* corners_then_vertices, std::size_t vertices, const u32* list) {
    const std::size_t corners = 3 * faces_;
    BasicHullMesh<Point> out;
    out.vertex_ids.assign(corners_then_vertices + corners, corners_then_vertices + corners + vertices);
    out.triangles.resize(faces_);
    static_assert(sizeof(Triangle) == 3 * sizeof(u32));
    std::copy(corners_then_vertices, corners_then_vertices + corners,
              reinterpret_cast<u32*>(out.triangles.data()));
    out.vertices = vertex_coordinates(out.vertex_ids, list);
    return out;
  }

  // The result's coordinates: from the host copy, or gathered from the vertex list where it is.
  std::vector<Point> vertex_coordinates(const std::vector<PointIndex>& ids, const u32* list) {
    std::vector<Point> out(ids.size());
    if (!host_) {
      gather(list, out);
      return out;
    }
    for (std::size_t k = 0; k < ids.size(); ++k)
      out[k] = (*host_)[ids[k]];
    return out;
  }

  // With edges that are not strictly convex: the concave edges and the thin vertices (CountConcave,
  // CountThin).  None: the others are flat edges inside coplanar facets, and the mesh is the exact hull.
  // The creases and the vertex flags stay in keep_ and point_rank_, and the concave edges' faces are
  // stamped in look_ (free at the finish), for repair_faults().
  u32 defects() {
    const std::size_t n = n_;
    keep_.grow(n);
    point_rank_.grow(n);
    exec_.fill(keep_.data(), n, u32{0});
    exec_.fill(point_rank_.data(), n, u32{0});
    RoundsState* st = state_.data();
    exec_.fill(&st->defects, 1, u32{0});
    exec_.fill(look_.data(), faces_, u32{0});
    exec_.for_each(faces_,
                   CountConcave<Point>{view(), keep_.data(), point_rank_.data(), &st->defects, look_.data()});
    exec_.for_each(n, CountThin{keep_.data(), point_rank_.data(), &st->defects});
    u32 count = 0;
    exec_.download(&count, &st->defects, 1);
    return count;
  }

  // The defects repaired where they are (fault_repair.hpp): the faces within `rings` of one stamped and
  // read back with the ring around them, the host's plan written, the slots left over filled by the last
  // faces.  Returns the patches repaired; `checked`: every patch was, and the new faces passed
  // CheckRepaired (the finish need not count again); the patches' vertices are added to `vertices`.
  static constexpr std::size_t kMaxRepairFaces = std::size_t{1} << 16;
  std::size_t repair_faults(u32 rings, bool& checked, std::uint64_t& vertices) {
    checked = false;
    // The rings in look_ (defects() stamped the concave edges' faces), the stamped faces listed.
    exec_.for_each(faces_,
                   FaultRing{CountThin{keep_.data(), point_rank_.data(), nullptr}, fv_.data(), look_.data()});
    for (u32 ring = 1; ring <= rings; ++ring)
      exec_.for_each(faces_, SpreadStamp{fn_.data(), look_.data(), ring});
    exec_.for_each(faces_, Stamped{look_.data(), flags_.data()});
    work_list_.grow(faces_);
    const u32 stamped = exec_.select(flags_.data(), face_rank_.data(), work_list_.data(), faces_);
    if (stamped > kMaxRepairFaces) return 0;  // flat or cospherical input: the exact finish answers
    const std::vector<FaceRow> rows = face_rows(work_list_.data(), stamped);
    RepairPlan plan =
        plan_repair<Point>(rows, rings, c_, [&](const std::vector<PointIndex>& ids) { return fetch(ids); });
    vertices += plan.vertices;
    if (plan.patches == 0) return 0;
    write_rows(plan.writes);
    fill_holes(plan.holes, plan.repaired);
    if (plan.patches_left == 0) {
      RoundsState* st = state_.data();
      exec_.fill(&st->defects, 1, u32{0});
      exec_.for_each(plan.repaired.size(), CheckRepaired<Point>{view(), listed(plan.repaired), &st->defects});
      u32 left = 0;
      exec_.download(&left, &st->defects, 1);
      checked = left == 0;
    }
    return plan.patches;
  }

  // The rows of the `count` faces listed at `ids` where the executor computes (their rings from look_).
  std::vector<FaceRow> face_rows(const u32* ids, std::size_t count) {
    std::vector<FaceRow> rows(count);
    repair_rows_.grow(count);
    exec_.for_each(count, GatherRows{ids, fv_.data(), fn_.data(), look_.data(), repair_rows_.data()});
    exec_.download(rows.data(), repair_rows_.data(), count);
    return rows;
  }
  std::vector<FaceRow> face_rows(const std::vector<u32>& ids) { return face_rows(listed(ids), ids.size()); }
  void write_rows(const std::vector<FaceRow>& rows) {
    repair_rows_.grow(rows.size());
    exec_.upload(repair_rows_.data(), rows.data(), rows.size());
    exec_.for_each(rows.size(), WriteRows{repair_rows_.data(), fv_.data(), fn_.data(), killer_.data()});
  }

  // The slots a repair left over (`holes`, ascending) filled by the mesh's last faces, their neighbours
  // relinked, so that the faces are 0..F-1 again; `renumber` (face ids) follows the moves.
  void fill_holes(const std::vector<u32>& holes, std::vector<u32>& renumber) {
    const std::size_t live = faces_ - holes.size();
    std::vector<u32> movers, targets;
    for (std::size_t f = live; f < faces_; ++f) {
      if (!std::binary_search(holes.begin(), holes.end(), static_cast<u32>(f)))
        movers.push_back(static_cast<u32>(f));
    }
    for (const u32 h : holes) {
      if (h < live) targets.push_back(h);
    }
    faces_ = live;
    if (movers.empty()) return;
    std::unordered_map<u32, u32> to;
    for (std::size_t k = 0; k < movers.size(); ++k)
      to.emplace(movers[k], targets[k]);
    auto moved = [&](u32& f) {
      const auto it = to.find(f);
      if (it != to.end()) f = it->second;
    };
    std::vector<FaceRow> rows = face_rows(movers);
    std::vector<u32> around;
    for (const FaceRow& row : rows) {
      for (const u32 nb : row.n) {
        if (!to.count(nb)) around.push_back(nb);
      }
    }
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    for (std::size_t k = 0; k < rows.size(); ++k)
      rows[k].id = targets[k];
    for (const FaceRow& row : face_rows(around))
      rows.push_back(row);
    for (FaceRow& row : rows) {
      for (u32& nb : row.n)
        moved(nb);
    }
    write_rows(rows);
    for (u32& f : renumber)
      moved(f);
  }

  // The exact reference hull of the mesh's vertices and the points still outside (see the design).
  BasicHullMesh<Point> exact_finish(ResidentStats& stats, const std::string& why) {
    stats.note = why;
    stats.exact_finish = true;
    std::vector<PointIndex> candidates = corners();
    const std::size_t mesh_part = candidates.size();
    candidates.resize(mesh_part + active_);
    exec_.download(candidates.data() + mesh_part, index_[0].data(), active_);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    return hull_of(candidates, host_ ? std::vector<Point>{} : fetch(candidates));
  }

  // step()'s log of the rounds: the candidates turned down, and each round's first entry.
  Buffer<Rejection> rejections_;
  Buffer<u32> rejection_count_, round_first_entry_;
  u32 rejection_capacity_ = 0, round_capacity_ = 0;

  Exec& exec_;
  const std::vector<Point>* host_;  // null: the points are only where the executor computes
  const Point* points_;
  std::size_t n_;
  std::vector<Point> read_back_;  // all_points() without a host copy
  std::uint64_t points_read_back_ = 0;
  Buffer<u32> gather_ids_;
  Buffer<Point> gathered_;
  std::chrono::steady_clock::time_point lap_start_;
  std::uint64_t lap_launches_ = 0, lap_waits_ = 0;  // the executor's counts at the last lap
  Vec3d c_{};
  double max_coordinate_ = 0;        // every point's coordinates are at most this in size
  bool first_pending_ = false;       // the first distribution (kFirst) is the next launch's
  const u32* first_list_ = nullptr;  // the points it distributes (NotInsideP), or null for all
  bool unkept_listed_ = false;       // the points the first distribution did not keep are still listed
  std::size_t marks_in_use_ = 0;     // entries of flags_ and face_rank_ that grow_faces() keeps
  std::size_t faces_ = 0, capacity_ = 0, entries_used_ = 0, entry_capacity_ = 0, active_ = 0;
  std::size_t work_capacity_ = 0;  // work faces a round has room for (cands_, work_list_)
  u32 round_ = 0;
  Buffer<u32> fv_, fn_, fv_out_, fn_out_, killer_, look_, flags_, face_rank_;
  Buffer<u64> claim_, extreme_;
  Buffer<RoundsState> state_;  // the counts where the executor computes (see RoundsState)
  Buffer<Entry> entries_;
  Buffer<u32> work_list_;        // the rounds' work faces (and the repair's stamped faces)
  Buffer<FaceRow> repair_rows_;  // the repair's rows, read back and written (repair_faults())
  Buffer<Candidate> cands_;      // the rounds' candidates, per work item
  Buffer<u32> index_[2], face_of_[2], keep_, point_rank_;
};

template <class Point, class Exec>
bool ResidentHull<Point, Exec>::iterate(ResidentStats& stats, RecordedIteration* out) {
  // Few points left: the device loop runs whole iterations in one launch until they are done.
  // A small mesh is sized as if every face refined: its launches need no wait for the refined count, and
  // with few points left a device loop (one block) runs its iterations.  A large one is sized by the
  // count, and waits for it.
  const bool small = faces_ <= kSpeculateFaces;
  bool loop = false;
  if constexpr (Exec::kDeviceLoop) loop = !out && loop_goes_on_here() && active_ <= exec_.tuning.loop_points;
  const bool wait_for_refined = out || !small;
  if (!wait_for_refined) grow_for_iteration(loop ? 2 * faces_ : faces_, true, loop);
  if (out) {
    *out = RecordedIteration{};
    out->faces_before = faces_;
    // The rounds' rejections (a face may meet the same one in several rounds: all are kept here, in order,
    // and the records keep the first), with each round's first entry; a log without room for a round
    // stops it before it begins, and the host grows the log.
    rejection_capacity_ = static_cast<u32>(std::max<std::size_t>(4096, 2 * faces_));
    rejections_.grow(rejection_capacity_);
    rejection_count_.grow(1);
    exec_.fill(rejection_count_.data(), 1, u32{0});
    round_capacity_ = 64;
    round_first_entry_.grow(round_capacity_);
  }
  lap(stats, ResidentPhase::kHost);
  u32 from = first_pending_ ? kFirst : kFurthest;
  std::size_t face_ids = 0;
  while (true) {
    // Waiting for the refined count, the launch stops after the marks; recording, after the rounds too.
    u32 to = kCompact;
    if (wait_for_refined && from <= kFurthest) {
      to = kFurthest;
    } else if (out && from <= kRounds) {
      to = kRounds;
    }
    RoundsState state{};
    if (out && from <= kRounds && to >= kRounds) {
      state = run_phases(from, to, loop,
                         RejectionLog{rejections_.data(), rejection_count_.data(), rejection_capacity_, 0,
                                      round_first_entry_.data(), out->first_round, round_capacity_});
    } else {
      state = run_phases(from, to, loop);
    }
    const ResidentPhase phase = to == kFurthest ? ResidentPhase::kRefine
                                : to == kRounds ? ResidentPhase::kRounds
                                                : ResidentPhase::kRoute;
    const std::uint64_t bytes = phase == ResidentPhase::kRoute ? routing_bytes(active_) : mesh_bytes();
    (to == kFurthest ? stats.refine_ms
     : to == kRounds ? stats.rounds_ms
                     : stats.route_ms) += lap(stats, phase, bytes);
    take_counters(state, stats);
    stats.iterations += state.loop_iterations;
    stats.loop_iterations += loop ? state.loop_iterations : 0;
    stats.refined_faces += state.loop_refined;
    active_ = state.kept_points;
    if (state.loop_exit == kExitStall) {
      faces_ = state.live_faces;
      return no_face_refined();
    }
    if (state.loop_exit == kExitOverflow) {
      // Mid-rounds: the host grows what was short, and the rounds go on.
      grow_after_overflow(state, stats);
      if (out && state.needed_rejections > rejection_capacity_) {
        const std::size_t room = 2 * std::size_t{state.needed_rejections};
        if (room > 0xffffffffu) throw DeviceError("resident engine: too many rejections to record");
        rejections_.grow(room, rejection_capacity_);
        rejection_capacity_ = static_cast<u32>(room);
      }
      if (out && state.needed_rounds > round_capacity_) {
        round_first_entry_.grow(2 * std::size_t{state.needed_rounds}, round_capacity_);
        round_capacity_ = 2 * state.needed_rounds;
      }
      from = kRounds;
      continue;
    }
    if (state.loop_exit == kExitRoom || (to == kFurthest && state.loop_exit == kExitDone && active_ > 0)) {
      // The marks are made and the refined count known: room for the split and the rounds.
      faces_ = state.live_faces;
      if (out) {
        out->refined = state.refined;
        out->first_round = round_ + 1;
      }
      // A device loop whose mesh grew past its limit hands the iteration to the grid's launches.
      loop = loop && loop_goes_on_here();
      if (loop) {
        grow_for_iteration(2 * faces_, true, true);
      } else {
        grow_for_iteration(state.refined);
      }
      from = kSplit;
      continue;
    }
    if (to == kRounds) {
      // Recording: the iteration's faces, entries and log, read back before the routing.
      faces_ = state.faces;
      entries_used_ = state.entries;
      face_ids = faces_;
      out->fv.resize(3 * faces_);
      out->killer.resize(faces_);
      out->entries.resize(entries_used_);
      exec_.download(out->fv.data(), fv_.data(), out->fv.size());
      exec_.download(out->killer.data(), killer_.data(), out->killer.size());
      exec_.download(out->entries.data(), entries_.data(), out->entries.size());
      out->round_first_entry.resize(round_ + 1 - out->first_round);
      exec_.download(out->round_first_entry.data(), round_first_entry_.data(), out->round_first_entry.size());
      u32 rejected = 0;
      exec_.download(&rejected, rejection_count_.data(), 1);
      out->rejections.resize(rejected);  // all of them: every round had room
      exec_.download(out->rejections.data(), rejections_.data(), out->rejections.size());
      // The log is filled by atomics in any order: by round, then candidate, the same on every executor.
      std::sort(out->rejections.begin(), out->rejections.end(), [](const Rejection& a, const Rejection& b) {
        return a.round != b.round ? a.round < b.round : a.id != b.id ? a.id < b.id : a.kind < b.kind;
      });
      from = kRoute;
      continue;
    }
    faces_ = state.live_faces;
    shrink_points();
    break;
  }
  if (out) {
    out->new_id.resize(face_ids);
    exec_.download(out->new_id.data(), face_rank_.data(), face_ids);
  }
  return true;
}

}  // namespace cudahull::resident
