// Transparent huge pages for the process's large host arrays, through glibc's malloc tunable
// (GLIBC_TUNABLES=glibc.malloc.hugetlb=1: malloc marks its large mappings with madvise(MADV_HUGEPAGE)).
//
// Why: the engine's per-iteration arrays (faces, tables, claims) grow with the mesh, and every fresh page
// costs a fault on first touch; with 2 MB pages a dense sphere's host time falls by about a quarter
// (docs/benchmarks.md, "Measurements behind the code").  glibc reads the tunable only at start-up, so main()
// sets it and executes the same program again, once.  CUDAHULL_HUGE_PAGES=0 leaves the process as it is.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <string>

namespace cudahull::cli {

inline constexpr const char* kHugePagesTunable = "glibc.malloc.hugetlb=1";

// Called first in main(): returns only when the tunable is already set, turned off, or the exec failed (then
// the process goes on with ordinary pages).
inline void use_huge_pages(char** argv) {
  if (std::getenv("CUDAHULL_HUGE_PAGES") != nullptr) return;  // "0", or set by the exec below
  const char* current = std::getenv("GLIBC_TUNABLES");
  std::string tunables = current != nullptr ? current : "";
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return;  // the caller chose
  tunables += (tunables.empty() ? "" : ":") + std::string(kHugePagesTunable);
  if (::setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0 || ::setenv("CUDAHULL_HUGE_PAGES", "1", 1) != 0)
    return;
  ::execv("/proc/self/exe", argv);
  // Still here: no /proc, say.  Undo, so that no child inherits a half-made setting.
  if (current != nullptr) {
    ::setenv("GLIBC_TUNABLES", current, 1);
  } else {
    ::unsetenv("GLIBC_TUNABLES");
  }
  ::setenv("CUDAHULL_HUGE_PAGES", "0", 1);
}

// Whether this process started with the tunable (for `cudahull bench --json`).
inline bool huge_pages_in_use() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  return tunables != nullptr && std::string(tunables).find(kHugePagesTunable) != std::string::npos;
}

}  // namespace cudahull::cli
