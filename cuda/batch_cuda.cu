// Batched hulls on the device (batch_cuda.hpp).
//
// design:
//   the clouds the kernel takes: 4 .. BatchTuning::block_points points (cudahull/tuning.hpp; fewer: the
//     single-cloud path's lower-dimensional answer; more: the single-cloud path's grid, which a large cloud
//     fills better)
//   teams: a cloud of at most warp_points points on a warp, a furthest point at a time (resident::
//     small_hull(), QuickHull's own step: a short loop, which many warps run from the instruction cache at
//     once); a cloud of more than large_block_points points on a block of kLargeThreads (its points' phases
//     are the work), the rest on a block of kThreads (a small hull's phases have a few dozen items: the
//     latency of its barriers, not the threads, sets its time), five blocks an SM, or four for clouds of
//     more than mid_block_points; the resident engine's iteration on each block (resident::batch_hull())
//   pass 1: a launch a kind of team, as many blocks as fit at once, each team with a slot of face room for
//     the largest hull its launch expects (batch_vertices(); a warp's: every point); a team takes clouds one
//     after another from a counter (a large one does not hold the others up).  Per point, the iteration's own
//     arrays (six words) at the cloud's place in the packed points
//   pass 2: the clouds a block had no room for, on blocks with room for every point a vertex (up to
//     kSecondPassPoints points; larger ones take the single-cloud path)
//   pass 3: the clouds a block sent to the single-cloud path (a stall, or a defect the rounds left on
//     coplanar facets), up to kRetryOnWarpPoints points, on warps
//   read back: the clouds that did not end alone (listed on the device, with their status), for the later
//     passes and the single-cloud path; the hulls and their sizes stay on the device (BatchRun's outputs)
//   the offsets (lay_out_batch_offsets()): each done cloud's sizes written from its pass's results, the
//     hosted clouds' from the host, a prefix sum a column; the totals alone read back (a host loop over
//     every cloud's result was a sixth of a batch's time)
//   describe (describe_batch_cuda()): a warp a done cloud, into the packed result's columns at the offsets
//     the caller laid out: vertex ids, faces on the cloud's indices, planes (a lane a face), the volume and
//     area (a lane a face's terms, added face after face in the mesh's order, as convex_hull() sums them
//     on the host)
//
// This file: the passes (run_pass()) and the run (batch_run_cuda()); a pass's kernels in
// batch_pass_kernels.cuh, the offsets in batch_offsets.cu, the describe in batch_describe.cu.
#include <cuda_runtime.h>

#include <algorithm>
#include <memory>
#include <type_traits>
#include <vector>

#include "batch_pass_kernels.cuh"
#include "batch_shared.cuh"
#include "cudahull/cuda/batch_cuda.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/phase_times.hpp"

namespace cudahull {
namespace {

constexpr u32 kSecondPassPoints = 16384;  // the largest cloud the second launch takes
// Which clouds take which kind of team (a warp, a block of four or five an SM, a large block): BatchTuning
// (cudahull/tuning.hpp), whose defaults docs/benchmarks.md, "Tuning (ResidentTuning, BatchTuning)", explains.
// The clouds of at most this many points that a block sent to the single-cloud path take a warp first
// (small_hull(), with room for every point), hundreds of times quicker than the single-cloud path, one
// cloud after another (docs/benchmarks.md, "The measurements behind the code's constants").
constexpr u32 kRetryOnWarpPoints = 4096;
// The largest cloud a team can take: a block's room, batch_room(), counts its face slots in 32 bits.
constexpr std::size_t kMaxBlockPoints = std::size_t{1} << 20;

// Milliseconds of the default stream's work between construction and stop() (CUDA events).
class EventTimer {
 public:
  EventTimer() {
    check(cudaEventCreate(&events_[0]), "timing the batch");
    check(cudaEventCreate(&events_[1]), "timing the batch");
    cudaEventRecord(events_[0], 0);
  }
  EventTimer(const EventTimer&) = delete;
  EventTimer& operator=(const EventTimer&) = delete;
  ~EventTimer() {
    cudaEventDestroy(events_[0]);
    cudaEventDestroy(events_[1]);
  }
  void stop() const { cudaEventRecord(events_[1], 0); }
  // After the stop's work has finished (a synchronising copy or call).
  double ms() const {
    float ms = 0;
    cudaEventElapsedTime(&ms, events_[0], events_[1]);
    return ms;
  }

