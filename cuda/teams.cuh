// The teams that run the resident engine's phases on the device (cudahull/resident/rounds.hpp says what a
// team provides): one block, whose barrier is __syncthreads(), or a cooperative grid, whose barrier is the
// grid's.  Small composable pieces: a block's prefix sum (CUB's BlockScan, Items a thread at a time), a
// warp's ballot append and a warp's per-segment maximum, shared by both teams.
#pragma once

#include <cuda_runtime.h>

#include <cooperative_groups.h>

#include <algorithm>

#include <cub/block/block_scan.cuh>
#include <cub/warp/warp_scan.cuh>

#include "cuda_errors.hpp"
#include "cudahull/resident/rounds.hpp"
#include "cudahull/resident/swaps.hpp"

namespace cudahull::resident {

// How many blocks of `threads` threads of `kernel` the current device runs at once (at least one): the most
// a cooperative launch may have, and a persistent launch's slots.  Throws DeviceError named by `who`.
template <class Kernel>
unsigned blocks_that_fit(Kernel* kernel, int threads, const char* who) {
  int device = 0, sms = 0, per_sm = 0;
  cudaError_t e = cudaGetDevice(&device);
  if (e == cudaSuccess) e = cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device);
  if (e == cudaSuccess) e = cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, kernel, threads, 0);
  if (e != cudaSuccess) throw_cuda_error(who, "querying the occupancy", e);
  return static_cast<unsigned>(std::max(1, sms * per_sm));
}

// An exclusive prefix sum over at most Block values, one a thread: each warp scans its own (CUB's
// WarpScan, shuffles) and adds the sums of the warps before it.  A small hull's marks and wins are a few
// dozen values: this path has one barrier in the middle where BlockScan over Items a thread has several,
// and no thread loads values past n (ncu on 100-point clouds: the raking scan's loads and stores were 7%
// of the batch kernel's instructions).
template <int Block, class Value>
__device__ u32 block_exclusive_scan_one_each(u32 n, const Value& value, u32* out) {
  using WarpScan = cub::WarpScan<u32>;
  constexpr int kWarps = Block / 32;
  __shared__ typename WarpScan::TempStorage storage[kWarps];
  __shared__ u32 warp_sum[kWarps];
  const u32 i = threadIdx.x, warp = i / 32;
  const u32 v = i < n ? value(i) : 0u;
  u32 inclusive = 0;
  WarpScan(storage[warp]).InclusiveSum(v, inclusive);
  if (i % 32 == 31) warp_sum[warp] = inclusive;
  __syncthreads();
  u32 before = 0, total = 0;
#pragma unroll
  for (int w = 0; w < kWarps; ++w) {
    const u32 s = warp_sum[w];
    before += static_cast<u32>(w) < warp ? s : 0u;
    total += s;
  }
  if (i < n) out[i] = before + inclusive - v;
  return total;
}

// An exclusive prefix sum over n values by one block (Items per thread at a time), value(i) the i-th;
// every thread gets the total.  `out` may hold the values: each is read before it is written.
template <int Block, int Items, class Value>
__device__ u32 block_exclusive_scan(u32 n, const Value& value, u32* out) {
  if (n <= Block) {   // the same for every thread of the block
    __syncthreads();  // the values written by the block before
    const u32 total = block_exclusive_scan_one_each<Block>(n, value, out);
    __syncthreads();  // the ranks written, and the warps' sums free for the next scan
    return total;
  }
  using Scan = cub::BlockScan<u32, Block>;
  __shared__ typename Scan::TempStorage storage;
  __syncthreads();  // the values written by the block before
  u32 carry = 0;
  for (u32 base = 0; base < n; base += Block * Items) {
    u32 values[Items], ranks[Items];
    const u32 first = base + threadIdx.x * Items;
#pragma unroll
    for (int k = 0; k < Items; ++k)
      values[k] = first + k < n ? value(first + k) : 0u;
    u32 total = 0;
    __syncthreads();
    Scan(storage).ExclusiveSum(values, ranks, total);
#pragma unroll
    for (int k = 0; k < Items; ++k) {
      if (first + k < n) out[first + k] = carry + ranks[k];
    }
    carry += total;
  }
  __syncthreads();
  return carry;
}

