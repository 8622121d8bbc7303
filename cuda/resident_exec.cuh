// The resident engine's device executor: the operations of cudahull/resident/resident_ops.hpp as
// kernels, one thread per face or point; prefix sums from CUB.  A prefix sum brings its total back (4
// bytes, one wait) where the host sizes the next step by it (exclusive_scan), or not at all (scan: the
// operation after it writes the total into the state, which the host reads once an iteration).
#pragma once

#include <cuda_runtime.h>

#include <thrust/iterator/counting_iterator.h>
#include <algorithm>
#include <array>
#include <cstring>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_select.cuh>
#include <type_traits>
#include <unordered_map>
#include <utility>

#include "cuda_errors.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/host_transfer.hpp"
#include "cudahull/resident/finish.hpp"
#include "cudahull/resident/iteration.hpp"
#include "cudahull/tuning.hpp"
#include "resident_kernels.cuh"
#include "teams.cuh"

namespace cudahull {
namespace resident {
namespace {

constexpr CudaCheck check{"resident engine"};

// Device memory the engine holds now and at most (the points included; whole blocks, see device_memory.hpp,
// whose cached blocks are not counted), for the stats.
struct DeviceBytes {
  std::size_t now = 0, peak = 0;
  void add(std::size_t bytes) {
    now += bytes;
    peak = std::max(peak, now);
  }
};
DeviceBytes device_bytes;

unsigned blocks_for(std::size_t n) {
  return static_cast<unsigned>((n + kBlock - 1) / kBlock);
}

}  // namespace

struct CudaExec {
  explicit CudaExec(const ResidentTuning& tuning = {}) : tuning(tuning) {}
  // A buffer on the default stream (device_memory.hpp: a cached block, or the pool's, which keeps freed
  // memory): growing between iterations neither waits for the device nor returns memory to the driver.
  template <class T>
  class Buffer {
   public:
    Buffer() = default;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    ~Buffer() { release(); }
    void grow(std::size_t n, std::size_t keep = 0) {
      if (n <= capacity_) return;
      if (n * sizeof(T) <= array_.block_bytes()) {  // the block has room (its size is a power of two)
        capacity_ = n;
        return;
      }
      if (keep == 0) release();  // nothing to copy: the old block goes first, so both are never held
      DeviceArray<T> fresh(n, "resident engine", "a buffer");
      if (keep > 0 && array_.get())
        check(cudaMemcpyAsync(fresh.get(), array_.get(), std::min(keep, capacity_) * sizeof(T),
                              cudaMemcpyDeviceToDevice, 0),
              "growing a buffer");
      device_bytes.add(fresh.block_bytes());
      release();
      array_ = std::move(fresh);
      capacity_ = n;
    }
    T* data() { return array_.get(); }
    std::size_t capacity() const { return capacity_; }
    // Back to the cache (or the pool), empty.
    void release() {
      device_bytes.now -= array_.block_bytes();
      array_.reset();
      capacity_ = 0;
    }
    void swap(Buffer& other) {
      array_.swap(other.array_);
      std::swap(capacity_, other.capacity_);
    }

   private:
    DeviceArray<T> array_;
    std::size_t capacity_ = 0;  // elements asked for (the block's bytes are what device_bytes counts)
  };

