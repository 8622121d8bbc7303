// The CUDA backend (issue 4): Algorithm 2 of the paper on the device, with the same per-point functions as
// the CPU backend (routing.hpp), so both backends give bit-identical routing, counts and extreme points.
//
// Resident on the device for the whole run: the points (AoS of the backend's `Point`, Point3 or Point3d,
// uploaded once), the index array of the active points (two buffers, compacted from one into the other),
// each point's face (int32, as CpuBackend::face_of_) and per face of the current mesh its external count and
// packed extreme key.  Per iteration the host sends the O(faces) tables as one block (through ordinary or
// pinned buffers by size, upload_staged()) and reads back the O(faces) counts and keys plus the compacted
// count: never O(points) data (point_faces(), for the debugger, aside).
// Its kernels are in cuda_backend_queries.cuh (section 3.1) and cuda_backend_distribute.cuh (Algorithm 2).
#include <cuda_runtime.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "cuda_backend_distribute.cuh"
#include "cuda_backend_launch.cuh"
#include "cuda_backend_queries.cuh"
#include "cuda_backend_resources.hpp"
#include "cuda_errors.hpp"
#include "cudahull/cuda/cuda_backend.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/routing.hpp"

namespace cudahull {
namespace {

std::size_t align_up(std::size_t x, std::size_t a) {
  return (x + a - 1) / a * a;
}

// `Point` is Point3 (float) or Point3d (double): the points on the device, the faces of the tables and every
// kernel that reads them follow it; the rest (indices, faces of points, counts, keys, planes) is the same.
template <class Point>
class CudaBackend final : public BasicBackend<Point> {
 public:
  using Tables = BasicIterationTables<Point>;
  using Geometry = BasicFaceGeometry<Point>;

