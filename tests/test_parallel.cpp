// The worker pool (parallel.hpp): every index of a pass runs exactly once for any worker count, whether the
// pool, the caller or plain threads take its chunks; a chunk's exception reaches its caller and leaves the
// pool usable; two callers at once, wakes and watch settings change no result.  Oracle: a count per index.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "cudahull/parallel.hpp"

namespace cudahull {
namespace {

// A pool wider than the two cores CI has, unless the run sets its own: the race below needs a job of more
// workers after one of fewer, which a one-worker pool never runs (read once, when the pool is made).
const bool kWidePool = setenv("CUDAHULL_THREADS", "16", 0) == 0;

// How often each index of [0, n) ran, after parallel_chunks() with `workers` and `grain`.
std::vector<int> chunk_hits(std::size_t n, unsigned workers, std::size_t grain) {
  std::unique_ptr<std::atomic<int>[]> hits(new std::atomic<int>[n]());
  std::atomic<bool> worker_in_range{true};
  parallel_chunks(
      n, workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        if (worker >= std::max(1u, workers) || begin > end || end > n) worker_in_range = false;
        for (std::size_t i = begin; i < end; ++i)
          hits[i].fetch_add(1, std::memory_order_relaxed);
      },
      grain);
  EXPECT_TRUE(worker_in_range.load());
  std::vector<int> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = hits[i].load();
  return out;
}

std::vector<int> block_hits(std::size_t n, unsigned workers, std::size_t block) {
  std::unique_ptr<std::atomic<int>[]> hits(new std::atomic<int>[n]());
  std::atomic<int> sides{0};
  parallel_blocks_beside(
      n, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t i = begin; i < end; ++i)
          hits[i].fetch_add(1, std::memory_order_relaxed);
      },
      [&] { sides.fetch_add(1); }, block);
  EXPECT_EQ(sides.load(), 1) << "the side task runs once";
  std::vector<int> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = hits[i].load();
  return out;
}

TEST(WorkerPool, EveryIndexRunsOnceForAnyWorkerCount) {
  for (unsigned workers : {0u, 1u, 2u, 3u, 7u, 16u, 64u})  // 64: more than the pool has, plain threads
    for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{5}, std::size_t{4095},
                          std::size_t{4097}, std::size_t{100003}})
      for (std::size_t grain : {std::size_t{1}, std::size_t{64}, std::size_t{4096}}) {
        const std::vector<int> hits = chunk_hits(n, workers, grain);
        for (std::size_t i = 0; i < n; ++i)
          ASSERT_EQ(hits[i], 1) << "index " << i << " of " << n << ", " << workers << " workers, grain "
                                << grain;
      }
}

TEST(WorkerPool, EveryBlockRunsOnceBesideTheSideTask) {
  for (unsigned workers : {1u, 2u, 5u, 16u})
    for (std::size_t n :
         {std::size_t{0}, std::size_t{1}, std::size_t{47}, std::size_t{1000}, std::size_t{65537}})
      for (std::size_t block : {std::size_t{48}, std::size_t{4096}}) {
        const std::vector<int> hits = block_hits(n, workers, block);
        for (std::size_t i = 0; i < n; ++i)
          ASSERT_EQ(hits[i], 1) << "index " << i << " of " << n << ", " << workers << " workers";
      }
}

TEST(WorkerPool, AnExceptionReachesTheCallerAndThePoolGoesOn) {
  for (unsigned workers : {2u, 3u, 16u, 64u}) {
    for (std::size_t thrower : {std::size_t{0}, std::size_t{50000}, std::size_t{99999}}) {
      EXPECT_THROW(parallel_chunks(
                       100000, workers,
                       [&](std::size_t begin, std::size_t end, unsigned) {
                         if (begin <= thrower && thrower < end) throw std::runtime_error("chunk failed");
                       },
                       1),
                   std::runtime_error)
          << workers << " workers, thrown at " << thrower;
    }
    const std::vector<int> hits = chunk_hits(100000, workers, 1);
    for (int h : hits)
      ASSERT_EQ(h, 1);
  }
}

