#include "cudahull/cuda/device_info.hpp"

#include <cuda_runtime.h>

#include <string>

namespace cudahull {

namespace {

// "12.4" from the runtime's 12040.
std::string cuda_version(int version) {
  return std::to_string(version / 1000) + "." + std::to_string(version % 1000 / 10);
}

// Why the runtime found no device, in words that do not mislead: without any NVIDIA driver it answers
// cudaErrorInsufficientDriver ("CUDA driver version is insufficient for CUDA runtime version"), which
// reads as if the driver only needed an update.
std::string why_no_device(cudaError_t status) {
  if (status == cudaErrorInsufficientDriver) {
    int driver = 0, runtime = 0;
    cudaDriverGetVersion(&driver);  // 0 where no driver is installed
    cudaRuntimeGetVersion(&runtime);
    if (driver == 0) return "libcuda.so.1, the NVIDIA driver, was not found";
    return "the NVIDIA driver supports CUDA " + cuda_version(driver) + ", older than the CUDA " +
           cuda_version(runtime) + " runtime this build uses: update the driver";
  }
  return cudaGetErrorString(status);
}

}  // namespace

CudaDeviceInfo query_cuda_device() {
  CudaDeviceInfo info;
  int count = 0;
  cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    info.reason = why_no_device(status);
    cudaGetLastError();  // clear the sticky error so later calls are not confused by it
    return info;
  }
  if (count == 0) {
    info.reason = "no CUDA device found";
    return info;
  }
  cudaDeviceProp prop{};
  status = cudaGetDeviceProperties(&prop, 0);
  if (status != cudaSuccess) {
    info.reason = cudaGetErrorString(status);
    return info;
  }
  info.usable = true;
  info.name = prop.name;
  info.total_memory = prop.totalGlobalMem;
  info.compute_major = prop.major;
  info.compute_minor = prop.minor;
  return info;
}

}  // namespace cudahull
