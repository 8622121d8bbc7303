// Writing point sets (`cudahull gen`): .ply (binary little-endian float, fast for tens of millions of
// points), .xyz/.txt ("x y z" lines), .obj ("v" lines) or .off, by extension; written atomically.
#pragma once

#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

void write_points(const std::string& path, const std::vector<Point3>& points);

}  // namespace cudahull
