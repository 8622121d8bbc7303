// The checker's report: failure lines up to a limit, printf-style formatting, coordinates in full
// precision, and the threaded scan whose failures merge in key order.  Internal to reference/.
#pragma once

#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cudahull/hull_checker.hpp"
#include "cudahull/types.hpp"

namespace cudahull::checking {

struct Report {
  CheckResult& result;
  std::size_t max;
  // Some coordinate is outside the fast predicates' exact range: every test takes the wide predicates.
  bool wide = false;
  void fail(std::string line) {
    result.ok = false;
    if (result.failures.size() < max) result.failures.push_back(std::move(line));
  }
  bool full() const { return result.failures.size() >= max; }
};

inline std::string fmt(const char* f, ...) __attribute__((format(printf, 1, 2)));
inline std::string fmt(const char* f, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, f);
  std::vsnprintf(buf, sizeof buf, f, ap);
  va_end(ap);
  return buf;
}

// Coordinates in full precision: 9 significant digits identify a float, 17 a double.
inline std::string coords(const Point3& p) {
  return fmt("(%.9g %.9g %.9g)", p.x, p.y, p.z);
}
inline std::string coords(const Point3d& p) {
  return fmt("(%.17g %.17g %.17g)", p.x, p.y, p.z);
}

// Runs fn(i, sink, chunk) for i in [0, n) on several threads, each on one contiguous chunk of indices; fn
// reports with sink(key, line).  The lines are
// merged in key order (so the report does not depend on scheduling) and a thread stops once it holds the
// report limit.  Returns how many failures were found (at least 1 if any).  `work` estimates the cost of one
// item in cheap predicate calls, to decide whether threads pay off.
template <class Fn>
std::size_t parallel_failures(std::size_t n, std::size_t work, Report& rep, const Fn& fn) {
  const std::size_t hc = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t chunks = std::min(hc, n * work / 50000 + 1);
  std::vector<std::vector<std::pair<std::uint64_t, std::string>>> lines(chunks);
  std::vector<std::size_t> counts(chunks, 0);
  auto body = [&](std::size_t t) {
    const std::size_t b = n * t / chunks, e = n * (t + 1) / chunks;
    auto sink = [&](std::uint64_t key, std::string line) {
      ++counts[t];
      lines[t].emplace_back(key, std::move(line));
    };
    for (std::size_t i = b; i < e && lines[t].size() < std::max<std::size_t>(rep.max, 1); ++i)
      fn(i, sink, t);
  };
  if (chunks == 1) {
    body(0);
  } else {
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < chunks; ++t)
      threads.emplace_back(body, t);
    for (std::thread& th : threads)
      th.join();
  }
  std::vector<std::pair<std::uint64_t, std::string>> all;
  for (auto& v : lines)
    for (auto& e : v)
      all.push_back(std::move(e));
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& e : all)
    rep.fail(std::move(e.second));
  std::size_t total = 0;
  for (std::size_t c : counts)
    total += c;
  return total;
}

}  // namespace cudahull::checking
