// The resident engine's device executor: the operations of engine/src/resident/resident_ops.hpp as
// kernels, one thread per face or point; prefix sums from CUB.  Each prefix sum brings its total back (4
// bytes, one wait): the host sizes the next step by it.
#include <cuda_runtime.h>

#include <cub/device/device_scan.cuh>
#include <string>

#include "cudahull/errors.hpp"
#include "resident/resident_driver.hpp"
#include "resident_cuda.hpp"

namespace cudahull {
namespace resident {
namespace {

void check(cudaError_t e, const char* what) {
  if (e == cudaSuccess) return;
  cudaGetLastError();
  throw DeviceError(std::string("resident engine: ") + what + ": " + cudaGetErrorName(e) + " (" +
                    cudaGetErrorString(e) + ")");
}

constexpr int kBlock = 256;

unsigned blocks_for(std::size_t n) {
  return static_cast<unsigned>((n + kBlock - 1) / kBlock);
}

template <class Op>
__global__ void for_each_kernel(std::size_t n, Op op) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) op(i);
}

// Lanes of a warp with the same segment combine their keys first: one atomic per segment and warp (the
// first iterations have millions of points on a few faces).
template <class Op>
__global__ void segmented_max_kernel(std::size_t n, Op op, u64* out) {
  const std::size_t j = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  const unsigned active = __ballot_sync(0xffffffffu, j < n);
  if (j >= n) return;
  const u32 segment = op.segment(j);
  const u64 key = op.key(j);
  const unsigned peers = __match_any_sync(active, segment);
  u64 best = key;
  for (unsigned rest = peers; rest != 0; rest &= rest - 1) {
    const u64 other = __shfl_sync(peers, key, __ffs(rest) - 1);
    best = other > best ? other : best;
  }
  if ((threadIdx.x & 31) == static_cast<unsigned>(__ffs(peers) - 1))
    atomicMax(reinterpret_cast<unsigned long long*>(&out[segment]), static_cast<unsigned long long>(best));
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

__global__ void scan_total_kernel(const u32* in, const u32* out, std::size_t n, u32* total) {
  *total = out[n - 1] + in[n - 1];
}

__global__ void scatter_selected_kernel(const u32* flags, const u32* rank, u32* list, std::size_t n) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n && flags[i]) list[rank[i]] = static_cast<u32>(i);
}

template <class T>
__global__ void fill_kernel(T* at, std::size_t n, T value) {
  const std::size_t i = blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x;
  if (i < n) at[i] = value;
}

}  // namespace

struct CudaExec {
  template <class T>
  class Buffer {
   public:
    Buffer() = default;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    ~Buffer() { cudaFree(ptr_); }
    void grow(std::size_t n, std::size_t keep = 0) {
      if (n <= capacity_) return;
      T* fresh = nullptr;
      const cudaError_t e = cudaMalloc(&fresh, n * sizeof(T));
      if (e != cudaSuccess) {
        std::size_t free_bytes = 0, total_bytes = 0;
        cudaGetLastError();
        cudaMemGetInfo(&free_bytes, &total_bytes);
        cudaGetLastError();
        throw DeviceError("resident engine: out of device memory allocating " +
                          std::to_string(n * sizeof(T) >> 20) + " MiB (" + std::to_string(free_bytes >> 20) +
                          " MiB free of " + std::to_string(total_bytes >> 20) + ")");
      }
      if (keep > 0 && ptr_)
        check(cudaMemcpy(fresh, ptr_, std::min(keep, capacity_) * sizeof(T), cudaMemcpyDeviceToDevice),
              "growing a buffer");
      cudaFree(ptr_);
      ptr_ = fresh;
      capacity_ = n;
    }
    T* data() { return ptr_; }
    void swap(Buffer& other) {
      std::swap(ptr_, other.ptr_);
      std::swap(capacity_, other.capacity_);
    }

   private:
    T* ptr_ = nullptr;
    std::size_t capacity_ = 0;
  };

