// The allocator of device_memory.hpp (design there): the cache of small blocks, the stream ordering of their
// reuse, and the policy of the device's default memory pool.
#include "cudahull/cuda/device_memory.hpp"

#include <cstdint>
#include <map>
#include <mutex>
#include <set>
#include <utility>
#include <vector>

#include "cuda_errors.hpp"

namespace cudahull {
namespace {

// Small device blocks kept for reuse between buffers and runs (a caching allocator, as PyTorch's, CuPy's and
// CUB's): a cudaMallocAsync costs the host microseconds even from a warm pool (docs/benchmarks.md,
// "Measurements behind the code"), and a resident run grows some 30 buffers, most of them small.  Blocks up
// to kLargest bytes, in power-of-two sizes, go back to the cache when their owner grows or dies and are
// taken again in stream order (device_memory.hpp: every cached block is ordered on the default stream); the
// cache holds at most kKeep bytes and frees what is beyond.  Larger blocks are allocated and freed in stream
// order.  It lives until the process ends (a program that resets the device with blocks in it must not use
// the CUDA paths again), and a trim of the pool leaves what it holds in place.
class BlockCache {
 public:
  static constexpr std::size_t kSmallest = 256, kLargest = std::size_t{4} << 20,
                               kKeep = std::size_t{64} << 20;

  DeviceBlock take(std::size_t bytes, cudaStream_t stream, const char* who, const char* what) {
    DeviceBlock block;
    cudaGetDevice(&block.device);
    block.bytes = bytes;
    if (bytes <= kLargest) {
      block.bytes = kSmallest;
      while (block.bytes < bytes)
        block.bytes *= 2;
      if ((block.ptr = cached(block.device, block.bytes))) {
        if (stream != 0) wait_for_default_stream(block.device, stream);
        return block;
      }
    }
    keep_freed_memory(block.device);
    cudaError_t e = cudaMallocAsync(&block.ptr, block.bytes, stream);
    if (e != cudaSuccess) {  // what the cache holds may be what is missing: back to the driver, then again
      cudaGetLastError();
      release(block.device);
      cudaMemPool_t pool = nullptr;
      if (cudaStreamSynchronize(0) == cudaSuccess &&
          (stream == 0 || cudaStreamSynchronize(stream) == cudaSuccess) &&
          cudaDeviceGetDefaultMemPool(&pool, block.device) == cudaSuccess)
        cudaMemPoolTrimTo(pool, 0);
      cudaGetLastError();
      e = cudaMallocAsync(&block.ptr, block.bytes, stream);
    }
    if (e != cudaSuccess) throw_out_of_memory(who, what, bytes, e);
    return block;
  }

  // The cache's blocks of `device` (the current one) back to the pool; whether this allocator ever took a
  // block there (if not, nothing of cudahull's is in its pool).
  bool release_cached(int device) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (pools_kept_.count(device) == 0) return false;
    }
    release(device);
    return true;
  }

  void give(const DeviceBlock& block, cudaStream_t stream) noexcept {
    // Another stream's block enters the cache idle (its stream waited for here, as cudaFree waited for the
    // whole device before); the default stream's in its order, with no wait.
    if (block.bytes <= kLargest && (stream == 0 || cudaStreamSynchronize(stream) == cudaSuccess)) {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (kept_ + block.bytes <= kKeep) {
        free_[{block.device, block.bytes}].push_back(block.ptr);
        kept_ += block.bytes;
        return;
      }
    }
    if (cudaFreeAsync(block.ptr, stream) != cudaSuccess) cudaGetLastError();
  }

 private:
  // A cached block of `size` bytes on `device`, or null.
  void* cached(int device, std::size_t size) {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::vector<void*>& list = free_[{device, size}];
    if (list.empty()) return nullptr;
    void* p = list.back();
    list.pop_back();
    kept_ -= size;
    return p;
  }

  // Work on `stream` from now on runs after `device`'s (the current one's) default stream's work so far,
  // which holds every cached block's last use.  One event a device, recorded anew each time: a wait takes the
  // latest record, and one by another thread in between is later on the same stream, so it covers this one.
  void wait_for_default_stream(int device, cudaStream_t stream) {
    cudaEvent_t event = nullptr;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      cudaEvent_t& made = events_[device];
      if (!made && cudaEventCreateWithFlags(&made, cudaEventDisableTiming) != cudaSuccess) made = nullptr;
      event = made;
    }
    if (!event || cudaEventRecord(event, 0) != cudaSuccess ||
        cudaStreamWaitEvent(stream, event, 0) != cudaSuccess) {
      cudaGetLastError();
      cudaStreamSynchronize(0);  // no event: the host waits instead
    }
  }

  // The device's default pool, told once to keep what is freed (the default threshold hands it back to the
  // driver at every synchronisation, and the next allocation would map it again).
  void keep_freed_memory(int device) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!pools_kept_.insert(device).second) return;
    }
    cudaMemPool_t pool = nullptr;
    if (cudaDeviceGetDefaultMemPool(&pool, device) == cudaSuccess) {
      std::uint64_t keep = UINT64_MAX;
      cudaMemPoolSetAttribute(pool, cudaMemPoolAttrReleaseThreshold, &keep);
    }
    cudaGetLastError();
  }

  // Everything held for `device` (the current one), freed.
  void release(int device) {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [key, list] : free_) {
      if (key.first != device) continue;
      for (void* p : list) {
        cudaFreeAsync(p, 0);
        kept_ -= key.second;
      }
      list.clear();
    }
  }

  std::mutex mutex_;
  std::map<std::pair<int, std::size_t>, std::vector<void*>> free_;  // (device, size) -> blocks
  std::size_t kept_ = 0;
  std::map<int, cudaEvent_t> events_;  // per device: wait_for_default_stream()'s event
  std::set<int> pools_kept_;           // the devices whose pool keep_freed_memory() has told
};

BlockCache& block_cache() {
  static BlockCache* cache = new BlockCache;  // never destroyed: the runtime may be gone at exit
  return *cache;
}

}  // namespace

DeviceBlock take_device_block(std::size_t bytes, cudaStream_t stream, const char* who, const char* what) {
  return block_cache().take(bytes, stream, who, what);
}

void give_device_block(const DeviceBlock& block, cudaStream_t stream) noexcept {
  block_cache().give(block, stream);
}

void release_device_memory_now() {
  int device = 0;
  if (cudaGetDevice(&device) != cudaSuccess) {
    cudaGetLastError();
    return;
  }
  // A process that never allocated here has nothing to give back (and a trim's synchronisation would
  // create the device's context).
  if (block_cache().release_cached(device)) trim_device_pool(0);
}

void trim_device_pool(std::size_t keep) {
  int device = 0;
  cudaMemPool_t pool = nullptr;
  if (cudaStreamSynchronize(0) == cudaSuccess && cudaGetDevice(&device) == cudaSuccess &&
      cudaDeviceGetDefaultMemPool(&pool, device) == cudaSuccess)
    cudaMemPoolTrimTo(pool, keep);
  cudaGetLastError();
}

}  // namespace cudahull
