// Reading point sets (README, "Input formats").
//
// read_points stores coordinates as float32: a decimal goes straight to the nearest float, a binary value is
// rounded to float once.  read_points_double keeps them as the file gives them: a decimal goes to the nearest
// double, a binary value (float, double or integer) is kept exactly.  A coordinate that is NaN, infinite or
// beyond the range of the type read into, a short line, a wrong element count or truncated binary data throws
// InputError whose one-line message names the file and the line (text formats) or the vertex index (binary
// formats).
#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

enum class PointFormat { kObj, kPly, kOff, kXyz };

// Called now and then while reading with the fraction done in [0, 1]; lets a UI or CLI show progress.
using ProgressFn = std::function<void(double fraction)>;

// Picks the format from the extension: .obj, .ply, .off, .xyz, .txt; "-" means xyz on stdin.
// Throws InputError for an unknown extension.
PointFormat point_format_from_path(const std::string& path);

// Reads all points of `path` ("-" reads xyz from standard input).
std::vector<Point3> read_points(const std::string& path, const ProgressFn& progress = {});

// Reads from an open stream; `name` is used in error messages only.
std::vector<Point3> read_points(std::istream& in, PointFormat format, const std::string& name,
                                const ProgressFn& progress = {});

// The points of a file at the precision the file gives, and the precision `auto` picks for it.
struct DoublePoints {
  std::vector<Point3d> points;
  // kDouble for .xyz/.txt, .obj, .off and ascii PLY (decimals are not floats in general) and for binary PLY
  // whose x, y or z is a double or a 32-bit integer; kFloat for binary PLY whose x, y and z are float or
  // 8- or 16-bit integers (the double values are then floats exactly).  Never kAuto.
  Precision precision = Precision::kDouble;
};

// As read_points, but at full precision (see above).  The points are the same as read_points' wherever
// those are exact; the errors are the same except that the range checked is double's.
DoublePoints read_points_double(const std::string& path, const ProgressFn& progress = {});
DoublePoints read_points_double(std::istream& in, PointFormat format, const std::string& name,
                                const ProgressFn& progress = {});

// Throws InputError, one line naming `name`, the point's 0-based index, the axis and the value, for the first
// coordinate of `points` outside the engines' exact range (in_fast_exact_range(), predicates.hpp: nonzero
// magnitudes from 2^-250 to 2^250), or not finite.  `cudahull bench` and the viewer, which run the engines,
// call it on double input; `cudahull hull` takes such input to the wide-range path instead.
void check_double_range(const std::vector<Point3d>& points, const std::string& name);

// The precision `auto` picks for `path` (DoublePoints::precision), from the format and, for PLY, the header
// alone: no point is read.  Throws InputError for an unknown extension, a missing file or a bad PLY header.
Precision auto_precision(const std::string& path);
// What --precision means for an input (`cudahull hull`, `bench`, the viewer): `requested` unless kAuto; kAuto
// is the file's auto_precision(), and float for generated points (`path` empty).
Precision resolve_precision(Precision requested, const std::string& path);
Precision auto_precision(std::istream& in, PointFormat format, const std::string& name);

}  // namespace cudahull
