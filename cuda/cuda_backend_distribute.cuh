// The CUDA backend's Algorithm 2 on the device (cuda_backend.cu launches it): a pass's preparation, the
// distribution pass with its fused compaction, and the point states for the debugger and the viewer.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <cstdint>

#include "cuda_backend_launch.cuh"
#include "cudahull/routing.hpp"

namespace cudahull {
namespace {

// Everything a pass needs done first, in one launch (each launch and copy on the stream costs a few
// microseconds, which is most of a late iteration): the pass's results cleared (`words` 64-bit words: the
// kept count, the per-face keys and counts), the retired apexes taken out of the point set without routing
// (CpuBackend: face_of_[i] = kRouteInternal), and with `planes` each face's planes prepared (routing.hpp,
// FacePlanes: with many points a face, the exact verdicts then cost a few dot products instead of up to four
// orient3d filters each).
template <class Point>
__global__ void begin_pass_kernel(unsigned long long* __restrict__ results, std::size_t words,
                                  const PointIndex* __restrict__ retired, std::size_t retired_count,
                                  std::int32_t* __restrict__ face_of,
                                  const BasicFaceGeometry<Point>* __restrict__ faces, std::int32_t face_count,
                                  Vec3d interior, FacePlanes* __restrict__ planes) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < words) results[k] = 0;
  if (k < retired_count) face_of[retired[k]] = kRouteInternal;
  if (planes != nullptr && k < static_cast<std::size_t>(face_count))
    prepare_face_planes(faces[k], interior, planes[k]);
}

