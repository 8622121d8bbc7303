// The CUDA backend's launch shapes, shared by its kernels (cuda_backend_queries.cuh,
// cuda_backend_distribute.cuh) and the backend that launches them (cuda_backend.cu): the block size, the
// distribution pass's occupancy, its shared accumulators and its buffer of kept points.
#pragma once

#include <cstddef>
#include <cstdint>

namespace cudahull {
namespace {

constexpr int kBlock = 256;
// Occupancy of the distribution pass: at least 2 blocks of 256 threads per SM, so at most 128 registers a
// thread.  Capping harder (3 or 4 blocks, 85 or 64 registers) spills and made the pass slower
// (docs/benchmarks.md, "Measurements behind the code").
#ifndef CUDAHULL_DISTRIBUTE_BLOCKS_PER_SM
#define CUDAHULL_DISTRIBUTE_BLOCKS_PER_SM 2
#endif
constexpr int kDistributeBlocksPerSm = CUDAHULL_DISTRIBUTE_BLOCKS_PER_SM;
// The pass with prepared planes needs fewer registers: 3 blocks (80 registers, a few spilled) made it
// faster than 2 (docs/benchmarks.md, "Measurements behind the code").
#ifndef CUDAHULL_PREPARED_BLOCKS_PER_SM
#define CUDAHULL_PREPARED_BLOCKS_PER_SM 3
#endif
constexpr int kPreparedBlocksPerSm = CUDAHULL_PREPARED_BLOCKS_PER_SM;
// Faces up to this many accumulate their counts and keys in shared memory (12 bytes a face) before one
// global atomic per face and block; beyond it, contention is low and the kernel goes straight to global.
constexpr std::int32_t kSharedFaces = 2048;
// Each warp's buffer of kept point indices (distribute_kernel's fused compaction): 4 KB a block.
constexpr unsigned kKeptBuffer = 128;

unsigned blocks_for(std::size_t n) {
  return static_cast<unsigned>((n + kBlock - 1) / kBlock);
}

}  // namespace
}  // namespace cudahull
