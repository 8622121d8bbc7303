#include "phases/initial_tetrahedron.hpp"

#include <utility>

#include "cudahull/exact_hull.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull::phases {

template <class Point>
InitialTetrahedron find_initial_tetrahedron(const std::vector<Point>& points, BasicBackend<Point>& backend) {
  InitialTetrahedron out;
  const auto n = static_cast<PointIndex>(points.size());
  auto P = [&](PointIndex i) { return to_vec3d(points[i]); };
  auto t0 = Clock::now();
  auto [p0, p1] = backend.extremes_x();
  out.backend_ms = ms_since(t0);
  if (points[p0].x == points[p1].x) {
    // Every x is equal: the points lie in a plane, on a line, or are one point.
    out.dimension = affine_dimension(points);
    out.note = "degenerate input: all points share one x (dimension " + std::to_string(out.dimension) + ")";
    return out;
  }
  t0 = Clock::now();
  PointIndex p2 = backend.furthest_from_line(p0, p1);
  if (collinear3d(P(p0), P(p1), P(p2))) {
    p2 = kNoPoint;
    for (PointIndex i = 0; i < n && p2 == kNoPoint; ++i) {
      if (!collinear3d(P(p0), P(p1), P(i))) p2 = i;
    }
    if (p2 == kNoPoint) {
      out.dimension = 1;
      out.note = "degenerate input: all points are collinear (dimension 1)";
      return out;
    }
  }
  PointIndex p3 = backend.furthest_from_plane(p0, p1, p2);
  out.backend_ms += ms_since(t0);
  if (orient3d(P(p0), P(p1), P(p2), P(p3)) == 0) {
    p3 = kNoPoint;
    for (PointIndex i = 0; i < n && p3 == kNoPoint; ++i) {
      if (orient3d(P(p0), P(p1), P(p2), P(i)) != 0) p3 = i;
    }
    if (p3 == kNoPoint) {
      out.dimension = 2;
      out.note = "degenerate input: all points are coplanar (dimension 2)";
      return out;
    }
  }
  if (orient3d(P(p0), P(p1), P(p2), P(p3)) > 0) std::swap(p1, p2);  // p3 must lie below (p0, p1, p2)
  out.corners = {p0, p1, p2, p3};
  return out;
}

template <class Point>
bool make_initial_tetrahedron(const std::vector<Point>& points, const std::array<PointIndex, 4>& corners,
                              Mesh& mesh, Vec3d& interior) {
  auto P = [&](PointIndex i) { return to_vec3d(points[i]); };
  const auto [p0, p1, p2, p3] = corners;
  mesh.make_tetrahedron(p0, p1, p2, p3);
  interior = {(P(p0).x + P(p1).x + P(p2).x + P(p3).x) / 4, (P(p0).y + P(p1).y + P(p2).y + P(p3).y) / 4,
              (P(p0).z + P(p1).z + P(p2).z + P(p3).z) / 4};
  for (FaceId f = 0; f < 4; ++f) {
    const MeshFace& face = mesh.face(f);
    if (orient3d(P(face.v[0]), P(face.v[1]), P(face.v[2]), interior) >= 0) return false;
  }
  return true;
}

// The two coordinate types (README, "Precision").
template InitialTetrahedron find_initial_tetrahedron(const std::vector<Point3>&, BasicBackend<Point3>&);
template bool make_initial_tetrahedron(const std::vector<Point3>&, const std::array<PointIndex, 4>&, Mesh&,
                                       Vec3d&);
template InitialTetrahedron find_initial_tetrahedron(const std::vector<Point3d>&, BasicBackend<Point3d>&);
template bool make_initial_tetrahedron(const std::vector<Point3d>&, const std::array<PointIndex, 4>&, Mesh&,
                                       Vec3d&);

}  // namespace cudahull::phases
