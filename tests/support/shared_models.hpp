// The shared scans (../shared/models beside the checkout, or CUDAHULL_MODELS_DIR) with their exact
// extreme-point counts, as ../shared/models/README.md gives them (float coordinates).
#pragma once

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <utility>

namespace cudahull::testing {

inline std::filesystem::path shared_models_dir() {
  const char* env = std::getenv("CUDAHULL_MODELS_DIR");
  return env && *env ? env : CUDAHULL_MODELS_DIR;
}

inline constexpr std::pair<const char*, std::size_t> kSharedModelCounts[] = {
    {"bun_zipper.ply", 1564},  {"stanford-bunny.obj", 1562}, {"dragonStandRight_0.ply", 439},
    {"dragon_scans.ply", 207}, {"teapot.obj", 878},          {"spot.obj", 305}};

}  // namespace cudahull::testing
