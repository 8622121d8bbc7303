// The CUDA backend's host-side resources (cuda_backend.cu): its errors, its grow-only pinned buffers, and
// the owners of its stream and events.
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>

#include "cuda_errors.hpp"

namespace cudahull {
namespace {

// Errors: every CUDA call is checked; a failure becomes a one-line DeviceError.

constexpr const char* kWho = "CUDA backend";

constexpr CudaCheck check{kWho};

[[noreturn]] void fail_alloc(const char* what, std::size_t bytes, cudaError_t e, bool pinned) {
  throw_out_of_memory(kWho, what, bytes, e, pinned);
}

// Grow-only pinned host buffer (staging for the asynchronous copies).
class PinnedBuffer {
 public:
  PinnedBuffer() = default;
  PinnedBuffer(const PinnedBuffer&) = delete;
  PinnedBuffer& operator=(const PinnedBuffer&) = delete;
  ~PinnedBuffer() { cudaFreeHost(ptr_); }

  void reserve(std::size_t bytes, const char* what) {
    if (bytes <= capacity_) return;
    bytes = std::max(bytes, capacity_ + capacity_ / 2);
    check(cudaFreeHost(ptr_), "freeing a pinned buffer");
    ptr_ = nullptr;
    capacity_ = 0;
    void* p = nullptr;
    const cudaError_t e = cudaMallocHost(&p, bytes);
    if (e != cudaSuccess) fail_alloc(what, bytes, e, true);
    ptr_ = static_cast<unsigned char*>(p);
    capacity_ = bytes;
  }
  unsigned char* get() const { return ptr_; }

 private:
  unsigned char* ptr_ = nullptr;
  std::size_t capacity_ = 0;
};

// Owners of the stream and the events, so that a constructor that throws half way leaks none: Release runs
// on the handle once it is set.
template <class Handle, void (*Release)(Handle)>
struct Owned {
  Handle handle = nullptr;
  Owned() = default;
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() {
    if (handle != nullptr) Release(handle);
  }
};
void release_stream(cudaStream_t stream) {
  cudaStreamSynchronize(stream);
  cudaStreamDestroy(stream);
}
void release_event(cudaEvent_t event) {
  cudaEventDestroy(event);
}
using Stream = Owned<cudaStream_t, release_stream>;
using Event = Owned<cudaEvent_t, release_event>;

}  // namespace
}  // namespace cudahull
