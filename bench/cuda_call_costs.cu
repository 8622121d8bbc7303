// The host's cost of single CUDA runtime calls on the GPU machine (docs/benchmarks.md, "Fewer host calls"):
// kernel launches, stream-ordered allocations, a memset, and small reads after a kernel from pageable and
// pinned memory.  Three rounds, each a mean over 20-100 calls.  Standalone:
//   nvcc -O2 -arch=sm_90 -std=c++17 bench/cuda_call_costs.cu -o /tmp/cuda_call_costs && /tmp/cuda_call_costs
#include <cuda_runtime.h>

#include <chrono>
#include <cstdio>
#include <vector>

namespace {

__global__ void empty_kernel(int* p) {
  if (p && threadIdx.x == 9999) *p = 1;
}
struct Params600 {
  unsigned v[150];
};
__global__ void params_kernel(Params600 b, int* p) {
  if (threadIdx.x == 9999) *p = static_cast<int>(b.v[3]);
}

double now_us() {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The mean wait of a read of `bytes` into `to` right after an empty kernel; `pinned_async`: cudaMemcpyAsync
// and a stream synchronisation instead of cudaMemcpy.
double read_after_kernel(int* device, void* to, std::size_t bytes, bool pinned_async) {
  double sum = 0;
  for (int i = 0; i < 20; ++i) {
    empty_kernel<<<1, 32>>>(device);
    const double t = now_us();
    if (pinned_async) {
      cudaMemcpyAsync(to, device, bytes, cudaMemcpyDeviceToHost, 0);
      cudaStreamSynchronize(0);
    } else {
      cudaMemcpy(to, device, bytes, cudaMemcpyDeviceToHost);
    }
    sum += now_us() - t;
  }
  return sum / 20;
}

}  // namespace

int main() {
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  const cudaError_t start = cudaFree(nullptr);
  std::printf("device start: %s\n", cudaGetErrorString(start));
  if (start != cudaSuccess) return 1;
  int* device = nullptr;
  cudaMalloc(&device, 1 << 20);
  unsigned char* pinned = nullptr;
  cudaMallocHost(&pinned, 1 << 16);
  std::vector<unsigned char> pageable(1 << 16);
  for (int round = 0; round < 3; ++round) {
    double t = now_us();
    for (int i = 0; i < 100; ++i)
      empty_kernel<<<1, 32>>>(device);
    std::printf("launch, no parameters: %.2f us\n", (now_us() - t) / 100);
    cudaDeviceSynchronize();
    const Params600 params{};
    t = now_us();
    for (int i = 0; i < 100; ++i)
      params_kernel<<<1, 32>>>(params, device);
    std::printf("launch, 600 bytes of parameters: %.2f us\n", (now_us() - t) / 100);
    cudaDeviceSynchronize();
    for (const std::size_t size :
         {std::size_t{4096}, std::size_t{65536}, std::size_t{1} << 20, std::size_t{8} << 20}) {
      std::vector<void*> blocks(20);
      t = now_us();
      for (void*& p : blocks)
        cudaMallocAsync(&p, size, 0);
      const double t1 = now_us();
      for (void* p : blocks)
        cudaFreeAsync(p, 0);
      std::printf("cudaMallocAsync %zu bytes: %.2f us, cudaFreeAsync: %.2f us\n", size, (t1 - t) / 20,
                  (now_us() - t1) / 20);
      cudaDeviceSynchronize();
    }
    t = now_us();
    for (int i = 0; i < 20; ++i)
      cudaMemsetAsync(device, 0, 64, 0);
    std::printf("cudaMemsetAsync: %.2f us\n", (now_us() - t) / 20);
    cudaDeviceSynchronize();
    std::printf("8-byte read after a kernel, pageable: %.2f us\n",
                read_after_kernel(device, pageable.data(), 8, false));
    std::printf("8-byte read after a kernel, pinned async + sync: %.2f us\n",
                read_after_kernel(device, pinned, 8, true));
    std::printf("8-byte read after a kernel, pinned: %.2f us\n", read_after_kernel(device, pinned, 8, false));
    std::printf("16 KB read after a kernel, pageable: %.2f us\n",
                read_after_kernel(device, pageable.data(), 16384, false));
    std::printf("4 KB read after a kernel, pinned async + sync: %.2f us\n",
                read_after_kernel(device, pinned, 4096, true));
  }
  cudaFreeHost(pinned);
  cudaFree(device);
  return 0;
}
