// The input model's own surface (issue 17's `input` layer): the faces of an OBJ, OFF or PLY as io's face
// reader (face_io.hpp) reads them, as indices into the points the viewer loaded from the same file (both
// readers keep the file's vertex order).  Polygons are split into fans.  Point clouds without faces (XYZ,
// a PLY with no face element) give none.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cudahull::viewer {

using InputTriangle = std::array<std::uint32_t, 3>;

// The faces of the model at `path` (.obj, .off or .ply; other formats give none), checked against
// `point_count`.  Throws InputError for a file the point reader accepted but whose faces cannot be read.
std::vector<InputTriangle> read_input_surface(const std::string& path, std::size_t point_count);

}  // namespace cudahull::viewer
