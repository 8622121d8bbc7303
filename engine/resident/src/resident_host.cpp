// resident_hull_host(): the resident engine on the host executor.
#include "cudahull/resident.hpp"
#include "cudahull/resident/host_exec.hpp"
#include "cudahull/resident/resident_driver.hpp"
#include "cudahull/resident/resident_stepping.hpp"

namespace cudahull {

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
