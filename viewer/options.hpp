// The viewer's command line, parsed (main.cpp), and its two modes: a window (app_window.cpp) or headless
// (main.cpp).  Both return the exit code, or throw the cudahull error types that main() maps to codes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "loader.hpp"
#include "script.hpp"

namespace cudahull::viewer {

struct ViewerOptions {
  PointSource source;
  std::string backend = "auto";
  std::string engine = "stepping";         // --engine: "stepping", "resident" or "auto"
  Precision precision = Precision::kAuto;  // --precision; kAuto as resolve_precision() (point_io.hpp)
  bool headless = false;
  int width = 1280, height = 800;  // window (logical pixels) or headless image (pixels)
  bool size_given = false;
  std::optional<int> steps;
  std::string screenshot;
  std::string script_path;
  std::vector<ScriptCommand> script;  // parsed before anything opens
  std::optional<long long> frames;    // windowed: close this many frames after the plan is done
  int bench_frames = 0;               // headless: time this many frames after the plan, JSON on stdout
  bool quiet = false;
  bool no_interop = false;
  std::string record;  // a .mp4 or .gif of every step the run takes (recorder.hpp)
  double record_fps = 2.0;
  std::string window_screenshot;  // window: a PNG of the last frame, panels included
  std::string ui_layout;  // window: write the panels' rectangles as JSON here on closing (ui_layout.hpp)  //
                          // upload per-point state from the CPU even where CUDA-GL interop would work
};

int run_window(const ViewerOptions& options);
int run_headless(const ViewerOptions& options);

// "cudahull-viewer: ..." on stderr unless quiet.
void log_line(const ViewerOptions& options, const std::string& line);

}  // namespace cudahull::viewer
