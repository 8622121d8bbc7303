// The input model's own surface (issue 17's `input` layer): the triangles of an OBJ (through tinyobjloader)
// or of a PLY's face element, as indices into the points the viewer loaded from the same file (both readers
// keep the file's vertex order).  Polygons are split into fans; faces that name a vertex out of range are
// dropped.  Point clouds without faces (XYZ, a PLY with no face element) give none.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cudahull::viewer {

using InputTriangle = std::array<std::uint32_t, 3>;

// The faces of the model at `path` (.obj or .ply; other formats give none), checked against `point_count`.
// Throws InputError for a file the point reader accepted but whose faces cannot be read.
std::vector<InputTriangle> read_input_surface(const std::string& path, std::size_t point_count);

}  // namespace cudahull::viewer
