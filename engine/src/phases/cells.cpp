#include "phases/cells.hpp"

#include "cudahull/parallel.hpp"
#include "phases/vector_math.hpp"

namespace cudahull::phases {

SeparatingPlane plane_through_edge(const Vec3d& a, const Vec3d& b, const Vec3d& along, const Vec3d& inside) {
  Vec3d m = normalized(cross(normalized(sub(b, a)), along));
  double d = -dot(m, a);
  if (dot(m, inside) + d < 0) {
    m = {-m.x, -m.y, -m.z};
    d = -d;
  }
  return {m.x, m.y, m.z, d};
}

template <class Point>
Vec3d unit_normal(const Mesh& mesh, const std::vector<Point>& points, FaceId f) {
  const MeshFace& face = mesh.face(f);
  const Vec3d a = to_vec3d(points[face.v[0]]), b = to_vec3d(points[face.v[1]]),
              c = to_vec3d(points[face.v[2]]);
  return normalized(cross(sub(b, a), sub(c, a)));
}

template <class Point>
FaceCell face_cell(const Mesh& mesh, const std::vector<Point>& points, FaceId f) {
  auto P = [&](PointIndex i) { return to_vec3d(points[i]); };
  const MeshFace& face = mesh.face(f);
  FaceCell cell;
  const Vec3d n = unit_normal(mesh, points, f);
  cell.face_plane = {n.x, n.y, n.z, -dot(n, P(face.v[0]))};
  for (int i = 0; i < 3; ++i) {
    const Vec3d along = add(n, unit_normal(mesh, points, face.n[i]));
    cell.edge_plane[i] =
        plane_through_edge(P(face.v[i]), P(face.v[(i + 1) % 3]), along, P(face.v[(i + 2) % 3]));
  }
  return cell;
}

template <class Point>
void refinement_planes(const Mesh& mesh, const std::vector<Point>& points,
                       std::vector<RefinementEntry>& refinement,
                       const std::vector<std::array<FaceId, 3>>& children) {
  auto P = [&](PointIndex i) { return to_vec3d(points[i]); };
  parallel_chunks(
      refinement.size(), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          // Child i is (v[i], v[i+1], apex) of the old face.  plane[i] through the apex and old vertex i
          // separates child i-1 from child i, along the average of their normals.
          const std::array<FaceId, 3>& kids = children[k];
          const Vec3d normal[3] = {unit_normal(mesh, points, kids[0]), unit_normal(mesh, points, kids[1]),
                                   unit_normal(mesh, points, kids[2])};
          const Vec3d apex = P(refinement[k].apex);
          for (int i = 0; i < 3; ++i) {
            const Vec3d along = add(normal[i], normal[(i + 2) % 3]);
            const Vec3d inside = P(mesh.face(kids[(i + 1) % 3]).v[0]);
            refinement[k].plane[i] = plane_through_edge(apex, P(mesh.face(kids[i]).v[0]), along, inside);
          }
        }
      },
      512);
}

template <class Point>
SeparatingPlane swap_plane(const Mesh& mesh, const std::vector<Point>& points, FaceId n1, FaceId n2,
                           PointIndex u) {
  const MeshFace& face = mesh.face(n1);  // (x, u, y)
  const Vec3d along = add(unit_normal(mesh, points, n1), unit_normal(mesh, points, n2));
  return plane_through_edge(to_vec3d(points[face.v[0]]), to_vec3d(points[face.v[2]]), along,
                            to_vec3d(points[u]));
}

// The two coordinate types (README, "Precision").
template Vec3d unit_normal(const Mesh&, const std::vector<Point3>&, FaceId);
template FaceCell face_cell(const Mesh&, const std::vector<Point3>&, FaceId);
template void refinement_planes(const Mesh&, const std::vector<Point3>&, std::vector<RefinementEntry>&,
                                const std::vector<std::array<FaceId, 3>>&);
template SeparatingPlane swap_plane(const Mesh&, const std::vector<Point3>&, FaceId, FaceId, PointIndex);
template Vec3d unit_normal(const Mesh&, const std::vector<Point3d>&, FaceId);
template FaceCell face_cell(const Mesh&, const std::vector<Point3d>&, FaceId);
template void refinement_planes(const Mesh&, const std::vector<Point3d>&, std::vector<RefinementEntry>&,
                                const std::vector<std::array<FaceId, 3>>&);
template SeparatingPlane swap_plane(const Mesh&, const std::vector<Point3d>&, FaceId, FaceId, PointIndex);

}  // namespace cudahull::phases
