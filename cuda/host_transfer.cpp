// Large host copies through pinned staging buffers (design: host_transfer.hpp).
#include "cudahull/cuda/host_transfer.hpp"

#include <cuda_runtime.h>

#include <algorithm>
#include <mutex>

#include "cuda_errors.hpp"
#include "cudahull/parallel.hpp"

namespace cudahull {

namespace {

constexpr std::size_t kStageBytes = std::size_t{8} << 20;   // a chunk: one staging buffer
constexpr std::size_t kCopyBlock = std::size_t{512} << 10;  // a worker's share of a chunk's host side
constexpr int kDevices = 64;

// A device's two staging buffers, and for each the event of the last copy that used it (events belong to a
// device, so the staging is made a device).  Never freed: the process's, as the driver's own staging is.
struct Staging {
  void* buffer[2] = {nullptr, nullptr};
  cudaEvent_t used[2] = {nullptr, nullptr};
  bool unavailable = false;  // pinned memory could not be had: cudaMemcpy from then on
};

std::mutex staging_mutex;  // one staged copy at a time; the others take cudaMemcpy
Staging stagings[kDevices];

// The current device's staging, made on first use; nullptr where it cannot be.  Under staging_mutex.
Staging* current_staging() {
  int device = 0;
  if (cudaGetDevice(&device) != cudaSuccess || device < 0 || device >= kDevices) {
    cudaGetLastError();
    return nullptr;
  }
  Staging& staging = stagings[device];
  if (staging.buffer[1] != nullptr || staging.unavailable) return staging.unavailable ? nullptr : &staging;
  for (int k = 0; k < 2; ++k) {
    if (cudaMallocHost(&staging.buffer[k], kStageBytes) != cudaSuccess ||
        cudaEventCreateWithFlags(&staging.used[k], cudaEventDisableTiming) != cudaSuccess) {
      cudaGetLastError();
      staging.unavailable = true;
      return nullptr;
    }
  }
  return &staging;
}

// The staging for a copy of `bytes`, with the lock that holds it; nullptr for cudaMemcpy.
Staging* staging_for(std::size_t bytes, std::unique_lock<std::mutex>& lock) {
  if (bytes < kStagedFrom) return nullptr;
  lock = std::unique_lock<std::mutex>(staging_mutex, std::try_to_lock);
  return lock.owns_lock() ? current_staging() : nullptr;
}

}  // namespace

void copy_host_to_device(void* device, const void* host, std::size_t bytes, const char* who,
                         const char* what) {
  const CudaCheck check{who};
  std::unique_lock<std::mutex> lock;
  Staging* staging = staging_for(bytes, lock);
  if (staging == nullptr) {
    if (bytes != 0) check(cudaMemcpy(device, host, bytes, cudaMemcpyHostToDevice), what);
    return;
  }
  const auto* from = static_cast<const unsigned char*>(host);
  auto* to = static_cast<unsigned char*>(device);
  for (std::size_t at = 0, chunk = 0; at < bytes; at += kStageBytes, ++chunk) {
    const int k = static_cast<int>(chunk & 1);
    const std::size_t size = std::min(kStageBytes, bytes - at);
    check(cudaEventSynchronize(staging->used[k]), what);  // the bus has taken this buffer's last chunk
    parallel_memcpy(staging->buffer[k], from + at, size, kCopyBlock);
    check(cudaMemcpyAsync(to + at, staging->buffer[k], size, cudaMemcpyHostToDevice, 0), what);
    check(cudaEventRecord(staging->used[k], 0), what);
  }
  check(cudaStreamSynchronize(0), what);
}

void copy_device_to_host(void* host, const void* device, std::size_t bytes, const char* who,
                         const char* what) {
  const CudaCheck check{who};
  std::unique_lock<std::mutex> lock;
  Staging* staging = staging_for(bytes, lock);
  if (staging == nullptr) {
    if (bytes != 0) check(cudaMemcpy(host, device, bytes, cudaMemcpyDeviceToHost), what);
    return;
  }
  const auto* from = static_cast<const unsigned char*>(device);
  auto* to = static_cast<unsigned char*>(host);
  const std::size_t chunks = (bytes + kStageBytes - 1) / kStageBytes;
  // A failed copy can leave a chunk in flight: both buffers free before the first is written.
  for (int k = 0; k < 2; ++k)
    check(cudaEventSynchronize(staging->used[k]), what);
  auto start = [&](std::size_t chunk) {
    const int k = static_cast<int>(chunk & 1);
    const std::size_t at = chunk * kStageBytes;
    check(cudaMemcpyAsync(staging->buffer[k], from + at, std::min(kStageBytes, bytes - at),
                          cudaMemcpyDeviceToHost, 0),
          what);
    check(cudaEventRecord(staging->used[k], 0), what);
  };
  start(0);
  for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
    // The next chunk crosses the bus into the other buffer (its last chunk already copied out) while this
    // one is copied out on all cores.
    if (chunk + 1 < chunks) start(chunk + 1);
    const int k = static_cast<int>(chunk & 1);
    const std::size_t at = chunk * kStageBytes;
    check(cudaEventSynchronize(staging->used[k]), what);
    parallel_memcpy(to + at, staging->buffer[k], std::min(kStageBytes, bytes - at), kCopyBlock);
  }
}

}  // namespace cudahull
