#include "loader.hpp"

#include <filesystem>

#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/hull_runner.hpp"
#include "cudahull/resident.hpp"

namespace cudahull::viewer {

std::string PointSource::label() const {
  if (!path.empty()) return std::filesystem::path(path).filename().string();
  return distribution + " " + std::to_string(count) + " seed " + std::to_string(seed);
}

std::string precision_note(Precision requested, Precision used) {
  const PrecisionPlan plan = plan_precision(requested, used);
  return std::string(precision_name(plan.precision)) + " (" + plan.reason + ")";
}

namespace {

// The points alone (load_points() adds the model's faces).
ScenePoints load_positions(const PointSource& source, Precision requested, const ProgressFn& progress) {
  // plan_hull()'s rule, from the input's own precision (io reads a file's header only where auto asks).
  const Precision precision = plan_precision(requested, resolve_precision(requested, source.path)).precision;
  if (precision == Precision::kDouble) {
    std::vector<Point3d> exact;
    if (!source.path.empty()) {
      exact = read_points_double(source.path, progress).points;
      check_double_range(exact, source.path);
    } else {
      for (const Point3& p :
           generate_points(distribution_from_name(source.distribution), source.count, source.seed))
        exact.push_back({p.x, p.y, p.z});
    }
    std::vector<Point3> positions;
    positions.reserve(exact.size());
    for (const Point3d& p : exact)
      positions.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
    return {std::make_shared<const std::vector<Point3>>(std::move(positions)),
            std::make_shared<const std::vector<Point3d>>(std::move(exact)), nullptr};
  }
  if (!source.path.empty())
    return {std::make_shared<const std::vector<Point3>>(read_points(source.path, progress)), nullptr,
            nullptr};
  return {std::make_shared<const std::vector<Point3>>(
              generate_points(distribution_from_name(source.distribution), source.count, source.seed)),
          nullptr, nullptr};
}

}  // namespace

ScenePoints load_points(const PointSource& source, Precision precision, const ProgressFn& progress) {
  ScenePoints points = load_positions(source, precision, progress);
  if (!source.path.empty())
    points.surface = std::make_shared<const std::vector<InputTriangle>>(
        read_input_surface(source.path, points.positions->size()));
  return points;
}

Scene::BackendFactory backend_factory(const std::string& requested, std::string* note,
                                      const std::string& engine) {
  ConvexHullOptions request;
  request.backend = backend_from_name(requested);
  request.engine = engine_from_name(engine);
  // The engine and the backend as plan_hull() chooses them; the precision is the loaded points'.
  const HullPlan plan = plan_hull(request, HullInput{});
  if (!plan.unavailable.empty()) throw DeviceError("--" + plan.unavailable);
  const bool resident = plan.engine == EngineChoice::kResident;
  const std::string engine_note = resident ? ", resident engine" : "";
  *note = (plan.backend == BackendChoice::kCuda ? "cuda, " + plan.device : std::string("cpu")) + engine_note +
          " (" + plan.backend_reason + ")";
  // The engines the plan names (hull_runner.hpp): the resident one a step at a time, or the stepping
  // engine's backend.
  if (resident)
    return {{},
            {},
            [plan](const std::vector<Point3>& p) { return resident_stepper(p, plan); },
            [plan](const std::vector<Point3d>& p) { return resident_stepper(p, plan); }};
  return {[plan] { return planned_backend<Point3>(plan); },
          [plan] { return planned_backend<Point3d>(plan); },
          {},
          {}};
}

BackgroundLoad::BackgroundLoad(PointSource source, Precision precision)
    : source_(std::move(source)), precision_(precision) {
  worker_ = std::thread([this] {
    try {
      points_ = load_points(source_, precision_,
                            [this](double f) { progress_.store(f, std::memory_order_relaxed); });
    } catch (...) {
      error_ = std::current_exception();
    }
    ready_.store(true, std::memory_order_release);
  });
}

BackgroundLoad::~BackgroundLoad() {
  if (worker_.joinable()) worker_.join();
}

ScenePoints BackgroundLoad::take() {
  if (worker_.joinable()) worker_.join();
  if (error_) std::rethrow_exception(error_);
  return points_;
}

}  // namespace cudahull::viewer
