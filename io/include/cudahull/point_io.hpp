// Reading point sets (README, "Input formats").
//
// Every reader stores coordinates as float32.  A coordinate that is NaN, infinite or beyond float range, a
// short line, a wrong element count or truncated binary data throws InputError whose one-line message names
// the file and the line (text formats) or the vertex index (binary formats).
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

}  // namespace cudahull
