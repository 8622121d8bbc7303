// Batched hulls on the device (issue 27): every small cloud of a batch on one block, each running the
// resident engine's own iteration (cudahull/resident/batch.hpp), in one launch, or two where some clouds
// asked for more room than the first pass gave them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

// The exact meshes of a batch's clouds, as the device made them, read back in one piece.
template <class Point>
struct BatchMeshes {
  // Per cloud: 1 when its exact hull (dimension 3) is here; 0 when the single-cloud path must take it
  // (fewer than 4 points or more than a block takes, a flat cloud, a stall, or a defect that the
  // single-cloud path's local repair mends).
  std::vector<std::uint8_t> done;
  // Cloud c's hull: vertex ids (its own indices, ascending), their coordinates and the triangles on them.
  BasicHullMesh<Point> mesh(std::size_t c) const;

  std::vector<std::uint32_t> faces, vertices;  // per cloud
  std::vector<std::size_t> word_at, point_at;  // per cloud: where its words and coordinates begin
  std::vector<std::uint32_t> words;            // per cloud: 3 corners a face, then the vertex list
  std::vector<Point> coordinates;              // per cloud: its vertices'
  unsigned passes = 0;                         // launches (a second for the clouds short of room)
  std::size_t clouds_in_second_pass = 0;
  std::size_t device_bytes = 0;  // the most device memory the batch held at once
  double kernel_ms = 0;          // the launches alone (CUDA events)
};

// The clouds of `count` points at `device_points` (the current device's memory), bounded by `offsets`
// (B + 1 of them, in host memory), each on one block, but those `skip` marks (when given: B flags).
// Throws DeviceError.
template <class Point>
BatchMeshes<Point> batch_meshes_cuda(const Point* device_points, std::size_t count,
                                     const std::size_t* offsets, std::size_t clouds,
                                     const std::uint8_t* skip = nullptr);

}  // namespace cudahull
