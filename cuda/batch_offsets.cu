// The packed result's offsets on the device (lay_out_batch_offsets(), read_offsets_at(), batch_cuda.hpp):
// each done cloud's sizes from its pass's results, the hosted clouds' from the host, a prefix sum a column
// (batch_cuda.cu's design, "the offsets").
#include <cuda_runtime.h>

#include <array>
#include <cstdint>
#include <cub/device/device_scan.cuh>
#include <vector>

#include "batch_shared.cuh"
#include "cudahull/cuda/batch_cuda.hpp"
#include "cudahull/cuda/device_memory.hpp"

namespace cudahull {

namespace {

// A pass's done clouds' sizes at their places in the offsets (one past the cloud: the prefix sum's input).
__global__ void pass_sizes_kernel(const BatchResult* results, const u32* clouds, u32 listed,
                                  std::int64_t* vertex_offsets, std::int64_t* face_offsets) {
  for (u32 k = blockIdx.x * blockDim.x + threadIdx.x; k < listed; k += gridDim.x * blockDim.x) {
    const BatchResult r = results[k];
    if (r.status != resident::kBatchDone) continue;
    vertex_offsets[clouds[k] + 1] = r.vertices;
    face_offsets[clouds[k] + 1] = r.faces;
  }
}

__global__ void hosted_sizes_kernel(const HostedSizes* hosted, std::size_t count,
                                    std::int64_t* vertex_offsets, std::int64_t* face_offsets,
                                    std::int64_t* polygon_offsets) {
  for (std::size_t h = blockIdx.x * std::size_t{blockDim.x} + threadIdx.x; h < count;
       h += std::size_t{gridDim.x} * blockDim.x) {
    const HostedSizes s = hosted[h];
    vertex_offsets[s.cloud + 1] = static_cast<std::int64_t>(s.vertices);
    face_offsets[s.cloud + 1] = static_cast<std::int64_t>(s.faces);
    polygon_offsets[s.cloud + 1] = static_cast<std::int64_t>(s.polygon);
  }
}

// The three columns' values at each index of `at`, three a row.
__global__ void gather_kernel(const std::int64_t* vertex_offsets, const std::int64_t* face_offsets,
                              const std::int64_t* polygon_offsets, const std::size_t* at, std::size_t count,
                              std::int64_t* out) {
  for (std::size_t i = blockIdx.x * std::size_t{blockDim.x} + threadIdx.x; i < count;
       i += std::size_t{gridDim.x} * blockDim.x) {
    out[3 * i] = vertex_offsets[at[i]];
    out[3 * i + 1] = face_offsets[at[i]];
    out[3 * i + 2] = polygon_offsets[at[i]];
  }
}

// The last offset of each of the three columns, side by side: the totals, read back in one copy.
__global__ void totals_kernel(const std::int64_t* vertex_offsets, const std::int64_t* face_offsets,
                              const std::int64_t* polygon_offsets, std::size_t clouds, std::int64_t* totals) {
  totals[0] = vertex_offsets[clouds];
  totals[1] = face_offsets[clouds];
  totals[2] = polygon_offsets[clouds];
}

}  // namespace

template <class Point>
BatchTotals lay_out_batch_offsets(const BatchRun<Point>& run, const std::vector<HostedSizes>& hosted,
                                  std::size_t clouds, std::int64_t* vertex_offsets,
                                  std::int64_t* face_offsets, std::int64_t* polygon_offsets) {
  std::int64_t* const columns[3] = {vertex_offsets, face_offsets, polygon_offsets};
  for (std::int64_t* column : columns)
    check(cudaMemsetAsync(column, 0, (clouds + 1) * sizeof(std::int64_t), 0), "clearing the offsets");
  for (const auto& output : run.outputs) {
    pass_sizes_kernel<<<list_blocks(output->listed), kListThreads>>>(
        reinterpret_cast<const BatchResult*>(output->results.get()), output->clouds.get(), output->listed,
        vertex_offsets, face_offsets);
    check(cudaGetLastError(), "placing the hulls' sizes");
  }
  DeviceArray<HostedSizes> hosted_on_device;
  if (!hosted.empty()) {
    hosted_on_device = DeviceArray<HostedSizes>(hosted.size(), kWho, "the hosted hulls' sizes");
    check(cudaMemcpyAsync(hosted_on_device.get(), hosted.data(), hosted.size() * sizeof(HostedSizes),
                          cudaMemcpyHostToDevice, 0),
          "uploading the hosted hulls' sizes");
    hosted_sizes_kernel<<<list_blocks(hosted.size()), kListThreads>>>(
        hosted_on_device.get(), hosted.size(), vertex_offsets, face_offsets, polygon_offsets);
    check(cudaGetLastError(), "placing the hosted hulls' sizes");
  }
  // Each column's running sums (cub::DeviceScan, in place: the three the same size, one scratch), then the
  // totals in one copy: the host waits on the device once.
  if (clouds != 0) {
    const auto items = static_cast<std::int64_t>(clouds);
    std::size_t bytes = 0;
    check(cub::DeviceScan::InclusiveSum(nullptr, bytes, vertex_offsets + 1, items),
          "sizing the offsets' sums");
    const DeviceArray<char> scratch(bytes, kWho, "the offsets' sums");
    for (std::int64_t* column : columns)
      check(cub::DeviceScan::InclusiveSum(scratch.get(), bytes, column + 1, items), "summing the offsets");
  }
  const DeviceArray<std::int64_t> on_device(3, kWho, "the totals");
  totals_kernel<<<1, 1>>>(vertex_offsets, face_offsets, polygon_offsets, clouds, on_device.get());
  check(cudaGetLastError(), "reading the totals");
  std::int64_t totals[3] = {0, 0, 0};
  check(cudaMemcpy(totals, on_device.get(), sizeof(totals), cudaMemcpyDeviceToHost),
        "laying out the offsets");
  return {static_cast<std::size_t>(totals[0]), static_cast<std::size_t>(totals[1]),
          static_cast<std::size_t>(totals[2])};
}

std::vector<std::array<std::int64_t, 3>> read_offsets_at(const std::int64_t* vertex_offsets,
                                                         const std::int64_t* face_offsets,
                                                         const std::int64_t* polygon_offsets,
                                                         const std::vector<std::size_t>& at) {
  std::vector<std::array<std::int64_t, 3>> values(at.size());
  if (at.empty()) return values;
  const DeviceArray<std::size_t> indices(at.size(), kWho, "the offsets to read");
  const DeviceArray<std::int64_t> gathered(3 * at.size(), kWho, "the offsets read");
  check(cudaMemcpyAsync(indices.get(), at.data(), at.size() * sizeof(std::size_t), cudaMemcpyHostToDevice, 0),
        "uploading the offsets to read");
  gather_kernel<<<list_blocks(at.size()), kListThreads>>>(vertex_offsets, face_offsets, polygon_offsets,
                                                          indices.get(), at.size(), gathered.get());
  check(cudaGetLastError(), "gathering the offsets");
  static_assert(sizeof(values[0]) == 3 * sizeof(std::int64_t));
  check(
      cudaMemcpy(values.data(), gathered.get(), 3 * at.size() * sizeof(std::int64_t), cudaMemcpyDeviceToHost),
      "reading the offsets");
  return values;
}

template BatchTotals lay_out_batch_offsets(const BatchRun<Point3>&, const std::vector<HostedSizes>&,
                                           std::size_t, std::int64_t*, std::int64_t*, std::int64_t*);
template BatchTotals lay_out_batch_offsets(const BatchRun<Point3d>&, const std::vector<HostedSizes>&,
                                           std::size_t, std::int64_t*, std::int64_t*, std::int64_t*);

}  // namespace cudahull