  explicit CudaBackend(int device) : device_(device) {
    int count = 0;
    cudaError_t e = cudaGetDeviceCount(&count);
    if (e != cudaSuccess) {
      cudaGetLastError();
      throw DeviceError("CUDA backend: no usable CUDA device: " + cuda_error_text(e));
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
    for (int b = 0; b < 2; ++b) {
      check(cudaEventCreateWithFlags(&event_holder_[b].handle, cudaEventDisableTiming), "creating an event");
      staging_free_[b] = event_holder_[b].handle;
    }

    // The exact orient3d fallback keeps its expansions on the thread's stack (a few KB of local memory).
    // Reserve it now, so that no launch has to grow the local memory (a hidden synchronisation).  This
    // backend's own kernels (its `Point`) decide; the limit is per device and only ever raised here, so a
    // float and a double backend on one device both keep enough.
    std::size_t frame = 0;
    for (const auto& by_prepared : kDistributeKernels<Point>) {
      for (DistributeKernel<Point> kernel : by_prepared) {
        cudaFuncAttributes attr{};
        check(cudaFuncGetAttributes(&attr, kernel), "reading the kernel attributes");
        frame = std::max(frame, attr.localSizeBytes);
      }
    }
    std::size_t stack = 0;
    check(cudaDeviceGetLimit(&stack, cudaLimitStackSize), "reading the stack limit");
    const std::size_t want = align_up(frame, 256);
    if (stack < want) check(cudaDeviceSetLimit(cudaLimitStackSize, want), "setting the stack limit");

    for (int shared = 0; shared < 2; ++shared) {
      for (int prepared = 0; prepared < 2; ++prepared)
        distribute_blocks_[shared][prepared] =
            resident_blocks(kDistributeKernels<Point>[shared][prepared], shared ? kSharedFaces : 0);
    }

    scalars_host_.reserve(64, "result scalars");
    reserve(argmax_result_, 2, "argmax results");
    reserve(argmax_partial_, static_cast<std::size_t>(sm_count_) * 8, "argmax partials");
  }

  ~CudaBackend() override { cudaSetDevice(device_); }  // the members free the rest

  std::string name() const override { return name_; }

  void upload_points(const std::vector<Point>& points) override {
    select_device();
    n_points_ = points.size();
    n_active_ = n_points_;
    face_count_ = 0;
    if (n_points_ > 0xffffffffu) {
      throw DeviceError("CUDA backend: " + std::to_string(n_points_) +
                        " points exceed the 32-bit index range");
    }
    reserve(points_, n_points_, "the points");
    reserve(active_, n_points_, "the index array");
    reserve(active_alt_, n_points_, "the compacted index array");
    reserve(face_of_, n_points_, "the per-point faces");
    if (n_points_ == 0) return;
    // The per-iteration buffers start at a working size, so that a small hull does not grow them in most
    // of its iterations (each growth gives a block back, a small one after a wait for the stream, and takes
    // another: with cudaFree and cudaMalloc that was several synchronisations in a run of a small hull
    // (docs/benchmarks.md, "Measurements behind the code")).
    reserve(tables_dev_, kInitialTableBytes, "the iteration tables");
    staging_[0].reserve(kInitialTableBytes, "the table staging area");
    reserve(extremes_dev_, extremes_bytes(kInitialFaces), "the per-face counts and extremes");
    extremes_host_.reserve(extremes_bytes(kInitialFaces), "the per-face results");
    reserve(planes_, kInitialFaces, "the prepared face planes");
    check(cudaMemcpyAsync(points_.get(), points.data(), n_points_ * sizeof(Point), cudaMemcpyHostToDevice,
                          stream_),
          "uploading the points");
    bytes_to_ += n_points_ * sizeof(Point);
    all_active_ = true;  // the index array is the identity until the first compaction
    check(cudaMemsetAsync(face_of_.get(), 0, n_points_ * sizeof(std::int32_t), stream_),
          "clearing the per-point faces");
    // The caller's vector may change after return: wait for the (pageable) copy.
    check(cudaStreamSynchronize(stream_), "uploading the points");
  }

  void restart() override {
    n_active_ = n_points_;
    face_count_ = 0;
    all_active_ = true;
    if (n_points_ == 0) return;
    check(cudaMemsetAsync(face_of_.get(), 0, n_points_ * sizeof(std::int32_t), stream_),
          "clearing the per-point faces");
    check(cudaStreamSynchronize(stream_), "restarting");
  }

  std::array<PointIndex, 2> extremes_x() override {
    select_device();
    if (n_points_ == 0) return {0, 0};
    const unsigned blocks =
        std::min<unsigned>(blocks_for(n_points_), static_cast<unsigned>(argmax_partial_.size() / 2));
    extremes_x_partial<<<blocks, kBlock, 0, stream_>>>(points_.get(), n_points_, argmax_partial_.get());
    check(cudaGetLastError(), "launching extremes_x_partial");
    for (int slot = 0; slot < 2; ++slot) {
      argmax_final<<<1, kBlock, 0, stream_>>>(argmax_partial_.get() + slot * blocks, static_cast<int>(blocks),
                                              argmax_result_.get() + slot);
      check(cudaGetLastError(), "launching argmax_final");
    }
    const PointIndex* r = read_argmax(2);
    return {r[0], r[1]};
  }

  PointIndex furthest_from_line(PointIndex a, PointIndex b) override {
    select_device();
    if (n_points_ == 0) return 0;
    ScoreLine<Point> s{};
    s.a = a;
    s.b = b;
    launch_argmax(s, 0);
    return read_argmax(1)[0];
  }

  PointIndex furthest_from_plane(PointIndex a, PointIndex b, PointIndex c) override {
    select_device();
    if (n_points_ == 0) return 0;
    ScorePlane<Point> s{};
    s.a = a;
    s.b = b;
    s.c = c;
    launch_argmax(s, 0);
    return read_argmax(1)[0];
  }

  void distribute_points(const Tables& tables) override {
    select_device();
    face_count_ = tables.faces.size();
    const auto face_count = static_cast<std::int32_t>(face_count_);

    // One block on the device: the sections at 16-byte aligned offsets.
    constexpr int kSections = 7;
    const std::size_t sizes[kSections] = {tables.refinement.size() * sizeof(RefinementEntry),
                                          tables.decision.size() * sizeof(DecisionEntry),
                                          tables.faces.size() * sizeof(Geometry),
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
    times_ = {};
    auto t0 = Clock::now();
    reserve(tables_dev_, total, "the iteration tables", true);
    times_.allocate = ms_since(t0);
    t0 = Clock::now();
    upload_staged(sources, sizes, offsets, kSections, total);  // ~160 MB at 2M faces
    times_.stage = ms_since(t0);
    times_.table_bytes = total;

    unsigned char* base = tables_dev_.get();
    BasicRoutingView<Point> view;
    view.refinement = reinterpret_cast<const RefinementEntry*>(base + offsets[0]);
    view.old_face_split = reinterpret_cast<const std::int32_t*>(base + offsets[5]);
    view.old_face_route = reinterpret_cast<const std::int32_t*>(base + offsets[6]);
    view.decision = reinterpret_cast<const DecisionEntry*>(base + offsets[1]);
    view.faces = reinterpret_cast<const Geometry*>(base + offsets[2]);
    view.face_count = face_count;
    view.initial_cells =
        tables.initial_cells.empty() ? nullptr : reinterpret_cast<const SeparatingPlane*>(base + offsets[3]);
    view.interior = tables.interior;
    const auto* retired = reinterpret_cast<const PointIndex*>(base + offsets[4]);

    // The pass's results, in the layout compact_index_array copies back in one piece: the number of points
    // kept, then per face the extreme keys and the counts.
    const std::size_t words = (extremes_bytes(face_count_) + 7) / 8;
    reserve(extremes_dev_, 8 * words, "the per-face counts and extremes", true);
    unsigned long long* best = extremes_best();
    std::uint32_t* count = extremes_count();
    results_on_host_ = false;
    // Planes prepared once a face pay off when there are more points than faces (not in a sphere's late
    // iterations: two million faces and a few thousand points).
    const bool prepared = n_active_ != 0 && n_active_ >= face_count_;
    if (prepared) reserve(planes_, face_count_, "the prepared face planes", true);
    const std::size_t threads = std::max({words, tables.retired.size(), prepared ? face_count_ : 0});
    begin_pass_kernel<<<blocks_for(threads), kBlock, 0, stream_>>>(
        reinterpret_cast<unsigned long long*>(extremes_dev_.get()), words, retired, tables.retired.size(),
        face_of_.get(), view.faces, face_count, view.interior, prepared ? planes_.get() : nullptr);
    check(cudaGetLastError(), "launching begin_pass_kernel");
    if (n_active_ == 0) return;
    const bool shared = face_count <= kSharedFaces;
    const unsigned blocks = std::min<unsigned>(blocks_for(n_active_), distribute_blocks_[shared][prepared]);
    const std::size_t smem = shared ? face_count_ * (sizeof(unsigned long long) + sizeof(std::uint32_t)) : 0;
    kDistributeKernels<Point>[shared][prepared]<<<blocks, kBlock, smem, stream_>>>(
        points_.get(), active_indices(), n_active_, face_of_.get(), view, planes_.get(), count, best,
        active_alt_.get(), kept_count());
    check(cudaGetLastError(), "launching distribute_kernel");
  }

  // The pass compacted the index array itself (distribute_kernel); here its count comes back together with
  // the per-face results: one copy and one wait an iteration.
  std::size_t compact_index_array() override {
    select_device();
    read_results();
    std::uint64_t kept = 0;
    std::memcpy(&kept, results_host_, sizeof kept);
    if (n_active_ != 0) {
      active_.swap(active_alt_);
      all_active_ = false;
      n_active_ = static_cast<std::size_t>(kept);
    }
    return n_active_;
  }

  void get_extreme_points(std::vector<FaceExtreme>& out) override {
    select_device();
    out.assign(face_count_, {});
    if (face_count_ == 0) return;
    if (!results_on_host_) read_results();
    const auto* best = reinterpret_cast<const unsigned long long*>(results_host_ + kKeptBytes);
    const auto* count = reinterpret_cast<const std::uint32_t*>(results_host_ + kKeptBytes + 8 * face_count_);
    const auto t0 = Clock::now();
    parallel_chunks(
        face_count_, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t f = begin; f < end; ++f) {
            out[f].count = count[f];
            if (count[f]) out[f].furthest = unpack_extreme_index(best[f]);
          }
        },
        65536);
    if (phase_times_wanted()) {
      std::fprintf(stderr,
                   "  cuda ms: allocate %.2f stage %.2f (%.1f MB) copy+pass+readback wait %.2f unpack %.2f\n",
                   times_.allocate, times_.stage, static_cast<double>(times_.table_bytes) / 1e6, times_.wait,
                   ms_since(t0));
    }
  }

