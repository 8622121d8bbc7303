// The resident engine's device executor: the operations of cudahull/resident/resident_ops.hpp as
// kernels, one thread per face or point; prefix sums from CUB.  A prefix sum brings its total back (4
// bytes, one wait) where the host sizes the next step by it (exclusive_scan), or not at all (scan: the
// operation after it writes the total into the state, which the host reads once an iteration).
#include <cuda_runtime.h>

#include <cooperative_groups.h>

#include <thrust/iterator/counting_iterator.h>
#include <chrono>
#include <cstring>
#include <cub/block/block_radix_sort.cuh>
#include <cub/block/block_scan.cuh>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_select.cuh>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cuda_errors.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/resident_cuda.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/resident/resident_driver.hpp"
#include "cudahull/resident/resident_stepping.hpp"
#include "teams.cuh"

namespace cudahull {
namespace resident {
namespace {

constexpr CudaCheck check{"resident engine"};

constexpr int kBlock = 256;
constexpr int kOneBlockThreads = 512;  // the rounds of a small mesh (fused_rounds_kernel)

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

template <class Op>
__global__ void for_each_kernel(std::size_t n, Op op) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) op(i);
}

template <class KeyOp>
__global__ void reduce_max_kernel(std::size_t n, KeyOp key, u64* out) {
  u64 best = 0;
  for (std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x; i < n;
       i += static_cast<std::size_t>(gridDim.x) * blockDim.x) {
    const u64 k = key(i);
    best = k > best ? k : best;
  }
  for (int offset = 16; offset > 0; offset /= 2) {
    const u64 other = __shfl_down_sync(0xffffffffu, best, offset);
    best = other > best ? other : best;
  }
  if ((threadIdx.x & 31) == 0 && best != 0)
    atomicMax(reinterpret_cast<unsigned long long*>(out), static_cast<unsigned long long>(best));
}

// K maxima at once (one pass over the points for section 3.1's directions): each block reduces every key
// (warps, then shared memory), then one atomic per key and block: few blocks, so that the atomics on the K
// results do not queue.
template <int K, class KeysOp>
__global__ void __launch_bounds__(kBlock) reduce_max_many_kernel(std::size_t n, KeysOp keys, u64* out) {
  __shared__ u64 per_warp[kBlock / 32][K];
  u64 best[K] = {};
  u64 mine[K];
  for (std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x; i < n;
       i += static_cast<std::size_t>(gridDim.x) * blockDim.x) {
    keys(i, mine);
#pragma unroll
    for (int k = 0; k < K; ++k)
      best[k] = mine[k] > best[k] ? mine[k] : best[k];
  }
#pragma unroll
  for (int k = 0; k < K; ++k) {
    u64 b = best[k];
    for (int offset = 16; offset > 0; offset /= 2) {
      const u64 other = __shfl_down_sync(0xffffffffu, b, offset);
      b = other > b ? other : b;
    }
    if ((threadIdx.x & 31) == 0) per_warp[threadIdx.x / 32][k] = b;
  }
  __syncthreads();
  if (threadIdx.x < K) {
    u64 b = 0;
    for (int w = 0; w < kBlock / 32; ++w)
      b = per_warp[w][threadIdx.x] > b ? per_warp[w][threadIdx.x] : b;
    if (b != 0)
      atomicMax(reinterpret_cast<unsigned long long*>(out + threadIdx.x), static_cast<unsigned long long>(b));
  }
}

__global__ void scan_total_kernel(const u32* in, const u32* out, std::size_t n, u32* total) {
  *total = out[n - 1] + in[n - 1];
}

__global__ void scatter_selected_kernel(const u32* flags, const u32* rank, u32* list, std::size_t n) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n && flags[i]) list[rank[i]] = static_cast<u32>(i);
}

template <class Pred>
__global__ void flag_kernel(std::size_t n, Pred pred, unsigned char* flags) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) flags[i] = pred(static_cast<u32>(i)) ? 1 : 0;
}

template <class T>
__global__ void fill_kernel(T* at, std::size_t n, T value) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) at[i] = value;
}