  template <class Op>
  void for_each(std::size_t n, const Op& op) {
    if (n == 0) return;
    for_each_kernel<<<blocks_for(n), kBlock>>>(n, op);
    check(cudaGetLastError(), "launching a kernel");
  }
  template <class Op>
  void segmented_max(std::size_t n, const Op& op) {
    if (n == 0) return;
    segmented_max_kernel<<<blocks_for(n), kBlock>>>(n, op, op.extreme);
    check(cudaGetLastError(), "launching the furthest-point kernel");
  }
  template <class KeyOp>
  u64 reduce_max(std::size_t n, const KeyOp& key) {
    scalar64_.grow(1);
    check(cudaMemset(scalar64_.data(), 0, sizeof(u64)), "clearing a reduction");
    const unsigned blocks = std::max(1u, std::min(blocks_for(n), 4096u));
    reduce_max_kernel<<<blocks, kBlock>>>(n, key, scalar64_.data());
    check(cudaGetLastError(), "launching a reduction");
    u64 out = 0;
    read(&out, scalar64_.data(), 1);
    return out;
  }
  u32 exclusive_scan(const u32* in, u32* out, std::size_t n) {
    if (n == 0) return 0;
    std::size_t bytes = 0;
    check(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, static_cast<int>(n)), "sizing a scan");
    scratch_.grow(bytes);
    check(cub::DeviceScan::ExclusiveSum(scratch_.data(), bytes, in, out, static_cast<int>(n)), "a scan");
    scalar32_.grow(1);
    scan_total_kernel<<<1, 1>>>(in, out, n, scalar32_.data());
    check(cudaGetLastError(), "launching a scan total");
    u32 total = 0;
    read(&total, scalar32_.data(), 1);
    return total;
  }
  u32 select(const u32* flags, u32* rank, u32* list, std::size_t n) {
    const u32 count = exclusive_scan(flags, rank, n);
    if (count != 0) {
      scatter_selected_kernel<<<blocks_for(n), kBlock>>>(flags, rank, list, n);
      check(cudaGetLastError(), "launching a select");
    }
    return count;
  }
  template <class T>
  void fill(T* at, std::size_t n, T value) {
    if (n == 0) return;
    fill_kernel<<<blocks_for(n), kBlock>>>(at, n, value);
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

  std::uint64_t host_syncs = 0, bytes_to_device = 0, bytes_from_device = 0;

 private:
  template <class T>
  void read(T* to, const T* from, std::size_t n) {
    if (n != 0) check(cudaMemcpy(to, from, n * sizeof(T), cudaMemcpyDeviceToHost), "a read-back");
    ++host_syncs;
    bytes_from_device += n * sizeof(T);
  }
  Buffer<u64> scalar64_;
  Buffer<u32> scalar32_;
  Buffer<unsigned char> scratch_;
};

}  // namespace resident

template <class Point>
struct ResidentCudaHull<Point>::Impl {
  resident::CudaExec exec;
  resident::CudaExec::Buffer<Point> points;
  const std::vector<Point>* host = nullptr;
};

template <class Point>
ResidentCudaHull<Point>::ResidentCudaHull() : impl_(std::make_unique<Impl>()) {}
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
}

template <class Point>
BasicHullMesh<Point> ResidentCudaHull<Point>::run(ResidentStats* stats) {
  if (!impl_->host) throw std::logic_error("ResidentCudaHull::run() before upload()");
  resident::CudaExec& exec = impl_->exec;
  exec.host_syncs = exec.bytes_to_device = exec.bytes_from_device = 0;
  resident::ResidentHull<Point, resident::CudaExec> hull(exec, *impl_->host, impl_->points.data());
  ResidentStats local;
  ResidentStats& out = stats ? *stats : local;
  BasicHullMesh<Point> result = hull.run(out);
  out.host_syncs = exec.host_syncs;
  out.bytes_to_device = exec.bytes_to_device;
  out.bytes_from_device = exec.bytes_from_device;
  return result;
}

// The two coordinate types (README, "Precision").
template class ResidentCudaHull<Point3>;
template class ResidentCudaHull<Point3d>;

}  // namespace cudahull
