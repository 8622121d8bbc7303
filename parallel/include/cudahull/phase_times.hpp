// Wall-clock timing for the profile that `CUDAHULL_PHASE_TIMES=1` prints (the engine's host phases and the
// CUDA backend's staging and waits, as in the paper's Fig. 9; docs/benchmarks.md) and for `cudahull bench`.
#pragma once

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

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

// One call's phases, timed lap by lap and printed on one line to stderr when it dies ("<who>: check 0.12
// ms, plan 0.30 ms, ..."), when CUDAHULL_PHASE_TIMES is set; otherwise nothing is timed.  A phase with
// device work: the caller finishes that work before the lap (only when wanted(): it costs a wait).
class PhaseLaps {
 public:
  explicit PhaseLaps(const char* who) : wanted_(phase_times_wanted()) {
    if (!wanted_) return;
    line_ = std::string(who) + ":";
    t0_ = Clock::now();
  }
  PhaseLaps(const PhaseLaps&) = delete;
  PhaseLaps& operator=(const PhaseLaps&) = delete;
  ~PhaseLaps() {
    if (wanted_) std::fprintf(stderr, "%s\n", line_.c_str());
  }
  bool wanted() const { return wanted_; }
  void lap(const char* phase) {
    if (!wanted_) return;
    char text[96];
    std::snprintf(text, sizeof text, "%s %s %.3f ms", line_.back() == ':' ? "" : ",", phase, ms_since(t0_));
    line_ += text;
    t0_ = Clock::now();
  }
  // A step run beside a parallel pass (parallel_blocks_beside()'s `side`), timed on its own: span.time(step)
  // runs it, note() adds its time to the next lap's entry.
  struct Span {
    Clock::time_point start{}, end{};
    template <class Step>
    void time(Step&& step) {
      start = Clock::now();
      step();
      end = Clock::now();
    }
  };
  void note(const char* part, const Span& span) {
    if (!wanted_) return;
    char text[96];
    std::snprintf(text, sizeof text, "%s (%s %.3f ms)", line_.back() == ':' ? "" : ",", part,
                  std::chrono::duration<double, std::milli>(span.end - span.start).count());
    line_ += text;
  }

 private:
  bool wanted_;
  std::string line_;
  Clock::time_point t0_{};
};

}  // namespace cudahull
