// Writing point sets (`cudahull gen`): .ply (binary little-endian, fast for tens of millions of points),
// .xyz/.txt ("x y z" lines), .obj ("v" lines) or .off, by extension; written atomically.  Point3 is written
// as float (PLY `float` properties, text %.9g), Point3d as double (PLY `double` properties, text %.17g): read
// back in the same precision, every coordinate is the same bit for bit.
#pragma once

#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

template <class Point = Point3>
void write_points(const std::string& path, const std::vector<Point>& points);

extern template void write_points(const std::string&, const std::vector<Point3>&);
extern template void write_points(const std::string&, const std::vector<Point3d>&);

}  // namespace cudahull
