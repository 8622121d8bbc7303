// The persistent worker threads behind parallel_chunks().  Started on first use, one fewer than the
// hardware threads (the caller works too), and never stopped: they sleep on a condition variable between
// jobs, after a short spin so that back-to-back rounds of a batched edit do not pay a wake-up each.
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>

#include "cudahull/parallel.hpp"

namespace cudahull::detail {

namespace {

thread_local bool on_pool_worker = false;

class WorkerPool {
 public:
  explicit WorkerPool(unsigned size) : size_(size) {
    for (unsigned w = 1; w <= size_; ++w)
      std::thread([this, w] { work(w); }).detach();
  }

  bool try_run(std::size_t n, unsigned workers, ChunkCall call, void* body) {
    if (on_pool_worker || workers > size_ + 1) return false;
    std::unique_lock caller(run_mutex_, std::try_to_lock);
    if (!caller.owns_lock()) return false;
    {
      std::lock_guard lock(mutex_);
      n_ = n;
      workers_ = workers;
      call_ = call;
      body_ = body;
      error_ = nullptr;
      pending_ = workers - 1;
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    std::exception_ptr mine;
    try {
      call(body, 0, std::min(n, chunk(n, workers)), 0);
    } catch (...) {
      mine = std::current_exception();
    }
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return pending_ == 0; });
    if (mine) std::rethrow_exception(mine);
    if (error_) std::rethrow_exception(error_);
    return true;
  }

 private:
  static std::size_t chunk(std::size_t n, unsigned workers) { return (n + workers - 1) / workers; }

  void work(unsigned w) {
    on_pool_worker = true;
    std::uint64_t seen = 0;
    for (;;) {
      // Spin a little (about 20 us) for the next job before sleeping.
      for (int spin = 0; spin < 4000 && generation_.load(std::memory_order_acquire) == seen; ++spin)
        std::this_thread::yield();
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return generation_.load(std::memory_order_acquire) != seen; });
      seen = generation_.load(std::memory_order_acquire);
      if (w >= workers_) continue;  // this job uses fewer workers
      const std::size_t n = n_, size = chunk(n_, workers_);
      const ChunkCall call = call_;
      void* body = body_;
      lock.unlock();
      const std::size_t begin = std::min(n, w * size), end = std::min(n, begin + size);
      std::exception_ptr error;
      try {
        call(body, begin, end, w);
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      if (error && !error_) error_ = error;
      if (--pending_ == 0) done_.notify_one();
    }
  }

  const unsigned size_;
  std::mutex run_mutex_;  // one job at a time
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::atomic<std::uint64_t> generation_{0};
  std::size_t n_ = 0;
  unsigned workers_ = 0;
  ChunkCall call_ = nullptr;
  void* body_ = nullptr;
  std::exception_ptr error_;
  unsigned pending_ = 0;
};

}  // namespace

bool run_on_worker_pool(std::size_t n, unsigned workers, ChunkCall call, void* body) {
  // Never destroyed: detached workers may still be asleep in it while the process exits.
  static WorkerPool* pool = new WorkerPool(hardware_workers() - 1);
  return pool->try_run(n, workers, call, body);
}

}  // namespace cudahull::detail
