// The stepping engine's phases, for the resident engine (shared_phases.hpp).
#include "cudahull/resident/shared_phases.hpp"

#include "phases/cells.hpp"
#include "phases/initial_tetrahedron.hpp"
#include "phases/vector_math.hpp"

namespace cudahull::resident {

template <class Point>
std::string first_tetrahedron(const std::vector<Point>& points, BasicBackend<Point>& queries,
                              std::vector<std::uint32_t>& fv, std::vector<std::uint32_t>& fn, Vec3d& c) {
  const phases::InitialTetrahedron tetrahedron = phases::find_initial_tetrahedron(points, queries);
  if (tetrahedron.dimension < 3) return tetrahedron.note;
  Mesh mesh;
  if (!phases::make_initial_tetrahedron(points, tetrahedron.corners, mesh, c))
    return "tetrahedron too flat for an interior point";
  fv.resize(12);
  fn.resize(12);
  for (std::uint32_t f = 0; f < 4; ++f) {
    for (int k = 0; k < 3; ++k) {
      fv[3 * f + k] = mesh.face(f).v[k];
      fn[3 * f + k] = mesh.face(f).n[k];
    }
  }
  return "";
}
template std::string first_tetrahedron(const std::vector<Point3>&, BasicBackend<Point3>&,
                                       std::vector<std::uint32_t>&, std::vector<std::uint32_t>&, Vec3d&);
template std::string first_tetrahedron(const std::vector<Point3d>&, BasicBackend<Point3d>&,
                                       std::vector<std::uint32_t>&, std::vector<std::uint32_t>&, Vec3d&);

SeparatingPlane plane_through(const Vec3d& a, const Vec3d& b, const Vec3d& d, const Vec3d& inside) {
  return phases::plane_through_edge(a, b, phases::sub(d, a), inside);
}

}  // namespace cudahull::resident
