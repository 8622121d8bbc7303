// The shared scans (../shared/models beside the checkout, or CUDAHULL_MODELS_DIR) with their exact
// extreme-point counts, as ../shared/models/README.md gives them (float coordinates).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <utility>
#include <vector>

#include "cudahull/point_io.hpp"

namespace cudahull::testing {

inline std::filesystem::path shared_models_dir() {
  const char* env = std::getenv("CUDAHULL_MODELS_DIR");
  return env && *env ? env : CUDAHULL_MODELS_DIR;
}

inline constexpr std::pair<const char*, std::size_t> kSharedModelCounts[] = {
    {"bun_zipper.ply", 1564},  {"stanford-bunny.obj", 1562}, {"dragonStandRight_0.ply", 439},
    {"dragon_scans.ply", 207}, {"teapot.obj", 878},          {"spot.obj", 305}};

// Calls `check(name, points, count)` on each shared model, read in float, with its count; skips the test
// when the folder is not there.
template <class Check>
void for_each_shared_model(Check check) {
  const std::filesystem::path dir = shared_models_dir();
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no models folder " << dir;
  for (const auto& [name, count] : kSharedModelCounts)
    check(name, read_points((dir / name).string()), count);
}

}  // namespace cudahull::testing
