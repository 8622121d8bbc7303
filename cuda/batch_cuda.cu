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
#include <cuda_runtime.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cub/device/device_scan.cuh>
#include <string>
#include <type_traits>
#include <vector>

#include "cuda_errors.hpp"
#include "cudahull/cuda/batch_cuda.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/detail/plane_impl.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/resident/small_hull.hpp"
#include "teams.cuh"

namespace cudahull {
namespace {

using resident::BatchCloud;
using resident::BatchOutput;
using resident::BatchResult;
using resident::BatchRoom;
using resident::BatchSlot;
using resident::u32;
using resident::u64;

constexpr const char* kWho = "batched hulls";
constexpr int kThreads = 128;       // a block a cloud: most small clouds' phases have fewer items than this
constexpr int kLargeThreads = 512;  // a block a large cloud: its points' phases are the work
constexpr u32 kSecondPassPoints = 16384;  // the largest cloud the second launch takes
// Which clouds take which kind of team (a warp, a block of four or five an SM, a large block): BatchTuning
// (cudahull/tuning.hpp), whose defaults docs/benchmarks.md, "Tuning (ResidentTuning, BatchTuning)", explains.
// A warp's pass whose clouds have at most this many points stages them in shared memory (batch_warp_kernel,
// kStaged): BatchTuning::warp_points' default, so that every cloud a warp takes by default is staged.
constexpr std::size_t kStagedWarpPoints = BatchTuning{}.warp_points;
// The clouds of at most this many points that a block sent to the single-cloud path take a warp first
// (small_hull(), with room for every point), hundreds of times quicker than the single-cloud path, one
// cloud after another (docs/benchmarks.md, "The measurements behind the code's constants").
constexpr u32 kRetryOnWarpPoints = 4096;
// The largest cloud a team can take: a block's room, batch_room(), counts its face slots in 32 bits.
constexpr std::size_t kMaxBlockPoints = std::size_t{1} << 20;

constexpr CudaCheck check{kWho};

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

// After a batch the pool keeps what it holds, up to this share of the device's memory, for the next batch
// of its size: what the batch used, and what the last batch's result (often alive while the next one runs)
// holds, since mapping it again and handing it back cost a batch about a tenth of its time; keeping what
// the batch used alone left the next result's columns to map again (docs/benchmarks.md, "The measurements
// behind the code's constants"). cudahull::release_device_memory() hands it back at once.
constexpr std::size_t kBatchKeepShare = 16;

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

// Everything a pass's teams share: the points and offsets, the clouds listed for the pass, the slots (one
// a team) and the per-point arrays, the output and the results.
template <class Point>
struct PassArgs {
  const Point* points;
  const std::size_t* offsets;  // B + 1, as the caller gave them
  const u32* clouds;           // the pass's clouds
  u32 count;                   // how many
  u32* next;                   // the next of them to take
  BatchSlot slot;    // slot 0's pointers; slot s is `s` rooms further on (the state: the kernel's own)
  u32* point_words;  // six arrays of the batch's point count, one after another
  u32 points_total;
  BatchOutput<Point> out;
  BatchResult* results;  // per listed cloud
};

template <class Point>
__device__ BatchSlot slot_of(const PassArgs<Point>& a, u32 s) {
  const BatchRoom& room = a.slot.room;
  const std::size_t f = std::size_t{s} * room.faces, words = std::size_t{s} * (room.faces / 32 + 1);
  BatchSlot slot = a.slot;
  slot.fv += 3 * f;
  slot.fn += 3 * f;
  slot.fv_spare += 3 * f;
  slot.fn_spare += 3 * f;
  slot.killer += f;
  slot.look += f;
  slot.flags += f + s;  // room.faces + 1 a slot: the marks' prefix sum reads one past the faces
  slot.face_rank += f + s;
  slot.win_mask += words;
  slot.word_rank += words;
  slot.extreme += f;
  slot.claim += f;
  slot.entries += std::size_t{s} * room.entries;
  slot.list += std::size_t{s} * room.work;
  slot.cands += std::size_t{s} * room.work;
  return slot;
}

// Listed cloud k: its points where they are, and its per-point arrays.
template <class Point>
__device__ BatchCloud<Point> cloud_listed(const PassArgs<Point>& a, u32 k) {
  const u32 c = a.clouds[k], begin = static_cast<u32>(a.offsets[c]),
            n = static_cast<u32>(a.offsets[c + 1] - a.offsets[c]);
  const std::size_t at = begin, total = a.points_total;
  u32* w = a.point_words;
  return BatchCloud<Point>{a.points + at,
                           n,
                           w + at,
                           w + total + at,
                           w + 2 * total + at,
                           w + 3 * total + at,
                           w + 4 * total + at,
                           w + 5 * total + at};
}

// Listed cloud k's hull on `team` in `slot`: the resident iteration (batch_hull()).
template <class Team, class Point>
__device__ void hull_listed(const Team& team, const BatchSlot& slot, const PassArgs<Point>& a, u32 k) {
  resident::batch_hull(team, slot, cloud_listed(a, k), a.out, a.results + k);
}

// Listed cloud k's hull on a warp, a furthest point at a time (small_hull()): its points copied to `staged`
// first, in double (kStaged: every cloud of the pass has at most kStagedWarpPoints), or read where they are.
template <bool kStaged, class Team, class Point>
__device__ void small_hull_listed(const Team& team, const BatchSlot& slot, const PassArgs<Point>& a, u32 k,
                                  Point3d* staged) {
  if constexpr (kStaged) {
    BatchCloud<Point> in = cloud_listed(a, k);
    team.for_range(in.n, [&](u32 i) { staged[i] = Point3d{in.points[i].x, in.points[i].y, in.points[i].z}; });
    team.barrier();
    const BatchCloud<Point3d> cloud{staged,         in.n,          in.index, in.face,
                                    in.index_spare, in.face_spare, in.keep,  in.point_rank};
    resident::small_hull(team, slot, cloud, a.out, a.results + k);
  } else {
    resident::small_hull(team, slot, cloud_listed(a, k), a.out, a.results + k);
  }
}

// A pass's kernel: each block a team, taking clouds from the counter until none is left.  kMinBlocks: the
// blocks an SM must hold at once (__launch_bounds__: the registers a thread may use).
template <class Point, int Block, int kMinBlocks>
__global__ void __launch_bounds__(Block, kMinBlocks) batch_kernel(PassArgs<Point> a) {
  __shared__ u32 taken;
  // The team's state (RoundsState: its counts, read by every thread after nearly every barrier) in shared
  // memory, not in the slot: the SM's own memory, not L2 (generic pointers: the engine's code is the same).
  // 2-3% off the kernel on small clouds (docs/benchmarks.md, "Batched hulls").
  __shared__ resident::RoundsState state;
  BatchSlot slot = slot_of(a, blockIdx.x);
  slot.st = &state;
  // Compact code: five blocks an SM, each in a phase of its own, fetch the kernel's instructions from L2
  // (ncu: no instruction to issue in a fifth of the samples); the candidate search as loops took 19% off
  // 20,000 balls of 100 (docs/benchmarks.md, "Batched hulls").
  const resident::BlockTeam<Block, true> team{{}, slot.st};
  while (true) {
    if (threadIdx.x == 0) taken = atomicAdd(a.next, 1u);
    __syncthreads();
    const u32 k = taken;
    __syncthreads();  // every thread has read it before thread 0 takes the next
    if (k >= a.count) return;
    hull_listed(team, slot, a, k);
  }
}

// The warps' kernel (WarpTeam): each warp a team with a slot of its own, taking clouds from the counter
// until none is left; kWarps a block, kMinBlocks blocks an SM (the registers, as batch_kernel's).  kStaged:
// every cloud of the pass has at most kStagedWarpPoints points, staged in the SM's own memory.
template <class Point, int kWarps, int kMinBlocks, bool kStaged>
__global__ void __launch_bounds__(32 * kWarps, kMinBlocks) batch_warp_kernel(PassArgs<Point> a) {
  __shared__ resident::RoundsState states[kWarps];  // as batch_kernel's: the SM's own memory
  // Each warp's cloud in the SM's own memory, in double: every step reads the corners of every face (ncu:
  // the loads' latency, a third of the stall samples from global memory), and a float cloud converted at
  // each test cost 4% of the kernel's instructions.
  __shared__ Point3d staged[kStaged ? kWarps : 1][kStaged ? kStagedWarpPoints : 1];
  const u32 warp = threadIdx.x / 32, lane = threadIdx.x % 32;
  BatchSlot slot = slot_of(a, blockIdx.x * kWarps + warp);
  slot.st = &states[warp];
  const resident::WarpTeam team{};
  while (true) {
    u32 k = 0;
    if (lane == 0) k = atomicAdd(a.next, 1u);
    k = __shfl_sync(0xffffffffu, k, 0);
    if (k >= a.count) return;
    small_hull_listed<kStaged>(team, slot, a, k, staged[kStaged ? warp : 0]);
  }
}

// The kinds of team a pass runs its clouds on: a block of kThreads (five an SM, or four above
// BatchTuning::mid_block_points), or of kLargeThreads.  The small blocks are held to the registers of five
// blocks an SM: at the 168 a thread the iteration would take, three fit, and the SM waits on memory with
// nothing to issue.  Clouds of more than mid_block_points take four an SM: 128 registers a thread spill
// less, and their longer phases wait on memory more than on the barriers.
// The smallest clouds take a warp each (kWarp: kWarpsPerBlock warps a block, small_hull()), four blocks an
// SM: small_hull() at 128 registers a thread spills less than at five's 96; three and two blocks were
// slower.  The resident iteration on a warp a cloud lost to blocks: twenty warps an SM, each in a phase of
// its own, waited on instruction fetch (docs/benchmarks.md, "The measurements behind the code's constants").
enum class TeamKind { kWarp, kBlock, kMidBlock, kLargeBlock };
constexpr int kWarpsPerBlock = kThreads / 32;
template <TeamKind kKind>
constexpr int kBlockThreads = kKind == TeamKind::kLargeBlock ? kLargeThreads : kThreads;
template <TeamKind kKind>
constexpr u32 kTeamsPerBlock = kKind == TeamKind::kWarp ? kWarpsPerBlock : 1;
template <TeamKind kKind>
constexpr int kMinBlocksOf = kKind == TeamKind::kLargeBlock                             ? 1
                             : kKind == TeamKind::kMidBlock || kKind == TeamKind::kWarp ? 4
                                                                                        : 5;

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

__global__ void every_cloud_kernel(u32* clouds, u32 count) {
  for (u32 k = blockIdx.x * blockDim.x + threadIdx.x; k < count; k += gridDim.x * blockDim.x)
    clouds[k] = k;
}

// A listed cloud of a pass that did not end (its index in the list, its status: kBatchRoom, kBatchSingle).
struct Unfinished {
  u32 k, status;
};

// A pass's clouds that did not end, listed at `unfinished` (`count` of them): the host reads back these
// alone, not every cloud's result.
__global__ void list_unfinished_kernel(const BatchResult* results, u32 listed, u32* count,
                                       Unfinished* unfinished) {
  for (u32 k = blockIdx.x * blockDim.x + threadIdx.x; k < listed; k += gridDim.x * blockDim.x) {
    const u32 status = results[k].status;
    if (status != resident::kBatchDone) unfinished[atomicAdd(count, 1u)] = {k, status};
  }
}

constexpr int kListThreads = 256;
u32 list_blocks(std::size_t items) {
  return static_cast<u32>(std::min<std::size_t>((items + kListThreads - 1) / kListThreads, 4096));
}

// The kernel of a pass on kKind's teams: that one alone instantiated (a conditional expression would
// compile the warps' kernel for every kind of block, and the blocks' for the warps).
template <TeamKind kKind, class Point>
void (*pass_kernel(bool staged))(PassArgs<Point>) {
  if constexpr (kKind == TeamKind::kWarp)
    return staged ? batch_warp_kernel<Point, kWarpsPerBlock, kMinBlocksOf<kKind>, true>
                  : batch_warp_kernel<Point, kWarpsPerBlock, kMinBlocksOf<kKind>, false>;
  else
    return batch_kernel<Point, kBlockThreads<kKind>, kMinBlocksOf<kKind>>;
}

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
  s.killer = memory.take<u32>(f, "the faces' killers");
  s.look = memory.take<u32>(f, "the faces' stamps");
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

// The describe (describe_batch_cuda()): a warp a done cloud of a pass.
template <class Point>
struct DescribeArgs {
  const u32* words;          // the pass's output: per cloud 3 corners a face (into its vertex list), the list
  const Point* coordinates;  // per cloud its vertices', in the list's order
  const BatchResult* results;
  const u32* clouds;  // the pass's clouds, as listed
  u32 listed;
  BatchColumns columns;
};

constexpr int kDescribeThreads = 128;

template <class Point>
__global__ void __launch_bounds__(kDescribeThreads) describe_kernel(DescribeArgs<Point> a) {
  const u32 lane = threadIdx.x % 32, warps = gridDim.x * (kDescribeThreads / 32);
  for (u32 k = blockIdx.x * (kDescribeThreads / 32) + threadIdx.x / 32; k < a.listed; k += warps) {
    const BatchResult r = a.results[k];
    if (r.status != resident::kBatchDone) continue;
    const u32 c = a.clouds[k];
    const std::int64_t vertex_at = a.columns.vertex_offsets[c], face_at = a.columns.face_offsets[c];
    const u32* corners = a.words + r.word_at;
    const u32* ids = corners + 3 * std::size_t{r.faces};
    const Point* xyz = a.coordinates + r.point_at;
    for (u32 v = lane; v < r.vertices; v += 32)
      a.columns.vertices[vertex_at + v] = static_cast<std::int32_t>(ids[v]);
    for (u32 f = lane; f < r.faces; f += 32) {
      const u32 w[3] = {corners[3 * f], corners[3 * f + 1], corners[3 * f + 2]};
      std::int32_t* face = a.columns.faces + 3 * (face_at + f);
      for (int j = 0; j < 3; ++j)
        face[j] = static_cast<std::int32_t>(ids[w[j]]);
      detail::facet_plane_in_range(to_vec3d(xyz[w[0]]), to_vec3d(xyz[w[1]]), to_vec3d(xyz[w[2]]),
                                   a.columns.planes + 4 * (face_at + f));
    }
    // As convex_hull() measures a mesh (describe.cpp, measure_solid; plane_impl.hpp, measure_mesh()):
    // the faces' terms from the first face's first corner, added in the mesh's order one after another, and
    // the exact pass where the first is uncertain: the same bits.  Each lane loads (and computes the terms
    // of) its own faces, and every lane adds them all in order from the shuffles: lane 0 alone, face after
    // face, took about half again as long (docs/benchmarks.md, "The measurements behind the code's
    // constants").
    const auto corner = [&](u32 f, int k) { return to_vec3d(xyz[corners[3 * f + k]]); };
    const Vec3d apex = corner(0, 0);
    static_assert(detail::SolidMeasures::kErrorSums == 32, "a lane an error sum");
    detail::SolidMeasures measures;
    double error_sum = 0;  // this lane's faces' bounds (f mod 32 = lane), as measure_mesh()'s sums
    for (u32 base = 0; base < r.faces; base += 32) {
      const u32 f = base + lane;
      detail::SolidMeasures::FaceTerms mine{0, 0, 0};
      if (f < r.faces)
        mine = detail::SolidMeasures::face_terms(corner(f, 0), corner(f, 1), corner(f, 2), apex);
      error_sum = detail::add_rn(error_sum, mine.six_volume_error);
      for (u32 j = 0; j < 32 && base + j < r.faces; ++j)
        measures.add_terms(
            {__shfl_sync(0xffffffffu, mine.twice_area, j), __shfl_sync(0xffffffffu, mine.six_volume, j), 0});
    }
    for (u32 j = 0; j < 32; ++j)
      measures.six_volume_error =
          detail::add_rn(measures.six_volume_error, __shfl_sync(0xffffffffu, error_sum, j));
    if (measures.volume_uncertain()) {  // the same sums on every lane: the warp takes the pass together
      measures.exact_volume_pass();
      for (u32 base = 0; base < r.faces; base += 32) {
        const u32 f = base + lane;
        const double mine = f < r.faces ? detail::SolidMeasures::exact_six_volume(corner(f, 0), corner(f, 1),
                                                                                  corner(f, 2), apex)
                                        : 0.0;
        for (u32 j = 0; j < 32 && base + j < r.faces; ++j)
          measures.add_exact(__shfl_sync(0xffffffffu, mine, j));
      }
    }
    if (lane == 0) {
      a.columns.volumes[c] = measures.volume();
      a.columns.areas[c] = measures.area();
      a.columns.dimensions[c] = 3;
    }
  }
}

}  // namespace

template <class Point>
struct BatchRun<Point>::PassOutput {
  DeviceArray<u32> words;
  DeviceArray<Point> coordinates;
  DeviceArray<u32> results;  // BatchResult a listed cloud, then the counters
  DeviceArray<u32> clouds;   // the listed clouds
  u32 listed = 0;
};

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

namespace {

// A pass's done clouds' sizes at their places in the offsets (one past the cloud: the prefix sum's input).
__global__ void pass_sizes_kernel(const BatchResult* results, const u32* clouds, u32 listed,
                                  std::int64_t* vertex_offsets, std::int64_t* face_offsets) {
  for (u32 k = blockIdx.x * blockDim.x + threadIdx.x; k < listed; k += gridDim.x * blockDim.x) {
    const BatchResult r = results[k];
    if (r.status != resident::kBatchDone) continue;
    vertex_offsets[clouds[k] + 1] = r.vertices;
    face_offsets[clouds[k] + 1] = r.faces;
  }
}

__global__ void hosted_sizes_kernel(const HostedSizes* hosted, std::size_t count,
                                    std::int64_t* vertex_offsets, std::int64_t* face_offsets,
                                    std::int64_t* polygon_offsets) {
  for (std::size_t h = blockIdx.x * std::size_t{blockDim.x} + threadIdx.x; h < count;
       h += std::size_t{gridDim.x} * blockDim.x) {
    const HostedSizes s = hosted[h];
    vertex_offsets[s.cloud + 1] = static_cast<std::int64_t>(s.vertices);
    face_offsets[s.cloud + 1] = static_cast<std::int64_t>(s.faces);
    polygon_offsets[s.cloud + 1] = static_cast<std::int64_t>(s.polygon);
  }
}

// The three columns' values at each index of `at`, three a row.
__global__ void gather_kernel(const std::int64_t* vertex_offsets, const std::int64_t* face_offsets,
                              const std::int64_t* polygon_offsets, const std::size_t* at, std::size_t count,
                              std::int64_t* out) {
  for (std::size_t i = blockIdx.x * std::size_t{blockDim.x} + threadIdx.x; i < count;
       i += std::size_t{gridDim.x} * blockDim.x) {
    out[3 * i] = vertex_offsets[at[i]];
    out[3 * i + 1] = face_offsets[at[i]];
    out[3 * i + 2] = polygon_offsets[at[i]];
  }
}

// The last offset of each of the three columns, side by side: the totals, read back in one copy.
__global__ void totals_kernel(const std::int64_t* vertex_offsets, const std::int64_t* face_offsets,
                              const std::int64_t* polygon_offsets, std::size_t clouds, std::int64_t* totals) {
  totals[0] = vertex_offsets[clouds];
  totals[1] = face_offsets[clouds];
  totals[2] = polygon_offsets[clouds];
}

}  // namespace

template <class Point>
BatchTotals lay_out_batch_offsets(const BatchRun<Point>& run, const std::vector<HostedSizes>& hosted,
                                  std::size_t clouds, std::int64_t* vertex_offsets,
                                  std::int64_t* face_offsets, std::int64_t* polygon_offsets) {
  std::int64_t* const columns[3] = {vertex_offsets, face_offsets, polygon_offsets};
  for (std::int64_t* column : columns)
    check(cudaMemsetAsync(column, 0, (clouds + 1) * sizeof(std::int64_t), 0), "clearing the offsets");
  for (const auto& output : run.outputs) {
    pass_sizes_kernel<<<list_blocks(output->listed), kListThreads>>>(
        reinterpret_cast<const BatchResult*>(output->results.get()), output->clouds.get(), output->listed,
        vertex_offsets, face_offsets);
    check(cudaGetLastError(), "placing the hulls' sizes");
  }
  DeviceArray<HostedSizes> hosted_on_device;
  if (!hosted.empty()) {
    hosted_on_device = DeviceArray<HostedSizes>(hosted.size(), kWho, "the hosted hulls' sizes");
    check(cudaMemcpyAsync(hosted_on_device.get(), hosted.data(), hosted.size() * sizeof(HostedSizes),
                          cudaMemcpyHostToDevice, 0),
          "uploading the hosted hulls' sizes");
    hosted_sizes_kernel<<<list_blocks(hosted.size()), kListThreads>>>(
        hosted_on_device.get(), hosted.size(), vertex_offsets, face_offsets, polygon_offsets);
    check(cudaGetLastError(), "placing the hosted hulls' sizes");
  }
  // Each column's running sums (cub::DeviceScan, in place: the three the same size, one scratch), then the
  // totals in one copy: the host waits on the device once.
  if (clouds != 0) {
    const auto items = static_cast<std::int64_t>(clouds);
    std::size_t bytes = 0;
    check(cub::DeviceScan::InclusiveSum(nullptr, bytes, vertex_offsets + 1, items),
          "sizing the offsets' sums");
    const DeviceArray<char> scratch(bytes, kWho, "the offsets' sums");
    for (std::int64_t* column : columns)
      check(cub::DeviceScan::InclusiveSum(scratch.get(), bytes, column + 1, items), "summing the offsets");
  }
  const DeviceArray<std::int64_t> on_device(3, kWho, "the totals");
  totals_kernel<<<1, 1>>>(vertex_offsets, face_offsets, polygon_offsets, clouds, on_device.get());
  check(cudaGetLastError(), "reading the totals");
  std::int64_t totals[3] = {0, 0, 0};
  check(cudaMemcpy(totals, on_device.get(), sizeof(totals), cudaMemcpyDeviceToHost),
        "laying out the offsets");
  return {static_cast<std::size_t>(totals[0]), static_cast<std::size_t>(totals[1]),
          static_cast<std::size_t>(totals[2])};
}

std::vector<std::array<std::int64_t, 3>> read_offsets_at(const std::int64_t* vertex_offsets,
                                                         const std::int64_t* face_offsets,
                                                         const std::int64_t* polygon_offsets,
                                                         const std::vector<std::size_t>& at) {
  std::vector<std::array<std::int64_t, 3>> values(at.size());
  if (at.empty()) return values;
  const DeviceArray<std::size_t> indices(at.size(), kWho, "the offsets to read");
  const DeviceArray<std::int64_t> gathered(3 * at.size(), kWho, "the offsets read");
  check(cudaMemcpyAsync(indices.get(), at.data(), at.size() * sizeof(std::size_t), cudaMemcpyHostToDevice, 0),
        "uploading the offsets to read");
  gather_kernel<<<list_blocks(at.size()), kListThreads>>>(vertex_offsets, face_offsets, polygon_offsets,
                                                          indices.get(), at.size(), gathered.get());
  check(cudaGetLastError(), "gathering the offsets");
  static_assert(sizeof(values[0]) == 3 * sizeof(std::int64_t));
  check(
      cudaMemcpy(values.data(), gathered.get(), 3 * at.size() * sizeof(std::int64_t), cudaMemcpyDeviceToHost),
      "reading the offsets");
  return values;
}

template <class Point>
void describe_batch_cuda(const BatchRun<Point>& run, const BatchColumns& columns) {
  for (const auto& output : run.outputs) {
    DescribeArgs<Point> a{};
    a.words = output->words.get();
    a.coordinates = output->coordinates.get();
    a.results = reinterpret_cast<const BatchResult*>(output->results.get());
    a.clouds = output->clouds.get();
    a.listed = output->listed;
    a.columns = columns;
    const u32 blocks = (output->listed + kDescribeThreads / 32 - 1) / (kDescribeThreads / 32);
    describe_kernel<Point><<<blocks, kDescribeThreads>>>(a);
    check(cudaGetLastError(), "launching the describe");
  }
  check(cudaDeviceSynchronize(), "describing the hulls (kernel fault)");
}

// The current device's memory, asked once a device: cudaMemGetInfo() is a host round trip a batch need not
// pay (docs/benchmarks.md, "The measurements behind the code's constants").  0 where it cannot be read.
static std::size_t device_total_memory() {
  constexpr int kDevices = 64;
  static std::atomic<std::size_t> totals[kDevices];
  int device = 0;
  if (cudaGetDevice(&device) != cudaSuccess || device < 0 || device >= kDevices) {
    cudaGetLastError();
    return 0;
  }
  std::size_t total = totals[device].load(std::memory_order_relaxed);
  if (total == 0) {
    std::size_t free_bytes = 0;
    if (cudaMemGetInfo(&free_bytes, &total) != cudaSuccess) {
      cudaGetLastError();
      return 0;
    }
    totals[device].store(total, std::memory_order_relaxed);
  }
  return total;
}

std::size_t batch_pool_keep() {
  return std::max(kPoolKeep, device_total_memory() / kBatchKeepShare);
}

void trim_batch_pool() {
  trim_device_pool(batch_pool_keep());
}

std::shared_ptr<void> batch_column(std::size_t bytes, const char* what) {
  // No pool trim when it dies (shared_device_array's): the caller's library may free a result's columns one
  // by one, in its own loop; the next batch's trim hands back what they held.
  const auto owner = std::make_shared<DeviceArray<char>>(bytes, kWho, what);
  return std::shared_ptr<void>(owner, owner->get());
}

void copy_to_device(void* device, const void* host, std::size_t bytes) {
  if (bytes != 0) check(cudaMemcpy(device, host, bytes, cudaMemcpyHostToDevice), "copying up the hulls");
}

void copy_to_host(void* host, const void* device, std::size_t bytes) {
  if (bytes != 0) check(cudaMemcpy(host, device, bytes, cudaMemcpyDeviceToHost), "reading back the hulls");
}

void finish_device_work() {
  check(cudaStreamSynchronize(0), "finishing the hulls");
}

int current_cuda_device() {
  int device = 0;
  check(cudaGetDevice(&device), "asking for the device");
  return device;
}

template struct BatchRun<Point3>;
template struct BatchRun<Point3d>;
template BatchRun<Point3> batch_run_cuda(const Point3*, std::size_t, const std::size_t*, std::size_t,
                                         const std::uint8_t*, const BatchTuning&);
template BatchRun<Point3d> batch_run_cuda(const Point3d*, std::size_t, const std::size_t*, std::size_t,
                                          const std::uint8_t*, const BatchTuning&);
template BatchTotals lay_out_batch_offsets(const BatchRun<Point3>&, const std::vector<HostedSizes>&,
                                           std::size_t, std::int64_t*, std::int64_t*, std::int64_t*);
template BatchTotals lay_out_batch_offsets(const BatchRun<Point3d>&, const std::vector<HostedSizes>&,
                                           std::size_t, std::int64_t*, std::int64_t*, std::int64_t*);
template void describe_batch_cuda(const BatchRun<Point3>&, const BatchColumns&);
template void describe_batch_cuda(const BatchRun<Point3d>&, const BatchColumns&);

}  // namespace cudahull