  template <class Op>
  void for_each(std::size_t n, const Op& op) {
    if (n == 0) return;
    for_each_kernel<<<blocks_for(n), kBlock>>>(n, op);
    ++launches;
    check(cudaGetLastError(), "launching a kernel");
  }
  template <class Op>
  void segmented_max(std::size_t n, const Op& op) {
    if (n == 0) return;
    segmented_max_kernel<<<blocks_for(n), kBlock>>>(static_cast<u32>(n), op);
    ++launches;
    check(cudaGetLastError(), "launching the furthest-point kernel");
  }
  template <class KeyOp>
  u64 reduce_max(std::size_t n, const KeyOp& key) {
    scalar64_.grow(1);
    check(cudaMemset(scalar64_.data(), 0, sizeof(u64)), "clearing a reduction");
    const unsigned blocks = std::max(1u, std::min(blocks_for(n), 4096u));
    reduce_max_kernel<<<blocks, kBlock>>>(n, key, scalar64_.data());
    ++launches;
    check(cudaGetLastError(), "launching a reduction");
    u64 out = 0;
    read(&out, scalar64_.data(), 1);
    return out;
  }
  // `meanwhile()` runs on the host while the device reduces (work that does not need the result).
  template <int K, class KeysOp, class Meanwhile>
  std::array<u64, K> reduce_max_many(std::size_t n, const KeysOp& keys, Meanwhile&& meanwhile) {
    scalar64_.grow(K);
    check(cudaMemsetAsync(scalar64_.data(), 0, K * sizeof(u64), 0), "clearing a reduction");
    const unsigned blocks = std::max(1u, std::min(blocks_for(n), 512u));
    reduce_max_many_kernel<K><<<blocks, kBlock>>>(n, keys, scalar64_.data());
    ++launches;
    check(cudaGetLastError(), "launching a reduction");
    meanwhile();
    std::array<u64, K> out{};
    read(out.data(), scalar64_.data(), K);
    return out;
  }
  // The indices i < n with pred(i), in order, into out; returns how many (one wait).  The predicate runs
  // in a kernel of its own, a byte per point (inside CUB's select it ran several times slower).
  template <class Pred>
  u32 select_if(std::size_t n, const Pred& pred, u32* out) {
    if (n == 0) return 0;
    select_flags_.grow(n);
    flag_kernel<<<blocks_for(n), kBlock>>>(n, pred, select_flags_.data());
    ++launches;
    check(cudaGetLastError(), "launching a select");
    const thrust::counting_iterator<u32> ids(0);
    scalar32_.grow(1);
    std::size_t bytes = 0;
    check(cub::DeviceSelect::Flagged(nullptr, bytes, ids, select_flags_.data(), out, scalar32_.data(),
                                     static_cast<std::int64_t>(n)),
          "sizing a select");
    scratch_.grow(bytes);
    ++launches;
    check(cub::DeviceSelect::Flagged(scratch_.data(), bytes, ids, select_flags_.data(), out, scalar32_.data(),
                                     static_cast<std::int64_t>(n)),
          "a select");
    u32 count = 0;
    read(&count, scalar32_.data(), 1);
    return count;
  }
  // The distinct values of in[0..n), all below `bound`, ascending, into out, and how many into *count
  // (no wait).  A radix sort over the bits `bound` needs, into scratch, then the repeats dropped.
  void sort_unique_to(const u32* in, std::size_t n, u32* out, u32* scratch, std::size_t bound, u32* count) {
    if (n == 0) {
      fill(count, 1, u32{0});
      return;
    }
    int bits = 1;
    while (bits < 32 && (std::size_t{1} << bits) < bound)
      ++bits;
    std::size_t sort_bytes = 0, unique_bytes = 0;
    const auto items = static_cast<std::int64_t>(n);
    check(cub::DeviceRadixSort::SortKeys(nullptr, sort_bytes, in, scratch, items, 0, bits), "sizing a sort");
    check(cub::DeviceSelect::Unique(nullptr, unique_bytes, scratch, out, count, items), "sizing a unique");
    scratch_.grow(std::max(sort_bytes, unique_bytes));
    ++launches;
    check(cub::DeviceRadixSort::SortKeys(scratch_.data(), sort_bytes, in, scratch, items, 0, bits), "a sort");
    ++launches;
    check(cub::DeviceSelect::Unique(scratch_.data(), unique_bytes, scratch, out, count, items), "a unique");
  }
  // The same, the total not brought back.
  void scan(const u32* in, u32* out, std::size_t n) {
    if (n == 0) return;
    std::size_t bytes = 0;
    check(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, static_cast<std::int64_t>(n)),
          "sizing a scan");
    scratch_.grow(bytes);
    ++launches;
    check(cub::DeviceScan::ExclusiveSum(scratch_.data(), bytes, in, out, static_cast<std::int64_t>(n)),
          "a scan");
  }
  // The finish of a mesh of at most kFinishFaces faces in one launch (finish_small_kernel; ids below
  // `bound`): out = [faults, vertices, renumbered corners, vertex list], read back at once by the caller.
  static constexpr int kFinishItems = 12;
  static constexpr std::size_t kFinishFaces = kSmallFinishFaces;
  static_assert(kOneBlockThreads * kFinishItems >= 3 * kFinishFaces, "one block sorts every corner");
  template <class Point>
  void finish_small(const MeshView<Point>& m, std::size_t faces, std::size_t bound, u32* out) {
    int bits = 1;
    while (bits < 32 && (std::size_t{1} << bits) < bound)
      ++bits;
    finish_small_kernel<Point, kOneBlockThreads, kFinishItems>
        <<<1, kOneBlockThreads>>>(m, static_cast<u32>(faces), bits, out);
    ++launches;
    check(cudaGetLastError(), "launching the finish");
  }
  u32 exclusive_scan(const u32* in, u32* out, std::size_t n) {
    if (n == 0) return 0;
    scan(in, out, n);
    scalar32_.grow(1);
    scan_total_kernel<<<1, 1>>>(in, out, n, scalar32_.data());
    ++launches;
    check(cudaGetLastError(), "launching a scan total");
    u32 total = 0;
    read(&total, scalar32_.data(), 1);
    return total;
  }
  u32 select(const u32* flags, u32* rank, u32* list, std::size_t n) {
    const u32 count = exclusive_scan(flags, rank, n);
    if (count != 0) {
      scatter_selected_kernel<<<blocks_for(n), kBlock>>>(flags, rank, list, n);
      ++launches;
      check(cudaGetLastError(), "launching a select");
    }
    return count;
  }
  template <class T>
  void fill(T* at, std::size_t n, T value) {
    if (n == 0) return;
    fill_kernel<<<blocks_for(n), kBlock>>>(at, n, value);
    ++launches;
    check(cudaGetLastError(), "launching a fill");
  }
  template <class T>
  void upload(T* to, const T* from, std::size_t n) {
    check(cudaMemcpy(to, from, n * sizeof(T), cudaMemcpyHostToDevice), "an upload");
    bytes_to_device += n * sizeof(T);
  }
  template <class T>
  void download(T* to, const T* from, std::size_t n) {
    read(to, from, n);
  }

