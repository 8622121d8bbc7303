// The batch's device memory beyond its passes (batch_cuda.hpp): what the pool keeps after a batch, and the
// result's plumbing for the API (its columns, the copies, the device).
#include <cuda_runtime.h>

#include <algorithm>
#include <atomic>
#include <memory>

#include "batch_shared.cuh"
#include "cudahull/cuda/batch_cuda.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/host_transfer.hpp"

namespace cudahull {
namespace {

// After a batch the pool keeps what it holds, up to this share of the device's memory, for the next batch
// of its size: what the batch used, and what the last batch's result (often alive while the next one runs)
// holds, since mapping it again and handing it back cost a batch about a tenth of its time; keeping what
// the batch used alone left the next result's columns to map again (docs/benchmarks.md, "The measurements
// behind the code's constants"). cudahull::release_device_memory() hands it back at once.
constexpr std::size_t kBatchKeepShare = 16;

}  // namespace

// The current device's memory, asked once a device: cudaMemGetInfo() is a host round trip a batch need not
// pay (docs/benchmarks.md, "The measurements behind the code's constants").  0 where it cannot be read.
static std::size_t device_total_memory() {
  constexpr int kDevices = 64;
  static std::atomic<std::size_t> totals[kDevices];
  int device = 0;
  if (cudaGetDevice(&device) != cudaSuccess || device < 0 || device >= kDevices) {
    cudaGetLastError();
    return 0;
  }
  std::size_t total = totals[device].load(std::memory_order_relaxed);
  if (total == 0) {
    std::size_t free_bytes = 0;
    if (cudaMemGetInfo(&free_bytes, &total) != cudaSuccess) {
      cudaGetLastError();
      return 0;
    }
    totals[device].store(total, std::memory_order_relaxed);
  }
  return total;
}

std::size_t batch_pool_keep() {
  return std::max(kPoolKeep, device_total_memory() / kBatchKeepShare);
}

void trim_batch_pool() {
  trim_device_pool(batch_pool_keep());
}

std::shared_ptr<void> batch_column(std::size_t bytes, const char* what) {
  // No pool trim when it dies (shared_device_array's): the caller's library may free a result's columns one
  // by one, in its own loop; the next batch's trim hands back what they held.
  const auto owner = std::make_shared<DeviceArray<char>>(bytes, kWho, what);
  return std::shared_ptr<void>(owner, owner->get());
}

void copy_to_device(void* device, const void* host, std::size_t bytes) {
  copy_host_to_device(device, host, bytes, kWho, "copying up the hulls");
}

void copy_to_host(void* host, const void* device, std::size_t bytes) {
  copy_device_to_host(host, device, bytes, kWho, "reading back the hulls");
}

void finish_device_work() {
  check(cudaStreamSynchronize(0), "finishing the hulls");
}

int current_cuda_device() {
  int device = 0;
  check(cudaGetDevice(&device), "asking for the device");
  return device;
}

}  // namespace cudahull
