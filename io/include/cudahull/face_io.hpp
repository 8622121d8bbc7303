// Reading meshes with faces: OBJ, OFF (and Qhull's `o` output) and PLY.  `cudahull check` reads a hull
// from any tool with it, and the viewer the model's own surface.
//
// Vertices are read as the point readers read them (point_io.hpp: float rounded once, double as the file
// gives them) and in the file's order, so they line up with read_points() of the same file.  Faces are
// polygons of at least three corners, 0-based.  A corner naming a vertex the file does not have, a face of
// fewer than three corners, a bad count or truncated data throws InputError naming the file and the line
// (text) or the face (binary PLY).
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "cudahull/point_io.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

template <class Point>
struct BasicFaceMesh {
  std::vector<Point> vertices;  // empty when read without them (vertex_count still says how many)
  std::size_t vertex_count = 0;
  std::vector<std::uint32_t> corners;         // every face's corners, face after face
  std::vector<std::size_t> face_start = {0};  // face f: corners[face_start[f] .. face_start[f + 1])
  std::vector<std::uint64_t> face_line;       // each face's line in a text file, 0 in binary PLY
  // Qhull's `o` output: OFF without its keyword (a first line "3"), every input point a vertex, printed
  // with 16 significant digits.
  bool qhull_off = false;
  std::size_t face_count() const { return face_start.size() - 1; }
};
using FaceMesh = BasicFaceMesh<Point3d>;

// The faces (and, with `with_vertices`, the vertices) of a .obj, .off or .ply file; other formats throw
// InputError.  OBJ: `v` and `f` lines (`f 1/2/3 4//5 ...` and negative, relative indices taken).  OFF: the
// faces after the vertices, colours after the corners ignored.  PLY: the `vertex_indices` (or
// `vertex_index`) list of element `face`, any integer type, ascii or binary.  Point3 or Point3d.
template <class Point = Point3d>
BasicFaceMesh<Point> read_faces(const std::string& path, bool with_vertices = true);
template <class Point = Point3d>
BasicFaceMesh<Point> read_faces(std::istream& in, PointFormat format, const std::string& name,
                                bool with_vertices = true);

extern template BasicFaceMesh<Point3> read_faces(const std::string&, bool);
extern template BasicFaceMesh<Point3d> read_faces(const std::string&, bool);
extern template BasicFaceMesh<Point3> read_faces(std::istream&, PointFormat, const std::string&, bool);
extern template BasicFaceMesh<Point3d> read_faces(std::istream&, PointFormat, const std::string&, bool);

}  // namespace cudahull
