// The persistent worker threads behind parallel_chunks().  Started on first use, one fewer than the
// hardware threads (the caller works too), and never stopped.  Each sleeps on its own semaphore, so a job
// for k workers wakes exactly k - 1 threads (a shared condition variable woke all of them for every job,
// which cost more than the job in the engine's many small per-iteration passes).  They do not spin for
// the next job: spinning workers slowed the serial edits between jobs.
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <semaphore>

#include "cudahull/parallel.hpp"

namespace cudahull::detail {

namespace {

thread_local bool on_pool_worker = false;

class WorkerPool {
 public:
  explicit WorkerPool(unsigned size) : size_(size) {
    wake_.reserve(size_ + 1);
    for (unsigned w = 0; w <= size_; ++w)
      wake_.push_back(std::make_unique<std::binary_semaphore>(0));
    for (unsigned w = 1; w <= size_; ++w)
      std::thread([this, w] { work(w); }).detach();
  }

  bool try_run(std::size_t n, unsigned workers, ChunkCall call, void* body) {
    if (on_pool_worker || workers > size_ + 1) return false;
    std::unique_lock caller(run_mutex_, std::try_to_lock);
    if (!caller.owns_lock()) return false;
    n_ = n;
    workers_ = workers;
    call_ = call;
    body_ = body;
    error_ = nullptr;
    pending_.store(workers - 1, std::memory_order_relaxed);
    for (unsigned w = 1; w < workers; ++w)
      wake_[w]->release();  // publishes the job fields above to worker w
    std::exception_ptr mine;
    try {
      call(body, 0, std::min(n, chunk(n, workers)), 0);
    } catch (...) {
      mine = std::current_exception();
    }
    if (workers > 1) done_.acquire();
    if (mine) std::rethrow_exception(mine);
    if (error_) std::rethrow_exception(error_);
    return true;
  }

 private:
  static std::size_t chunk(std::size_t n, unsigned workers) { return (n + workers - 1) / workers; }

  void work(unsigned w) {
    on_pool_worker = true;
    for (;;) {
      wake_[w]->acquire();
      const std::size_t size = chunk(n_, workers_);
      const std::size_t begin = std::min(n_, w * size), end = std::min(n_, begin + size);
      try {
        call_(body_, begin, end, w);
      } catch (...) {
        std::lock_guard lock(error_mutex_);
        if (!error_) error_ = std::current_exception();
      }
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) done_.release();
    }
  }

  const unsigned size_;
  std::mutex run_mutex_;                                      // one job at a time
  std::vector<std::unique_ptr<std::binary_semaphore>> wake_;  // per worker (index 0 unused: the caller)
  std::binary_semaphore done_{0};                             // the last worker to finish releases it
  std::atomic<unsigned> pending_{0};
  std::size_t n_ = 0;
  unsigned workers_ = 0;
  ChunkCall call_ = nullptr;
  void* body_ = nullptr;
  std::mutex error_mutex_;
  std::exception_ptr error_;
};

}  // namespace

bool run_on_worker_pool(std::size_t n, unsigned workers, ChunkCall call, void* body) {
  // Never destroyed: detached workers may still be asleep in it while the process exits.
  static WorkerPool* pool = new WorkerPool(hardware_workers() - 1);
  return pool->try_run(n, workers, call, body);
}

}  // namespace cudahull::detail
