// The size thresholds the GPU paths decide by, as types (as CUB's tuning policies): ResidentTuning for the
// resident engine's executor, BatchTuning for the batch kernel.  The library never reads them from the
// environment: the plan carries the resident engine's (HullPlan::resident_tuning), the batch's options the
// batch kernel's (ConvexHullBatchOptions::tuning), defaulted to the members' values below, and the engines
// take them when they are built (ResidentCudaHull, batch_run_cuda()).  The command line (the edge) reads
// CUDAHULL_* variables into them for A/B runs (docs/cli.md).  docs/benchmarks.md, "Tuning (ResidentTuning,
// BatchTuning)", lists each default with the runs that chose it.
//
// design:
//   ResidentTuning  where the resident engine leaves the grid's launches for one block: whole iterations in
//                   one launch (the device loop) while few points and faces are left, the swap rounds in one
//                   block on a small mesh.  Any values give the same hull; only the launches differ
//   BatchTuning     which clouds the batch kernel takes, and on which kind of team: a warp, a block of
//                   four an SM, or a large block; the rest take the single-cloud path.  Any values give the
//                   same hulls (each cloud's is convex_hull()'s); only the teams and passes differ
#pragma once

#include <cstddef>

namespace cudahull {

struct ResidentTuning {
  // The device loop (one launch of one block runs whole iterations) takes an iteration with at most
  // loop_points points left, on a mesh of at most loop_faces faces, or of at most loop_few_points_faces
  // while no more points are left than faces (loop_goes_on(), iteration.hpp); past them the grid's
  // launches are faster.
  std::size_t loop_points = 16384;
  std::size_t loop_faces = 512;
  std::size_t loop_few_points_faces = 4096;
  // Meshes of at most this many faces run their swap rounds in one block (a grid barrier costs more the
  // more blocks wait at it).
  std::size_t one_block_faces = 4096;
};

struct BatchTuning {
  // The largest cloud a team takes (larger ones take the single-cloud path, whose grid a large cloud fills
  // better); at most 2^20 (a block's room counts its face slots in 32 bits): a larger value counts as that.
  std::size_t block_points = std::size_t{1} << 17;
  // Clouds of more than large_block_points points take a block of 512 threads (their points' phases are
  // the work), the rest a block of 128; of those, clouds of more than mid_block_points take the blocks held
  // to four an SM (fewer spills), the rest five.
  std::size_t large_block_points = 16384;
  std::size_t mid_block_points = 256;
  // Clouds of at most this many points take a warp each (small_hull(): it tests every face and point at
  // each step, so warps win on small clouds only).  At most the warps' retry limit (4,096 points): a larger
  // value counts as that; 0: no cloud on a warp, and no retry on warps of the clouds a block gives up on.
  std::size_t warp_points = 256;
};

}  // namespace cudahull
