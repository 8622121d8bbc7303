// Batched hulls on the device (batch_cuda.hpp).
//
// design:
//   the clouds a block takes: 4 .. kBlockPoints points (fewer: the single-cloud path's lower-dimensional
//     answer; more: the single-cloud path's grid, which a large cloud fills better)
//   pass 1: as many blocks as fit at once, each with a slot of face room for the largest hull the pass
//     expects (batch_vertices()); a block takes clouds one after another from a counter (a large one does
//     not hold the others up) and runs batch_hull() on each.  Per point, the iteration's own arrays (six
//     words) at the cloud's place in the packed points
//   pass 2: the clouds that asked for more room, with room for every point a vertex (up to kSecondPassPoints
//     points; larger ones take the single-cloud path)
//   read back: the results (status, sizes, places), then the words and coordinates the hulls took
#include <cuda_runtime.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "batch_cuda.hpp"
#include "cuda_errors.hpp"
#include "cudahull/resident/batch.hpp"
#include "device_memory.hpp"
#include "teams.cuh"

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
constexpr int kThreads = 128;  // a block a cloud: most small clouds' phases have fewer items than this
constexpr u32 kSecondPassPoints = 16384;  // the largest cloud the second launch takes

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw_cuda_error(kWho, what, e);
}

// The clouds with more points than this take the single-cloud path (or CUDAHULL_BATCH_BLOCK_POINTS, up to
// 2^20: a block's room, batch_room(), counts its face slots in 32 bits).
std::size_t block_points() {
  const char* env = std::getenv("CUDAHULL_BATCH_BLOCK_POINTS");
  return std::min<std::size_t>(env ? std::strtoull(env, nullptr, 10) : std::size_t{1} << 17,
                               std::size_t{1} << 20);
}

// The batch's device arrays (device_memory.hpp, on the default stream), given back with their owner, and
// the bytes held at once counted (`held`, `peak`: the batch's, across its passes).
class BatchMemory {
 public:
  BatchMemory(std::size_t& held, std::size_t& peak) : held_(held), peak_(peak) {}
  BatchMemory(const BatchMemory&) = delete;
  BatchMemory& operator=(const BatchMemory&) = delete;
  ~BatchMemory() {
    for (const DeviceBlock& block : blocks_) {
      give_device_block(block, 0);
      held_ -= block.bytes;
    }
  }
  template <class T>
  T* take(std::size_t n, const char* what) {
    const DeviceBlock block = take_device_block(std::max<std::size_t>(n, 1) * sizeof(T), 0, kWho, what);
    blocks_.push_back(block);
    held_ += block.bytes;
    peak_ = std::max(peak_, held_);
    return static_cast<T*>(block.ptr);
  }

 private:
  std::vector<DeviceBlock> blocks_;
  std::size_t &held_, &peak_;
};

// Everything a pass's blocks share: the points and offsets, the clouds listed for the pass, the slots (one
// a block) and the per-point arrays, the output and the results.
template <class Point>
struct PassArgs {
  const Point* points;
  const u32* offsets;  // B + 1
  const u32* clouds;   // the pass's clouds
  u32 count;           // how many
  u32* next;           // the next of them to take
  BatchSlot slot;      // slot 0's pointers; slot s is `s` rooms further on
  u32* point_words;    // six arrays of the batch's point count, one after another
  u32 points_total;
  BatchOutput<Point> out;
  BatchResult* results;  // per listed cloud
};

template <class Point>
__device__ BatchSlot slot_of(const PassArgs<Point>& a, u32 s) {
  const BatchRoom& room = a.slot.room;
  const std::size_t f = std::size_t{s} * room.faces, words = std::size_t{s} * (room.faces / 32 + 1);
  BatchSlot slot = a.slot;
  slot.fv += 3 * f;
  slot.fn += 3 * f;
  slot.fv_spare += 3 * f;
  slot.fn_spare += 3 * f;
  slot.killer += f;
  slot.look += f;
  slot.flags += f + s;  // room.faces + 1 a slot: the marks' prefix sum reads one past the faces
  slot.face_rank += f + s;
  slot.win_mask += words;
  slot.word_rank += words;
  slot.extreme += f;
  slot.claim += f;
  slot.entries += std::size_t{s} * room.entries;
  slot.list += std::size_t{s} * room.work;
  slot.cands += std::size_t{s} * room.work;
  slot.st += s;
  return slot;
}

