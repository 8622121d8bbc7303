// The resident engine's host executor: every operation as a plain loop on one thread, in index order.  The
// device executor (cuda/resident_cuda.cu) runs the same operations as kernels; the atomics of the
// operations resolve to the same values either way, so both give the same mesh.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "cudahull/resident/resident_ops.hpp"
#include "cudahull/resident/rounds.hpp"

namespace cudahull::resident {

struct HostExec {
  static constexpr bool kFusedIterations = false;  // iterate(): the host waits for each count
  static constexpr bool kDeviceLoop = false;       // no loop of whole iterations of its own
  static constexpr std::size_t kFinishFaces = 0;   // no finish of its own (finish_small)
  template <class T>
  class Buffer {
   public:
    // Room for n elements; the first `keep` keep their values.
    void grow(std::size_t n, std::size_t /*keep*/ = 0) {
      if (n > data_.size()) data_.resize(n);
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
    for (std::size_t i = 0; i < n; ++i)
      op(i);
  }
  template <class Op>
  void segmented_max(std::size_t n, const Op& op) {
    for_each(n, op);
  }
  template <class KeyOp>
  std::uint64_t reduce_max(std::size_t n, const KeyOp& key) {
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
    std::vector<std::uint32_t> values(in, in + n);
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    std::copy(values.begin(), values.end(), out);
    *count = static_cast<std::uint32_t>(values.size());
  }
  // The indices i < n with pred(i), in order, into out; returns how many.
  template <class Pred>
  std::uint32_t select_if(std::size_t n, const Pred& pred, std::uint32_t* out) {
    std::uint32_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (pred(static_cast<std::uint32_t>(i))) out[count++] = static_cast<std::uint32_t>(i);
    }
    ++host_syncs;
    return count;
  }
  // out[i] = in[0] + ... + in[i-1]; returns the total.
  std::uint32_t exclusive_scan(const std::uint32_t* in, std::uint32_t* out, std::size_t n) {
    std::uint32_t sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t v = in[i];
      out[i] = sum;
      sum += v;
    }
    ++host_syncs;
    return sum;
  }
  // The same, the total not wanted (an operation after it writes what it needs of it).
  void scan(const std::uint32_t* in, std::uint32_t* out, std::size_t n) {
    exclusive_scan(in, out, n);
    --host_syncs;
  }
  // mark(i) for every i < n, flags' exclusive prefix sum into ranks, then move(i) for every i < n.
  template <class Mark, class Move>
  void mark_scan_move(std::size_t n, const Mark& mark, std::uint32_t* flags, std::uint32_t* ranks,
                      const Move& move) {
    if constexpr (!std::is_same_v<Mark, AlreadyMarked>) for_each(n, mark);
    scan(flags, ranks, n);
    for_each(n, move);
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

  // The rounds of an iteration (rounds.hpp) on one thread.
  template <class Point, class Log>
  void fused_rounds(const FindCandidate<Point, Log>& find, u64* claim, u32* look, Candidate* cands, u32* list,
                    RoundsState* st, RoundsLaunch launch) {
    start_rounds(st, launch);
    const std::size_t words = std::size_t{launch.face_capacity} / 32 + 1;
    win_mask_.resize(words);
    word_rank_.resize(words);
    swap_and_removal_rounds(HostTeam{}, RoundsBuffers<Point, Log>{find, claim, look, cands, list,
                                                                  win_mask_.data(), word_rank_.data(), st});
  }

  std::vector<u32> win_mask_, word_rank_;  // the rounds' bits per face and ranks per word
  std::uint64_t host_syncs = 0, bytes_to_device = 0, bytes_from_device = 0;
};

// The host executor running the driver's fused path as the GPU runs it: the iteration with its counts in
// the state (RoundsState) and one read at its end, and the finish of a small mesh in one step.  The CPU
// tests compare its mesh with the stepped iterations' (HostExec) and so check the driver's device path
// without a GPU.
struct FusedHostExec : HostExec {
  static constexpr bool kFusedIterations = true;
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
