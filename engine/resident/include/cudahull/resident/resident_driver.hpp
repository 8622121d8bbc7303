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
#include <string>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/mesh.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/resident/first_mesh.hpp"
#include "cudahull/resident/iteration.hpp"
#include "cudahull/resident/resident_buffers.hpp"
#include "cudahull/resident/resident_finish.hpp"
#include "cudahull/resident/resident_ops.hpp"
#include "cudahull/resident/resident_recording.hpp"
#include "cudahull/resident/shared_phases.hpp"

namespace cudahull::resident {

template <class Point, class Exec>
class ResidentHull : private ResidentFinish<Point, Exec> {
  // Its state and buffers (resident_buffers.hpp) and its finish (resident_finish.hpp); the stepper's
  // recorder (resident_recording.hpp) records a step.
  using Buffers = ResidentBuffers<Point, Exec>;
  using Finish = ResidentFinish<Point, Exec>;
  using Buffers::active_, Buffers::all_points, Buffers::c_, Buffers::capacity_, Buffers::entries_used_,
      Buffers::entry_capacity_, Buffers::exec_, Buffers::extreme_, Buffers::face_of_, Buffers::face_rank_,
      Buffers::faces_, Buffers::fetch, Buffers::first_list_, Buffers::first_mesh, Buffers::flags_,
      Buffers::fn_, Buffers::fv_, Buffers::fv_out_, Buffers::grow_after_overflow, Buffers::grow_entries,
      Buffers::grow_faces, Buffers::grow_for_iteration, Buffers::grow_spares, Buffers::grow_work,
      Buffers::hull_of, Buffers::index_, Buffers::iteration_buffers, Buffers::keep_, Buffers::listed,
      Buffers::n_, Buffers::point_rank_, Buffers::points_, Buffers::points_read_back_,
      Buffers::release_rounds, Buffers::shrink_points, Buffers::state_, Buffers::swap_spares, Buffers::view,
      Buffers::work_capacity_;
  using Finish::exact_finish, Finish::finish;

 public:
  // `count` points live at `points`, where the executor computes (the host vector itself for HostExec, a
  // device copy or the caller's device array for CudaExec).  `host_points`, when given, is the same data on
  // the host, where the exact checks read.  Without it (points only the executor holds, e.g. a CuPy array)
  // the driver reads back the few coordinates it checks: P's 14 points, the result's vertices, the exact
  // finish's candidates; every point only for section 3.1's tetrahedron or lower-dimensional input.
  ResidentHull(Exec& exec, const Point* points, std::size_t count, const std::vector<Point>* host_points)
      : Finish(exec, points, count, host_points) {}

  BasicHullMesh<Point> run(ResidentStats& stats) {
    BasicHullMesh<Point> hull = run_all(stats);
    stats.points_read_back = points_read_back_;
    return hull;
  }

  // Stepping with records (resident_stepping.hpp: the viewer, --trace, --table).  The same iterations as
  // run(), one per step(), the rounds stepped by the host (the mesh is the fused rounds' own, which the tests
  // check edit for edit), and what each did read back by `recorder` (RecordedIteration): O(faces) bytes a
  // step, asked for.
  // begin(): P, the first mesh and the first distribution; false when that is already the answer (no points,
  // lower-dimensional input), then in `done`.
  bool begin(ResidentStats& stats, BasicHullMesh<Point>& done) {
    start_laps(stats);
    if (setup(stats, done, true)) return true;
    close_laps(stats);
    return false;
  }
  // One iteration, recorded; false when no face could refine (a stall: end(stats, true) finishes exactly).
  bool step(ResidentStats& stats, IterationRecorder<Point, Exec>& recorder) {
    return iterate(stats, recorder);
  }
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
      Unrecorded plain;
      if (!iterate(stats, plain)) {
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
    exec_.for_each(fv.size(), first_mesh(fv, fn));
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

  // One iteration (iteration.hpp), or on a device loop as many as it can run, the host reading the state
  // after each launch; false when no face could refine.  `recording` is Unrecorded (run()) or the stepper's
  // IterationRecorder (step()): then every candidate the rounds turn down is logged and what the iteration
  // did is read back.
  template <class Recording>
  bool iterate(ResidentStats& stats, Recording& recording);

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

  BasicHullMesh<Point> lower_dimensional(ResidentStats& stats, const std::string& why) {
    stats.note = why;
    return exact_hull(all_points());
  }

  std::chrono::steady_clock::time_point lap_start_;
  std::uint64_t lap_launches_ = 0, lap_waits_ = 0;  // the executor's counts at the last lap
  double max_coordinate_ = 0;                       // every point's coordinates are at most this in size
  bool first_pending_ = false;                      // the first distribution (kFirst) is the next launch's
  bool unkept_listed_ = false;  // the points the first distribution did not keep are still listed
  u32 round_ = 0;
};

template <class Point, class Exec>
template <class Recording>
bool ResidentHull<Point, Exec>::iterate(ResidentStats& stats, Recording& recording) {
  // Few points left: the device loop runs whole iterations in one launch until they are done.
  // A small mesh is sized as if every face refined: its launches need no wait for the refined count, and
  // with few points left a device loop (one block) runs its iterations.  A large one is sized by the
  // count, and waits for it.  A recorded iteration waits for it too, and stops after the rounds to read them.
  constexpr bool records = Recording::kRecords;
  const bool small = faces_ <= kSpeculateFaces;
  bool loop = false;
  if constexpr (Exec::kDeviceLoop)
    loop = !records && loop_goes_on_here() && active_ <= exec_.tuning.loop_points;
  const bool wait_for_refined = records || !small;
  if (!wait_for_refined) grow_for_iteration(loop ? 2 * faces_ : faces_, true, loop);
  recording.begin(exec_, faces_);
  lap(stats, ResidentPhase::kHost);
  u32 from = first_pending_ ? kFirst : kFurthest;
  std::size_t face_ids = 0;
  while (true) {
    // Waiting for the refined count, the launch stops after the marks; recording, after the rounds too.
    u32 to = kCompact;
    if (wait_for_refined && from <= kFurthest) {
      to = kFurthest;
    } else if (records && from <= kRounds) {
      to = kRounds;
    }
    const RoundsState state = run_phases(from, to, loop, recording.log());
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
      recording.grow_log(exec_, state);
      from = kRounds;
      continue;
    }
    if (state.loop_exit == kExitRoom || (to == kFurthest && state.loop_exit == kExitDone && active_ > 0)) {
      // The marks are made and the refined count known: room for the split and the rounds.
      faces_ = state.live_faces;
      recording.refined(state.refined, round_ + 1);
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
      recording.read_rounds(exec_, view(), faces_, entries_used_, round_);
      from = kRoute;
      continue;
    }
    faces_ = state.live_faces;
    shrink_points();
    break;
  }
  recording.end(exec_, face_rank_.data(), face_ids);
  return true;
}

}  // namespace cudahull::resident
