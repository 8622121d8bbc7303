#include "input_surface.hpp"

#include "cudahull/errors.hpp"
#include "cudahull/face_io.hpp"

namespace cudahull::viewer {

std::vector<InputTriangle> read_input_surface(const std::string& path, std::size_t point_count) {
  const PointFormat format = point_format_from_path(path);
  if (format == PointFormat::kXyz) return {};
  // The points are loaded already: only the faces are read here.
  const FaceMesh mesh = read_faces<Point3d>(path, /*with_vertices=*/false);
  if (mesh.vertex_count != point_count)
    throw InputError(path + ": faces: " + std::to_string(mesh.vertex_count) + " vertices, but " +
                     std::to_string(point_count) + " points were loaded");
  std::vector<InputTriangle> out;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const std::uint32_t* c = mesh.corners.data() + mesh.face_start[f];
    const std::size_t n = mesh.face_start[f + 1] - mesh.face_start[f];
    for (std::size_t k = 1; k + 1 < n; ++k)
      out.push_back({c[0], c[k], c[k + 1]});
  }
  return out;
}

}  // namespace cudahull::viewer
