// resident_hull_host(): the resident engine on the host executor.
#include "cudahull/resident.hpp"
#include "resident/host_exec.hpp"
#include "resident/resident_driver.hpp"

namespace cudahull {

template <class Point>
BasicHullMesh<Point> resident_hull_host(const std::vector<Point>& points, ResidentStats* stats) {
  if (points.size() >= 0xffffffffu) throw std::invalid_argument("too many points (at most 2^32 - 2)");
  resident::HostExec exec;
  resident::ResidentHull<Point, resident::HostExec> hull(exec, points, points.data());
  ResidentStats local;
  ResidentStats& out = stats ? *stats : local;
  BasicHullMesh<Point> result = hull.run(out);
  out.host_syncs = exec.host_syncs;
  out.bytes_to_device = exec.bytes_to_device;
  out.bytes_from_device = exec.bytes_from_device;
  return result;
}

// The two coordinate types (README, "Precision").
template HullMesh resident_hull_host(const std::vector<Point3>&, ResidentStats*);
template HullMeshd resident_hull_host(const std::vector<Point3d>&, ResidentStats*);

}  // namespace cudahull
