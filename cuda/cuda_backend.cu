// The CUDA backend (issue 4): Algorithm 2 of the paper on the device, with the same per-point functions as
// the CPU backend (routing.hpp), so both backends give bit-identical routing, counts and extreme points.
//
// Resident on the device for the whole run: the points (float AoS, uploaded once), the index array of the
// active points (two buffers, compacted from one into the other), each point's face (int32, as
// CpuBackend::face_of_) and per face of the current mesh its external count and packed extreme key.  Per
// iteration the host sends the O(faces) tables in one copy from pinned staging and reads back the O(faces)
// counts and keys plus the compacted count: never O(points) data (point_faces(), for the debugger, aside).
#include <cuda_runtime.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <cub/device/device_select.cuh>
#include <string>
#include <utility>

#include "cuda_backend.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/routing.hpp"

namespace cudahull {
namespace {

// ---------------------------------------------------------------------------------------------------------
// Errors: every CUDA call is checked; a failure becomes a one-line DeviceError.

std::string error_text(cudaError_t e) {
  return std::string(cudaGetErrorName(e)) + " (" + cudaGetErrorString(e) + ")";
}

[[noreturn]] void fail(const char* what, cudaError_t e) {
  cudaGetLastError();  // clear a non-sticky error; a sticky one (kernel fault) stays with the context
  throw DeviceError(std::string("CUDA backend: ") + what + ": " + error_text(e));
}

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) fail(what, e);
}

std::string memory_text(std::size_t bytes) {
  return std::to_string(bytes) + " bytes (" + std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB)";
}

[[noreturn]] void fail_alloc(const char* what, std::size_t bytes, cudaError_t e, bool pinned) {
  cudaGetLastError();
  std::string msg = std::string("CUDA backend: out of ") + (pinned ? "pinned host" : "device") +
                    " memory allocating " + memory_text(bytes) + " for " + what;
  std::size_t free_bytes = 0, total_bytes = 0;
  if (!pinned && cudaMemGetInfo(&free_bytes, &total_bytes) == cudaSuccess) {
    msg += " (" + memory_text(free_bytes) + " free of " + memory_text(total_bytes) + ")";
  }
  cudaGetLastError();
  throw DeviceError(msg + ": " + error_text(e));
}

// Grow-only device buffer: reused across iterations, reallocated only when a larger size is needed.
template <class T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  ~DeviceBuffer() { cudaFree(ptr_); }

  // Ensures room for n elements; `slack` grows by half again so that a slowly growing size reallocates
  // rarely.  Contents are not kept.
  void reserve(std::size_t n, const char* what, bool slack = false) {
    if (n <= capacity_) return;
    if (slack) n = std::max(n, capacity_ + capacity_ / 2);
    n = std::max<std::size_t>(n, 1);
    check(cudaFree(ptr_), "freeing a device buffer");
    ptr_ = nullptr;
    capacity_ = 0;
    void* p = nullptr;
    const cudaError_t e = cudaMalloc(&p, n * sizeof(T));
    if (e != cudaSuccess) fail_alloc(what, n * sizeof(T), e, false);
    ptr_ = static_cast<T*>(p);
    capacity_ = n;
  }
  T* get() const { return ptr_; }
  std::size_t capacity() const { return capacity_; }
  void swap(DeviceBuffer& other) {
    std::swap(ptr_, other.ptr_);
    std::swap(capacity_, other.capacity_);
  }

 private:
  T* ptr_ = nullptr;
  std::size_t capacity_ = 0;
};

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

constexpr int kBlock = 256;
// Occupancy of the distribution pass: at least 2 blocks of 256 threads per SM, so at most 128 registers a
// thread.  Measured on the H100 (docs/benchmarks.md): capping harder (3 or 4 blocks, 85 or 64 registers)
// spills and made the 10M-point cube slower (3.4 and 3.9 ms on the device against 2.7).
#ifndef CUDAHULL_DISTRIBUTE_BLOCKS_PER_SM
#define CUDAHULL_DISTRIBUTE_BLOCKS_PER_SM 2
#endif
constexpr int kDistributeBlocksPerSm = CUDAHULL_DISTRIBUTE_BLOCKS_PER_SM;
// Faces up to this many accumulate their counts and keys in shared memory (12 bytes a face) before one
// global atomic per face and block; beyond it, contention is low and the kernel goes straight to global.
constexpr std::int32_t kSharedFaces = 2048;

