// Host side of the predicates: the statistics counters.  The predicates themselves are inline
// (detail/predicates_impl.hpp) so that the CPU and CUDA backends compile the same code.
#include "cudahull/predicates.hpp"

#include <mutex>
#include <vector>

namespace cudahull {
namespace detail {

#if defined(__GNUC__)
__thread PredicateCounterBlock* predicate_counters_tls = nullptr;
#else
thread_local PredicateCounterBlock* predicate_counters_tls = nullptr;
#endif

namespace {

// Live per-thread blocks plus the totals of threads that have exited.
struct Registry {
  std::mutex mutex;
  std::vector<PredicateCounterBlock*> live;
  unsigned long long retired_calls = 0;
  unsigned long long retired_exact = 0;
  // Calls made while a thread is being torn down land here (after its own block is gone).
  PredicateCounterBlock orphan;
};

Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: threads may exit after static destruction
  return *r;
}

// Owns the calling thread's block; folds its counts into the totals when the thread exits.
struct ThreadRegistration {
  PredicateCounterBlock* block = new PredicateCounterBlock;
  ThreadRegistration() {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    r.live.push_back(block);
  }
  ~ThreadRegistration() {
    Registry& r = registry();
    {
      std::lock_guard lock(r.mutex);
      r.retired_calls += block->orient3d_calls.load(std::memory_order_relaxed);
      r.retired_exact += block->orient3d_exact.load(std::memory_order_relaxed);
      std::erase(r.live, block);
    }
    predicate_counters_tls = &r.orphan;
    delete block;
  }
};

}  // namespace

PredicateCounterBlock* register_predicate_counters() {
  thread_local ThreadRegistration registration;
  predicate_counters_tls = registration.block;
  return registration.block;
}

}  // namespace detail

PredicateStats predicate_stats() {
  detail::Registry& r = detail::registry();
  std::lock_guard lock(r.mutex);
  PredicateStats stats;
  stats.orient3d_calls = r.retired_calls + r.orphan.orient3d_calls.load(std::memory_order_relaxed);
  stats.orient3d_exact = r.retired_exact + r.orphan.orient3d_exact.load(std::memory_order_relaxed);
  for (const detail::PredicateCounterBlock* block : r.live) {
    stats.orient3d_calls += block->orient3d_calls.load(std::memory_order_relaxed);
    stats.orient3d_exact += block->orient3d_exact.load(std::memory_order_relaxed);
  }
  return stats;
}

// Counts that other threads add concurrently with the reset may survive it (each thread increments its own
// block without a lock); reset while the predicates are idle for exact numbers.
void reset_predicate_stats() {
  detail::Registry& r = detail::registry();
  std::lock_guard lock(r.mutex);
  r.retired_calls = 0;
  r.retired_exact = 0;
  r.orphan.orient3d_calls.store(0, std::memory_order_relaxed);
  r.orphan.orient3d_exact.store(0, std::memory_order_relaxed);
  for (detail::PredicateCounterBlock* block : r.live) {
    block->orient3d_calls.store(0, std::memory_order_relaxed);
    block->orient3d_exact.store(0, std::memory_order_relaxed);
  }
}

}  // namespace cudahull
