// The persistent worker threads behind parallel_chunks().  Started on first use, one fewer than the
// hardware threads (the caller works too), and never stopped.  Each sleeps on its own semaphore, so a job
// for k workers wakes exactly k - 1 threads (a shared condition variable woke all of them for every job,
// which cost more than the job in the engine's many small per-iteration passes).  After a job a worker
// watches for the next one for a short while (watch_time()) before it sleeps: the engine's batched swap
// rounds run about ten jobs back to back, and waking a sleeping thread can take longer than many of those
// jobs (docs/benchmarks.md, "Measurements behind the code").  It watches with a pause instruction, so that a
// hyperthread sibling doing serial edits is not slowed; for longer, spinning workers did slow the serial
// edits between jobs.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <semaphore>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "cudahull/parallel.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace cudahull::detail {

namespace {

thread_local bool on_pool_worker = false;

// How long a worker watches for the next job (and the caller for the last worker) before sleeping
// (set_worker_watch(), parallel.hpp).
std::atomic<std::int64_t> watch_us{200};
std::chrono::microseconds watch_time() {
  return std::chrono::microseconds(watch_us.load(std::memory_order_relaxed));
}

inline void cpu_pause() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

class WorkerPool {
 public:
  explicit WorkerPool(unsigned size) : size_(size) {
    wake_.reserve(size_ + 1);
    for (unsigned w = 0; w <= size_; ++w) {
      wake_.push_back(std::make_unique<std::counting_semaphore<>>(0));
      ready_.push_back(std::make_unique<std::atomic<bool>>(false));
    }
    for (unsigned w = 1; w <= size_; ++w)
      std::thread([this, w] { work(w); }).detach();
  }

  // Wakes the workers without a job, each to watch for one until `until`: worker 1 is woken here, and
  // wakes the others (one futex wake on the caller's thread, not one a worker).
  void wake(std::chrono::steady_clock::time_point until) {
    if (size_ == 0) return;
    watch_until_.store(until.time_since_epoch().count(), std::memory_order_relaxed);
    waking_.store(true, std::memory_order_release);
    wake_[1]->release();
  }

  bool try_run(std::size_t n, unsigned workers, ChunkCall call, void* body) {
    if (on_pool_worker || workers > size_ + 1) return false;
    std::unique_lock caller(run_mutex_, std::try_to_lock);
    if (!caller.owns_lock()) return false;
    ++job_;
    // The last job's claims are closed before its fields change: a worker that read them (every chunk
    // taken) and then this job's wider `workers_` would otherwise claim a chunk of this job under the last
    // job's claims, which still matched, and that chunk would run twice.  The fields' release stores
    // order this store before them for a worker that reads any of them.
    claims_.store(std::uint64_t{job_} << 32 | kClosed, std::memory_order_relaxed);
    n_.store(n, std::memory_order_release);
    workers_.store(workers, std::memory_order_release);
    call_.store(call, std::memory_order_release);
    body_.store(body, std::memory_order_release);
    error_ = nullptr;
    remaining_.store(workers, std::memory_order_relaxed);
    // Publishes the fields above with the job's chunks; chunk 0 is the caller's.
    claims_.store(std::uint64_t{job_} << 32 | 1, std::memory_order_release);
    for (unsigned w = 1; w < workers; ++w) {
      ready_[w]->store(true, std::memory_order_release);
      wake_[w]->release();  // in case it sleeps; a watching worker leaves this count behind (see work())
    }
    std::exception_ptr mine;
    try {
      call(body, 0, std::min(n, chunk(n, workers)), 0);
    } catch (...) {
      mine = std::current_exception();
    }
    finish_chunk();
    // Then the chunks no worker has taken yet: a worker still waking (milliseconds after a long sleep, or
    // held back by the scheduler) leaves its chunk to the caller, who would otherwise wait for it.
    run_claimed_chunks();
    wait_for_chunks();
    if (mine) std::rethrow_exception(mine);
    if (error_) std::rethrow_exception(error_);
    return true;
  }

 private:
  static std::size_t chunk(std::size_t n, unsigned workers) { return (n + workers - 1) / workers; }
  // A job's claims between jobs: no chunk is left to take, whatever `workers_` reads.
  static constexpr std::uint32_t kClosed = 0xffffffffu;

  void work(unsigned w) {
    on_pool_worker = true;
    for (;;) {
      if (!watch(w)) {
        wake_[w]->acquire();
        if (w == 1) pass_on_wake();
        // No job: a wake() (watch for one), or a count left by a job that was taken while watching.
        if (!ready_[w]->exchange(false, std::memory_order_acquire)) continue;
      }
      run_claimed_chunks();
    }
  }

  // Takes the current job's chunks one at a time until none is left (each chunk, and its number as the
  // body's worker, taken by one thread only): none at all for a worker that comes after its job ended.
  void run_claimed_chunks() {
    for (;;) {
      std::uint64_t claims = claims_.load(std::memory_order_acquire);
      const unsigned next = static_cast<std::uint32_t>(claims);
      // The fields as published with `claims`' job.  A later job first closes these claims, then rewrites
      // the fields: a field of it read here makes the exchange below see the closing and fail.
      const unsigned workers = workers_.load(std::memory_order_acquire);
      if (next >= workers) return;
      const std::size_t n = n_.load(std::memory_order_acquire);
      const ChunkCall call = call_.load(std::memory_order_acquire);
      void* const body = body_.load(std::memory_order_acquire);
      if (!claims_.compare_exchange_weak(claims, claims + 1, std::memory_order_acq_rel)) continue;
      const std::size_t size = chunk(n, workers);
      const std::size_t begin = std::min(n, next * size), end = std::min(n, begin + size);
      try {
        call(body, begin, end, next);
      } catch (...) {
        std::lock_guard lock(error_mutex_);
        if (!error_) error_ = std::current_exception();
      }
      finish_chunk();
    }
  }

