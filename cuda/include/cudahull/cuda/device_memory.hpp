// Device memory for every CUDA path (the resident engine, the CUDA backend, the device points' check and the
// 2-D filter): one allocator, so that the paths share its cache of small blocks and one policy for the
// device's memory pool, and none calls cudaMalloc (which costs the host far more than a cached block) or
// cudaFree (which waits for the whole device).
//
// design:
//   blocks come from the device's default memory pool in stream order (cudaMallocAsync), the pool told to
//     keep what is freed; blocks up to 4 MiB, in power-of-two sizes, are kept in a cache for reuse (64 MiB
//     at most), the rest go back to the pool (cudaFreeAsync)
//   every block in the cache may be used by work enqueued on the legacy default stream: its last use was on
//     that stream, or has finished.  So:
//   - give on the default stream: into the cache at once (the resident engine's path: no wait, no event)
//   - give on another stream: that stream is synchronised first (where cudaFree waited for the whole
//     device before), so the block is idle when it enters the cache
//   - take on the default stream: a cached block as it is
//   - take on another stream: that stream is made to wait for the default stream's work so far (an event,
//     no host wait), which holds every cached block's last use
//   out of memory: the cache is freed and the pool trimmed, then once more; then a DeviceError naming the
//     caller's component
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>

// The design above orders blocks by the one legacy default stream (stream 0 here and in the callers).
#if defined(CUDA_API_PER_THREAD_DEFAULT_STREAM)
#error "device_memory orders a block's reuse after its last use by the one legacy default stream"
#endif

namespace cudahull {

// A block of device memory: its address, its size (at least what was asked for) and its device.
struct DeviceBlock {
  void* ptr = nullptr;
  std::size_t bytes = 0;
  int device = 0;
};

// A block of at least `bytes` on the current device, usable by work on `stream` from now on.  Throws
// DeviceError ("<who>: out of device memory allocating <bytes> for <what> ...").
DeviceBlock take_device_block(std::size_t bytes, cudaStream_t stream, const char* who, const char* what);

// `block` back, its last use enqueued on `stream` (or finished).  Never throws.
void give_device_block(const DeviceBlock& block, cudaStream_t stream) noexcept;

// What the pool keeps of its free memory after a run or a call (trim_device_pool()): the next one of a
// similar size allocates without mapping memory again; the rest goes back to the driver (the process may do
// other things, and cudaFree gave it back at once).
constexpr std::size_t kPoolKeep = std::size_t{256} << 20;

// Hands the current device pool's free memory beyond `keep` bytes back to the driver (after the default
// stream's work, whose frees it waits for); the cache's blocks stay.
void trim_device_pool(std::size_t keep = kPoolKeep);

// Everything the allocator holds on the current device and no array uses (the cache's blocks and the pool's
// free memory), back to the driver, after the default stream's work: for a caller that wants the memory
// for another library (cudahull::release_device_memory()).  Never throws; no device, or one this process's
// cudahull never allocated on: nothing.
void release_device_memory_now();

// trim_device_pool(keep) when it dies: declared before device arrays (in a function or a class), it hands
// what they free back to the driver after them.
class TrimPoolAtEnd {
 public:
  explicit TrimPoolAtEnd(std::size_t keep = kPoolKeep) : keep_(keep) {}
  // Keep at least `bytes` (what a batch used: the next one of its size maps nothing again).
  void keep_at_least(std::size_t bytes) { keep_ = std::max(keep_, bytes); }
  TrimPoolAtEnd(const TrimPoolAtEnd&) = delete;
  TrimPoolAtEnd& operator=(const TrimPoolAtEnd&) = delete;
  ~TrimPoolAtEnd() { trim_device_pool(keep_); }

 private:
  std::size_t keep_;
};

// A device array of `count` elements of T (room for one at least) that owns its block: given back, in
// `stream`'s order, when it dies or is reset (so before `stream` is destroyed).
template <class T>
class DeviceArray {
 public:
  DeviceArray() = default;
  DeviceArray(std::size_t count, const char* who, const char* what, cudaStream_t stream = 0)
      : block_(take_device_block(std::max<std::size_t>(count, 1) * sizeof(T), stream, who, what)),
        count_(count),
        stream_(stream) {}
  DeviceArray(DeviceArray&& other) noexcept { swap(other); }
  DeviceArray& operator=(DeviceArray&& other) noexcept {
    DeviceArray(std::move(other)).swap(*this);
    return *this;
  }
  ~DeviceArray() { reset(); }

  T* get() const { return static_cast<T*>(block_.ptr); }
  std::size_t size() const { return count_; }               // elements asked for
  std::size_t block_bytes() const { return block_.bytes; }  // the block's size (it may hold more)
  void reset() noexcept {
    if (block_.ptr) give_device_block(block_, stream_);
    block_ = {};
    count_ = 0;
  }
  void swap(DeviceArray& other) noexcept {
    std::swap(block_, other.block_);
    std::swap(count_, other.count_);
    std::swap(stream_, other.stream_);
  }

 private:
  DeviceBlock block_;
  std::size_t count_ = 0;
  cudaStream_t stream_ = 0;
};

// The same array (on the default stream), shared: given back with the last pointer, and the pool trimmed.
template <class T>
std::shared_ptr<T> shared_device_array(std::size_t count, const char* who, const char* what) {
  struct Owner {
    Owner(std::size_t count, const char* who, const char* what) : array(count, who, what) {}
    TrimPoolAtEnd trim;
    DeviceArray<T> array;
  };
  const auto owner = std::make_shared<Owner>(count, who, what);
  return std::shared_ptr<T>(owner, owner->array.get());
}

}  // namespace cudahull
