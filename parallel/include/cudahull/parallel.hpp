// A minimal fork-join loop for the host: the CPU backend's point passes and the engine's per-face passes
// and batched mesh edits.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace cudahull {

// std::allocator, except that resize() leaves new elements of a trivial type uninitialised instead of
// zeroing them: for the arrays a parallel pass fills, which a zeroing resize() would first write on the
// calling core, whose cache lines each worker would then have to take from it before writing its own.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A vector for a parallel pass to fill: resize() writes nothing (DefaultInitAllocator).
template <class T>
using PassVector = std::vector<T, DefaultInitAllocator<T>>;

// Asked once: glibc answers hardware_concurrency() by opening and reading /sys/devices/system/cpu/online,
// and the engine asks before every parallel pass (dozens of times for a small cube, once most of its host
// time (docs/benchmarks.md, "Measurements behind the code")).  CUDAHULL_THREADS=N (N >= 1) sets the count
// instead, as OMP_NUM_THREADS does elsewhere.
inline unsigned hardware_workers() {
  static const unsigned workers = [] {
    if (const char* text = std::getenv("CUDAHULL_THREADS")) {
      const long asked = std::strtol(text, nullptr, 10);
      if (asked >= 1) return static_cast<unsigned>(std::min(asked, 1024L));
    }
    return std::max(1u, std::thread::hardware_concurrency());
  }();
  return workers;
}

// The workers for a pass of n items that is worth spreading over the cores only from `least` items up (a
// small mesh's pass costs less on the calling thread than the workers' wake-up and the lines they share).
inline unsigned workers_from(std::size_t n, std::size_t least) {
  return n >= least ? hardware_workers() : 1;
}

namespace detail {
// How many SerialScopes are alive on this thread.
inline thread_local int serial_scopes = 0;
}  // namespace detail

// While one lives on a thread, parallel_chunks() on that thread runs every range there, as for one worker:
// for callers that keep every core busy with work of their own (convex_hull_batch(): a cloud a worker, each
// cloud's engine passes on its worker's thread).  Results do not change: the callers' bodies are written
// for any split of their range.
class SerialScope {
 public:
  SerialScope() { ++detail::serial_scopes; }
  ~SerialScope() { --detail::serial_scopes; }
  SerialScope(const SerialScope&) = delete;
  SerialScope& operator=(const SerialScope&) = delete;
};

// Wakes the worker threads that parallel_chunks() hands its jobs to, so that they watch for one for the
// next `watch` instead of sleeping: for a caller about to run short passes after a long wait (the merge
// after the device's hull), whose first job would otherwise wait for every worker to be woken.  Returns at
// once; the caller pays one wake-up, the first worker wakes the rest.
void wake_workers(std::chrono::microseconds watch);

// How long an idle worker watches for the next job (and a caller for the last worker) before it sleeps;
// zero: at once.  The default, 200 us, and the A/B that chose it are in docs/benchmarks.md; the command
// line sets it from CUDAHULL_WORKER_WATCH_US, for A/B runs.  Takes effect at the workers' next watch.
void set_worker_watch(std::chrono::microseconds watch);

namespace detail {
using ChunkCall = void (*)(void* body, std::size_t begin, std::size_t end, unsigned worker);
// Runs call(body, begin, end, w) for w in [0, workers) on the process's persistent worker threads (the
// caller takes chunk 0).  Returns false, having run nothing, when the pool cannot take the job: it is busy
// with another caller's job, the caller is one of its workers, or `workers` exceeds its size.  A batched
// edit round is a few microseconds of work per core, so starting fresh threads for it would cost more.
bool run_on_worker_pool(std::size_t n, unsigned workers, ChunkCall call, void* body);
}  // namespace detail

