// cudahull-viewer: steps the CudaHull algorithm one iteration at a time and shows it (issue 5), in a
// window or headless.  See `cudahull-viewer --help`.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <exception>
#include <new>
#include <nlohmann/json.hpp>

#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "headless_context.hpp"
#include "options.hpp"
#include "recorder.hpp"
#include "run_plan.hpp"
#include "session.hpp"

namespace cudahull::viewer {

void log_line(const ViewerOptions& options, const std::string& line) {
  if (!options.quiet && !line.empty()) std::fprintf(stderr, "cudahull-viewer: %s\n", line.c_str());
}

int run_headless(const ViewerOptions& o) {
  std::string backend_note;
  auto factory = backend_factory(o.backend, &backend_note, o.engine);
  auto points = load_points(o.source, o.precision);
  auto context = HeadlessContext::create();
  log_line(o, "headless: " + context->description() + ": " + gl_description());
  {
    Session session;
    session.allow_interop(!o.no_interop);
    session.set_scene(std::make_unique<Scene>(points, factory, o.source.label()), true);
    log_line(o, o.source.label() + ": " + std::to_string(points.positions->size()) + " points; backend " +
                    backend_note + "; precision " + precision_note(o.precision, points.precision()) +
                    "; per-point state: " + session.upload_path() +
                    "; text: " + session.renderer().text_note());
    session.record_fps = o.record_fps;
    if (!o.record.empty()) session.start_recording(o.record, o.width, o.height);
    RunPlan plan({o.steps, o.script, o.screenshot, o.width, o.height});
    std::string line;
    while (plan.next(session, line))
      log_line(o, line);
    // A headless recording with nothing else to do records the whole run.
    if (session.recording() && !o.steps && o.script.empty() && o.screenshot.empty()) session.run_to_end();
    log_line(o, session.stop_recording());
    const Scene& scene = *session.scene();
    log_line(o, "at position " + std::to_string(scene.position()) + (scene.done() ? " (done)" : "") +
                    "; per-point bytes read back from the backend: " +
                    std::to_string(scene.point_readback_bytes()));
    if (o.bench_frames > 0) {
      // For docs/benchmarks.md (issue 5: fps at 1M, 10M, 20M points): one JSON line on stdout.
      const double ms = session.time_frames(o.bench_frames, o.width, o.height);
      // Step latency: one iteration plus the redraw that shows it (state write or upload included), for up
      // to 3 steps from here.
      double step_ms = 0;
      int timed_steps = 0;
      for (; timed_steps < 3 && !session.scene()->done(); ++timed_steps) {
        const auto t0 = std::chrono::steady_clock::now();
        session.scene()->step(1);
        session.time_frames(0, o.width, o.height);
        step_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      }
      nlohmann::json j{
          {"points", scene.points().size()},
          {"position", scene.position()},
          {"width", o.width},
          {"height", o.height},
          {"frames", o.bench_frames},
          {"ms_per_frame", ms},
          {"fps", ms > 0 ? 1000.0 / ms : 0.0},
          {"renderer", gl_description()},
          {"upload_path", session.upload_path()},
          {"point_draw", session.renderer().uses_splats(session.settings()) ? "splats" : "GL points"},
          {"point_readback_bytes", scene.point_readback_bytes()},
          {"step_ms", timed_steps > 0 ? step_ms / timed_steps : 0.0},
          {"timed_steps", timed_steps}};
      std::printf("%s\n", j.dump().c_str());
    }
  }  // GL objects go before the context
  return kExitOk;
}

}  // namespace cudahull::viewer