// The teams that run the rounds' body (rounds.hpp) on the device: one block, or a cooperative grid.
// Thread 0 times each phase up to the barrier after it (so the slowest block's time), into the state.
__device__ inline u64 now_ns() {
  u64 t;
  asm volatile("mov.u64 %0, %%globaltimer;" : "=l"(t));
  return t;
}

// The phase timing of the teams that run the rounds (Team: the team itself, CRTP, with its state st, its
// clock t0 and leader()): the leader stamps the clock at start_timing() and adds the time since the last
// stamp to the state's phase at time(phase).
template <class Team>
struct LeaderTiming {
  __device__ void start_timing() const {
    const Team& team = static_cast<const Team&>(*this);
    if (team.leader()) team.t0 = now_ns();
  }
  __device__ void time(int phase) const {
    const Team& team = static_cast<const Team&>(*this);
    if (!team.leader()) return;
    const u64 t = now_ns();
    team.st->phase_ns[phase] += t - team.t0;
    team.t0 = t;
  }
};

// A block's threads: __syncthreads() for a barrier, which costs far less than the grid's.  kCompact: the
// rounds' candidate search as loops (FindCandidate::first), for a kernel whose blocks are in different
// phases at once (the batch's).
template <int Block, bool kCompact = false>
struct BlockTeam : LeaderTiming<BlockTeam<Block, kCompact>> {
  static constexpr bool kCompactCode = kCompact;
  RoundsState* st;
  mutable u64 t0 = 0;
  template <class F>
  __device__ void for_range(u32 n, const F& f) const {
    for (u32 i = threadIdx.x; i < n; i += Block)
      f(i);
  }
  __device__ void barrier() const { __syncthreads(); }
  __device__ bool leader() const { return threadIdx.x == 0; }
  // A warp appends its ballot at once: one atomic a warp.
  template <class Pred>
  __device__ void list_if(u32 n, const Pred& pred, u32* list, u32* count, u32 capacity) const {
    list_by_warps(threadIdx.x, Block, n, pred, list, count, capacity);
  }
  template <class Op>
  __device__ void max_per_segment(u32 n, const Op& op) const {
    max_by_warps(threadIdx.x, Block, n, op);
  }
  template <class Value>
  __device__ u32 exclusive_scan(u32 n, const Value& value, u32* out) const {
    return block_exclusive_scan<Block, 4>(n, value, out);
  }
  // Thread `tid` of `threads` (a multiple of 32): the indices below n that pass, appended in any order
  // (those past `capacity` counted, not written).
  template <class Pred>
  __device__ static void list_by_warps(u32 tid, u32 threads, u32 n, const Pred& pred, u32* list, u32* count,
                                       u32 capacity) {
    const u32 lane = tid & 31;
    for (u32 warp_first = tid - lane; warp_first < n; warp_first += threads) {
      const u32 i = warp_first + lane;
      const unsigned mask = __ballot_sync(0xffffffffu, i < n && pred(i));
      if (mask == 0) continue;
      u32 at = 0;
      if (lane == 0) at = atomicAdd(count, static_cast<u32>(__popc(mask)));
      at = __shfl_sync(0xffffffffu, at, 0);
      const u32 slot = at + __popc(mask & ((1u << lane) - 1));
      if ((mask & (1u << lane)) && slot < capacity) list[slot] = i;
    }
  }
  // Thread `tid` of `threads`: per segment the largest key.  Lanes of a warp with the same segment combine
  // their keys first: one atomic per segment and warp (the first iterations have millions of points on a
  // few faces).
  template <class Op>
  __device__ static void max_by_warps(u32 tid, u32 threads, u32 n, const Op& op) {
    const u32 lane = tid & 31;
    for (u32 warp_first = tid - lane; warp_first < n; warp_first += threads) {
      const u32 j = warp_first + lane;
      const unsigned active = __ballot_sync(0xffffffffu, j < n);
      if (j >= n) continue;
      const u32 segment = op.segment(j);
      const u64 key = op.key(j);
      const unsigned peers = __match_any_sync(active, segment);
#if __CUDA_ARCH__ >= 800
      // The peers' largest key in two reductions (its high word, then the low words that share it): a
      // shuffle a peer cost 11% of the batch kernel's instructions where all 32 lanes share a face.
      const u32 high = __reduce_max_sync(peers, static_cast<u32>(key >> 32));
      const u32 low =
          __reduce_max_sync(peers, static_cast<u32>(key >> 32) == high ? static_cast<u32>(key) : 0u);
      const u64 best = (static_cast<u64>(high) << 32) | low;
#else
      u64 best = key;
      for (unsigned rest = peers; rest != 0; rest &= rest - 1) {
        const u64 other = __shfl_sync(peers, key, __ffs(rest) - 1);
        best = other > best ? other : best;
      }
#endif
      if (lane == static_cast<u32>(__ffs(peers) - 1) && best != 0)
        atomicMax(reinterpret_cast<unsigned long long*>(&op.extreme[segment]),
                  static_cast<unsigned long long>(best));
    }
  }
};

