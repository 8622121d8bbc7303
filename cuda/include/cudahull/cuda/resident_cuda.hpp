// The resident engine on the GPU (issue 15): the points uploaded once, then the whole of Algorithm 1 on
// the device (cuda/resident_cuda.cu), the host reading back O(1) bytes a step and the hull at the end.
#pragma once

#include <memory>
#include <vector>

#include "cudahull/resident.hpp"
#include "cudahull/tuning.hpp"

namespace cudahull {

template <class Point>
class ResidentCudaHull {
 public:
  // `tuning`: where the runs leave the grid's launches for one block (cudahull/tuning.hpp).
  explicit ResidentCudaHull(const ResidentTuning& tuning = {});
  ~ResidentCudaHull();
  ResidentCudaHull(const ResidentCudaHull&) = delete;
  ResidentCudaHull& operator=(const ResidentCudaHull&) = delete;

  // Copies the points to the device; `points` must outlive run() (its exact checks read them).
  void upload(const std::vector<Point>& points);
  // Borrows `count` points already in this device's memory (a CuPy array, a PyTorch tensor): nothing is
  // copied, and run() reads back only the coordinates its exact checks need (all of them only for
  // lower-dimensional input or section 3.1's tetrahedron).  They must stay unchanged until run() returns.
  // The caller checks them (finite, in range): run() uses them as they are.
  void use_device_points(const Point* device_points, std::size_t count);
  // The exact hull of the uploaded points; may run again on the same points.  Throws DeviceError.
  BasicHullMesh<Point> run(ResidentStats* stats = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The resident engine one iteration a step on the GPU, with records (make_resident_stepping_engine's,
// entry for entry): the viewer's, `--trace`'s and `--table`'s CUDA engine.  Uploads `points`, and borrows
// them for the exact checks.  Throws DeviceError.
template <class Point>
std::unique_ptr<SteppingEngine> make_resident_cuda_stepping_engine(const std::vector<Point>& points,
                                                                   const ResidentTuning& tuning = {});

// The current device's pace for a run's floors (fill_floors(), resident.hpp): its peak memory bandwidth from
// its attributes, and a launch's and a wait's host time measured with empty kernels, once a process.
// Zeros where the device cannot be asked.
HardwarePace device_pace();

}  // namespace cudahull
