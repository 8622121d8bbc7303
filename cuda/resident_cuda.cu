// The resident engine on the device: ResidentCudaHull and the CUDA stepping engine, the driver
// (resident_driver.hpp) on the device executor (CudaExec, resident_exec.cuh), and the device's pace.
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <vector>

#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/resident_cuda.hpp"
#include "cudahull/resident/resident_driver.hpp"
#include "cudahull/resident/resident_stepping.hpp"
#include "resident_exec.cuh"

namespace cudahull {
namespace resident {
namespace {

__global__ void empty_kernel() {}

// The current device's pace, measured once a process: its peak memory bandwidth from its attributes (two
// transfers a memory clock across the bus), and a launch's and a wait's host time from empty kernels (a
// launch: the mean of 64 queued; a wait: the mean of 16 launches each waited for, less a launch).
HardwarePace measure_device_pace() {
  static const HardwarePace pace = [] {
    HardwarePace p;
    int device = 0, clock_khz = 0, bus_bits = 0;
    if (cudaGetDevice(&device) != cudaSuccess ||
        cudaDeviceGetAttribute(&clock_khz, cudaDevAttrMemoryClockRate, device) != cudaSuccess ||
        cudaDeviceGetAttribute(&bus_bits, cudaDevAttrGlobalMemoryBusWidth, device) != cudaSuccess)
      return p;
    p.bytes_per_ms = 2.0 * clock_khz * (bus_bits / 8.0);  // kHz x bytes = bytes per ms
    using Clock = std::chrono::steady_clock;
    auto ms_since = [](Clock::time_point t0) {
      return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    };
    empty_kernel<<<1, 1>>>();  // the first launch loads the module: not timed
    check(cudaDeviceSynchronize(), "timing a launch");
    auto t0 = Clock::now();
    for (int i = 0; i < 64; ++i)
      empty_kernel<<<1, 1>>>();
    p.launch_ms = ms_since(t0) / 64;
    check(cudaDeviceSynchronize(), "timing a launch");
    t0 = Clock::now();
    for (int i = 0; i < 16; ++i) {
      empty_kernel<<<1, 1>>>();
      check(cudaStreamSynchronize(0), "timing a wait");
    }
    p.wait_ms = std::max(0.0, ms_since(t0) / 16 - p.launch_ms);
    return p;
  }();
  return pace;
}

}  // namespace
}  // namespace resident

template <class Point>
struct ResidentCudaHull<Point>::Impl {
  explicit Impl(const ResidentTuning& tuning) : exec(tuning) {}
  resident::CudaExec exec;
  resident::CudaExec::Buffer<Point> points;
  const std::vector<Point>* host = nullptr;
  const Point* device = nullptr;  // the points run() reads: points.data() or the caller's
  std::size_t count = 0;
  bool given = false;  // upload() or use_device_points() was called
};

template <class Point>
ResidentCudaHull<Point>::ResidentCudaHull(const ResidentTuning& tuning)
    : impl_(std::make_unique<Impl>(tuning)) {}
template <class Point>
ResidentCudaHull<Point>::~ResidentCudaHull() = default;

template <class Point>
void ResidentCudaHull<Point>::upload(const std::vector<Point>& points) {
  if (points.size() >= 0xffffffffu) throw std::invalid_argument("too many points (at most 2^32 - 2)");
  impl_->points.grow(std::max<std::size_t>(points.size(), 1));
  if (!points.empty())
    resident::check(cudaMemcpy(impl_->points.data(), points.data(), points.size() * sizeof(Point),
                               cudaMemcpyHostToDevice),
                    "uploading the points");
  impl_->host = &points;
  impl_->device = impl_->points.data();
  impl_->count = points.size();
  impl_->given = true;
}

template <class Point>
void ResidentCudaHull<Point>::use_device_points(const Point* device_points, std::size_t count) {
  if (count >= 0xffffffffu) throw std::invalid_argument("too many points (at most 2^32 - 2)");
  if (count != 0 && !device_points) throw std::invalid_argument("no device points");
  impl_->host = nullptr;
  impl_->device = device_points;
  impl_->count = count;
  impl_->given = true;
}

template <class Point>
BasicHullMesh<Point> ResidentCudaHull<Point>::run(ResidentStats* stats) {
  if (!impl_->given) throw std::logic_error("ResidentCudaHull::run() before upload() or use_device_points()");
  resident::CudaExec& exec = impl_->exec;
  exec.host_syncs = exec.bytes_to_device = exec.bytes_from_device = 0;
  resident::device_bytes.peak = resident::device_bytes.now;
  ResidentStats local;
  ResidentStats& out = stats ? *stats : local;
  BasicHullMesh<Point> result;
  {
    resident::ResidentHull<Point, resident::CudaExec> hull(exec, impl_->device, impl_->count, impl_->host);
    result = hull.run(out);
  }
  trim_device_pool();
  out.host_syncs = exec.host_syncs;
  out.bytes_to_device = exec.bytes_to_device;
  out.bytes_from_device = exec.bytes_from_device;
  out.device_bytes_peak = resident::device_bytes.peak;
  return result;
}

namespace {
// The stepping engine on the device executor, with the device copy of the points it reads.
template <class Point>
class CudaResidentStepper final : public resident::ResidentStepper<Point, resident::CudaExec> {
  using Base = resident::ResidentStepper<Point, resident::CudaExec>;

 public:
  CudaResidentStepper(const std::vector<Point>& points, const ResidentTuning& tuning)
      : Base(points, "cuda-resident", true, tuning) {}

 protected:
  const Point* upload_points() override {
    const std::vector<Point>& points = *this->points_;
    device_points_.grow(std::max<std::size_t>(points.size(), 1));
    if (!points.empty())
      resident::check(cudaMemcpy(device_points_.data(), points.data(), points.size() * sizeof(Point),
                                 cudaMemcpyHostToDevice),
                      "uploading the points");
    this->exec_.bytes_to_device += points.size() * sizeof(Point);
    return device_points_.data();
  }

 private:
  resident::CudaExec::Buffer<Point> device_points_;
};
}  // namespace

template <class Point>
std::unique_ptr<SteppingEngine> make_resident_cuda_stepping_engine(const std::vector<Point>& points,
                                                                   const ResidentTuning& tuning) {
  if (points.size() >= 0xffffffffu) throw std::invalid_argument("too many points (at most 2^32 - 2)");
  return std::make_unique<CudaResidentStepper<Point>>(points, tuning);
}

HardwarePace device_pace() {
  return resident::measure_device_pace();
}

// The two coordinate types (README, "Precision").
template class ResidentCudaHull<Point3>;
template class ResidentCudaHull<Point3d>;
template std::unique_ptr<SteppingEngine> make_resident_cuda_stepping_engine(const std::vector<Point3>&,
                                                                            const ResidentTuning&);
template std::unique_ptr<SteppingEngine> make_resident_cuda_stepping_engine(const std::vector<Point3d>&,
                                                                            const ResidentTuning&);

}  // namespace cudahull