namespace {

const char* kFooter =
    "Modes:\n"
    "  window (default): Space run/pause, S or Right step, Left back one step, E run to end, R reset,\n"
    "    F fit view, Ctrl-C/Ctrl-V copy/paste the view as JSON, F1 help; drop a file to open it.\n"
    "  --headless: renders offscreen through EGL (the GPU's EGL device, else Mesa) with no window.\n"
    "Screenshots (PNG, written to a temporary name and renamed):\n"
    "  --screenshot OUT.png       after --steps K (default: the end); with --script, after the script.\n"
    "  --screenshot 'out/%03d.png' without --script: one PNG per position 0..K (or to the end),\n"
    "                             %d being the position (0 = the bare points, 1 = the tetrahedron, ...).\n"
    "Script (--script FILE), one command per line, # comments:\n"
    "  step [N] | run | rewind N | select-face ID | show LAYER | hide LAYER | camera JSON |\n"
    "  screenshot PATH | set NAME VALUE | record start PATH.mp4|.gif | record stop | substep K|off|all |\n"
    "  hover X Y | click X Y | next-rejected | next-removal | frame rejected|removal|swap SEQ |\n"
    "  explain-point I | export-mesh PATH | export-trace PATH | export-decisions PATH\n"
    "  LAYER: hull wireframe internal external vertices cells swaps normals refinement labels input\n"
    "  set: point-size N|auto, point-opacity A, hull-opacity A, wire-width N, point-colors state|face,\n"
    "       face-colors state|age, point-mode auto|points|splats, legend on|off, record-fps N\n"
    "Recording (--record OUT.mp4|.gif, or record start/stop): one frame per step, sub-step or jump, through\n"
    "  ffmpeg.  Window only: --ui-layout FILE (the panels' rectangles as JSON), --window-screenshot PNG.\n"
    "Exit codes: 0 ok; 1 cannot write a screenshot; 2 usage or a bad script line; 3 unreadable or invalid\n"
    "input; 4 no OpenGL 4.5 (no display, no EGL) or device failure.";

int fail(int code, const std::string& message) {
  return cudahull::report_error("cudahull-viewer", code, message);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cudahull;
  using namespace cudahull::viewer;
  CLI::App app{
      "cudahull-viewer: steps the CudaHull algorithm (Stein, Geva, El-Sana 2012) one iteration at a time "
      "and\n"
      "shows the polyhedron and the points."};
  app.footer(kFooter);
  app.set_version_flag("--version", "cudahull-viewer 0.1.0");
  ViewerOptions o;
  std::vector<std::string> gen;
  std::string dist_help = "Generate N points instead of reading INPUT; DIST:";
  for (const auto& name : distribution_names())
    dist_help += " " + name;
  app.add_option("INPUT", o.source.path, "Points: .ply .obj .off .xyz .txt");
  auto* gen_opt = app.add_option("--gen", gen, dist_help)->expected(2)->type_name("DIST N");
  app.add_option("--seed", o.source.seed, "Seed for --gen")->capture_default_str();
  app.add_option(
         "--backend", o.backend,
         "auto (CUDA when a usable device is present, else the CPU), cuda (exit 4 without a device) or cpu")
      ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
      ->capture_default_str();
  app.add_option("--engine", o.engine,
                 "stepping (the host edits the mesh, the backend moves the points), resident (every phase "
                 "where the points are, on the GPU with a CUDA backend, its records read back each step) or "
                 "auto (as `cudahull hull`: resident on a GPU, stepping on the CPU)")
      ->check(CLI::IsMember({"stepping", "resident", "auto"}))
      ->capture_default_str();
  std::string precision = "auto";
  app.add_option(
         "--precision", precision,
         "auto (as `cudahull hull`: the file's format decides, float for --gen), float or double: the "
         "coordinates the engine computes on")
      ->check(CLI::IsMember({"auto", "float", "double"}))
      ->capture_default_str();
  app.add_flag("--headless", o.headless, "Render offscreen with no window (EGL)");
  auto* width_opt = app.add_option("--width", o.width, "Window or image width")->check(CLI::Range(16, 16384));
  auto* height_opt =
      app.add_option("--height", o.height, "Window or image height")->check(CLI::Range(16, 16384));
  int steps = 0;
  auto* steps_opt = app.add_option("--steps", steps, "Take K steps first")->check(CLI::Range(0, 1 << 30));
  app.add_option("--screenshot", o.screenshot, "Write a PNG (see below for %d sequences)");
  app.add_option("--script", o.script_path, "Run the commands in FILE (see below)");
  long long frames = 0;
  auto* frames_opt = app.add_option("--frames", frames,
                                    "Window: close N frames after the steps, script and "
                                    "screenshot are done (for tests)")
                         ->check(CLI::Range(0ll, 1ll << 40));
  app.add_option("--bench-frames", o.bench_frames,
                 "Headless: after everything else, time N frames and print one JSON line (fps) on stdout")
      ->check(CLI::Range(1, 100000));
  app.add_flag("--no-interop", o.no_interop,
               "Upload per-point state from the CPU even where CUDA-GL interop works (for comparisons)");
  app.add_option("--ui-layout", o.ui_layout,
                 "Window: on closing, write each panel's rectangle (and the 3-d view's) as JSON to FILE");
  app.add_option("--record", o.record,
                 "Record OUT.mp4 or OUT.gif (ffmpeg): one frame per step or sub-step the run takes (without "
                 "--script or --steps, to the end)");
  app.add_option("--record-fps", o.record_fps, "Frames a second of --record and `record start`")
      ->check(CLI::Range(0.1, 120.0))
      ->capture_default_str();
  app.add_option("--window-screenshot", o.window_screenshot,
                 "Window: on closing, write a PNG of the whole window, panels included");
  app.add_flag("-q,--quiet", o.quiet, "No log lines on stderr");

  try {
    app.parse(argc, argv);
    if (!o.source.path.empty() && *gen_opt) throw CLI::ValidationError("give INPUT or --gen, not both");
    if (*gen_opt) {
      o.source.distribution = gen[0];
      distribution_from_name(gen[0]);  // std::invalid_argument names the valid ones
      try {
        const long long n = std::stoll(gen[1]);
        if (n < 0) throw std::out_of_range("negative");
        o.source.count = static_cast<std::uint64_t>(n);
      } catch (const std::logic_error&) {
        throw CLI::ValidationError("--gen: N must be a number of points, not '" + gen[1] + "'");
      }
    }
    o.precision = precision_from_name(precision);
    if (*steps_opt) o.steps = steps;
    if (*frames_opt) o.frames = frames;
    o.size_given = *width_opt || *height_opt;
    if (o.headless && o.source.empty()) throw CLI::ValidationError("--headless needs INPUT or --gen DIST N");
    if (!o.record.empty() && !is_recording_path(o.record))
      throw CLI::ValidationError("--record: a recording is a .mp4 or a .gif, not '" + o.record + "'");
    if (o.headless && o.screenshot.empty() && o.script_path.empty() && o.bench_frames == 0 &&
        o.record.empty())
      throw CLI::ValidationError(
          "--headless needs --screenshot, --script, --record or --bench-frames (it has no other output)");
    if (!o.headless && o.bench_frames > 0) throw CLI::ValidationError("--bench-frames is for --headless");
    if (o.headless && !o.window_screenshot.empty())
      throw CLI::ValidationError("--window-screenshot is for the window; headless, use --screenshot");
    if (o.headless && !o.ui_layout.empty())
      throw CLI::ValidationError("--ui-layout is for the window (headless runs draw no panels)");
    if (o.headless && *frames_opt) throw CLI::ValidationError("--frames is for the window, not --headless");
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(kExitUsage, std::string(e.what()) + " (see cudahull-viewer --help)");
  } catch (const std::invalid_argument& e) {
    return fail(kExitUsage, e.what());
  }

  return run_reporting_errors<ScriptError>("cudahull-viewer", [&] {
    if (!o.script_path.empty()) o.script = read_script(o.script_path);
    return o.headless ? run_headless(o) : run_window(o);
  });
}