 private:
  cudaEvent_t events_[2];
};

// The batch's device arrays (device_memory.hpp, on the default stream), given back with their owner, and
// the bytes held at once counted (`held`, `peak`: the batch's, across its passes).
class BatchMemory {
 public:
  BatchMemory(std::size_t& held, std::size_t& peak) : held_(held), peak_(peak) {}
  BatchMemory(const BatchMemory&) = delete;
  BatchMemory& operator=(const BatchMemory&) = delete;
  ~BatchMemory() {
    for (const DeviceBlock& block : blocks_) {
      give_device_block(block, 0);
      held_ -= block.bytes;
    }
  }
  template <class T>
  T* take(std::size_t n, const char* what) {
    const DeviceBlock block = take_device_block(std::max<std::size_t>(n, 1) * sizeof(T), 0, kWho, what);
    blocks_.push_back(block);
    held_ += block.bytes;
    peak_ = std::max(peak_, held_);
    return static_cast<T*>(block.ptr);
  }

 private:
  std::vector<DeviceBlock> blocks_;
  std::size_t &held_, &peak_;
};

// A pass's clouds, in cloud order: listed, or (`every`) all the batch's clouds 0 .. count - 1, which the
// host never lists (a list of every cloud, written to fresh pages and uploaded, costs host time).
struct CloudList {
  std::vector<u32> listed;
  bool every = false;
  std::size_t count = 0;
  std::size_t points = 0;  // the largest cloud's
  u32 operator[](std::size_t k) const { return every ? static_cast<u32>(k) : listed[k]; }
  std::size_t size() const { return every ? count : listed.size(); }
};

// One pass over the listed clouds (ids into `offsets`), each with room for a hull of `vertices` vertices;
// the hulls and results kept on the device in `run.outputs`.  Returns the clouds that did not end, by
// their index in the list.
template <TeamKind kKind, class Point>
std::vector<Unfinished> run_pass(const Point* points, std::size_t count, const std::size_t* device_offsets,
                                 const CloudList& listed, u32 vertices, std::size_t word_room,
                                 std::size_t coordinate_room, BatchRun<Point>& run, std::size_t& held) {
  PhaseLaps laps(kKind == TeamKind::kWarp ? "batch pass on warps" : "batch pass on blocks");
  BatchMemory memory(held, run.device_bytes);
  constexpr int kBlock = kBlockThreads<kKind>;
  constexpr u32 kTeams = kTeamsPerBlock<kKind>;
  void (*kernel)(PassArgs<Point>) = pass_kernel<kKind, Point>(listed.points <= kStagedWarpPoints);
  // A slot a team, for every team of the blocks launched.
  const u32 blocks = static_cast<u32>(std::min<std::size_t>((listed.size() + kTeams - 1) / kTeams,
                                                            resident::blocks_that_fit(kernel, kBlock, kWho)));
  const u32 slots = blocks * kTeams;

  // What the pass leaves for the describe: its hulls, its results and its cloud list.
  auto output = std::make_shared<typename BatchRun<Point>::PassOutput>();
  static_assert(sizeof(BatchResult) == 5 * sizeof(u32));
  const std::size_t result_words = 5 * listed.size();
  output->words = DeviceArray<u32>(word_room, kWho, "the hulls' words");
  output->coordinates = DeviceArray<Point>(coordinate_room, kWho, "the hulls' vertices");
  // The results, then the counter of clouds taken, the two of output taken and the unfinished clouds'.
  output->results = DeviceArray<u32>(result_words + 4, kWho, "the results");
  output->clouds = DeviceArray<u32>(listed.size(), kWho, "the cloud list");
  output->listed = static_cast<u32>(listed.size());
  const std::size_t kept = output->words.block_bytes() + output->coordinates.block_bytes() +
                           output->results.block_bytes() + output->clouds.block_bytes();
  run.kept_bytes += kept;
  held += kept;
  run.device_bytes = std::max(run.device_bytes, held);

  PassArgs<Point> a{};
  a.points = points;
  a.offsets = device_offsets;
  a.count = static_cast<u32>(listed.size());
  a.points_total = static_cast<u32>(count);
  const BatchRoom room =
      kKind == TeamKind::kWarp ? resident::small_hull_room(vertices) : resident::batch_room(vertices);
  BatchSlot& s = a.slot;
  s.room = room;
  const std::size_t f = std::size_t{slots} * room.faces, words = std::size_t{slots} * (room.faces / 32 + 1);
  s.fv = memory.take<u32>(3 * f, "the faces");
  s.fn = memory.take<u32>(3 * f, "the faces' links");
  s.fv_spare = memory.take<u32>(3 * f, "the compaction's faces");
  s.fn_spare = memory.take<u32>(3 * f, "the compaction's links");
  s.replaced_by = memory.take<u32>(f, "the faces' replacing entries");
  s.revisit = memory.take<u32>(f, "the faces' revisit rounds");
  s.flags = memory.take<u32>(f + slots, "the faces' marks");
  s.face_rank = memory.take<u32>(f + slots, "the marks' ranks");
  s.win_mask = memory.take<u32>(words, "the rounds' wins");
  s.word_rank = memory.take<u32>(words, "the rounds' win ranks");
  s.extreme = memory.take<u64>(f, "the furthest points");
  s.claim = memory.take<u64>(f, "the claims");
  s.entries = memory.take<resident::Entry>(std::size_t{slots} * room.entries, "the decision entries");
  s.list = memory.take<u32>(std::size_t{slots} * room.work, "the rounds' work");
  s.cands = memory.take<resident::Candidate>(std::size_t{slots} * room.work, "the rounds' candidates");
  a.point_words = memory.take<u32>(6 * count, "the points' marks");
  a.out.words = output->words.get();
  a.out.coordinates = output->coordinates.get();
  a.out.word_capacity = static_cast<u32>(word_room);
  a.out.coordinate_capacity = static_cast<u32>(coordinate_room);
  a.results = reinterpret_cast<BatchResult*>(output->results.get());
  a.next = output->results.get() + result_words;
  a.out.used = a.next + 1;
  a.clouds = output->clouds.get();
  if (listed.every) {
    every_cloud_kernel<<<list_blocks(listed.size()), kListThreads>>>(output->clouds.get(), a.count);
    check(cudaGetLastError(), "listing the clouds");
  } else {
    check(cudaMemcpyAsync(output->clouds.get(), listed.listed.data(), listed.size() * sizeof(u32),
                          cudaMemcpyHostToDevice, 0),
          "uploading the cloud list");
  }
  u32* unfinished_count = a.next + 3;
  Unfinished* unfinished = memory.take<Unfinished>(listed.size(), "the unfinished clouds");
  check(cudaMemsetAsync(a.next, 0, 4 * sizeof(u32), 0), "clearing the counters");
  if (laps.wanted()) cudaDeviceSynchronize();
  laps.lap("arrays");
  const EventTimer timer;
  kernel<<<blocks, kBlock>>>(a);
  check(cudaGetLastError(), "launching the batch");
  timer.stop();
  list_unfinished_kernel<<<list_blocks(listed.size()), kListThreads>>>(a.results, a.count, unfinished_count,
                                                                       unfinished);
  check(cudaGetLastError(), "listing the unfinished clouds");
  u32 unfinished_clouds = 0;
  check(cudaMemcpy(&unfinished_clouds, unfinished_count, sizeof(u32), cudaMemcpyDeviceToHost),
        "reading the results (kernel fault)");
  std::vector<Unfinished> left(unfinished_clouds);
  if (!left.empty())
    check(cudaMemcpy(left.data(), unfinished, left.size() * sizeof(Unfinished), cudaMemcpyDeviceToHost),
          "reading the unfinished clouds");
  // In list order, whatever order the device listed them in: the later passes' lists are the same each run.
  std::sort(left.begin(), left.end(), [](const Unfinished& x, const Unfinished& y) { return x.k < y.k; });
  laps.lap("kernel and results");
  run.kernel_ms += timer.ms();
  if (listed.every)
    std::fill(run.done.begin(), run.done.end(), 1);
  else
    for (const u32 c : listed.listed)
      run.done[c] = 1;
  for (const Unfinished& u : left)
    run.done[listed[u.k]] = 0;
  run.clouds_done += listed.size() - left.size();
  run.outputs.push_back(std::move(output));
  ++run.passes;
  laps.lap("results kept");
  return left;
}

}  // namespace

template <class Point>
BatchRun<Point> batch_run_cuda(const Point* device_points, std::size_t count, const std::size_t* offsets,
                               std::size_t clouds, const std::uint8_t* skip, const BatchTuning& tuning) {
  PhaseLaps laps("batch run");
  BatchRun<Point> run(clouds);
  // Indices are 32 bits on the device: a larger batch takes the single-cloud path cloud by cloud.
  if (count >= 0xffffffffu / 8 || clouds >= 0xffffffffu / 8) return run;
  const std::size_t largest = std::min(tuning.block_points, kMaxBlockPoints);
  // Pass 1's clouds by the kind of block that takes them (TeamKind), each group with room for its
  // largest hull.
  struct Group {
    CloudList clouds;
    u32 vertices = 0;
    std::size_t word_room = 0, coordinate_room = 0;
    void count(u32 v, std::size_t n) {
      ++clouds.count;
      clouds.points = std::max(clouds.points, n);
      vertices = std::max(vertices, v);
      word_room += 7 * std::size_t{v};  // 2 v faces of 3 corners, and v vertices
      coordinate_room += v;
    }
    void add(u32 c, u32 v, std::size_t n) {
      clouds.listed.push_back(c);
      count(v, n);
    }
    // `all` clouds of at most n points, the largest room v, the rooms' sum `rooms`.
    void count_all(std::size_t all, u32 v, std::size_t n, std::size_t rooms) {
      clouds.count = all;
      clouds.points = n;
      vertices = v;
      word_room = 7 * rooms;
      coordinate_room = rooms;
    }
  };
  Group groups[4];  // TeamKind's order
  const std::size_t large_points = tuning.large_block_points;
  const std::size_t mid_points = tuning.mid_block_points;
  // Above kRetryOnWarpPoints a warp's steps are too long (and its pairs of points and faces past 32 bits).
  const std::size_t warp_points = std::min<std::size_t>(tuning.warp_points, kRetryOnWarpPoints);
  // The kind of team for a cloud of n points (-1: none, the single-cloud path's): one interval of sizes a
  // kind.  Cloud c's, unless `skip` sends it to the single-cloud path.
  const auto kind_of_size = [&](std::size_t n) {
    if (n < 4 || n > largest) return -1;
    return n <= warp_points ? 0 : n > large_points ? 3 : n > mid_points ? 2 : 1;
  };
  const auto kind_of = [&](std::size_t c) {
    return skip && skip[c] ? -1 : kind_of_size(offsets[c + 1] - offsets[c]);
  };
  // A warp's cloud has room for every point a vertex at once (7 n words of output, where a block's clouds
  // have 7 batch_vertices(n): 0.96 of that at 100 points, 0.56 at 256; and small_hull_room(n), a third of a
  // block's slot): a sphere's hull needs no second pass.
  const auto room_of = [&](std::size_t c, int kind) {
    return resident::batch_vertices(static_cast<u32>(offsets[c + 1] - offsets[c]), kind == 0);
  };
  // The groups counted first: where one kind takes every cloud, none is listed.  Where the sizes' range
  // falls to one kind, its group is counted at once from the range and the points' sum (a warp's room is
  // its point count; a block's is the same for one size): a host loop over every cloud's kind and room is
  // what a batch of small clouds can least afford (docs/benchmarks.md, "The measurements behind the code's
  // constants").
  std::size_t smallest = clouds != 0 ? offsets[1] - offsets[0] : 0, biggest = smallest;
  for (std::size_t c = 1; c < clouds; ++c) {
    const std::size_t n = offsets[c + 1] - offsets[c];
    smallest = std::min(smallest, n);
    biggest = std::max(biggest, n);
  }
  const int one_kind = clouds != 0 && skip == nullptr && kind_of_size(smallest) == kind_of_size(biggest)
                           ? kind_of_size(smallest)
                           : -1;
  if (one_kind == 0) {
    groups[0].count_all(clouds, static_cast<u32>(biggest), biggest, offsets[clouds] - offsets[0]);
  } else if (one_kind > 0 && smallest == biggest) {
    const u32 room = room_of(0, one_kind);
    groups[one_kind].count_all(clouds, room, biggest, std::size_t{room} * clouds);
  } else {
    for (std::size_t c = 0; c < clouds; ++c)
      if (const int kind = kind_of(c); kind >= 0)
        groups[kind].count(room_of(c, kind), offsets[c + 1] - offsets[c]);
  }
  bool any = false;
  for (Group& group : groups) {
    group.clouds.every = group.clouds.count == clouds;
    any = any || group.clouds.count != 0;
  }
  if (!any) return run;
  if (std::none_of(std::begin(groups), std::end(groups), [](const Group& g) { return g.clouds.every; })) {
    for (Group& group : groups)
      group.clouds.listed.reserve(group.clouds.count);
    for (std::size_t c = 0; c < clouds; ++c)  // counted and sized above: listed alone
      if (const int kind = kind_of(c); kind >= 0) groups[kind].clouds.listed.push_back(static_cast<u32>(c));
  }
  laps.lap("groups");

  // After the arrays below: what the pool holds beyond a kBatchKeepShare of the device's memory, back to
  // the driver.
  TrimPoolAtEnd trim(batch_pool_keep());
  std::size_t held = 0;
  BatchMemory memory(held, run.device_bytes);
  // The offsets as the caller gave them (the kernels read them as 32 bits: the count is below 2^32).
  auto* device_offsets = memory.take<std::size_t>(clouds + 1, "the offsets");
  check(cudaMemcpy(device_offsets, offsets, (clouds + 1) * sizeof(std::size_t), cudaMemcpyHostToDevice),
        "uploading the offsets");
  laps.lap("offsets up");
  Group again, on_warps;  // the later passes' clouds: on blocks, with room for every point; on warps
  const auto pass = [&](auto kind, const Group& group) {
    return run_pass<decltype(kind)::value>(device_points, count, device_offsets, group.clouds, group.vertices,
                                           group.word_room, group.coordinate_room, run, held);
  };
  // A pass, and where a block's clouds that did not end go next (room: from a first pass only).  A warp's
  // cloud goes nowhere else: it had room for every point, and its other endings are the single path's.
  const auto pass_and_route = [&](auto kind, const Group& group, bool first) {
    if (group.clouds.size() == 0) return;
    const std::vector<Unfinished> left = pass(kind, group);
    if constexpr (decltype(kind)::value != TeamKind::kWarp) {
      for (const Unfinished& u : left) {
        const u32 c = group.clouds[u.k], n = static_cast<u32>(offsets[c + 1] - offsets[c]);
        if (u.status == resident::kBatchRoom) {
          // Room for every point a vertex costs a slot some 900 bytes a point: a larger cloud takes the
          // single-cloud path, which grows its room as it goes.
          if (first && n <= kSecondPassPoints) again.add(c, n, n);
        } else if (u.status == resident::kBatchSingle && warp_points != 0 && n <= kRetryOnWarpPoints) {
          // A block's stall or defect (coplanar facets the rounds cannot finish: integer grids, cylinders)
          // is no obstacle to small_hull(): the warps take it before the single-cloud path would.
          on_warps.add(c, n, n);
        }
      }
    }
  };
  pass_and_route(std::integral_constant<TeamKind, TeamKind::kWarp>{}, groups[0], true);
  pass_and_route(std::integral_constant<TeamKind, TeamKind::kBlock>{}, groups[1], true);
  pass_and_route(std::integral_constant<TeamKind, TeamKind::kMidBlock>{}, groups[2], true);
  pass_and_route(std::integral_constant<TeamKind, TeamKind::kLargeBlock>{}, groups[3], true);
  run.clouds_in_second_pass = again.clouds.size();
  // Room for every point: the blocks of the largest of its clouds' kind (at most kSecondPassPoints points:
  // never a large block).
  if (again.vertices > mid_points)
    pass_and_route(std::integral_constant<TeamKind, TeamKind::kMidBlock>{}, again, false);
  else
    pass_and_route(std::integral_constant<TeamKind, TeamKind::kBlock>{}, again, false);
  pass_and_route(std::integral_constant<TeamKind, TeamKind::kWarp>{}, on_warps, false);
  laps.lap("passes");
  return run;
}

template struct BatchRun<Point3>;
template struct BatchRun<Point3d>;
template BatchRun<Point3> batch_run_cuda(const Point3*, std::size_t, const std::size_t*, std::size_t,
                                         const std::uint8_t*, const BatchTuning&);
template BatchRun<Point3d> batch_run_cuda(const Point3d*, std::size_t, const std::size_t*, std::size_t,
                                          const std::uint8_t*, const BatchTuning&);

}  // namespace cudahull
