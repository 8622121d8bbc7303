// resident_hull_host(): the resident engine on the host executor.
#include "cudahull/resident.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <vector>

#include "cudahull/resident/host_exec.hpp"
#include "cudahull/resident/resident_driver.hpp"
#include "cudahull/resident/resident_stepping.hpp"

namespace cudahull {

HardwarePace host_pace() {
  static const double bytes_per_ms = [] {
    const std::size_t n = std::size_t{32} << 20;
    std::vector<unsigned char> from(n, 1), to(n, 0);
    double best = 0;
    for (int r = 0; r < 3; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      std::memcpy(to.data(), from.data(), n);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (ms > 0) best = std::max(best, 2.0 * static_cast<double>(n) / ms);
      from[r] = to[n - 1 - r];  // each copy's result is read: none can be left out
    }
    return best;
  }();
  return HardwarePace{bytes_per_ms, 0, 0};
}

namespace {
template <class Exec, class Point>
BasicHullMesh<Point> run_on(const std::vector<Point>& points, ResidentStats* stats, bool executor_only) {
  Exec exec;
  resident::ResidentHull<Point, Exec> hull(exec, points.data(), points.size(),
                                           executor_only ? nullptr : &points);
  ResidentStats local;
  ResidentStats& out = stats ? *stats : local;
  BasicHullMesh<Point> result = hull.run(out);
  out.host_syncs = exec.host_syncs;
  out.bytes_to_device = exec.bytes_to_device;
  out.bytes_from_device = exec.bytes_from_device;
  return result;
}
}  // namespace

template <class Point>
BasicHullMesh<Point> resident_hull_host(const std::vector<Point>& points, ResidentStats* stats,
                                        ResidentPath path, bool executor_points_only) {
  if (points.size() >= 0xffffffffu) throw std::invalid_argument("too many points (at most 2^32 - 2)");
  if (path == ResidentPath::kDevice)
    return run_on<resident::DevicePathHostExec>(points, stats, executor_points_only);
  return run_on<resident::HostExec>(points, stats, executor_points_only);
}

// The two coordinate types (README, "Precision").
template HullMesh resident_hull_host(const std::vector<Point3>&, ResidentStats*, ResidentPath, bool);
template HullMeshd resident_hull_host(const std::vector<Point3d>&, ResidentStats*, ResidentPath, bool);

template <class Point>
std::unique_ptr<SteppingEngine> make_resident_stepping_engine(const std::vector<Point>& points) {
  if (points.size() >= 0xffffffffu) throw std::invalid_argument("too many points (at most 2^32 - 2)");
  return std::make_unique<resident::ResidentStepper<Point, resident::HostExec>>(points, "cpu-resident",
                                                                                false);
}
template std::unique_ptr<SteppingEngine> make_resident_stepping_engine(const std::vector<Point3>&);
template std::unique_ptr<SteppingEngine> make_resident_stepping_engine(const std::vector<Point3d>&);

}  // namespace cudahull
