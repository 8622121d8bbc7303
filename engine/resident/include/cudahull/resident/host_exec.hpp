// The resident engine's host executor: every operation as a plain loop on one thread, in index order.  The
// device executor (cuda/resident_cuda.cu) runs the same operations as kernels; the atomics of the
// operations resolve to the same values either way, so both give the same mesh.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "cudahull/resident/iteration.hpp"
#include "cudahull/resident/resident_ops.hpp"
#include "cudahull/tuning.hpp"

namespace cudahull::resident {

struct HostExec {
  static constexpr bool kDeviceLoop = false;      // no loop of whole iterations of its own
  static constexpr std::size_t kFinishFaces = 0;  // no finish of its own (finish_small)
  template <class T>
  class Buffer {
   public:
    // Room for n elements; the first `keep` keep their values.  The rest are filled with a pattern, as
    // the device's new block holds garbage: a value used but not kept shows on the host too.
    void grow(std::size_t n, std::size_t keep = 0) {
      if (n <= data_.size()) return;
      std::vector<T> fresh(n);
      std::memset(static_cast<void*>(fresh.data()), 0xa5, n * sizeof(T));
      std::copy(data_.begin(), data_.begin() + static_cast<std::ptrdiff_t>(std::min(keep, data_.size())),
                fresh.begin());
      data_.swap(fresh);
    }
    T* data() { return data_.data(); }
    void swap(Buffer& other) { data_.swap(other.data_); }
    void release() { std::vector<T>().swap(data_); }
    std::size_t capacity() const { return data_.size(); }

   private:
    std::vector<T> data_;
  };

  template <class Op>
  void for_each(std::size_t n, const Op& op) {
    ++launches;
    for (std::size_t i = 0; i < n; ++i)
      op(i);
  }
  template <class Op>
  void segmented_max(std::size_t n, const Op& op) {
    for_each(n, op);
  }
  template <class KeyOp>
  std::uint64_t reduce_max(std::size_t n, const KeyOp& key) {
    ++launches;
    std::uint64_t best = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t k = key(i);
      if (k > best) best = k;
    }
    ++host_syncs;
    return best;
  }
  // The largest of each of K keys over i < n (keys(i, out) writes point i's K keys); `meanwhile()` is the
  // caller's work that does not need the result (the GPU's executor runs it while the device reduces).
  template <int K, class KeysOp, class Meanwhile>
  std::array<std::uint64_t, K> reduce_max_many(std::size_t n, const KeysOp& keys, Meanwhile&& meanwhile) {
    meanwhile();
    ++launches;
    std::array<std::uint64_t, K> best{};
    std::uint64_t mine[K];
    for (std::size_t i = 0; i < n; ++i) {
      keys(i, mine);
      for (int k = 0; k < K; ++k)
        best[k] = mine[k] > best[k] ? mine[k] : best[k];
    }
    ++host_syncs;
    return best;
  }
  // The distinct values of in[0..n), ascending, into out, and how many into *count (values below
  // `bound`; scratch: n entries).
  void sort_unique_to(const std::uint32_t* in, std::size_t n, std::uint32_t* out, std::uint32_t* /*scratch*/,
                      std::size_t /*bound*/, std::uint32_t* count) {
    ++launches;
    std::vector<std::uint32_t> values(in, in + n);
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    std::copy(values.begin(), values.end(), out);
    *count = static_cast<std::uint32_t>(values.size());
  }
  // The indices i < n with pred(i), in order, into out; returns how many.
  template <class Pred>
  std::uint32_t select_if(std::size_t n, const Pred& pred, std::uint32_t* out) {
    ++launches;
    std::uint32_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (pred(static_cast<std::uint32_t>(i))) out[count++] = static_cast<std::uint32_t>(i);
    }
    ++host_syncs;
    return count;
  }
  // out[i] = in[0] + ... + in[i-1]; returns the total.
  std::uint32_t exclusive_scan(const std::uint32_t* in, std::uint32_t* out, std::size_t n) {
    ++launches;
    std::uint32_t sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t v = in[i];
      out[i] = sum;
      sum += v;
    }
    ++host_syncs;
    return sum;
  }
  // The indices i with flags[i] != 0, in order, into list; returns how many (rank is scratch).
  std::uint32_t select(const std::uint32_t* flags, std::uint32_t* rank, std::uint32_t* list, std::size_t n) {
    const std::uint32_t count = exclusive_scan(flags, rank, n);
    for (std::size_t i = 0; i < n; ++i) {
      if (flags[i]) list[rank[i]] = static_cast<std::uint32_t>(i);
    }
    return count;
  }
  template <class T>
  void fill(T* at, std::size_t n, T value) {
    ++launches;
    for (std::size_t i = 0; i < n; ++i)
      at[i] = value;
  }
  template <class T>
  void upload(T* to, const T* from, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
      to[i] = from[i];
    bytes_to_device += n * sizeof(T);
  }
  template <class T>
  void download(T* to, const T* from, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
      to[i] = from[i];
    ++host_syncs;
    bytes_from_device += n * sizeof(T);
  }

  // The iteration's phases (iteration.hpp) on one thread, whatever the launch (the device's runs them a
  // range a kernel, or a loop of them in one block).
  template <class Point, class Log>
  void iterations(IterationBuffers<Point, Log> b, const IterationLaunch& launch, bool loop) {
    const std::size_t words = std::size_t{launch.face_capacity} / 32 + 1;
    win_mask_.resize(words);
    word_rank_.resize(words);
    b.win_mask = win_mask_.data();
    b.word_rank = word_rank_.data();
    if (loop) {
      ++launches;
      resident_iterations(HostTeam{}, b, launch);
      return;
    }
    // As the device's executor: a range of phases a launch, each after the last (iteration.hpp).
    for_each_phase_range(launch, [&](auto range, const IterationLaunch& part) {
      ++launches;
      resident_iterations(HostTeam{}, b, part, range);
    });
  }

  std::vector<u32> win_mask_, word_rank_;  // the rounds' bits per face and ranks per word
  std::uint64_t host_syncs = 0, bytes_to_device = 0, bytes_from_device = 0;
  std::uint64_t launches = 0;  // operations run (a kernel launch each on the device)
};

// The host executor taking the driver's paths as the GPU's executor does: the device loop once few points
// are left (with its room checks and regrowth), and the finish of a small mesh in one step.  The CPU tests
// compare its mesh with HostExec's and so check the driver's device paths without a GPU.
struct DevicePathHostExec : HostExec {
  static constexpr bool kDeviceLoop = true;
  explicit DevicePathHostExec(const ResidentTuning& tuning = {}) : tuning(tuning) {}
  ResidentTuning tuning;  // the device loop's limits, as CudaExec's (one_block_faces: the device's alone)
  static constexpr std::size_t kFinishFaces = kSmallFinishFaces;

  // As the GPU's finish_small_kernel: out = [faults, vertices, the corners renumbered, the vertex list].
  template <class Point>
  void finish_small(const MeshView<Point>& m, std::size_t faces, std::size_t /*bound*/, u32* out) {
    u32 faults = 0;
    for_each(faces, CountFaults<Point>{m, &faults});
    const std::size_t corners = 3 * faces;
    u32* list = out + 2 + corners;
    sort_unique_to(m.fv, corners, list, nullptr, 0, &out[1]);
    for_each(corners, FindCorners{m.fv, list, &out[1], out + 2});
    out[0] = faults;
  }
};

}  // namespace cudahull::resident
