// A minimal fork-join loop for the host: the CPU backend's point passes and the engine's per-face passes.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace cudahull {

inline unsigned hardware_workers() {
  return std::max(1u, std::thread::hardware_concurrency());
}

// Runs body(begin, end, worker) over [0, n) split into one contiguous chunk per worker; small ranges (under
// `grain`) run on the calling thread, where a thread start would cost more than the work.
template <class Body>
void parallel_chunks(std::size_t n, unsigned workers, Body&& body, std::size_t grain = 4096) {
  if (workers <= 1 || n < grain) {
    body(std::size_t{0}, n, 0u);
    return;
  }
  std::vector<std::thread> threads;
  const std::size_t chunk = (n + workers - 1) / workers;
  for (unsigned w = 1; w < workers; ++w) {
    const std::size_t begin = std::min(n, w * chunk), end = std::min(n, begin + chunk);
    threads.emplace_back([&body, begin, end, w] { body(begin, end, w); });
  }
  body(std::size_t{0}, std::min(n, chunk), 0u);
  for (auto& t : threads)
    t.join();
}

}  // namespace cudahull
