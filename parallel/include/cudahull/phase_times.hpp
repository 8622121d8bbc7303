// Wall-clock timing for the profile that `CUDAHULL_PHASE_TIMES=1` prints (the engine's host phases and the
// CUDA backend's staging and waits, as in the paper's Fig. 9; docs/benchmarks.md) and for `cudahull bench`.
#pragma once

#include <chrono>
#include <cstdlib>

namespace cudahull {

using Clock = std::chrono::steady_clock;

inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Whether CUDAHULL_PHASE_TIMES is set: then each iteration's phases go to stderr.
inline bool phase_times_wanted() {
  static const bool wanted = std::getenv("CUDAHULL_PHASE_TIMES") != nullptr;
  return wanted;
}

}  // namespace cudahull
