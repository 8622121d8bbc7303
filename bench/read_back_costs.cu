// What a large result costs to bring back to the host on the GPU machine (docs/benchmarks.md, "Phases and
// their floors": the finish of a large sphere is a read-back of its mesh).  For a result of MB megabytes
// (default 240, sphere 10M's corners), each a median of 5: filling a fresh std::vector (its zeroing and first
// touch alone), cudaMemcpy into it afterwards, cudaMemcpy into fresh untouched memory, the same through two
// pinned 8 MB buffers taking turns (the copy of one chunk beside the DMA of the next), and cudaHostRegister
// of fresh memory then one DMA.  Run with GLIBC_TUNABLES=glibc.malloc.hugetlb=1 too (the command line sets
// it).
//   nvcc -O2 -arch=sm_90 -std=c++17 bench/read_back_costs.cu -o /tmp/read_back_costs && /tmp/read_back_costs
//   [MB]
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <thread>
#include <vector>

namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double median_of(int runs, const std::function<double()>& once) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r)
    t.push_back(once());
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t bytes = (argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 240) << 20;
  const std::size_t words = bytes / 4;
  unsigned* device = nullptr;
  if (cudaMalloc(&device, bytes) != cudaSuccess) return 1;
  cudaMemset(device, 1, bytes);
  cudaDeviceSynchronize();
  constexpr std::size_t kChunk = std::size_t{8} << 20;
  void* pinned[2] = {nullptr, nullptr};
  double t0 = now_ms();
  cudaMallocHost(&pinned[0], kChunk);
  cudaMallocHost(&pinned[1], kChunk);
  std::printf("two pinned 8 MB buffers made once: %.2f ms\n", now_ms() - t0);
  cudaStream_t stream;
  cudaStreamCreate(&stream);
  cudaEvent_t done[2];
  cudaEventCreateWithFlags(&done[0], cudaEventDisableTiming);
  cudaEventCreateWithFlags(&done[1], cudaEventDisableTiming);

  const double fill = median_of(5, [&] {
    const double s = now_ms();
    std::vector<unsigned> v(words);
    const double t = now_ms() - s;
    if (v[words / 2] != 0) std::abort();
    return t;
  });
  const double fill_then_read = median_of(5, [&] {
    std::vector<unsigned> v(words);
    const double s = now_ms();
    cudaMemcpy(v.data(), device, bytes, cudaMemcpyDeviceToHost);
    return now_ms() - s;
  });
  const double read_fresh = median_of(5, [&] {
    const double s = now_ms();
    std::unique_ptr<unsigned[]> v(new unsigned[words]);
    cudaMemcpy(v.get(), device, bytes, cudaMemcpyDeviceToHost);
    const double t = now_ms() - s;
    if (v[words / 2] != 0x01010101u) std::abort();
    return t;
  });
  // Through the two pinned buffers taking turns: each chunk's copy out of pinned memory on this thread, or
  // split among `threads` threads (fresh memory is first touched, and copied, on several cores at once).
  const auto staged_read = [&](unsigned threads) {
    return median_of(5, [&] {
      const double s = now_ms();
      std::unique_ptr<unsigned char[]> v(new unsigned char[bytes]);
      const auto* from = reinterpret_cast<const unsigned char*>(device);
      const std::size_t chunks = (bytes + kChunk - 1) / kChunk;
      const auto issue = [&](std::size_t c) {
        cudaMemcpyAsync(pinned[c % 2], from + c * kChunk, std::min(kChunk, bytes - c * kChunk),
                        cudaMemcpyDeviceToHost, stream);
        cudaEventRecord(done[c % 2], stream);
      };
      for (std::size_t c = 0; c < chunks && c < 2; ++c)
        issue(c);
      for (std::size_t c = 0; c < chunks; ++c) {
        cudaEventSynchronize(done[c % 2]);
        const std::size_t size = std::min(kChunk, bytes - c * kChunk), part = (size + threads - 1) / threads;
        const auto copy = [&, c](std::size_t begin, std::size_t end) {
          std::memcpy(v.get() + c * kChunk + begin, static_cast<unsigned char*>(pinned[c % 2]) + begin,
                      end - begin);
        };
        if (threads == 1) {
          copy(0, size);
        } else {
          std::vector<std::thread> team;
          for (unsigned t = 0; t < threads; ++t) {
            const std::size_t begin = std::min(size, t * part), end = std::min(size, begin + part);
            team.emplace_back(copy, begin, end);
          }
          for (std::thread& t : team)
            t.join();
        }
        if (c + 2 < chunks) issue(c + 2);
      }
      const double t = now_ms() - s;
      if (v[bytes / 2] != 1) std::abort();
      return t;
    });
  };
  const double staged = staged_read(1), staged4 = staged_read(4), staged8 = staged_read(8);
  const double registered = median_of(5, [&] {
    const double s = now_ms();
    std::unique_ptr<unsigned[]> v(new unsigned[words]);
    cudaHostRegister(v.get(), bytes, cudaHostRegisterDefault);
    cudaMemcpy(v.get(), device, bytes, cudaMemcpyDeviceToHost);
    cudaHostUnregister(v.get());
    return now_ms() - s;
  });
  const double pinned_dma = median_of(5, [&] {
    const double s = now_ms();
    for (std::size_t at = 0; at < bytes; at += kChunk)
      cudaMemcpyAsync(pinned[0], reinterpret_cast<const char*>(device) + at, std::min(kChunk, bytes - at),
                      cudaMemcpyDeviceToHost, stream);
    cudaStreamSynchronize(stream);
    return now_ms() - s;
  });
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("%zu MB (GLIBC_TUNABLES=%s), medians of 5, ms:\n", bytes >> 20, tunables ? tunables : "");
  std::printf("  fresh std::vector (zeroing, first touch):  %8.2f\n", fill);
  std::printf("  cudaMemcpy into it afterwards:             %8.2f\n", fill_then_read);
  std::printf("  cudaMemcpy into fresh untouched memory:    %8.2f\n", read_fresh);
  std::printf("  two pinned 8 MB buffers, then memcpy:      %8.2f\n", staged);
  std::printf("  the same, copied out on 4 threads:         %8.2f\n", staged4);
  std::printf("  the same, copied out on 8 threads:         %8.2f\n", staged8);
  std::printf("  cudaHostRegister of fresh memory + DMA:    %8.2f\n", registered);
  std::printf("  DMA alone into pinned memory (floor):      %8.2f\n", pinned_dma);
  return 0;
}
