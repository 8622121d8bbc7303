// The resident engine's device executor's kernels (resident_exec.cuh launches them): the operations of
// cudahull/resident/resident_ops.hpp one thread per face or point, the reductions, the iteration's phases in
// one launch (iteration_kernel) and a small mesh's finish in one block.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <cub/block/block_radix_sort.cuh>
#include <cub/block/block_scan.cuh>

#include "cudahull/resident/finish.hpp"
#include "cudahull/resident/iteration.hpp"
#include "teams.cuh"

namespace cudahull {
namespace resident {
namespace {

constexpr int kBlock = 256;
constexpr int kOneBlockThreads = 512;  // the rounds of a small mesh (fused_rounds_kernel)

template <class Op>
__global__ void for_each_kernel(std::size_t n, Op op) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) op(i);
}

template <class KeyOp>
__global__ void reduce_max_kernel(std::size_t n, KeyOp key, u64* out) {
  u64 best = 0;
  for (std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x; i < n;
       i += static_cast<std::size_t>(gridDim.x) * blockDim.x) {
    const u64 k = key(i);
    best = k > best ? k : best;
  }
  for (int offset = 16; offset > 0; offset /= 2) {
    const u64 other = __shfl_down_sync(0xffffffffu, best, offset);
    best = other > best ? other : best;
  }
  if ((threadIdx.x & 31) == 0 && best != 0)
    atomicMax(reinterpret_cast<unsigned long long*>(out), static_cast<unsigned long long>(best));
}

// K maxima at once (one pass over the points for section 3.1's directions): each block reduces every key
// (warps, then shared memory), then one atomic per key and block: few blocks, so that the atomics on the K
// results do not queue.
template <int K, class KeysOp>
__global__ void __launch_bounds__(kBlock) reduce_max_many_kernel(std::size_t n, KeysOp keys, u64* out) {
  __shared__ u64 per_warp[kBlock / 32][K];
  u64 best[K] = {};
  u64 mine[K];
  for (std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x; i < n;
       i += static_cast<std::size_t>(gridDim.x) * blockDim.x) {
    keys(i, mine);
#pragma unroll
    for (int k = 0; k < K; ++k)
      best[k] = mine[k] > best[k] ? mine[k] : best[k];
  }
#pragma unroll
  for (int k = 0; k < K; ++k) {
    u64 b = best[k];
    for (int offset = 16; offset > 0; offset /= 2) {
      const u64 other = __shfl_down_sync(0xffffffffu, b, offset);
      b = other > b ? other : b;
    }
    if ((threadIdx.x & 31) == 0) per_warp[threadIdx.x / 32][k] = b;
  }
  __syncthreads();
  if (threadIdx.x < K) {
    u64 b = 0;
    for (int w = 0; w < kBlock / 32; ++w)
      b = per_warp[w][threadIdx.x] > b ? per_warp[w][threadIdx.x] : b;
    if (b != 0)
      atomicMax(reinterpret_cast<unsigned long long*>(out + threadIdx.x), static_cast<unsigned long long>(b));
  }
}

__global__ void scan_total_kernel(const u32* in, const u32* out, std::size_t n, u32* total) {
  *total = out[n - 1] + in[n - 1];
}

__global__ void scatter_selected_kernel(const u32* flags, const u32* rank, u32* list, std::size_t n) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n && flags[i]) list[rank[i]] = static_cast<u32>(i);
}

template <class Pred>
__global__ void flag_kernel(std::size_t n, Pred pred, unsigned char* flags) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) flags[i] = pred(static_cast<u32>(i)) ? 1 : 0;
}

template <class T>
__global__ void fill_kernel(T* at, std::size_t n, T value) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) at[i] = value;
}

// Per segment the largest key (the records' furthest points).
template <class Op>
__global__ void segmented_max_kernel(u32 n, Op op) {
  BlockTeam<kBlock>::max_by_warps(blockIdx.x * kBlock + threadIdx.x, gridDim.x * kBlock, n, op);
}