// Per segment the largest key (the records' furthest points).
template <class Op>
__global__ void segmented_max_kernel(u32 n, Op op) {
  BlockTeam<kBlock>::max_by_warps(blockIdx.x * kBlock + threadIdx.x, gridDim.x * kBlock, n, op);
}

// The iteration's phases (iteration.hpp) in one launch: one block (a small mesh with few points: whole
// iterations, the device loop; or the rounds of a small mesh), whose barrier is __syncthreads(), or a
// cooperative grid, whose barrier is the grid's.  `Range`: the phases compiled in (a grid runs a range a
// launch, each with the registers of its own phases).
template <class Point, class Log, class Range, int Block, bool kOneBlock>
__global__ void __launch_bounds__(Block)
    iteration_kernel(IterationBuffers<Point, Log> b, u32* block_offset, IterationLaunch launch) {
  if constexpr (kOneBlock) {
    resident_iterations(BlockTeam<Block>{{}, b.st}, b, launch, Range{});
  } else {
    resident_iterations(GridTeam<Block>{{}, b.st, block_offset}, b, launch, Range{});
  }
}

// The driver's finish() of a small mesh (3 * faces <= Block * Items corners) in one block, for one read:
// out = [faults, vertices, the corners renumbered (3 * faces), the vertex list (ascending)].  The faults are
// counted (CountFaults), the corners sorted (a block radix sort over the bits of ids below `bound`), the
// distinct ones listed, and each corner renumbered by bisection in that list, in shared memory.  The same
// result as the general path's CUB sort and select.
template <class Point, int Block, int Items>
__global__ void __launch_bounds__(Block)
    finish_small_kernel(MeshView<Point> m, u32 faces, int bits, u32* out) {
  using Sort = cub::BlockRadixSort<u32, Block, Items>;
  using Scan = cub::BlockScan<u32, Block>;
  // The sort's and the scan's storage and the sorted corners, one after another in the same bytes.
  __shared__ union {
    typename Sort::TempStorage sort;
    typename Scan::TempStorage scan;
    u32 sorted[Block * Items];
  } shared;
  __shared__ u32 faults;
  const u32 corners = 3 * faces, first = threadIdx.x * Items;
  if (threadIdx.x == 0) faults = 0;
  __syncthreads();
  const CountFaults<Point> count{m, &faults};
  for (u32 f = threadIdx.x; f < faces; f += Block)
    count(f);
  // Past the corners, keys above every id (all ones in the sorted bits: a stable sort keeps them last).
  u32 keys[Items];
#pragma unroll
  for (int k = 0; k < Items; ++k)
    keys[k] = first + k < corners ? m.fv[first + k] : ~0u;
  Sort(shared.sort).Sort(keys, 0, bits);
  __syncthreads();
#pragma unroll
  for (int k = 0; k < Items; ++k)
    shared.sorted[first + k] = keys[k];
  __syncthreads();
  u32 distinct[Items], ranks[Items];
#pragma unroll
  for (int k = 0; k < Items; ++k)
    distinct[k] =
        first + k < corners && (first + k == 0 || shared.sorted[first + k - 1] != keys[k]) ? 1u : 0u;
  __syncthreads();
  u32 vertices = 0;
  Scan(shared.scan).ExclusiveSum(distinct, ranks, vertices);
  __syncthreads();
  u32* list = out + 2 + corners;
#pragma unroll
  for (int k = 0; k < Items; ++k) {
    if (distinct[k]) {
      shared.sorted[ranks[k]] = keys[k];
      list[ranks[k]] = keys[k];
    }
  }
  __syncthreads();
  for (u32 c = threadIdx.x; c < corners; c += Block) {
    const u32 v = m.fv[c];
    u32 lo = 0, hi = vertices;  // sorted[lo..hi) holds v
    while (hi - lo > 1) {
      const u32 mid = lo + (hi - lo) / 2;
      if (shared.sorted[mid] <= v) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    out[2 + c] = lo;
  }
  if (threadIdx.x == 0) {
    out[0] = faults;
    out[1] = vertices;
  }
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
      check(cudaMemcpy(to, from, bytes, cudaMemcpyDeviceToHost), "a read-back");
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
      out.look = b.look;
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