  static constexpr bool kDeviceLoop = true;  // whole iterations of a small mesh in one launch
  // Up to tuning.loop_points points left on a mesh of up to tuning.loop_faces faces (or loop_few_points_faces
  // with no more points left than faces: loop_goes_on()), the driver runs the iterations as a device loop
  // (one block: each pass takes the points and faces a few at a time per thread); meshes of up to
  // tuning.one_block_faces faces run their rounds in one block (cudahull/tuning.hpp).
  ResidentTuning tuning;

  // The iteration's phases (iteration.hpp): a device loop in one block; otherwise a cooperative grid for
  // each range of phases (the marks; the split and the rounds, in one block for a small mesh; the routing
  // and the compaction), launched one after another with no wait.  The state stays on the device.
  template <class Point, class Log>
  void iterations(IterationBuffers<Point, Log> b, IterationLaunch launch, bool loop) {
    // A bit per face and the wins before each word (rounds.hpp).
    const std::size_t words = std::size_t{launch.face_capacity} / 32 + 1;
    win_mask_.grow(2 * words);
    b.win_mask = win_mask_.data();
    b.word_rank = win_mask_.data() + words;
    if (loop) {
      launch_phases<Point, NoLog, AllPhases, kOneBlockThreads, true>(strip_log(b), launch, 1);
      return;
    }
    // A thread per face or point up to what fits at once; the rounds of a small mesh in one block (a grid
    // barrier costs more the more blocks wait at it).  The face count is on the device: half the capacity
    // stands for it (a small mesh is sized for every face refining).
    const std::size_t faces = launch.face_capacity / 2, items = std::max<std::size_t>(faces, launch.active);
    for_each_phase_range(launch, [&](auto range, const IterationLaunch& part) {
      using Range = decltype(range);
      if constexpr (std::is_same_v<Range, RoundPhases>) {
        if (faces <= tuning.one_block_faces) {
          launch_phases<Point, Log, Range, kOneBlockThreads, true>(b, part, 1);
        } else {
          launch_phases<Point, Log, Range, kBlock, false>(b, part, blocks_for(faces));
        }
      } else {
        launch_phases<Point, NoLog, Range, kBlock, false>(strip_log(b), part, blocks_for(items));
      }
    });
  }

  std::uint64_t host_syncs = 0, bytes_to_device = 0, bytes_from_device = 0;
  std::uint64_t launches = 0;  // kernels launched

