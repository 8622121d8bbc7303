#include "loader.hpp"

#include <filesystem>

#include "cuda_backend.hpp"
#include "cudahull/cpu_backend.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "device_info.hpp"

namespace cudahull::viewer {

std::string PointSource::label() const {
  if (!path.empty()) return std::filesystem::path(path).filename().string();
  return distribution + " " + std::to_string(count) + " seed " + std::to_string(seed);
}

std::shared_ptr<const std::vector<Point3>> load_points(const PointSource& source,
                                                       const ProgressFn& progress) {
  if (!source.path.empty())
    return std::make_shared<const std::vector<Point3>>(read_points(source.path, progress));
  return std::make_shared<const std::vector<Point3>>(
      generate_points(distribution_from_name(source.distribution), source.count, source.seed));
}

Scene::BackendFactory backend_factory(const std::string& requested, std::string* note) {
  if (requested != "cpu") {
    const CudaDeviceInfo info = query_cuda_device();
    if (info.usable) {
      *note =
          "cuda, " + info.name + (requested == "auto" ? " (auto: a usable CUDA device)" : " (as requested)");
      return [] { return make_cuda_backend(); };
    }
    if (requested == "cuda") throw DeviceError("--backend cuda: no usable CUDA device: " + info.reason);
    *note = "cpu (auto: no usable CUDA device: " + info.reason + ")";
  } else {
    *note = "cpu (as requested)";
  }
  return [] { return make_cpu_backend(); };
}

BackgroundLoad::BackgroundLoad(PointSource source) : source_(std::move(source)) {
  worker_ = std::thread([this] {
    try {
      points_ = load_points(source_, [this](double f) { progress_.store(f, std::memory_order_relaxed); });
    } catch (...) {
      error_ = std::current_exception();
    }
    ready_.store(true, std::memory_order_release);
  });
}

BackgroundLoad::~BackgroundLoad() {
  if (worker_.joinable()) worker_.join();
}

std::shared_ptr<const std::vector<Point3>> BackgroundLoad::take() {
  if (worker_.joinable()) worker_.join();
  if (error_) std::rethrow_exception(error_);
  return points_;
}

}  // namespace cudahull::viewer
