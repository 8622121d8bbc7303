// Copies between pageable host memory (a NumPy array's, a std::vector's) and the current CUDA device, at
// the bus's pace where they are large.
//
// design:
//   cudaMemcpy to or from pageable memory runs at a fraction of the bus's pace: the driver stages it through
//   pinned buffers of its own and copies the host's side on the calling core.  Pinning the caller's memory
//   in place (cudaHostRegister) costs more than the copy it would speed.  So a copy of kStagedFrom bytes or
//   more goes through two pinned staging buffers that the process makes once a device and keeps: the
//   host's side of each chunk is copied on all cores (parallel_memcpy) while the bus carries the other
//   buffer's chunk, both ways.  Smaller copies, copies while another thread holds the buffers, and copies
//   where pinned memory cannot be had take cudaMemcpy, as before.  Either way the copy has landed when the
//   call returns, and it runs on the default stream, after the work queued there.
#pragma once

#include <cstddef>

namespace cudahull {

// The least copy that goes through the staging buffers.
inline constexpr std::size_t kStagedFrom = std::size_t{16} << 20;

// `bytes` from host memory at `host` to the current device's memory at `device`, and back.  Each throws
// DeviceError("<who>: <what>: <error>").
void copy_host_to_device(void* device, const void* host, std::size_t bytes, const char* who,
                         const char* what);
void copy_device_to_host(void* host, const void* device, std::size_t bytes, const char* who,
                         const char* what);

}  // namespace cudahull