// One warp: __syncwarp() for a barrier (it orders the lanes' memory as __syncthreads() does a block's).  A
// batch's smallest clouds take a warp each (small_hull.hpp): a block's other warps would mostly wait at
// its barriers (ncu on 100-point clouds: half the stall samples), and an SM holds three times as many
// clouds at once (16 warps against 5 blocks).  The compact code: many warps in different places share the
// SM's instruction cache. What small_hull() asks of a team (and batch_tetrahedron(), write_batch_hull()): no
// rounds, so no list_if (its lists: list(), list_two()) and no phase timing.
struct WarpTeam {
  __device__ static u32 lane() { return threadIdx.x & 31; }
  template <class F>
  __device__ void for_range(u32 n, const F& f) const {
    for (u32 i = lane(); i < n; i += 32)
      f(i);
  }
  __device__ void barrier() const { __syncwarp(); }
  __device__ bool leader() const { return lane() == 0; }
  template <class Op>
  __device__ void max_per_segment(u32 n, const Op& op) const {
    BlockTeam<32>::max_by_warps(lane(), 32, n, op);
  }
  // The largest key(i) over i < n (0 where there is none), to every lane: a lane's own, then the warp's in
  // two reductions (the high words, then the low words that share the largest).
  template <class Key>
  __device__ u64 max_of(u32 n, const Key& key) const {
    u64 best = 0;
    for (u32 i = lane(); i < n; i += 32) {
      const u64 k = key(i);
      best = k > best ? k : best;
    }
#if __CUDA_ARCH__ >= 800
    const u32 high = __reduce_max_sync(0xffffffffu, static_cast<u32>(best >> 32));
    const u32 low =
        __reduce_max_sync(0xffffffffu, static_cast<u32>(best >> 32) == high ? static_cast<u32>(best) : 0u);
    return (static_cast<u64>(high) << 32) | low;
#else
    for (int offset = 16; offset > 0; offset /= 2) {
      const u64 other = __shfl_xor_sync(0xffffffffu, best, offset);
      best = other > best ? other : best;
    }
    return best;
#endif
  }
  // An exclusive count of the indices below n that pass (pred(i), once each), in index order, into `out`;
  // the total to every lane.  A ballot a 32: the flags' prefix sum without a scan.
  template <class Pred>
  __device__ u32 count_scan(u32 n, const Pred& pred, u32* out) const {
    __syncwarp();  // what pred reads, written by the warp before
    const unsigned below = (1u << lane()) - 1;
    u32 carry = 0;
    for (u32 base = 0; base < n; base += 32) {
      const u32 i = base + lane();
      const unsigned passed = __ballot_sync(0xffffffffu, i < n && pred(i));
      if (i < n) out[i] = carry + __popc(passed & below);
      carry += __popc(passed);
    }
    __syncwarp();
    return carry;
  }
  // The indices below n that pass (pred(i), once each), in index order, each told its rank among them
  // (emit(i, rank), on its lane); the count to every lane.  A loop of its own, not list_two()'s first list
  // alone as on HostTeam: the unused second ballot cost the batch kernel time
  // (docs/benchmarks.md, "The measurements behind the code's constants").
  template <class Pred, class Emit>
  __device__ u32 list(u32 n, const Pred& pred, const Emit& emit) const {
    __syncwarp();
    const unsigned below = (1u << lane()) - 1;
    u32 carry = 0;
    for (u32 base = 0; base < n; base += 32) {
      const u32 i = base + lane();
      const bool passed = i < n && pred(i);
      const unsigned passing = __ballot_sync(0xffffffffu, passed);
      if (passed) emit(i, carry + __popc(passing & below));
      carry += __popc(passing);
    }
    __syncwarp();
    return carry;
  }
  // Two such lists in one pass (kind(i): bit 0 the first, bit 1 the second), as HostTeam's.
  template <class Kind, class First, class Second>
  __device__ TwoCounts list_two(u32 n, const Kind& kind, const First& first, const Second& second) const {
    __syncwarp();
    const unsigned below = (1u << lane()) - 1;
    TwoCounts carry{0, 0};
    for (u32 base = 0; base < n; base += 32) {
      const u32 i = base + lane();
      const u32 k = i < n ? kind(i) : 0u;
      const unsigned in_first = __ballot_sync(0xffffffffu, k & 1u),
                     in_second = __ballot_sync(0xffffffffu, k & 2u);
      if (k & 1u) first(i, carry.first + __popc(in_first & below));
      if (k & 2u) second(i, carry.second + __popc(in_second & below));
      carry.first += __popc(in_first);
      carry.second += __popc(in_second);
    }
    __syncwarp();
    return carry;
  }
  // 32 values at a time (CUB's WarpScan), each chunk after the ones before it.
  template <class Value>
  __device__ u32 exclusive_scan(u32 n, const Value& value, u32* out) const {
    using WarpScan = cub::WarpScan<u32>;
    typename WarpScan::TempStorage unused;  // the shuffle scan keeps nothing in memory
    __syncwarp();                           // the values written by the warp before
    u32 carry = 0;
    for (u32 base = 0; base < n; base += 32) {
      const u32 i = base + lane();
      const u32 v = i < n ? value(i) : 0u;
      u32 inclusive = 0, total = 0;
      WarpScan(unused).InclusiveSum(v, inclusive, total);
      if (i < n) out[i] = carry + inclusive - v;
      carry += total;
    }
    __syncwarp();
    return carry;
  }
};