std::size_t align_up(std::size_t x, std::size_t a) {
  return (x + a - 1) / a * a;
}

// ---------------------------------------------------------------------------------------------------------
// Section 3.1 queries: argmax of a per-point score, ties to the lowest index (as CpuBackend::argmax, whose
// strict > within a chunk and lowest-index merge pick the lowest index among equal maxima).

struct Candidate {
  double score;
  PointIndex index;
};

__device__ __forceinline__ bool better(double s, PointIndex i, double best_s, PointIndex best_i) {
  return s > best_s || (s == best_s && i < best_i);
}

// Reduces (s, i) over the block; thread 0 gets the result.
__device__ __forceinline__ void block_argmax(double& s, PointIndex& i) {
  __shared__ double warp_s[kBlock / 32];
  __shared__ PointIndex warp_i[kBlock / 32];
  for (int offset = 16; offset > 0; offset /= 2) {
    const double os = __shfl_down_sync(0xffffffffu, s, offset);
    const PointIndex oi = __shfl_down_sync(0xffffffffu, i, offset);
    if (better(os, oi, s, i)) {
      s = os;
      i = oi;
    }
  }
  const int lane = threadIdx.x % 32, warp = threadIdx.x / 32;
  if (lane == 0) {
    warp_s[warp] = s;
    warp_i[warp] = i;
  }
  __syncthreads();
  if (warp == 0) {
    s = lane < kBlock / 32 ? warp_s[lane] : -INFINITY;
    i = lane < kBlock / 32 ? warp_i[lane] : 0xffffffffu;
    for (int offset = 16; offset > 0; offset /= 2) {
      const double os = __shfl_down_sync(0xffffffffu, s, offset);
      const PointIndex oi = __shfl_down_sync(0xffffffffu, i, offset);
      if (better(os, oi, s, i)) {
        s = os;
        i = oi;
      }
    }
  }
}

template <class Score>
__global__ void __launch_bounds__(kBlock) argmax_partial(const Point3* __restrict__ points, std::size_t n,
                                                         Score score, Candidate* __restrict__ partial) {
  double best_s = -INFINITY;
  PointIndex best_i = 0xffffffffu;
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  for (std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; k < n; k += stride) {
    const double s = score(points[k]);
    if (better(s, static_cast<PointIndex>(k), best_s, best_i)) {
      best_s = s;
      best_i = static_cast<PointIndex>(k);
    }
  }
  block_argmax(best_s, best_i);
  if (threadIdx.x == 0) partial[blockIdx.x] = {best_s, best_i};
}

__global__ void __launch_bounds__(kBlock)
    argmax_final(const Candidate* __restrict__ partial, int count, PointIndex* __restrict__ result) {
  double best_s = -INFINITY;
  PointIndex best_i = 0xffffffffu;
  for (int k = threadIdx.x; k < count; k += blockDim.x) {
    if (better(partial[k].score, partial[k].index, best_s, best_i)) {
      best_s = partial[k].score;
      best_i = partial[k].index;
    }
  }
  block_argmax(best_s, best_i);
  if (threadIdx.x == 0) *result = best_i;
}

// CpuBackend::extremes_x: lowest x (as the highest -x; exact in double) and highest x.
struct ScoreMinusX {
  __device__ double operator()(const Point3& q) const { return -static_cast<double>(q.x); }
};
struct ScoreX {
  __device__ double operator()(const Point3& q) const { return static_cast<double>(q.x); }
};

