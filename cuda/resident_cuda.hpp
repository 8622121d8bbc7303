// The resident engine on the GPU (issue 15): the points uploaded once, then the whole of Algorithm 1 on
// the device (cuda/resident_cuda.cu), the host reading back O(1) bytes a step and the hull at the end.
#pragma once

#include <memory>
#include <vector>

#include "cudahull/resident.hpp"

namespace cudahull {

template <class Point>
class ResidentCudaHull {
 public:
  ResidentCudaHull();
  ~ResidentCudaHull();
  ResidentCudaHull(const ResidentCudaHull&) = delete;
  ResidentCudaHull& operator=(const ResidentCudaHull&) = delete;

  // Copies the points to the device; `points` must outlive run() (its exact checks read them).
  void upload(const std::vector<Point>& points);
  // The exact hull of the uploaded points; may run again on the same points.  Throws DeviceError.
  BasicHullMesh<Point> run(ResidentStats* stats = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cudahull