 private:
  // Small reads go through a pinned buffer (one a thread, made once: pinning is slow): a read of a few bytes
  // after a kernel is faster from pinned memory than from pageable (docs/benchmarks.md, "Measurements behind
  // the code").
  class PinnedStage {
   public:
    static constexpr std::size_t kBytes = std::size_t{64} << 10;
    PinnedStage() = default;
    PinnedStage(const PinnedStage&) = delete;
    PinnedStage& operator=(const PinnedStage&) = delete;
    ~PinnedStage() {
      if (ptr_) cudaFreeHost(ptr_);
    }
    void* get() {
      if (!ptr_ && !failed_ && cudaMallocHost(&ptr_, kBytes) != cudaSuccess) {
        ptr_ = nullptr;
        failed_ = true;  // pageable reads then, as before
        cudaGetLastError();
      }
      return ptr_;
    }

   private:
    void* ptr_ = nullptr;
    bool failed_ = false;
  };
  static PinnedStage& pinned_stage() {
    thread_local PinnedStage stage;
    return stage;
  }
  template <class T>
  void read(T* to, const T* from, std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (n == 0) {
    } else if (void* staged = bytes <= PinnedStage::kBytes ? pinned_stage().get() : nullptr) {
      check(cudaMemcpyAsync(staged, from, bytes, cudaMemcpyDeviceToHost, 0), "a read-back");
      check(cudaStreamSynchronize(0), "a read-back");
      std::memcpy(static_cast<void*>(to), staged, bytes);
    } else {
      // Large ones (a finished sphere's mesh) through the process's staging, copied out on all cores.
      copy_device_to_host(to, from, bytes, "resident engine", "a read-back");
    }
    ++host_syncs;
    bytes_from_device += n * sizeof(T);
  }
  template <class Point, class Log>
  static IterationBuffers<Point, NoLog> strip_log(const IterationBuffers<Point, Log>& b) {
    if constexpr (std::is_same_v<Log, NoLog>) {
      return b;
    } else {
      IterationBuffers<Point, NoLog> out{};
      out.m = b.m;
      out.fv_spare = b.fv_spare;
      out.fn_spare = b.fn_spare;
      out.index = b.index;
      out.face = b.face;
      out.index_spare = b.index_spare;
      out.face_spare = b.face_spare;
      out.keep = b.keep;
      out.point_rank = b.point_rank;
      out.flags = b.flags;
      out.face_rank = b.face_rank;
      out.revisit = b.revisit;
      out.list = b.list;
      out.win_mask = b.win_mask;
      out.word_rank = b.word_rank;
      out.extreme = b.extreme;
      out.claim = b.claim;
      out.cands = b.cands;
      out.st = b.st;
      out.first_list = b.first_list;
      return out;
    }
  }
  // One launch of iteration_kernel: one block, or a cooperative grid of at most the blocks that fit at
  // once (found once a kernel).
  template <class Point, class Log, class Range, int Block, bool kOneBlock>
  void launch_phases(const IterationBuffers<Point, Log>& b, IterationLaunch launch, unsigned wanted) {
    auto* kernel = iteration_kernel<Point, Log, Range, Block, kOneBlock>;
    if constexpr (kOneBlock) {
      kernel<<<1, Block>>>(b, nullptr, launch);
      ++launches;
      check(cudaGetLastError(), "launching an iteration");
      return;
    }
    unsigned& fit = resident_blocks_[reinterpret_cast<const void*>(kernel)];
    if (fit == 0) fit = blocks_that_fit(kernel, Block, "resident engine");
    const unsigned blocks = std::max(1u, std::min(fit, wanted));
    block_offset_.grow(blocks + 1);
    IterationBuffers<Point, Log> args_b = b;
    u32* offsets = block_offset_.data();
    void* args[] = {&args_b, &offsets, &launch};
    ++launches;
    check(cudaLaunchCooperativeKernel(reinterpret_cast<void*>(kernel), blocks, Block, args, 0, nullptr),
          "launching an iteration");
  }

  Buffer<u64> scalar64_;
  Buffer<u32> scalar32_;
  Buffer<unsigned char> scratch_;
  Buffer<u32> block_offset_, win_mask_;
  Buffer<unsigned char> select_flags_;
  std::unordered_map<const void*, unsigned> resident_blocks_;  // per cooperative kernel: the blocks that fit
};

}  // namespace resident
}  // namespace cudahull