// The iteration's phases (iteration.hpp) in one launch: one block (a small mesh with few points: whole
// iterations, the device loop; or the rounds of a small mesh), whose barrier is __syncthreads(), or a
// cooperative grid, whose barrier is the grid's.  `Range`: the phases compiled in (a grid runs a range a
// launch, each with the registers of its own phases).
template <class Point, class Log, class Range, int Block, bool kOneBlock>
__global__ void __launch_bounds__(Block)
    iteration_kernel(IterationBuffers<Point, Log> b, u32* block_offset, IterationLaunch launch) {
  if constexpr (kOneBlock) {
    resident_iterations(BlockTeam<Block>{{}, b.st}, b, launch, Range{});
  } else {
    resident_iterations(GridTeam<Block>{{}, b.st, block_offset}, b, launch, Range{});
  }
}

// The driver's finish() of a small mesh (3 * faces <= Block * Items corners) in one block, for one read:
// out = [faults, vertices, the corners renumbered (3 * faces), the vertex list (ascending)].  The faults are
// counted (CountFaults), the corners sorted (a block radix sort over the bits of ids below `bound`), the
// distinct ones listed, and each corner renumbered by bisection in that list, in shared memory.  The same
// result as the general path's CUB sort and select.
template <class Point, int Block, int Items>
__global__ void __launch_bounds__(Block)
    finish_small_kernel(MeshView<Point> m, u32 faces, int bits, u32* out) {
  using Sort = cub::BlockRadixSort<u32, Block, Items>;
  using Scan = cub::BlockScan<u32, Block>;
  // The sort's and the scan's storage and the sorted corners, one after another in the same bytes.
  __shared__ union {
    typename Sort::TempStorage sort;
    typename Scan::TempStorage scan;
    u32 sorted[Block * Items];
  } shared;
  __shared__ u32 faults;
  const u32 corners = 3 * faces, first = threadIdx.x * Items;
  if (threadIdx.x == 0) faults = 0;
  __syncthreads();
  const CountFaults<Point> count{m, &faults};
  for (u32 f = threadIdx.x; f < faces; f += Block)
    count(f);
  // Past the corners, keys above every id (all ones in the sorted bits: a stable sort keeps them last).
  u32 keys[Items];
#pragma unroll
  for (int k = 0; k < Items; ++k)
    keys[k] = first + k < corners ? m.fv[first + k] : ~0u;
  Sort(shared.sort).Sort(keys, 0, bits);
  __syncthreads();
#pragma unroll
  for (int k = 0; k < Items; ++k)
    shared.sorted[first + k] = keys[k];
  __syncthreads();
  u32 distinct[Items], ranks[Items];
#pragma unroll
  for (int k = 0; k < Items; ++k)
    distinct[k] =
        first + k < corners && (first + k == 0 || shared.sorted[first + k - 1] != keys[k]) ? 1u : 0u;
  __syncthreads();
  u32 vertices = 0;
  Scan(shared.scan).ExclusiveSum(distinct, ranks, vertices);
  __syncthreads();
  u32* list = out + 2 + corners;
#pragma unroll
  for (int k = 0; k < Items; ++k) {
    if (distinct[k]) {
      shared.sorted[ranks[k]] = keys[k];
      list[ranks[k]] = keys[k];
    }
  }
  __syncthreads();
  for (u32 c = threadIdx.x; c < corners; c += Block) {
    const u32 v = m.fv[c];
    u32 lo = 0, hi = vertices;  // sorted[lo..hi) holds v
    while (hi - lo > 1) {
      const u32 mid = lo + (hi - lo) / 2;
      if (shared.sorted[mid] <= v) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    out[2 + c] = lo;
  }
  if (threadIdx.x == 0) {
    out[0] = faults;
    out[1] = vertices;
  }
}

}  // namespace
}  // namespace resident
}  // namespace cudahull
