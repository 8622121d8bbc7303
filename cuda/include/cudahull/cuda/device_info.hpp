// What CUDA devices this process can use.  Never throws: a machine without a driver or a GPU simply has
// no usable device, which is what `--backend auto` needs to know to fall back to the CPU.
#pragma once

#include <string>

namespace cudahull {

struct CudaDeviceInfo {
  bool usable = false;
  std::string name;    // e.g. "NVIDIA H100 80GB HBM3"
  std::string reason;  // why not usable, e.g. "no CUDA-capable device is detected"
  std::size_t total_memory = 0;
  int compute_major = 0, compute_minor = 0;
};

CudaDeviceInfo query_cuda_device();

}  // namespace cudahull