// With kPrepared, `planes` holds every face's FacePlanes (classify_point_prepared, the same answers).
template <class Point, bool kShared, bool kPrepared>
__global__ void __launch_bounds__(kBlock, kPrepared ? kPreparedBlocksPerSm : kDistributeBlocksPerSm)
    distribute_kernel(const Point* __restrict__ points, const PointIndex* __restrict__ active, std::size_t n,
                      std::int32_t* __restrict__ face_of, BasicRoutingView<Point> view,
                      const FacePlanes* __restrict__ planes, std::uint32_t* __restrict__ count,
                      unsigned long long* __restrict__ best, PointIndex* __restrict__ kept,
                      unsigned long long* __restrict__ kept_count) {
  extern __shared__ unsigned long long shared_mem[];
  unsigned long long* s_best = shared_mem;
  std::uint32_t* s_count = reinterpret_cast<std::uint32_t*>(shared_mem + (kShared ? view.face_count : 0));
  if (kShared) {
    for (std::int32_t f = threadIdx.x; f < view.face_count; f += blockDim.x) {
      s_best[f] = 0;
      s_count[f] = 0;
    }
    __syncthreads();
  }
  unsigned long long* acc_best = kShared ? s_best : best;
  std::uint32_t* acc_count = kShared ? s_count : count;

  // The compaction of the index array (Algorithm 2's last step) is fused into the pass: each warp gathers
  // its external points, in order, in a buffer in shared memory and, when it is full, moves them to a range
  // of `kept` that it reserves with one atomicAdd.  Warps finish in any order, so the order of the ranges
  // varies; no result depends on it (counts add, extreme keys take the max, each point keeps its own face).
  // A separate cub::DeviceSelect pass cost two more launches and another read of the index array every
  // iteration; a block-wide scan here cost more (its barriers idle the block's warps, and two blocks an SM
  // is all the registers allow).
  __shared__ PointIndex kept_buffer[kBlock / 32][kKeptBuffer];
  PointIndex* const warp_kept = kept_buffer[threadIdx.x / 32];
  const unsigned lane = threadIdx.x % 32;
  unsigned warp_fill = 0;  // the same in every lane
  auto flush = [&] {
    __syncwarp();
    unsigned long long start = 0;
    if (lane == 0) start = atomicAdd(kept_count, static_cast<unsigned long long>(warp_fill));
    start = __shfl_sync(0xffffffffu, start, 0);
    for (unsigned j = lane; j < warp_fill; j += 32)
      kept[start + j] = warp_kept[j];
    __syncwarp();
    warp_fill = 0;
  };

  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  // Every lane of a warp runs the same number of rounds (the base is uniform), so the warp-wide
  // __match_any_sync, __ballot_sync and flushes below are safe.
  for (std::size_t base = static_cast<std::size_t>(blockIdx.x) * blockDim.x; base < n; base += stride) {
    const std::size_t k = base + threadIdx.x;
    std::int32_t g = kRouteInternal;
    unsigned long long key = 0;
    PointIndex i = 0;
    if (k < n) {
      i = active != nullptr ? active[k] : static_cast<PointIndex>(k);
      const std::int32_t old_face = face_of[i];
      if (old_face != kRouteInternal) {  // not retired
        const Point x = points[i];
        if (kPrepared) {
          double height = 0;
          g = classify_point_prepared(x, old_face, view, planes, &height);
          if (g != kRouteInternal) key = pack_extreme<Point>(height, i);
        } else {
          g = classify_point(x, old_face, view);
          if (g != kRouteInternal) key = pack_extreme<Point>(face_height(view.faces[g], x), i);
        }
        face_of[i] = g;
      }
    }
    // Lanes with the same face add their count once; a key is offered only when it beats the current
    // maximum (a stale read only costs an extra atomic: atomicMax is monotone).
    const unsigned peers = __match_any_sync(0xffffffffu, g);
    if (g != kRouteInternal) {
      if ((threadIdx.x % 32) == static_cast<unsigned>(__ffs(peers) - 1)) {
        atomicAdd(acc_count + g, static_cast<std::uint32_t>(__popc(peers)));
      }
      if (key > *static_cast<volatile unsigned long long*>(acc_best + g)) atomicMax(acc_best + g, key);
    }
    const unsigned kept_lanes = __ballot_sync(0xffffffffu, g != kRouteInternal);
    if (warp_fill + __popc(kept_lanes) > kKeptBuffer) flush();
    if (g != kRouteInternal) warp_kept[warp_fill + __popc(kept_lanes & ((1u << lane) - 1u))] = i;
    warp_fill += __popc(kept_lanes);
  }
  if (warp_fill != 0) flush();
  if (kShared) {
    __syncthreads();
    for (std::int32_t f = threadIdx.x; f < view.face_count; f += blockDim.x) {
      if (s_count[f] != 0) {
        atomicAdd(count + f, s_count[f]);
        atomicMax(best + f, s_best[f]);
      }
    }
  }
}

// The four variants of the pass, [kShared][kPrepared], for the occupancy queries and the launch.
template <class Point>
using DistributeKernel = decltype(&distribute_kernel<Point, false, false>);
template <class Point>
constexpr DistributeKernel<Point> kDistributeKernels[2][2] = {
    {&distribute_kernel<Point, false, false>, &distribute_kernel<Point, false, true>},
    {&distribute_kernel<Point, true, false>, &distribute_kernel<Point, true, true>}};

__global__ void point_faces_kernel(const PointIndex* __restrict__ active, std::size_t n,
                                   const std::int32_t* __restrict__ face_of, std::int32_t* __restrict__ out) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const PointIndex i = active != nullptr ? active[k] : static_cast<PointIndex>(k);
  out[i] = face_of[i];
}

// CUDA-GL interop (issue 5): every point's state, written where the viewer draws from.
__global__ void fill_kernel(std::int32_t* __restrict__ out, std::size_t n, std::int32_t value) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < n) out[k] = value;
}
__global__ void mark_kernel(const PointIndex* __restrict__ ids, std::size_t n, std::int32_t* __restrict__ out,
                            std::int32_t value) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < n) out[ids[k]] = value;
}

}  // namespace
}  // namespace cudahull
