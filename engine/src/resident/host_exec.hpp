// The resident engine's host executor: every operation as a plain loop on one thread, in index order.  The
// device executor (cuda/resident_cuda.cu) runs the same operations as kernels; the atomics of the
// operations resolve to the same values either way, so both give the same mesh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cudahull::resident {

struct HostExec {
  static constexpr bool kFusedRounds = false;  // the driver steps the rounds
  template <class T>
  class Buffer {
   public:
    // Room for n elements; the first `keep` keep their values.
    void grow(std::size_t n, std::size_t /*keep*/ = 0) {
      if (n > data_.size()) data_.resize(n);
    }
    T* data() { return data_.data(); }
    void swap(Buffer& other) { data_.swap(other.data_); }

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
  // The same, the total written to *total where the executor computes (no wait for it).
  void exclusive_scan_to(const std::uint32_t* in, std::uint32_t* out, std::size_t n, std::uint32_t* total) {
    *total = exclusive_scan(in, out, n);
    --host_syncs;
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

  std::uint64_t host_syncs = 0, bytes_to_device = 0, bytes_from_device = 0;
};

}  // namespace cudahull::resident
