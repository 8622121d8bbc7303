// A batch pass on the device (batch_cuda.cu launches it): the teams' slots and clouds, the kernels of the
// blocks (the resident iteration, batch_hull()) and of the warps (small_hull()), the kinds of team, and the
// clouds a pass leaves unfinished.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>

#include "batch_shared.cuh"
#include "cudahull/resident/small_hull.hpp"
#include "cudahull/tuning.hpp"
#include "teams.cuh"

namespace cudahull {
namespace {

constexpr int kThreads = 128;       // a block a cloud: most small clouds' phases have fewer items than this
constexpr int kLargeThreads = 512;  // a block a large cloud: its points' phases are the work
// A warp's pass whose clouds have at most this many points stages them in shared memory (batch_warp_kernel,
// kStaged): BatchTuning::warp_points' default, so that every cloud a warp takes by default is staged.
constexpr std::size_t kStagedWarpPoints = BatchTuning{}.warp_points;

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
  slot.replaced_by += f;
  slot.revisit += f;
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

}  // namespace
}  // namespace cudahull