  void finish_chunk() {
    if (remaining_.fetch_sub(1, std::memory_order_acq_rel) == 1) remaining_.notify_one();
  }

  // Polls `ready()` with a pause instruction between tries for up to watch_time() (or until a wake()'s
  // time); true once it holds.
  template <class Ready>
  bool watch_for(Ready&& ready) {
    const auto now = std::chrono::steady_clock::now();
    const auto until = std::max(now + watch_time(),
                                std::chrono::steady_clock::time_point(std::chrono::steady_clock::duration(
                                    watch_until_.load(std::memory_order_relaxed))));
    for (int spins = 0;; ++spins) {
      if (ready()) return true;
      cpu_pause();
      if ((spins & 63) == 63 && std::chrono::steady_clock::now() > until) return false;
    }
  }

  // The caller, for the chunks still running on workers: watched, as the workers watch for jobs, then
  // asleep.
  void wait_for_chunks() {
    if (watch_for([&] { return remaining_.load(std::memory_order_acquire) == 0; })) return;
    for (unsigned left; (left = remaining_.load(std::memory_order_acquire)) != 0;)
      remaining_.wait(left, std::memory_order_acquire);
  }

  // Worker 1: a wake() asked for the others too (whether it found 1 asleep or awake).
  void pass_on_wake() {
    if (waking_.load(std::memory_order_relaxed) && waking_.exchange(false, std::memory_order_acq_rel))
      for (unsigned u = 2; u <= size_; ++u)
        wake_[u]->release();
  }

  // Watches worker w's ready flag for watch_time(); true (and the flag taken) when a job came.
  bool watch(unsigned w) {
    return watch_for([&] {
      if (w == 1) pass_on_wake();
      return ready_[w]->load(std::memory_order_relaxed) &&
             ready_[w]->exchange(false, std::memory_order_acquire);
    });
  }

  const unsigned size_;
  std::mutex run_mutex_;                                          // one job at a time
  std::vector<std::unique_ptr<std::counting_semaphore<>>> wake_;  // per worker (index 0 unused: the caller)
  std::vector<std::unique_ptr<std::atomic<bool>>> ready_;         // per worker: a job is waiting for it
  std::atomic<bool> waking_{false};                               // a wake() for worker 1 to pass on
  std::atomic<std::chrono::steady_clock::rep> watch_until_{0};    // a wake()'s watch, on the steady clock
  // The job: its number (high half) and next chunk to take (low half), its chunks not yet finished, and
  // its fields (atomics: a worker coming late reads them beside the next job's writes, and then leaves).
  std::atomic<std::uint64_t> claims_{0};
  std::atomic<unsigned> remaining_{0};
  std::uint32_t job_ = 0;
  std::atomic<std::size_t> n_{0};
  std::atomic<unsigned> workers_{0};
  std::atomic<ChunkCall> call_{nullptr};
  std::atomic<void*> body_{nullptr};
  std::mutex error_mutex_;
  std::exception_ptr error_;
};

WorkerPool& worker_pool() {
  // Never destroyed: detached workers may still be asleep in it while the process exits.
  static WorkerPool* pool = new WorkerPool(hardware_workers() - 1);
  return *pool;
}

}  // namespace

bool run_on_worker_pool(std::size_t n, unsigned workers, ChunkCall call, void* body) {
  return worker_pool().try_run(n, workers, call, body);
}

}  // namespace cudahull::detail

namespace cudahull {

void wake_workers(std::chrono::microseconds watch) {
  // Not from a worker, nor under a SerialScope: those run their passes on their own thread.
  if (hardware_workers() <= 1 || detail::on_pool_worker || detail::serial_scopes > 0) return;
  detail::worker_pool().wake(std::chrono::steady_clock::now() + watch);
}

void set_worker_watch(std::chrono::microseconds watch) {
  detail::watch_us.store(std::max<std::int64_t>(0, watch.count()), std::memory_order_relaxed);
}

void populate_pages(void* begin, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  // Whole pages only (madvise takes page-aligned ranges), in blocks of a huge page so that each is
  // populated by one worker; a kernel without MADV_POPULATE_WRITE (before 5.14) answers EINVAL, and the
  // pages fault in as they are written, as without this call.
  constexpr std::uintptr_t kPage = 4096, kBlock = std::uintptr_t{2} << 20;
  const auto at = reinterpret_cast<std::uintptr_t>(begin);
  const std::uintptr_t first = (at + kPage - 1) & ~(kPage - 1), last = (at + bytes) & ~(kPage - 1);
  if (last <= first) return;
  const std::size_t blocks = (last - first + kBlock - 1) / kBlock;
  parallel_chunks(
      blocks, hardware_workers(),
      [&](std::size_t b, std::size_t e, unsigned) {
        const std::uintptr_t from = first + b * kBlock,
                             to = std::min<std::uintptr_t>(last, first + e * kBlock);
        if (to > from) madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
      },
      1);
#else
  (void)begin;
  (void)bytes;
#endif
}

}  // namespace cudahull
