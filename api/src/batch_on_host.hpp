// The batch on the CPU (batch_on_host.cpp): the clouds on all cores, then their hulls packed.
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <vector>

#include "batch_common.hpp"
#include "cudahull/convex_hull.hpp"
#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/parallel.hpp"

namespace cudahull::batch {

// A cloud's share of the cores, below which it runs on one worker among the others: a cloud this large
// (and a large part of the batch) runs alone with its engine's passes on every core instead.
inline constexpr std::size_t kLargeCloud = std::size_t{1} << 15;

// The hulls of every cloud into `hulls`, `hull_of(c)` making cloud c's, on `threads` workers: the clouds
// handed out in order, each on its worker's thread.  A cloud that fails stops the clouds after it from
// starting; the lowest failing cloud's exception is thrown, an InputError named by its cloud.
template <class HullOf>
void run_batch_on_host(const std::size_t* offsets, std::size_t clouds, unsigned threads,
                       std::vector<ConvexHull>& hulls, HullOf hull_of) {
  std::vector<std::exception_ptr> errors(clouds);
  std::atomic<std::size_t> first_failed{clouds};
  auto run = [&](std::size_t c) {
    if (c > first_failed.load(std::memory_order_relaxed)) return;
    try {
      hulls[c] = hull_of(c);
    } catch (const InputError& error) {
      errors[c] = std::make_exception_ptr(in_cloud(error, c, offsets[c]));
    } catch (...) {
      errors[c] = std::current_exception();
    }
    if (errors[c]) {
      std::size_t seen = first_failed.load(std::memory_order_relaxed);
      while (c < seen && !first_failed.compare_exchange_weak(seen, c, std::memory_order_relaxed)) {
      }
    }
  };
  const std::size_t total = offsets[clouds];
  std::vector<char> large(clouds, 0);
  if (threads > 1) {
    // A cloud this large would keep its worker busy long after the others finish: it runs alone, first,
    // its engine's passes on every core.
    for (std::size_t c = 0; c < clouds; ++c) {
      const std::size_t n = offsets[c + 1] - offsets[c];
      large[c] = n >= kLargeCloud && n * 2 * threads > total;
    }
    for (std::size_t c = 0; c < clouds; ++c)
      if (large[c]) run(c);
  }
  std::atomic<std::size_t> next{0};
  parallel_chunks(
      threads, threads,
      [&](std::size_t begin, std::size_t end, unsigned) {
        // One slot a worker (or, where the pool is busy and this runs inline, all of them on this thread).
        for (std::size_t slot = begin; slot < end; ++slot) {
          const SerialScope serial;  // the cloud's engine passes stay on this worker's thread
          for (std::size_t c = next.fetch_add(1, std::memory_order_relaxed); c < clouds;
               c = next.fetch_add(1, std::memory_order_relaxed)) {
            if (!large[c]) run(c);
          }
        }
      },
      1);
  const std::size_t failed = first_failed.load();
  if (failed != clouds) std::rethrow_exception(errors[failed]);
}

// The per-cloud hulls packed into flat arrays, in cloud order (the copies on all cores: a batch of 100,000
// clouds has millions of faces).
ConvexHullBatch pack(std::vector<ConvexHull>&& hulls, Precision precision);

}  // namespace cudahull::batch