template <class Point, int Block>
__global__ void __launch_bounds__(Block) batch_kernel(PassArgs<Point> a) {
  __shared__ u32 taken;
  const BatchSlot slot = slot_of(a, blockIdx.x);
  const resident::BlockTeam<Block> team{slot.st};
  while (true) {
    if (threadIdx.x == 0) taken = atomicAdd(a.next, 1u);
    __syncthreads();
    const u32 k = taken;
    __syncthreads();  // every thread has read it before thread 0 takes the next
    if (k >= a.count) return;
    const u32 c = a.clouds[k], begin = a.offsets[c], n = a.offsets[c + 1] - begin;
    const std::size_t at = begin, total = a.points_total;
    u32* w = a.point_words;
    const BatchCloud<Point> cloud{a.points + at,
                                  n,
                                  w + at,
                                  w + total + at,
                                  w + 2 * total + at,
                                  w + 3 * total + at,
                                  w + 4 * total + at,
                                  w + 5 * total + at};
    resident::batch_hull(team, slot, cloud, a.out, a.results + k);
  }
}

// One pass over the listed clouds (ids into `offsets`), each with room for a hull of `vertices` vertices;
// results per listed cloud into `results`, the hulls' words and coordinates into `meshes` (appended).
template <class Point>
std::vector<BatchResult> run_pass(const Point* points, std::size_t count, const u32* device_offsets,
                                  const std::vector<u32>& listed, u32 vertices, std::size_t word_room,
                                  std::size_t coordinate_room, BatchMeshes<Point>& meshes,
                                  std::size_t& held) {
  BatchMemory memory(held, meshes.device_bytes);
  auto* kernel = batch_kernel<Point, kThreads>;
  const u32 slots = static_cast<u32>(
      std::min<std::size_t>(listed.size(), resident::blocks_that_fit(kernel, kThreads, kWho)));

  PassArgs<Point> a{};
  a.points = points;
  a.offsets = device_offsets;
  a.count = static_cast<u32>(listed.size());
  a.points_total = static_cast<u32>(count);
  const BatchRoom room = resident::batch_room(vertices);
  BatchSlot& s = a.slot;
  s.room = room;
  const std::size_t f = std::size_t{slots} * room.faces, words = std::size_t{slots} * (room.faces / 32 + 1);
  s.fv = memory.take<u32>(3 * f, "the faces");
  s.fn = memory.take<u32>(3 * f, "the faces' links");
  s.fv_spare = memory.take<u32>(3 * f, "the compaction's faces");
  s.fn_spare = memory.take<u32>(3 * f, "the compaction's links");
  s.killer = memory.take<u32>(f, "the faces' killers");
  s.look = memory.take<u32>(f, "the faces' stamps");
  s.flags = memory.take<u32>(f + slots, "the faces' marks");
  s.face_rank = memory.take<u32>(f + slots, "the marks' ranks");
  s.win_mask = memory.take<u32>(words, "the rounds' wins");
  s.word_rank = memory.take<u32>(words, "the rounds' win ranks");
  s.extreme = memory.take<u64>(f, "the furthest points");
  s.claim = memory.take<u64>(f, "the claims");
  s.entries = memory.take<resident::Entry>(std::size_t{slots} * room.entries, "the decision entries");
  s.list = memory.take<u32>(std::size_t{slots} * room.work, "the rounds' work");
  s.cands = memory.take<resident::Candidate>(std::size_t{slots} * room.work, "the rounds' candidates");
  s.st = memory.take<resident::RoundsState>(slots, "the states");
  a.point_words = memory.take<u32>(6 * count, "the points' marks");
  a.out.words = memory.take<u32>(word_room, "the hulls' words");
  a.out.coordinates = memory.take<Point>(coordinate_room, "the hulls' vertices");
  a.out.word_capacity = static_cast<u32>(word_room);
  a.out.coordinate_capacity = static_cast<u32>(coordinate_room);
  // The results, then the counter of clouds taken and the two of output taken, in one block.
  static_assert(sizeof(BatchResult) == 5 * sizeof(u32));
  const std::size_t result_words = 5 * listed.size();
  u32* results_then_counters = memory.take<u32>(result_words + 3, "the results");
  a.results = reinterpret_cast<BatchResult*>(results_then_counters);
  a.next = results_then_counters + result_words;
  a.out.used = a.next + 1;
  u32* clouds = memory.take<u32>(listed.size(), "the cloud list");
  a.clouds = clouds;
  check(cudaMemcpyAsync(clouds, listed.data(), listed.size() * sizeof(u32), cudaMemcpyHostToDevice, 0),
        "uploading the cloud list");
  check(cudaMemsetAsync(a.next, 0, 3 * sizeof(u32), 0), "clearing the counters");
  cudaEvent_t events[2];
  check(cudaEventCreate(&events[0]), "timing the batch");
  check(cudaEventCreate(&events[1]), "timing the batch");
  cudaEventRecord(events[0], 0);
  kernel<<<slots, kThreads>>>(a);
  check(cudaGetLastError(), "launching the batch");
  cudaEventRecord(events[1], 0);
  std::vector<u32> got(result_words + 3);
  check(cudaMemcpy(got.data(), results_then_counters, got.size() * sizeof(u32), cudaMemcpyDeviceToHost),
        "reading the results (kernel fault)");
  float kernel_ms = 0;
  cudaEventElapsedTime(&kernel_ms, events[0], events[1]);
  cudaEventDestroy(events[0]);
  cudaEventDestroy(events[1]);
  meshes.kernel_ms += kernel_ms;
  std::vector<BatchResult> results(listed.size());
  std::copy(got.begin(), got.begin() + static_cast<std::ptrdiff_t>(result_words),
            reinterpret_cast<u32*>(results.data()));
  const std::size_t words_used = std::min<std::size_t>(got[result_words + 1], word_room),
                    coordinates_used = std::min<std::size_t>(got[result_words + 2], coordinate_room);
  // The places are this pass's: moved past what earlier passes read.
  const std::size_t word_base = meshes.words.size(), point_base = meshes.coordinates.size();
  meshes.words.resize(word_base + words_used);
  meshes.coordinates.resize(point_base + coordinates_used);
  check(cudaMemcpy(meshes.words.data() + word_base, a.out.words, words_used * sizeof(u32),
                   cudaMemcpyDeviceToHost),
        "reading the hulls");
  check(cudaMemcpy(meshes.coordinates.data() + point_base, a.out.coordinates,
                   coordinates_used * sizeof(Point), cudaMemcpyDeviceToHost),
        "reading the hulls' vertices");
  for (std::size_t k = 0; k < listed.size(); ++k) {
    if (results[k].status != resident::kBatchDone) continue;
    const u32 c = listed[k];
    meshes.done[c] = 1;
    meshes.faces[c] = results[k].faces;
    meshes.vertices[c] = results[k].vertices;
    meshes.word_at[c] = word_base + results[k].word_at;
    meshes.point_at[c] = point_base + results[k].point_at;
  }
  ++meshes.passes;
  return results;
}

}  // namespace