// CpuBackend::furthest_from_line: |d x (q - a)|^2, the same double operations, each rounded once.
struct ScoreLine {
  double ax, ay, az, dx, dy, dz;
  __device__ double operator()(const Point3& q) const {
    const double wx = __dsub_rn(q.x, ax), wy = __dsub_rn(q.y, ay), wz = __dsub_rn(q.z, az);
    const double cx = __dsub_rn(__dmul_rn(dy, wz), __dmul_rn(dz, wy));
    const double cy = __dsub_rn(__dmul_rn(dz, wx), __dmul_rn(dx, wz));
    const double cz = __dsub_rn(__dmul_rn(dx, wy), __dmul_rn(dy, wx));
    return __dadd_rn(__dadd_rn(__dmul_rn(cx, cx), __dmul_rn(cy, cy)), __dmul_rn(cz, cz));
  }
};

// CpuBackend::furthest_from_plane: |face_height|.
struct ScorePlane {
  FaceGeometry face;
  __device__ double operator()(const Point3& q) const { return fabs(face_height(face, q)); }
};

// ---------------------------------------------------------------------------------------------------------
// Algorithm 2.

__global__ void iota_kernel(PointIndex* __restrict__ out, std::size_t n) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < n) out[k] = static_cast<PointIndex>(k);
}

// Apexes leave the point set without routing (CpuBackend: face_of_[i] = kRouteInternal).
__global__ void retire_kernel(const PointIndex* __restrict__ retired, std::size_t n,
                              std::int32_t* __restrict__ face_of) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < n) face_of[retired[k]] = kRouteInternal;
}

// One pass over the active points: route, exact verdict, and for external points the per-face count and
// the packed extreme key (getExtremePoints fused into the pass, as on the CPU).  With kShared, per-block
// accumulators in shared memory take the contention of the early iterations (few faces, many points).
template <bool kShared>
__global__ void __launch_bounds__(kBlock, kDistributeBlocksPerSm)
    distribute_kernel(const Point3* __restrict__ points, const PointIndex* __restrict__ active, std::size_t n,
                      std::int32_t* __restrict__ face_of, RoutingView view, std::uint32_t* __restrict__ count,
                      unsigned long long* __restrict__ best) {
  extern __shared__ unsigned long long shared_mem[];
  unsigned long long* s_best = shared_mem;
  std::uint32_t* s_count = reinterpret_cast<std::uint32_t*>(shared_mem + (kShared ? view.face_count : 0));
  if (kShared) {
    for (std::int32_t f = threadIdx.x; f < view.face_count; f += blockDim.x) {
      s_best[f] = 0;
      s_count[f] = 0;
    }
    __syncthreads();
  }
  unsigned long long* acc_best = kShared ? s_best : best;
  std::uint32_t* acc_count = kShared ? s_count : count;

  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  // Every lane of a warp runs the same number of rounds (the base is uniform), so the warp-wide
  // __match_any_sync below is safe.
  for (std::size_t base = static_cast<std::size_t>(blockIdx.x) * blockDim.x; base < n; base += stride) {
    const std::size_t k = base + threadIdx.x;
    std::int32_t g = kRouteInternal;
    unsigned long long key = 0;
    if (k < n) {
      const PointIndex i = active[k];
      const std::int32_t old_face = face_of[i];
      if (old_face != kRouteInternal) {  // not retired
        const Point3 x = points[i];
        g = classify_point(x, old_face, view);
        face_of[i] = g;
        if (g != kRouteInternal) key = pack_extreme(face_height(view.faces[g], x), i);
      }
    }
    // Lanes with the same face add their count once; a key is offered only when it beats the current
    // maximum (a stale read only costs an extra atomic: atomicMax is monotone).
    const unsigned peers = __match_any_sync(0xffffffffu, g);
    if (g != kRouteInternal) {
      if ((threadIdx.x % 32) == static_cast<unsigned>(__ffs(peers) - 1)) {
        atomicAdd(acc_count + g, static_cast<std::uint32_t>(__popc(peers)));
      }
      if (key > *static_cast<volatile unsigned long long*>(acc_best + g)) atomicMax(acc_best + g, key);
    }
  }
  if (kShared) {
    __syncthreads();
    for (std::int32_t f = threadIdx.x; f < view.face_count; f += blockDim.x) {
      if (s_count[f] != 0) {
        atomicAdd(count + f, s_count[f]);
        atomicMax(best + f, s_best[f]);
      }
    }
  }
}

