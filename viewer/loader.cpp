#include "loader.hpp"

#include <filesystem>

#include "cuda_backend.hpp"
#include "cudahull/cpu_backend.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/resident.hpp"
#include "device_info.hpp"
#include "resident_cuda.hpp"

namespace cudahull::viewer {

std::string PointSource::label() const {
  if (!path.empty()) return std::filesystem::path(path).filename().string();
  return distribution + " " + std::to_string(count) + " seed " + std::to_string(seed);
}

std::string precision_note(Precision requested, Precision used) {
  return std::string(precision_name(used)) + (requested == Precision::kAuto ? " (auto)" : " (as requested)");
}

namespace {

// The points alone (load_points() adds the model's faces).
ScenePoints load_positions(const PointSource& source, Precision precision, const ProgressFn& progress) {
  precision = resolve_precision(precision, source.path);
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
  const bool resident = engine == "resident";
  const std::string engine_note = resident ? ", resident engine" : "";
  if (requested != "cpu") {
    const CudaDeviceInfo info = query_cuda_device();
    if (info.usable) {
      *note = "cuda, " + info.name + engine_note +
              (requested == "auto" ? " (auto: a usable CUDA device)" : " (as requested)");
      if (resident)
        return {{},
                {},
                [](const std::vector<Point3>& p) { return make_resident_cuda_stepping_engine(p); },
                [](const std::vector<Point3d>& p) { return make_resident_cuda_stepping_engine(p); }};
      return {
          [] { return make_cuda_backend<Point3>(); }, [] { return make_cuda_backend<Point3d>(); }, {}, {}};
    }
    if (requested == "cuda") throw DeviceError("--backend cuda: no usable CUDA device: " + info.reason);
    *note = "cpu" + engine_note + " (auto: no usable CUDA device: " + info.reason + ")";
  } else {
    *note = "cpu" + engine_note + " (as requested)";
  }
  if (resident)
    return {{},
            {},
            [](const std::vector<Point3>& p) { return make_resident_stepping_engine(p); },
            [](const std::vector<Point3d>& p) { return make_resident_stepping_engine(p); }};
  return {[] { return make_cpu_backend<Point3>(); }, [] { return make_cpu_backend<Point3d>(); }, {}, {}};
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
