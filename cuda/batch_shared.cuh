// What the batch's files share (batch_cuda.cu, batch_offsets.cu, batch_describe.cu, batch_memory.cu): the
// engine's batch types, the errors, the list kernels' launch shape, and a pass's output on the device.
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>

#include "cuda_errors.hpp"
#include "cudahull/cuda/batch_cuda.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/resident/batch.hpp"

namespace cudahull {
namespace {

using resident::BatchCloud;
using resident::BatchOutput;
using resident::BatchResult;
using resident::BatchRoom;
using resident::BatchSlot;
using resident::u32;
using resident::u64;

constexpr const char* kWho = "batched hulls";
constexpr CudaCheck check{kWho};

constexpr int kListThreads = 256;
u32 list_blocks(std::size_t items) {
  return static_cast<u32>(std::min<std::size_t>((items + kListThreads - 1) / kListThreads, 4096));
}

}  // namespace

template <class Point>
struct BatchRun<Point>::PassOutput {
  DeviceArray<u32> words;
  DeviceArray<Point> coordinates;
  DeviceArray<u32> results;  // BatchResult a listed cloud, then the counters
  DeviceArray<u32> clouds;   // the listed clouds
  u32 listed = 0;
};

}  // namespace cudahull