struct IsExternal {
  const std::int32_t* face_of;
  __device__ bool operator()(PointIndex i) const { return face_of[i] != kRouteInternal; }
};

__global__ void point_faces_kernel(const PointIndex* __restrict__ active, std::size_t n,
                                   const std::int32_t* __restrict__ face_of, std::int32_t* __restrict__ out) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < n) out[active[k]] = face_of[active[k]];
}

// CUDA-GL interop (issue 5): every point's state, written where the viewer draws from.
__global__ void fill_kernel(std::int32_t* __restrict__ out, std::size_t n, std::int32_t value) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < n) out[k] = value;
}
__global__ void mark_kernel(const PointIndex* __restrict__ ids, std::size_t n, std::int32_t* __restrict__ out,
                            std::int32_t value) {
  const std::size_t k = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (k < n) out[ids[k]] = value;
}

unsigned blocks_for(std::size_t n) {
  return static_cast<unsigned>((n + kBlock - 1) / kBlock);
}

// Owners of the stream and the event, so that a constructor that throws half way leaks neither.
struct Stream {
  cudaStream_t handle = nullptr;
  Stream() = default;
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;
  ~Stream() {
    if (handle != nullptr) {
      cudaStreamSynchronize(handle);
      cudaStreamDestroy(handle);
    }
  }
};
struct Event {
  cudaEvent_t handle = nullptr;
  Event() = default;
  Event(const Event&) = delete;
  Event& operator=(const Event&) = delete;
  ~Event() {
    if (handle != nullptr) cudaEventDestroy(handle);
  }
};

// ---------------------------------------------------------------------------------------------------------

