// The CUDA backend's section 3.1 queries on the device (cuda_backend.cu launches them): argmax of a
// per-point score, ties to the lowest index (as CpuBackend::argmax, whose strict > within a chunk and
// lowest-index merge pick the lowest index among equal maxima).
#pragma once

#include <cuda_runtime.h>

#include <cub/block/block_reduce.cuh>

#include <cmath>
#include <cstddef>

#include "cuda_backend_launch.cuh"
#include "cudahull/routing.hpp"

namespace cudahull {
namespace {

struct Candidate {
  double score;
  PointIndex index;
};

__device__ __forceinline__ bool better(double s, PointIndex i, double best_s, PointIndex best_i) {
  return s > best_s || (s == best_s && i < best_i);
}

// The better of two candidates: a total order (the higher score, then the lower index), so CUB's reduction
// in any grouping picks the same one.
struct BetterCandidate {
  __device__ __forceinline__ Candidate operator()(const Candidate& a, const Candidate& b) const {
    return better(b.score, b.index, a.score, a.index) ? b : a;
  }
};

// Reduces the candidates over the block; thread 0 gets the result.
using BlockArgmax = cub::BlockReduce<Candidate, kBlock>;

template <class Point, class Score>
__global__ void __launch_bounds__(kBlock) argmax_partial(const Point* __restrict__ points, std::size_t n,
                                                         Score score, Candidate* __restrict__ partial) {
  score.prepare(points);
  double best_s = -INFINITY;
  PointIndex best_i = 0xffffffffu;
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  for (std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; k < n; k += stride) {
    const double s = score(points[k]);
    if (better(s, static_cast<PointIndex>(k), best_s, best_i)) {
      best_s = s;
      best_i = static_cast<PointIndex>(k);
    }
  }
  __shared__ BlockArgmax::TempStorage temp;
  const Candidate best = BlockArgmax(temp).Reduce(Candidate{best_s, best_i}, BetterCandidate{});
  if (threadIdx.x == 0) partial[blockIdx.x] = best;
}

__global__ void __launch_bounds__(kBlock)
    argmax_final(const Candidate* __restrict__ partial, int count, PointIndex* __restrict__ result) {
  double best_s = -INFINITY;
  PointIndex best_i = 0xffffffffu;
  for (int k = threadIdx.x; k < count; k += blockDim.x) {
    if (better(partial[k].score, partial[k].index, best_s, best_i)) {
      best_s = partial[k].score;
      best_i = partial[k].index;
    }
  }
  __shared__ BlockArgmax::TempStorage temp;
  const Candidate best = BlockArgmax(temp).Reduce(Candidate{best_s, best_i}, BetterCandidate{});
  if (threadIdx.x == 0) *result = best.index;
}

// CpuBackend::extremes_x, both ends in one pass: lowest x (as the highest -x; exact in double) in
// partial[0, gridDim), highest x in partial[gridDim, 2 gridDim).
template <class Point>
__global__ void __launch_bounds__(kBlock)
    extremes_x_partial(const Point* __restrict__ points, std::size_t n, Candidate* __restrict__ partial) {
  double low_s = -INFINITY, high_s = -INFINITY;
  PointIndex low_i = 0xffffffffu, high_i = 0xffffffffu;
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  for (std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; k < n; k += stride) {
    const double x = points[k].x;
    if (better(-x, static_cast<PointIndex>(k), low_s, low_i)) {
      low_s = -x;
      low_i = static_cast<PointIndex>(k);
    }
    if (better(x, static_cast<PointIndex>(k), high_s, high_i)) {
      high_s = x;
      high_i = static_cast<PointIndex>(k);
    }
  }
  __shared__ BlockArgmax::TempStorage temp;
  const Candidate low = BlockArgmax(temp).Reduce(Candidate{low_s, low_i}, BetterCandidate{});
  if (threadIdx.x == 0) partial[blockIdx.x] = low;
  __syncthreads();  // the reduction's shared storage is used again
  const Candidate high = BlockArgmax(temp).Reduce(Candidate{high_s, high_i}, BetterCandidate{});
  if (threadIdx.x == 0) partial[gridDim.x + blockIdx.x] = high;
}

// The fixed corners of the next two queries are read on the device (prepare(), once per thread), so no
// query waits for a point to come back to the host first.
// CpuBackend::furthest_from_line: |d x (q - a)|^2, the same double operations, each rounded once.
template <class Point>
struct ScoreLine {
  PointIndex a, b;
  double ax, ay, az, dx, dy, dz;
  __device__ void prepare(const Point* points) {
    const Point pa = points[a], pb = points[b];
    ax = pa.x;
    ay = pa.y;
    az = pa.z;
    dx = __dsub_rn(pb.x, ax);
    dy = __dsub_rn(pb.y, ay);
    dz = __dsub_rn(pb.z, az);
  }
  __device__ double operator()(const Point& q) const {
    const double wx = __dsub_rn(q.x, ax), wy = __dsub_rn(q.y, ay), wz = __dsub_rn(q.z, az);
    const double cx = __dsub_rn(__dmul_rn(dy, wz), __dmul_rn(dz, wy));
    const double cy = __dsub_rn(__dmul_rn(dz, wx), __dmul_rn(dx, wz));
    const double cz = __dsub_rn(__dmul_rn(dx, wy), __dmul_rn(dy, wx));
    return __dadd_rn(__dadd_rn(__dmul_rn(cx, cx), __dmul_rn(cy, cy)), __dmul_rn(cz, cz));
  }
};

// CpuBackend::furthest_from_plane: |face_height|.
template <class Point>
struct ScorePlane {
  PointIndex a, b, c;
  BasicFaceGeometry<Point> face;
  __device__ void prepare(const Point* points) {
    face.v[0] = points[a];
    face.v[1] = points[b];
    face.v[2] = points[c];
  }
  __device__ double operator()(const Point& q) const { return fabs(face_height(face, q)); }
};

}  // namespace
}  // namespace cudahull
