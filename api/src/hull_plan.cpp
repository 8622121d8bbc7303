// plan_hull(): every "auto" of a hull run resolved in one place, each choice with its reason (hull_plan.hpp).
#include "cudahull/hull_plan.hpp"

#include <optional>

#include "cudahull/resident.hpp"

namespace cudahull {

namespace {

constexpr const char* kWideRange =
    "coordinates outside 2^-250..2^250: the wide-range exact hull (host, slower)";

// The plan's choices and reasons in one line.
std::string one_line(const HullPlan& plan, const HullInput& input) {
  std::string line;
  if (plan.wide_range) {
    line = "no engine: the wide-range exact hull";
  } else if (input.dimension == 2) {
    line = plan.engine_reason;
  } else {
    line = std::string(choice_name(plan.engine)) + " engine (" + plan.engine_reason + ")";
  }
  line += std::string("; backend ") + choice_name(plan.backend) + " (" + plan.backend_reason +
          "); precision " + precision_name(plan.precision) + " (" + plan.precision_reason + ")";
  if (!plan.unavailable.empty()) line += "; cannot run: " + plan.unavailable;
  return line;
}

}  // namespace

PrecisionPlan plan_precision(Precision requested, Precision of_input) {
  if (requested == Precision::kAuto) return {of_input, "auto"};
  return {requested, "as requested"};
}

HullPlan plan_hull(const ConvexHullOptions& requested, const HullInput& input,
                   const std::function<CudaStatus()>& cuda) {
  // Asked once, and only by a choice that depends on it: a CPU run touches no CUDA runtime.
  std::optional<CudaStatus> status;
  auto gpu = [&]() -> const CudaStatus& {
    if (!status) status = cuda();
    return *status;
  };
  HullPlan plan;
  const PrecisionPlan precision = plan_precision(requested.precision, input.precision);
  plan.precision = precision.precision;
  plan.precision_reason = precision.reason;
  plan.wide_range = plan.precision == Precision::kDouble && input.outside_exact_range;

  if (input.on_device) {
    // Only the device reads them where they are: the resident engine (3-D) or the planar filter (2-D).
    plan.engine = input.dimension == 2 ? EngineChoice::kStepping : EngineChoice::kResident;
    plan.engine_reason = input.dimension == 2 ? "2-D input: the planar hull, filtered on the device"
                                              : "points in GPU memory: only it reads them in place";
    plan.backend = BackendChoice::kCuda;
    plan.backend_reason = "points in GPU memory";
    if (requested.backend == BackendChoice::kCpu) {
      // Left as asked, so that the caller can tell a wrong request from a missing device.
      plan.backend = BackendChoice::kCpu;
      plan.backend_reason = "as requested";
      plan.unavailable = "points in GPU memory need backend auto or cuda, not cpu";
    } else if (!gpu().usable) {
      plan.unavailable = "points in GPU memory, but no usable CUDA device: " + gpu().reason;
    } else {
      plan.device = gpu().device;
    }
  } else if (input.dimension == 2) {
    // The planar hull runs on the host whatever the backend; backend cuda still needs the device.
    plan.engine = EngineChoice::kStepping;
    plan.engine_reason = "2-D input: the planar hull, no engine";
    plan.backend = BackendChoice::kCpu;
    plan.backend_reason = plan.wide_range ? kWideRange : "2-D points in host memory: the host's planar hull";
    if (requested.backend == BackendChoice::kCuda && !gpu().usable)
      plan.unavailable = "backend cuda: no usable CUDA device: " + gpu().reason;
  } else {
    if (requested.engine != EngineChoice::kAuto) {
      plan.engine = requested.engine;
      plan.engine_reason = "as requested";
    } else if (requested.backend == BackendChoice::kCpu) {
      // On the CPU the stepping engine's worker threads make it the faster one.
      plan.engine = EngineChoice::kStepping;
      plan.engine_reason = "auto: backend cpu";
    } else if (gpu().usable) {
      plan.engine = EngineChoice::kResident;
      plan.engine_reason = "auto: a usable CUDA device";
    } else {
      plan.engine = EngineChoice::kStepping;
      plan.engine_reason = "auto: no usable CUDA device";
    }
    if (plan.wide_range) {
      // Neither engine is exact there; nor is the device asked, so backend cuda without one still runs.
      plan.backend = BackendChoice::kCpu;
      plan.backend_reason = kWideRange;
    } else if (requested.backend == BackendChoice::kCpu) {
      plan.backend = BackendChoice::kCpu;
      plan.backend_reason = "as requested";
    } else if (gpu().usable) {
      plan.backend = BackendChoice::kCuda;
      plan.device = gpu().device;
      plan.backend_reason =
          requested.backend == BackendChoice::kAuto ? "auto: a usable CUDA device" : "as requested";
    } else if (requested.backend == BackendChoice::kCuda) {
      plan.backend = BackendChoice::kCuda;
      plan.backend_reason = "as requested";
      plan.unavailable = "backend cuda: no usable CUDA device: " + gpu().reason;
    } else {
      plan.backend = BackendChoice::kCpu;
      plan.backend_reason = "auto: no usable CUDA device: " + gpu().reason;
    }
    plan.small_cloud = requested.engine == EngineChoice::kAuto && plan.engine == EngineChoice::kStepping &&
                       plan.backend == BackendChoice::kCpu && !plan.wide_range && input.count >= 4 &&
                       input.count <= kSmallHullPoints;
    // The upload costs less than a host copy of the points, which the resident engine does not need.
    plan.upload_first = plan.engine == EngineChoice::kResident && plan.backend == BackendChoice::kCuda &&
                        plan.unavailable.empty() && !plan.wide_range && input.count != 0;
  }
  plan.reason = one_line(plan, input);
  return plan;
}

}  // namespace cudahull