template <class Point>
BasicHullMesh<Point> BatchMeshes<Point>::mesh(std::size_t c) const {
  BasicHullMesh<Point> out;
  const std::size_t f = faces[c], v = vertices[c];
  const std::uint32_t* w = words.data() + word_at[c];
  out.triangles.resize(f);
  for (std::size_t k = 0; k < f; ++k)
    out.triangles[k] = {w[3 * k], w[3 * k + 1], w[3 * k + 2]};
  out.vertex_ids.assign(w + 3 * f, w + 3 * f + v);
  out.vertices.assign(coordinates.begin() + static_cast<std::ptrdiff_t>(point_at[c]),
                      coordinates.begin() + static_cast<std::ptrdiff_t>(point_at[c] + v));
  return out;
}

template <class Point>
BatchMeshes<Point> batch_meshes_cuda(const Point* device_points, std::size_t count,
                                     const std::size_t* offsets, std::size_t clouds,
                                     const std::uint8_t* skip) {
  BatchMeshes<Point> meshes;
  meshes.done.assign(clouds, 0);
  meshes.faces.assign(clouds, 0);
  meshes.vertices.assign(clouds, 0);
  meshes.word_at.assign(clouds, 0);
  meshes.point_at.assign(clouds, 0);
  // Indices are 32 bits on the device: a larger batch takes the single-cloud path cloud by cloud.
  if (count >= 0xffffffffu / 8 || clouds >= 0xffffffffu / 8) return meshes;
  const std::size_t largest = block_points();
  std::vector<u32> listed;
  u32 vertices = 0;
  std::size_t word_room = 0, coordinate_room = 0;
  for (std::size_t c = 0; c < clouds; ++c) {
    const std::size_t n = offsets[c + 1] - offsets[c];
    if (n < 4 || n > largest || (skip && skip[c])) continue;
    listed.push_back(static_cast<u32>(c));
    const u32 v = resident::batch_vertices(static_cast<u32>(n), false);
    vertices = std::max(vertices, v);
    word_room += 7 * std::size_t{v};  // 2 v faces of 3 corners, and v vertices
    coordinate_room += v;
  }
  if (listed.empty()) return meshes;

  const TrimPoolAtEnd trim;  // after the arrays below: what the batch freed beyond the pool's keep, back
  std::size_t held = 0;
  BatchMemory memory(held, meshes.device_bytes);
  u32* device_offsets = memory.take<u32>(clouds + 1, "the offsets");
  {
    const std::vector<u32> narrow(offsets, offsets + clouds + 1);
    check(cudaMemcpy(device_offsets, narrow.data(), narrow.size() * sizeof(u32), cudaMemcpyHostToDevice),
          "uploading the offsets");
  }
  const std::vector<BatchResult> first = run_pass(device_points, count, device_offsets, listed, vertices,
                                                  word_room, coordinate_room, meshes, held);
  std::vector<u32> again;
  vertices = 0;
  word_room = coordinate_room = 0;
  for (std::size_t k = 0; k < listed.size(); ++k) {
    if (first[k].status != resident::kBatchRoom) continue;
    const u32 c = listed[k], n = static_cast<u32>(offsets[c + 1] - offsets[c]);
    // Room for every point a vertex costs a slot some 900 bytes a point: a larger cloud takes the
    // single-cloud path, which grows its room as it goes.
    if (n > kSecondPassPoints) continue;
    again.push_back(c);
    vertices = std::max(vertices, n);
    word_room += 7 * std::size_t{n};
    coordinate_room += n;
  }
  meshes.clouds_in_second_pass = again.size();
  if (!again.empty())
    run_pass(device_points, count, device_offsets, again, vertices, word_room, coordinate_room, meshes, held);
  return meshes;
}

template struct BatchMeshes<Point3>;
template struct BatchMeshes<Point3d>;
template BatchMeshes<Point3> batch_meshes_cuda(const Point3*, std::size_t, const std::size_t*, std::size_t,
                                               const std::uint8_t*);
template BatchMeshes<Point3d> batch_meshes_cuda(const Point3d*, std::size_t, const std::size_t*, std::size_t,
                                                const std::uint8_t*);

}  // namespace cudahull