  bool has_device_point_states() const override { return true; }

  bool write_point_states_on_device(std::int32_t* out, std::size_t count,
                                    const std::vector<PointIndex>& vertices) override {
    select_device();
    if (count != n_points_ || count == 0) return false;
    fill_kernel<<<blocks_for(count), kBlock, 0, stream_>>>(out, count, kPointStateInternal);
    check(cudaGetLastError(), "launching fill_kernel");
    if (n_active_ != 0) {  // active points are external: their face
      point_faces_kernel<<<blocks_for(n_active_), kBlock, 0, stream_>>>(active_indices(), n_active_,
                                                                        face_of_.get(), out);
      check(cudaGetLastError(), "launching point_faces_kernel");
    }
    if (!vertices.empty()) {  // O(hull) to the device, nothing back
      reserve(vertex_ids_, vertices.size(), "the hull vertex ids");
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
    const DeviceArray<std::int32_t> faces(n_points_, kWho, "the debugger's point faces", stream_);
    check(cudaMemsetAsync(faces.get(), 0xff, n_points_ * sizeof(std::int32_t), stream_),
          "clearing the point faces");  // all bytes 0xff: -1
    if (n_active_ != 0) {
      point_faces_kernel<<<blocks_for(n_active_), kBlock, 0, stream_>>>(active_indices(), n_active_,
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

  // Room for n elements in a grow-only device array on the backend's stream (device_memory.hpp): reused
  // across iterations, replaced only when a larger size is needed; `slack` grows by half again so that a
  // slowly growing size is replaced rarely.  Contents are not kept.
  template <class T>
  void reserve(DeviceArray<T>& array, std::size_t n, const char* what, bool slack = false) {
    if (n <= array.size()) return;
    if (slack) n = std::max(n, array.size() + array.size() / 2);
    array.reset();  // the old block goes first, so that both are never held
    array = DeviceArray<T>(n, kWho, what, stream_);
  }

  // CUDAHULL_PHASE_TIMES=1 prints where each distribution's time goes on the host side of the backend, next
  // to the engine's phases (docs/benchmarks.md).
  struct PassTimes {
    double allocate = 0, stage = 0, wait = 0;
    std::size_t table_bytes = 0;
  };
  PassTimes times_;

  // The active points' indices for a kernel: null while every point is active (the kernels then use the
  // identity; no index array to fill and read for the first pass over all the points).
  const PointIndex* active_indices() const { return all_active_ ? nullptr : active_.get(); }

  // Enough resident blocks of `kernel` to fill the chip (the grid-stride loop takes the rest).
  template <class Kernel>
  unsigned resident_blocks(Kernel kernel, std::int32_t shared_faces) const {
    int per_sm = 0;
    check(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, kernel, kBlock,
                                                        shared_faces * (sizeof(unsigned long long) + 4)),
          "reading the occupancy");
    return static_cast<unsigned>(std::max(1, per_sm) * sm_count_);
  }

  // Pinned memory is slow to make: cudaMallocHost costs more than copying the same bytes
  // (docs/benchmarks.md, "Measurements behind the code").  So the tables go up by size:
  // - below kSmallPinned, through one pinned buffer (small, so cheap to grow);
  // - below kPinnedStaging, gathered in ordinary memory and copied from there (the driver stages such
  //   copies through pinned buffers of its own; growing a pinned buffer for a 10M-point ball's tables cost
  //   more than the copies);
  // - above, through two pinned buffers of kStagingChunk bytes, made once, taking turns: the cores fill one
  //   while the other's copy runs.  One pinned area as large as the tables was pinned afresh as a sphere's
  //   tables grew 2-3x an iteration: most of the 1M-point sphere's device time
  //   (docs/benchmarks.md).
  // read_results() picks its buffer by the same sizes (through_pinned()).
  static constexpr std::size_t kSmallPinned = std::size_t{256} << 10;
  // upload_points()'s first sizes: the tables and results of a hull of about 2,000 faces.
  static constexpr std::size_t kInitialTableBytes = std::size_t{128} << 10;
  static constexpr std::size_t kInitialFaces = 2048;
  static constexpr std::size_t kPinnedStaging = std::size_t{16} << 20;
  static constexpr std::size_t kStagingChunk = std::size_t{8} << 20;
  static bool through_pinned(std::size_t bytes) { return bytes < kSmallPinned || bytes >= kPinnedStaging; }

  void upload_staged(const void* const* sources, const std::size_t* sizes, const std::size_t* offsets,
                     int sections, std::size_t total) {
    if (total == 0) return;
    if (!through_pinned(total)) {
      tables_pageable_.resize(total);
      for (int s = 0; s < sections; ++s) {
        if (sizes[s] != 0) std::memcpy(tables_pageable_.data() + offsets[s], sources[s], sizes[s]);
      }
      // From pageable memory the call returns once the driver has taken the bytes: the buffer is free again.
      check(
          cudaMemcpyAsync(tables_dev_.get(), tables_pageable_.data(), total, cudaMemcpyHostToDevice, stream_),
          "uploading the iteration tables");
      bytes_to_ += total;
      return;
    }
    const std::size_t chunk = std::min(total, kStagingChunk);
    // Tables under kPinnedStaging are copied by this thread alone: waking the pool would cost more.
    const unsigned workers = total >= kPinnedStaging ? hardware_workers() : 1;
    for (std::size_t begin = 0, turn = 0; begin < total; begin += chunk, ++turn) {
      const std::size_t end = std::min(total, begin + chunk);
      const int b = static_cast<int>(turn % 2);
      // This buffer's previous copy (this iteration's, or the last one's) must be done before it is refilled.
      check(cudaEventSynchronize(staging_free_[b]), "waiting for a table upload");
      staging_[b].reserve(chunk, "the table staging area");
      for (int s = 0; s < sections; ++s) {
        const std::size_t from = std::max(begin, offsets[s]), to = std::min(end, offsets[s] + sizes[s]);
        if (from < to) {
          parallel_memcpy(staging_[b].get() + (from - begin),
                          static_cast<const unsigned char*>(sources[s]) + (from - offsets[s]), to - from,
                          std::size_t{256} << 10, workers);
        }
      }
      check(cudaMemcpyAsync(tables_dev_.get() + begin, staging_[b].get(), end - begin, cudaMemcpyHostToDevice,
                            stream_),
            "uploading the iteration tables");
      check(cudaEventRecord(staging_free_[b], stream_), "recording an event");
    }
    bytes_to_ += total;
  }

  // The distribution pass's results (kept count, per-face keys and counts) to the host, then wait.
  void read_results() {
    const std::size_t bytes = extremes_bytes(face_count_);
    auto t0 = Clock::now();
    if (through_pinned(bytes)) {
      extremes_host_.reserve(bytes, "the per-face results");
      results_host_ = extremes_host_.get();
    } else {  // see upload_staged(): a pinned buffer would cost more to make than this copy
      results_pageable_.resize(bytes);
      results_host_ = results_pageable_.data();
    }
    times_.allocate += ms_since(t0);
    t0 = Clock::now();
    check(cudaMemcpyAsync(results_host_, extremes_dev_.get(), bytes, cudaMemcpyDeviceToHost, stream_),
          "reading the per-face counts and extremes");
    check(cudaStreamSynchronize(stream_), "distributing the points (kernel fault)");
    times_.wait = ms_since(t0);
    bytes_from_ += bytes;
    results_on_host_ = true;
  }

  template <class Score>
  void launch_argmax(const Score& score, int slot) {
    const unsigned blocks =
        std::min<unsigned>(blocks_for(n_points_), static_cast<unsigned>(argmax_partial_.size()));
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

  static constexpr std::size_t kKeptBytes = sizeof(unsigned long long);
  static std::size_t extremes_bytes(std::size_t faces) {
    return kKeptBytes + faces * (sizeof(unsigned long long) + 4);
  }
  unsigned long long* kept_count() const {
    return reinterpret_cast<unsigned long long*>(extremes_dev_.get());
  }
  unsigned long long* extremes_best() const {
    return reinterpret_cast<unsigned long long*>(extremes_dev_.get() + kKeptBytes);
  }
  std::uint32_t* extremes_count() const {
    return reinterpret_cast<std::uint32_t*>(extremes_dev_.get() + kKeptBytes +
                                            sizeof(unsigned long long) * face_count_);
  }

  int device_;
  std::string name_;
  int sm_count_ = 0;
  unsigned distribute_blocks_[2][2] = {};  // [shared accumulators][prepared planes]: resident blocks
  // Destroyed after the buffers and the stream: the pool's free memory goes back to the driver, so that a
  // backend that is gone holds no device memory (but for the small blocks the allocator caches), as when
  // each buffer was a cudaMalloc.
  TrimPoolAtEnd trim_pool_at_end_{0};
  // Declared first among the buffers, so destroyed after them: each is given back in the stream's order (a
  // small block after a wait for the stream), then the stream is drained.
  Stream stream_holder_;
  Event event_holder_[2];
  cudaStream_t stream_ = nullptr;
  cudaEvent_t staging_free_[2] = {nullptr, nullptr};  // per staging buffer: its last copy is done

  std::size_t n_points_ = 0, n_active_ = 0, face_count_ = 0;
  DeviceArray<Point> points_;
  DeviceArray<PointIndex> active_, active_alt_;
  DeviceArray<PointIndex> vertex_ids_;  // write_point_states_on_device
  DeviceArray<std::int32_t> face_of_;
  DeviceArray<FacePlanes> planes_;
  DeviceArray<unsigned char> tables_dev_, extremes_dev_;
  bool results_on_host_ = false;           // results_host_ holds the last distribution's results
  unsigned char* results_host_ = nullptr;  // extremes_host_ or results_pageable_, by size (read_results())
  std::vector<unsigned char> results_pageable_, tables_pageable_;
  bool all_active_ = false;  // see active_indices()
  DeviceArray<Candidate> argmax_partial_;
  DeviceArray<PointIndex> argmax_result_;
  PinnedBuffer staging_[2], extremes_host_, scalars_host_;

  std::uint64_t bytes_to_ = 0, bytes_from_ = 0;
};

}  // namespace

template <class Point>
std::unique_ptr<BasicBackend<Point>> make_cuda_backend(int device) {
  return std::make_unique<CudaBackend<Point>>(device);
}
template std::unique_ptr<BasicBackend<Point3>> make_cuda_backend<Point3>(int);
template std::unique_ptr<BasicBackend<Point3d>> make_cuda_backend<Point3d>(int);

}  // namespace cudahull