// A job of few workers, then one of many, over and over: a worker that read the narrow job's claims (all
// taken) and then the wide job's fields, before the wide job published its claims, took a chunk of the wide
// job under the narrow one's claims, and that chunk ran twice (the CPU backend's per-worker tables were
// then freed twice).  Each index must run once in every job.
TEST(WorkerPool, AWideJobAfterANarrowOneRunsEachChunkOnce) {
  ASSERT_TRUE(kWidePool);
  const unsigned wide = std::max(2u, hardware_workers());
  // A chunk run twice also upsets the pool's count of chunks left: the caller may then wait for ever.
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::thread watchdog([&] {
    std::unique_lock lock(mutex);
    if (!finished.wait_for(lock, std::chrono::seconds(120), [&] { return done; })) {
      std::fprintf(stderr, "AWideJobAfterANarrowOneRunsEachChunkOnce: the pool hung\n");
      std::_Exit(1);
    }
  });
  int twice = 0;
  for (int job = 0; job < 200000 && twice == 0; ++job) {
    const unsigned workers = job % 2 == 0 ? 2u : wide;
    for (int hits : chunk_hits(4 * workers, workers, 1))
      if (hits != 1) ++twice;
  }
  {
    std::lock_guard lock(mutex);
    done = true;
  }
  finished.notify_one();
  watchdog.join();
  EXPECT_EQ(twice, 0) << "indices not run exactly once";
}

TEST(WorkerPool, TwoCallersWakesAndWatchSettingsKeepTheResults) {
  // No watch (workers sleep at once), a long one, and the default; woken ahead or not; two callers at once
  // (one takes the pool, the other plain threads or its own thread).
  for (long watch_us : {0L, 5000L, 200L}) {
    set_worker_watch(std::chrono::microseconds(watch_us));
    std::atomic<int> wrong{0};
    auto caller = [&](unsigned workers, bool wake) {
      for (int job = 0; job < 60; ++job) {
        if (wake) wake_workers(std::chrono::microseconds(300));
        const std::size_t n = 1000 + 997 * static_cast<std::size_t>(job);
        std::atomic<std::size_t> sum{0};
        parallel_chunks(
            n, workers,
            [&](std::size_t begin, std::size_t end, unsigned) {
              std::size_t s = 0;
              for (std::size_t i = begin; i < end; ++i)
                s += i;
              sum.fetch_add(s, std::memory_order_relaxed);
            },
            16);
        if (sum.load() != n * (n - 1) / 2) wrong.fetch_add(1);
      }
    };
    // Both ask for no more workers than the pool has, so they compete for it and the loser takes the
    // fallback (on one core both run on their own thread).
    std::thread other(caller, std::min(3u, hardware_workers()), false);
    caller(hardware_workers(), true);
    other.join();
    EXPECT_EQ(wrong.load(), 0) << "watch " << watch_us << " us";
  }
}

}  // namespace
}  // namespace cudahull

// resize_populated() (the finish's large results): the elements kept, the new ones zero, whether the growth
// is not populated (less than 16 MB), populated first (24 MB), or a few elements more past the capacity that
// reserved (a plain resize, which moves them); and populate_pages() leaves what it covers as it was, on
// ranges that start and end inside a page.
TEST(PopulatedPages, ResizeKeepsTheElementsAndZeroesTheNewOnes) {
  using Triangle = std::array<std::uint32_t, 3>;
  std::vector<Triangle> v(1000);
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = {std::uint32_t(i), std::uint32_t(3 * i), 7u};
  for (const std::size_t n : {std::size_t{1500}, std::size_t{1} << 21, (std::size_t{1} << 21) + 5}) {
    const std::size_t before = v.size();
    cudahull::resize_populated(v, n);
    ASSERT_EQ(v.size(), n);
    for (std::size_t i = 0; i < 1000; ++i)
      ASSERT_EQ(v[i], (Triangle{std::uint32_t(i), std::uint32_t(3 * i), 7u})) << "n " << n << ", i " << i;
    for (std::size_t i = std::max<std::size_t>(before, 1000); i < n; ++i)
      ASSERT_EQ(v[i], (Triangle{0, 0, 0})) << "n " << n << ", i " << i;
  }
  std::vector<unsigned char> bytes(std::size_t{5} << 20);
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<unsigned char>(i * 31);
  cudahull::populate_pages(bytes.data() + 123, bytes.size() - 4567);
  for (std::size_t i = 0; i < bytes.size(); ++i)
    ASSERT_EQ(bytes[i], static_cast<unsigned char>(i * 31)) << i;
}