// Runs body(begin, end, worker) over [0, n) split into one contiguous chunk per worker, with at most
// n / grain workers (so small ranges run on the calling thread, where handing them out would cost more
// than the work); `worker` is below the `workers` asked for.  Exceptions from any chunk reach the caller.
template <class Body>
void parallel_chunks(std::size_t n, unsigned workers, Body&& body, std::size_t grain = 4096) {
  if (workers <= 1 || n < grain || detail::serial_scopes > 0) {
    body(std::size_t{0}, n, 0u);
    return;
  }
  // At least `grain` items a worker: waking a thread for less costs more than it saves.
  workers = static_cast<unsigned>(std::min<std::size_t>(workers, n / grain));
  if (workers <= 1) {
    body(std::size_t{0}, n, 0u);
    return;
  }
  using BodyType = std::remove_reference_t<Body>;
  const detail::ChunkCall call = [](void* b, std::size_t begin, std::size_t end, unsigned w) {
    (*static_cast<BodyType*>(b))(begin, end, w);
  };
  if (detail::run_on_worker_pool(n, workers, call, const_cast<void*>(static_cast<const void*>(&body))))
    return;
  // The pool is taken (e.g. the viewer's engine thread and the CPU backend at once) or smaller than asked:
  // plain threads, whose exceptions reach the caller too (the caller's own first).
  std::vector<std::thread> threads;
  std::vector<std::exception_ptr> errors(workers);
  const std::size_t chunk = (n + workers - 1) / workers;
  for (unsigned w = 1; w < workers; ++w) {
    const std::size_t begin = std::min(n, w * chunk), end = std::min(n, begin + chunk);
    threads.emplace_back([&body, &errors, begin, end, w] {
      try {
        body(begin, end, w);
      } catch (...) {
        errors[w] = std::current_exception();
      }
    });
  }
  try {
    body(std::size_t{0}, std::min(n, chunk), 0u);
  } catch (...) {
    errors[0] = std::current_exception();
  }
  for (auto& t : threads)
    t.join();
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

// The least block parallel_blocks() deals out.
constexpr std::size_t kLeastBlock = 48;

// parallel_blocks() with `side()` run once, by the first thread to start, while the others take the blocks:
// a one-core step overlapped with a pass it does not depend on.
template <class Body, class Side>
void parallel_blocks_beside(std::size_t n, unsigned workers, Body&& body, Side&& side,
                            std::size_t block = 4096) {
  block = std::min(block, std::max(kLeastBlock, n / (4 * std::max(1u, workers))));
  const std::size_t blocks = (n + block - 1) / block;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> side_taken{false};
  // One more chunk than blocks, so that the side task has a worker even for a single block.
  parallel_chunks(
      blocks + 1, workers,
      [&](std::size_t, std::size_t, unsigned worker) {
        if (!side_taken.exchange(true, std::memory_order_relaxed)) side();
        for (std::size_t b; (b = next.fetch_add(1, std::memory_order_relaxed)) < blocks;)
          body(b * block, std::min(n, (b + 1) * block), worker);
      },
      1);
}

// parallel_chunks() with its range dealt out in blocks of `block` items to whichever thread is free, for
// passes whose items are independent: on a shared machine a worker the scheduler holds back takes fewer
// blocks, where an even split left the caller waiting for that worker's half.  `block` is the largest
// block: a pass of few items gets at least four blocks a worker (of kLeastBlock items or more), so that a
// hull of some thousand vertices keeps every core of a large machine busy, not as many as its blocks.
template <class Body>
void parallel_blocks(std::size_t n, unsigned workers, Body&& body, std::size_t block = 4096) {
  parallel_blocks_beside(
      n, workers, std::forward<Body>(body), [] {}, block);
}

// memcpy on all cores, in blocks of `block` bytes: one core copies the CUDA backend's per-iteration tables
// (about 110 MB at 2M faces) into pinned memory more slowly than the bus then carries them.
inline void parallel_memcpy(void* dst, const void* src, std::size_t bytes,
                            std::size_t block = std::size_t{1} << 20, unsigned workers = hardware_workers()) {
  parallel_chunks((bytes + block - 1) / block, workers,
                  [&](std::size_t begin, std::size_t end, unsigned) {
                    // A trailing chunk can be empty (begin == end == the block count), past the last partial
                    // block.
                    const std::size_t from = std::min(bytes, begin * block),
                                      to = std::min(bytes, end * block);
                    if (to > from)
                      std::memcpy(static_cast<unsigned char*>(dst) + from,
                                  static_cast<const unsigned char*>(src) + from, to - from);
                  },
                  4);
}

// The pages of [begin, begin + bytes) made resident on all cores (madvise(MADV_POPULATE_WRITE) on Linux 5.14
// and later; elsewhere nothing): for a large array about to be written on one core, whose page faults (the
// kernel zeroing each page) would otherwise be taken one at a time on that core.
void populate_pages(void* begin, std::size_t bytes);

// The least growth resize_populated() populates first: the staging's threshold
// (cudahull/cuda/host_transfer.hpp), not swept.
inline constexpr std::size_t kPopulateFrom = std::size_t{16} << 20;

// v.resize(n), with the new elements' pages populated on all cores first where they are kPopulateFrom bytes
// or more, so that the resize's zeroing and the copy into v after it write resident memory: for the
// results read back from the device (240 MB of triangles for a sphere of 10M points), whose first touch on
// one core cost more than the copy itself (docs/benchmarks.md, "The finish's result").
template <class T, class Allocator>
void resize_populated(std::vector<T, Allocator>& v, std::size_t n) {
  if (n > v.size() && (n - v.size()) * sizeof(T) >= kPopulateFrom) {
    v.reserve(n);
    populate_pages(v.data() + v.size(), (n - v.size()) * sizeof(T));
  }
  v.resize(n);
}

// std::sort on all cores: each worker sorts one chunk, then pairs of sorted runs merge, log2(workers)
// rounds.  For the result's million-vertex lists; small ones sort on the calling thread.
template <class T>
void parallel_sort(std::vector<T>& values) {
  const std::size_t n = values.size();
  const unsigned workers = hardware_workers();
  if (n < 65536 || workers == 1) {
    std::sort(values.begin(), values.end());
    return;
  }
  const std::size_t chunk = (n + workers - 1) / workers;
  std::vector<std::size_t> bounds(workers + 1);
  for (unsigned w = 0; w <= workers; ++w)
    bounds[w] = std::min(n, w * chunk);
  parallel_chunks(
      workers, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t w = begin; w < end; ++w)
          std::sort(values.begin() + bounds[w], values.begin() + bounds[w + 1]);
      },
      1);
  std::vector<T> merged(n);
  for (std::size_t width = 1; width < workers; width *= 2) {
    const std::size_t pairs = (workers + 2 * width - 1) / (2 * width);
    parallel_chunks(
        pairs, static_cast<unsigned>(pairs),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t p = begin; p < end; ++p) {
            const std::size_t i = p * 2 * width;
            const std::size_t lo = bounds[i], mid = bounds[std::min<std::size_t>(i + width, workers)],
                              hi = bounds[std::min<std::size_t>(i + 2 * width, workers)];
            std::merge(values.begin() + lo, values.begin() + mid, values.begin() + mid, values.begin() + hi,
                       merged.begin() + lo);
          }
        },
        1);
    values.swap(merged);
  }
}

}  // namespace cudahull
