// Where the points come from (a file, or a generated distribution) and loading them, in the foreground
// (headless) or on a worker thread with progress (the window, so large files do not freeze it).
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cudahull/point_io.hpp"
#include "cudahull/types.hpp"
#include "scene.hpp"

namespace cudahull::viewer {

struct PointSource {
  std::string path;          // a file, or empty
  std::string distribution;  // else a generator name (generators.hpp)
  std::uint64_t count = 0;
  std::uint64_t seed = 1;

  bool empty() const { return path.empty() && distribution.empty(); }
  std::string label() const;  // "bun_zipper.ply" or "ball 20000 seed 1"
};

// For the log and the UI: "double (auto)" or "float (as requested)", plan_precision()'s reason
// (hull_plan.hpp).
std::string precision_note(Precision requested, Precision used);

// Loads in `precision` as plan_precision() resolves it (kAuto: the file's own, float for generated points):
// float as read_points() rounds the file; double as the file gives it (read_points_double(), range-checked),
// plus the float render positions made from it.  Throws InputError (unreadable or invalid file) or
// std::invalid_argument (unknown distribution).
ScenePoints load_points(const PointSource& source, Precision precision, const ProgressFn& progress = {});

// --backend: "cpu", "cuda", or "auto" (CUDA when a usable device is present, else the CPU); --engine:
// "stepping" (the Engine over that backend) or "resident" (the resident engine on that device, with
// records), as plan_hull() (hull_plan.hpp) resolves them.  Throws DeviceError for "cuda" without a usable
// device.  `note` says what was chosen and why, in the plan's words.
Scene::BackendFactory backend_factory(const std::string& requested, std::string* note,
                                      const std::string& engine = "stepping");

// Loads on a worker thread (load_points(), precision resolved there).  The destructor waits for it.
class BackgroundLoad {
 public:
  BackgroundLoad(PointSource source, Precision precision);
  ~BackgroundLoad();
  BackgroundLoad(const BackgroundLoad&) = delete;
  BackgroundLoad& operator=(const BackgroundLoad&) = delete;

  const PointSource& source() const { return source_; }
  bool ready() const { return ready_.load(std::memory_order_acquire); }
  double progress() const { return progress_.load(std::memory_order_relaxed); }  // < 0: unknown
  // Once ready(): the points, or the loader's exception rethrown.
  ScenePoints take();

 private:
  PointSource source_;
  Precision precision_;
  std::atomic<bool> ready_{false};
  std::atomic<double> progress_{-1.0};
  ScenePoints points_;
  std::exception_ptr error_;
  std::thread worker_;
};

}  // namespace cudahull::viewer