class CudaBackend final : public Backend {
 public:
  explicit CudaBackend(int device) : device_(device) {
    int count = 0;
    cudaError_t e = cudaGetDeviceCount(&count);
    if (e != cudaSuccess) {
      cudaGetLastError();
      throw DeviceError("CUDA backend: no usable CUDA device: " + error_text(e));
    }
    if (device < 0 || device >= count) {
      throw DeviceError("CUDA backend: no CUDA device " + std::to_string(device) + " (" +
                        std::to_string(count) + " present)");
    }
    check(cudaSetDevice(device_), "selecting the device");
    cudaDeviceProp prop{};
    check(cudaGetDeviceProperties(&prop, device_), "reading the device properties");
    name_ = std::string("cuda (") + prop.name + ")";
    sm_count_ = prop.multiProcessorCount;
    check(cudaStreamCreateWithFlags(&stream_holder_.handle, cudaStreamNonBlocking), "creating a stream");
    stream_ = stream_holder_.handle;
    check(cudaEventCreateWithFlags(&event_holder_.handle, cudaEventDisableTiming), "creating an event");
    staging_free_ = event_holder_.handle;

    // The exact orient3d fallback keeps its expansions on the thread's stack (a few KB of local memory).
    // Reserve it now, so that no launch has to grow the local memory (a hidden synchronisation).
    std::size_t frame = 0;
    for (const void* kernel : {reinterpret_cast<const void*>(&distribute_kernel<true>),
                               reinterpret_cast<const void*>(&distribute_kernel<false>)}) {
      cudaFuncAttributes attr{};
      check(cudaFuncGetAttributes(&attr, kernel), "reading the kernel attributes");
      frame = std::max(frame, attr.localSizeBytes);
    }
    std::size_t stack = 0;
    check(cudaDeviceGetLimit(&stack, cudaLimitStackSize), "reading the stack limit");
    const std::size_t want = align_up(frame, 256);
    if (stack < want) check(cudaDeviceSetLimit(cudaLimitStackSize, want), "setting the stack limit");

    // Enough resident blocks to fill the chip; the grid-stride loops take the rest.
    int per_sm = 0;
    check(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, distribute_kernel<true>, kBlock,
                                                        kSharedFaces * (sizeof(unsigned long long) + 4)),
          "reading the occupancy");
    distribute_blocks_shared_ = std::max(1, per_sm) * sm_count_;
    check(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, distribute_kernel<false>, kBlock, 0),
          "reading the occupancy");
    distribute_blocks_global_ = std::max(1, per_sm) * sm_count_;

    scalars_host_.reserve(64, "result scalars");
    scalar_dev_.reserve(1, "the compacted count");
    argmax_result_.reserve(2, "argmax results");
    argmax_partial_.reserve(static_cast<std::size_t>(sm_count_) * 8, "argmax partials");
  }

  ~CudaBackend() override { cudaSetDevice(device_); }  // the members free the rest

  std::string name() const override { return name_; }

  void upload_points(const std::vector<Point3>& points) override {
    select_device();
    n_points_ = points.size();
    n_active_ = n_points_;
    face_count_ = 0;
    if (n_points_ > 0xffffffffu) {
      throw DeviceError("CUDA backend: " + std::to_string(n_points_) +
                        " points exceed the 32-bit index range");
    }
    points_.reserve(n_points_, "the points");
    active_.reserve(n_points_, "the index array");
    active_alt_.reserve(n_points_, "the compacted index array");
    face_of_.reserve(n_points_, "the per-point faces");
    if (n_points_ == 0) return;
    check(cudaMemcpyAsync(points_.get(), points.data(), n_points_ * sizeof(Point3), cudaMemcpyHostToDevice,
                          stream_),
          "uploading the points");
    bytes_to_ += n_points_ * sizeof(Point3);
    iota_kernel<<<blocks_for(n_points_), kBlock, 0, stream_>>>(active_.get(), n_points_);
    check(cudaGetLastError(), "launching iota_kernel");
    check(cudaMemsetAsync(face_of_.get(), 0, n_points_ * sizeof(std::int32_t), stream_),
          "clearing the per-point faces");
    // The caller's vector may change after return: wait for the (pageable) copy.
    check(cudaStreamSynchronize(stream_), "uploading the points");
  }

  std::array<PointIndex, 2> extremes_x() override {
    select_device();
    if (n_points_ == 0) return {0, 0};
    launch_argmax(ScoreMinusX{}, 0);
    launch_argmax(ScoreX{}, 1);
    const PointIndex* r = read_argmax(2);
    return {r[0], r[1]};
  }

  PointIndex furthest_from_line(PointIndex a, PointIndex b) override {
    select_device();
    if (n_points_ == 0) return 0;
    const Point3 pa = point_at(a), pb = point_at(b);
    ScoreLine s;
    s.ax = pa.x;
    s.ay = pa.y;
    s.az = pa.z;
    s.dx = static_cast<double>(pb.x) - s.ax;
    s.dy = static_cast<double>(pb.y) - s.ay;
    s.dz = static_cast<double>(pb.z) - s.az;
    launch_argmax(s, 0);
    return read_argmax(1)[0];
  }

  PointIndex furthest_from_plane(PointIndex a, PointIndex b, PointIndex c) override {
    select_device();
    if (n_points_ == 0) return 0;
    ScorePlane s{};
    s.face.v[0] = point_at(a);
    s.face.v[1] = point_at(b);
    s.face.v[2] = point_at(c);
    launch_argmax(s, 0);
    return read_argmax(1)[0];
  }

  void distribute_points(const IterationTables& tables) override {
    select_device();
    face_count_ = tables.faces.size();
    const auto face_count = static_cast<std::int32_t>(face_count_);

    // One staging area, one copy: the sections at 16-byte aligned offsets.
    constexpr int kSections = 7;
    const std::size_t sizes[kSections] = {tables.refinement.size() * sizeof(RefinementEntry),
                                          tables.decision.size() * sizeof(DecisionEntry),
                                          tables.faces.size() * sizeof(FaceGeometry),
                                          tables.initial_cells.size() * sizeof(SeparatingPlane),
                                          tables.retired.size() * sizeof(PointIndex),
                                          tables.old_face_split.size() * sizeof(std::int32_t),
                                          tables.old_face_route.size() * sizeof(std::int32_t)};
    const void* sources[kSections] = {tables.refinement.data(),    tables.decision.data(),
                                      tables.faces.data(),         tables.initial_cells.data(),
                                      tables.retired.data(),       tables.old_face_split.data(),
                                      tables.old_face_route.data()};
    std::size_t offsets[kSections], total = 0;
    for (int s = 0; s < kSections; ++s) {
      offsets[s] = total;
      total = align_up(total + sizes[s], 16);
    }
    // The previous iteration's copy out of the staging area must be done before it is overwritten.
    check(cudaEventSynchronize(staging_free_), "waiting for the previous table upload");
    staging_.reserve(total, "the table staging area");
    tables_dev_.reserve(total, "the iteration tables", true);
    for (int s = 0; s < kSections; ++s) {
      if (sizes[s] != 0)
        parallel_memcpy(staging_.get() + offsets[s], sources[s], sizes[s]);  // ~110 MB at 2M faces
    }
    if (total != 0) {
      check(cudaMemcpyAsync(tables_dev_.get(), staging_.get(), total, cudaMemcpyHostToDevice, stream_),
            "uploading the iteration tables");
      bytes_to_ += total;
    }
    check(cudaEventRecord(staging_free_, stream_), "recording an event");

    unsigned char* base = tables_dev_.get();
    RoutingView view;
    view.refinement = reinterpret_cast<const RefinementEntry*>(base + offsets[0]);
    view.old_face_split = reinterpret_cast<const std::int32_t*>(base + offsets[5]);
    view.old_face_route = reinterpret_cast<const std::int32_t*>(base + offsets[6]);
    view.decision = reinterpret_cast<const DecisionEntry*>(base + offsets[1]);
    view.faces = reinterpret_cast<const FaceGeometry*>(base + offsets[2]);
    view.face_count = face_count;
    view.initial_cells =
        tables.initial_cells.empty() ? nullptr : reinterpret_cast<const SeparatingPlane*>(base + offsets[3]);
    view.interior = tables.interior;
    const auto* retired = reinterpret_cast<const PointIndex*>(base + offsets[4]);

    // Per-face results, in the layout get_extreme_points copies back in one piece: keys, then counts.
    extremes_dev_.reserve(extremes_bytes(face_count_), "the per-face counts and extremes", true);
    unsigned long long* best = extremes_best();
    std::uint32_t* count = extremes_count();
    if (face_count_ != 0) {
      check(cudaMemsetAsync(extremes_dev_.get(), 0, extremes_bytes(face_count_), stream_),
            "clearing the per-face counts");
    }

    if (!tables.retired.empty()) {
      retire_kernel<<<blocks_for(tables.retired.size()), kBlock, 0, stream_>>>(retired, tables.retired.size(),
                                                                               face_of_.get());
      check(cudaGetLastError(), "launching retire_kernel");
    }
    if (n_active_ == 0) return;
    if (face_count <= kSharedFaces) {
      const unsigned blocks = std::min<unsigned>(blocks_for(n_active_), distribute_blocks_shared_);
      const std::size_t smem = face_count_ * (sizeof(unsigned long long) + sizeof(std::uint32_t));
      distribute_kernel<true><<<blocks, kBlock, smem, stream_>>>(points_.get(), active_.get(), n_active_,
                                                                 face_of_.get(), view, count, best);
    } else {
      const unsigned blocks = std::min<unsigned>(blocks_for(n_active_), distribute_blocks_global_);
      distribute_kernel<false><<<blocks, kBlock, 0, stream_>>>(points_.get(), active_.get(), n_active_,
                                                               face_of_.get(), view, count, best);
    }
    check(cudaGetLastError(), "launching distribute_kernel");
  }

  std::size_t compact_index_array() override {
    select_device();
    if (n_active_ == 0) return 0;
    const IsExternal keep{face_of_.get()};
    std::size_t temp_bytes = 0;
    check(cub::DeviceSelect::If(nullptr, temp_bytes, active_.get(), active_alt_.get(), scalar_dev_.get(),
                                static_cast<std::int64_t>(n_active_), keep, stream_),
          "sizing the compaction");
    cub_temp_.reserve(temp_bytes, "the compaction's temporary storage", true);
    check(cub::DeviceSelect::If(cub_temp_.get(), temp_bytes, active_.get(), active_alt_.get(),
                                scalar_dev_.get(), static_cast<std::int64_t>(n_active_), keep, stream_),
          "launching the compaction");
    auto* selected = reinterpret_cast<std::int64_t*>(scalars_host_.get());
    check(cudaMemcpyAsync(selected, scalar_dev_.get(), sizeof(std::int64_t), cudaMemcpyDeviceToHost, stream_),
          "reading the compacted count");
    check(cudaStreamSynchronize(stream_), "distributing and compacting the points (kernel fault)");
    bytes_from_ += sizeof(std::int64_t);
    active_.swap(active_alt_);
    n_active_ = static_cast<std::size_t>(*selected);
    return n_active_;
  }

  void get_extreme_points(std::vector<FaceExtreme>& out) override {
    select_device();
    out.assign(face_count_, {});
    if (face_count_ == 0) return;
    const std::size_t bytes = extremes_bytes(face_count_);
    extremes_host_.reserve(bytes, "the per-face results");
    check(cudaMemcpyAsync(extremes_host_.get(), extremes_dev_.get(), bytes, cudaMemcpyDeviceToHost, stream_),
          "reading the per-face counts and extremes");
    check(cudaStreamSynchronize(stream_), "reading the per-face counts and extremes");
    bytes_from_ += bytes;
    const auto* best = reinterpret_cast<const unsigned long long*>(extremes_host_.get());
    const auto* count = reinterpret_cast<const std::uint32_t*>(extremes_host_.get() + 8 * face_count_);
    parallel_chunks(
        face_count_, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t f = begin; f < end; ++f) {
            out[f].count = count[f];
            if (count[f]) out[f].furthest = unpack_extreme_index(best[f]);
          }
        },
        65536);
  }

  bool has_device_point_states() const override { return true; }

  bool write_point_states_on_device(std::int32_t* out, std::size_t count,
                                    const std::vector<PointIndex>& vertices) override {
    select_device();
    if (count != n_points_ || count == 0) return false;
    fill_kernel<<<blocks_for(count), kBlock, 0, stream_>>>(out, count, kPointStateInternal);
    check(cudaGetLastError(), "launching fill_kernel");
    if (n_active_ != 0) {  // active points are external: their face
      point_faces_kernel<<<blocks_for(n_active_), kBlock, 0, stream_>>>(active_.get(), n_active_,
                                                                        face_of_.get(), out);
      check(cudaGetLastError(), "launching point_faces_kernel");
    }
    if (!vertices.empty()) {  // O(hull) to the device, nothing back
      vertex_ids_.reserve(vertices.size(), "the hull vertex ids");
      check(cudaMemcpyAsync(vertex_ids_.get(), vertices.data(), vertices.size() * sizeof(PointIndex),
                            cudaMemcpyHostToDevice, stream_),
            "uploading the hull vertex ids");
      bytes_to_ += vertices.size() * sizeof(PointIndex);
      mark_kernel<<<blocks_for(vertices.size()), kBlock, 0, stream_>>>(vertex_ids_.get(), vertices.size(),
                                                                       out, kPointStateVertex);
      check(cudaGetLastError(), "launching mark_kernel");
    }
    check(cudaStreamSynchronize(stream_), "writing the point states (kernel fault)");
    return true;
  }

  void point_faces(std::vector<std::int32_t>& out) override {
    select_device();
    out.assign(n_points_, -1);
    if (n_points_ == 0) return;
    DeviceBuffer<std::int32_t> faces;
    faces.reserve(n_points_, "the debugger's point faces");
    check(cudaMemsetAsync(faces.get(), 0xff, n_points_ * sizeof(std::int32_t), stream_),
          "clearing the point faces");  // all bytes 0xff: -1
    if (n_active_ != 0) {
      point_faces_kernel<<<blocks_for(n_active_), kBlock, 0, stream_>>>(active_.get(), n_active_,
                                                                        face_of_.get(), faces.get());
      check(cudaGetLastError(), "launching point_faces_kernel");
    }
    check(cudaMemcpyAsync(out.data(), faces.get(), n_points_ * sizeof(std::int32_t), cudaMemcpyDeviceToHost,
                          stream_),
          "reading the point faces");
    check(cudaStreamSynchronize(stream_), "reading the point faces");
    bytes_from_ += n_points_ * sizeof(std::int32_t);
  }

  std::uint64_t bytes_to_backend() const override { return bytes_to_; }
  std::uint64_t bytes_from_backend() const override { return bytes_from_; }

 private:
  void select_device() { check(cudaSetDevice(device_), "selecting the device"); }

  // One point's coordinates, for the queries' fixed corners: 12 bytes.
  Point3 point_at(PointIndex i) {
    Point3 p;
    check(cudaMemcpyAsync(scalars_host_.get(), points_.get() + i, sizeof(Point3), cudaMemcpyDeviceToHost,
                          stream_),
          "reading a point");
    check(cudaStreamSynchronize(stream_), "reading a point");
    std::memcpy(&p, scalars_host_.get(), sizeof p);
    bytes_from_ += sizeof(Point3);
    return p;
  }

  template <class Score>
  void launch_argmax(const Score& score, int slot) {
    const unsigned blocks =
        std::min<unsigned>(blocks_for(n_points_), static_cast<unsigned>(argmax_partial_.capacity()));
    argmax_partial<<<blocks, kBlock, 0, stream_>>>(points_.get(), n_points_, score, argmax_partial_.get());
    check(cudaGetLastError(), "launching argmax_partial");
    argmax_final<<<1, kBlock, 0, stream_>>>(argmax_partial_.get(), static_cast<int>(blocks),
                                            argmax_result_.get() + slot);
    check(cudaGetLastError(), "launching argmax_final");
  }

  const PointIndex* read_argmax(int count) {
    check(cudaMemcpyAsync(scalars_host_.get(), argmax_result_.get(), count * sizeof(PointIndex),
                          cudaMemcpyDeviceToHost, stream_),
          "reading the argmax");
    check(cudaStreamSynchronize(stream_), "computing the argmax (kernel fault)");
    bytes_from_ += count * sizeof(PointIndex);
    return reinterpret_cast<const PointIndex*>(scalars_host_.get());
  }

  static std::size_t extremes_bytes(std::size_t faces) { return faces * (sizeof(unsigned long long) + 4); }
  unsigned long long* extremes_best() const {
    return reinterpret_cast<unsigned long long*>(extremes_dev_.get());
  }
  std::uint32_t* extremes_count() const {
    return reinterpret_cast<std::uint32_t*>(extremes_dev_.get() + sizeof(unsigned long long) * face_count_);
  }

  int device_;
  std::string name_;
  int sm_count_ = 0;
  unsigned distribute_blocks_shared_ = 0, distribute_blocks_global_ = 0;
  // Declared first among the resources, so destroyed last: the stream is drained before buffers go.
  Stream stream_holder_;
  Event event_holder_;
  cudaStream_t stream_ = nullptr;
  cudaEvent_t staging_free_ = nullptr;

  std::size_t n_points_ = 0, n_active_ = 0, face_count_ = 0;
  DeviceBuffer<Point3> points_;
  DeviceBuffer<PointIndex> active_, active_alt_;
  DeviceBuffer<PointIndex> vertex_ids_;  // write_point_states_on_device
  DeviceBuffer<std::int32_t> face_of_;
  DeviceBuffer<unsigned char> tables_dev_, extremes_dev_, cub_temp_;
  DeviceBuffer<std::int64_t> scalar_dev_;
  DeviceBuffer<Candidate> argmax_partial_;
  DeviceBuffer<PointIndex> argmax_result_;
  PinnedBuffer staging_, extremes_host_, scalars_host_;

  std::uint64_t bytes_to_ = 0, bytes_from_ = 0;
};

}  // namespace

std::unique_ptr<Backend> make_cuda_backend(int device) {
  return std::make_unique<CudaBackend>(device);
}

}  // namespace cudahull