// Every thread of a cooperative launch: the grid's barrier.  A prefix sum takes a contiguous tile of the
// values a block, then block 0 numbers the tiles (block_offset: one a block, and the total after them).
template <int Block>
struct GridTeam : LeaderTiming<GridTeam<Block>> {
  static constexpr bool kCompactCode = false;
  RoundsState* st;
  u32* block_offset;
  mutable u64 t0 = 0;
  __device__ u32 tid() const { return blockIdx.x * Block + threadIdx.x; }
  template <class F>
  __device__ void for_range(u32 n, const F& f) const {
    const u32 threads = gridDim.x * Block;
    for (u32 i = tid(); i < n; i += threads)
      f(i);
  }
  __device__ void barrier() const { cooperative_groups::this_grid().sync(); }
  __device__ bool leader() const { return tid() == 0; }
  template <class Pred>
  __device__ void list_if(u32 n, const Pred& pred, u32* list, u32* count, u32 capacity) const {
    BlockTeam<Block>::list_by_warps(tid(), gridDim.x * Block, n, pred, list, count, capacity);
  }
  template <class Op>
  __device__ void max_per_segment(u32 n, const Op& op) const {
    BlockTeam<Block>::max_by_warps(tid(), gridDim.x * Block, n, op);
  }
  template <class Value>
  __device__ u32 exclusive_scan(u32 n, const Value& value, u32* out) const {
    constexpr u32 kChunk = Block * 4;
    const u32 tile = ((n + gridDim.x - 1) / gridDim.x + kChunk - 1) / kChunk * kChunk;
    const u32 begin = min(n, blockIdx.x * tile), end = min(n, begin + tile);
    const u32 sum = block_exclusive_scan<Block, 4>(
        end - begin, [&](u32 i) { return value(begin + i); }, out + begin);
    if (threadIdx.x == 0) block_offset[blockIdx.x] = sum;
    barrier();
    if (blockIdx.x == 0) {
      const u32 total = block_exclusive_scan<Block, 1>(
          gridDim.x, [&](u32 k) { return block_offset[k]; }, block_offset);
      if (threadIdx.x == 0) block_offset[gridDim.x] = total;
    }
    barrier();
    const u32 offset = block_offset[blockIdx.x];
    for (u32 i = begin + threadIdx.x; i < end; i += Block)
      out[i] += offset;
    barrier();
    return block_offset[gridDim.x];
  }
};

}  // namespace cudahull::resident
