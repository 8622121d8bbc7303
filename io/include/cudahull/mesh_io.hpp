// Writing hulls and vertex lists.  Every writer writes to a temporary file beside the target and renames it
// only when complete, so a failure or an interrupt never leaves a half-written file.
#pragma once

#include <functional>
#include <ostream>
#include <string>

#include "cudahull/types.hpp"

namespace cudahull {

// Writes the hull as .obj, .off or .ply (ascii), chosen by the extension of `path` (OutputError otherwise).
// Coordinates use round-trip precision: %.9g for Point3 (float), %.17g for Point3d (double), so that reading
// them back in the same precision gives the same values bit for bit; PLY declares them float or double.
// Faces are the outward, counter-clockwise triangles; a planar hull (dimension 2) is written as one polygon
// face, a segment or a point as vertices only.  Defined for Point3 and Point3d.
template <class Point = Point3>
void write_mesh(const std::string& path, const BasicHullMesh<Point>& hull);

// Why write_mesh() could not write `path` (an unknown extension), or empty: for checking an output name
// before the work that produces the mesh.
std::string mesh_path_problem(const std::string& path);

// Writes one line per hull vertex, "index x y z", 0-based input indices sorted ascending.  "-" is stdout.
// Coordinates as write_mesh() writes them (%.9g float, %.17g double).  Defined for Point3 and Point3d.
template <class Point = Point3>
void write_vertices(const std::string& path, const BasicHullMesh<Point>& hull);

extern template void write_mesh(const std::string&, const HullMesh&);
extern template void write_mesh(const std::string&, const HullMeshd&);
extern template void write_vertices(const std::string&, const HullMesh&);
extern template void write_vertices(const std::string&, const HullMeshd&);

// Writes `write_body` to `path` atomically: a temporary name in the same folder, then rename(2).  The
// temporary file is removed on any failure and on SIGINT, SIGTERM or SIGHUP (unless the caller ignores it).
// "-" writes to stdout directly.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write_body);

}  // namespace cudahull
