// How a hull is run, decided in one place (issue 26): the engine, the backend and the precision that a
// request (ConvexHullOptions, or the command line's and the viewer's flags) gets for an input, "auto"
// resolved, with the reason in words.  convex_hull() and its relatives, make_backend(), the command line,
// the viewer and the Python module all ask plan_hull(), so they cannot disagree.
//
//   HullInput input;
//   input.precision = Precision::kDouble;  // a double array
//   input.count = n;
//   const HullPlan plan = plan_hull({}, input);
//   std::puts(plan.reason.c_str());  // "stepping engine (auto: no usable CUDA device); backend cpu ..."
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "cudahull/hull_options.hpp"
#include "cudahull/tuning.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

// What plan_hull() needs to know about the points.
struct HullInput {
  // The input's own precision, kFloat or kDouble: a float or a double array's; for a file, io's
  // resolve_precision() (its header's type, float for generated points).
  Precision precision = Precision::kFloat;
  int dimension = 3;  // 3, or 2 for x, y pairs (convex_hull_2d)
  std::size_t count = 0;
  bool on_device = false;  // in the current CUDA device's memory (convex_hull_device)
  // Whether a coordinate lies outside the engines' exact range (in_fast_exact_range(): nonzero magnitudes
  // 2^-250..2^250; a float never does).  Known once the points are read: false until then.
  bool outside_exact_range = false;
};

// plan_hull()'s precision rule alone: the request, or for kAuto the input's own.  For callers that read
// their points in it, before the rest of the plan can be made.
struct PrecisionPlan {
  Precision precision = Precision::kFloat;  // never kAuto
  std::string reason;                       // "auto" or "as requested"
};
PrecisionPlan plan_precision(Precision requested, Precision of_input);

struct HullPlan {
  // Never kAuto.  Points in GPU memory take the resident engine on CUDA, whatever was asked; 2-D input
  // runs no engine (kStepping here), its hull is the planar one.
  EngineChoice engine = EngineChoice::kStepping;
  BackendChoice backend = BackendChoice::kCpu;
  Precision precision = Precision::kFloat;
  // Double coordinates outside the engines' exact range: exact_hull_any() on the host (backend kCpu) and
  // neither engine; `engine` still names the one the request resolved to (the command line reports it).
  bool wide_range = false;
  // Host points go to the GPU as they are and are checked there: the resident engine on CUDA needs no
  // host copy of them, which would cost more than the upload.
  bool upload_first = false;
  // The stepping engine on the CPU chosen by "auto" for 4..kSmallHullPoints points: convex_hull() runs the
  // batch warps' small hull on the calling thread instead (small_hull_host(), resident.hpp), whose fixed
  // cost is microseconds where the engine's is a hundred; the engine still takes a flat cloud.
  bool small_cloud = false;
  std::string device;  // the CUDA device's name where backend is kCuda and the status named it
  // The resident engine's thresholds on the GPU (cudahull/tuning.hpp): plan_hull() gives the defaults; the
  // runners (hull_runner.hpp, convex_hull()) build the engine with them.  The command line sets them from
  // its environment for A/B runs.
  ResidentTuning resident_tuning;
  // Non-empty where the request cannot be met here, and why, as the error's one line (e.g. "backend cuda:
  // no usable CUDA device: ..."): the plan is otherwise the one that would run.
  std::string unavailable;
  // Why each choice: "as requested", "auto: a usable CUDA device", "auto: no usable CUDA device: ...", ...
  std::string engine_reason, backend_reason, precision_reason;
  std::string reason;  // all of it in one line
};

// The plan for `input` under `requested`.  `cuda` says whether this process has a usable CUDA device; it is
// asked only where a choice depends on it (never for backend cpu with a definite engine), at most once.
// Throws nothing: a request that cannot be met says so in `unavailable`.
HullPlan plan_hull(const ConvexHullOptions& requested, const HullInput& input,
                   const std::function<CudaStatus()>& cuda = cuda_status);

}  // namespace cudahull
