// Point readers: OBJ, PLY (ascii and binary), OFF, XYZ (README, "Input formats"), on the line source,
// number parsing and PLY header they share with the face reader (reading.hpp, face_io.cpp).
//
// Every reader is a template over the point type.  For Point3 (read_points) a text number goes straight from
// decimal to float with std::from_chars<float> (correctly rounded), so a coordinate is rounded exactly once,
// as types.hpp promises; binary doubles are rounded once from the double.  For Point3d (read_points_double) a
// text number goes to the nearest double with std::from_chars<double>, and binary values are kept exactly.
// The float path never goes through a double: decimal -> double -> float can differ from decimal -> float
// (double rounding), so the float results are those of direct parsing.
//
// OBJ is parsed here too, not with tinyobjloader: its number parser turns "nan", "inf", "abc" and a missing z
// into 0 without any warning, so the errors this file must report would pass silently, and its decimal
// conversion is not correctly rounded (it picks the wrong float for about a third of the decimals that lie
// next to a float rounding boundary).  Only `v` lines matter for a point set, and they are simple.
#include "cudahull/point_io.hpp"

#include "reading.hpp"

namespace cudahull {
namespace {

using namespace reading;

// The points of a text format with at most one a line (xyz, OBJ): `split(line, tokens)` puts a line's 3
// coordinates in `tokens` and returns true, returns false for a line with no point, or fails.  `none` is
// the error for a file without points.
template <typename P, class Split>
std::vector<P> read_point_lines(Source& src, const std::string& name, const Progress& progress,
                                const char* none, Split split) {
  std::vector<P> points;
  std::string_view line;
  std::string_view tokens[3];
  while (src.next_line(line)) {
    if (!split(line, tokens)) continue;
    check_not_too_many(points, name, src.line_number());
    points.push_back(parse_xyz_tokens<P>(tokens, name, src.line_number()));
    if (progress.due(points.size())) progress.report(src.fraction());
  }
  finish(points, src, name, none, progress);
  return points;
}

// ---------------------------------------------------------------------------------------------- XYZ

// One point per line, "x y z".  Columns after the third (normals, colours, intensities) are allowed and
// ignored without being parsed, since xyz files from scanners commonly carry them.  '#' starts a comment
// anywhere on a line; blank lines are skipped.
template <typename P>
std::vector<P> read_xyz(Source& src, const std::string& name, const Progress& progress) {
  return read_point_lines<P>(
      src, name, progress, "no points", [&](std::string_view line, std::string_view* tokens) {
        const std::size_t n = tokenize(strip_comment(line), tokens, 3);
        if (n > 0 && n < 3)
          fail_line(name, src.line_number(), "expected 3 coordinates, found " + std::to_string(n));
        return n > 0;
      });
}

// ---------------------------------------------------------------------------------------------- OBJ

// `v x y z [w]` and `v x y z r g b` lines; everything else (faces, normals, groups, unknown keywords) is
// ignored, as OBJ readers do.
template <typename P>
std::vector<P> read_obj(Source& src, const std::string& name, const Progress& progress) {
  return read_point_lines<P>(
      src, name, progress, "no vertices", [&](std::string_view line, std::string_view* tokens) {
        std::size_t i = 0;
        while (i < line.size() && is_space(line[i]))
          ++i;
        if (i == line.size() || line[i] != 'v' || (i + 1 < line.size() && !is_space(line[i + 1])))
          return false;
        const std::size_t n = tokenize(strip_comment(line.substr(i + 1)), tokens, 3);
        if (n < 3) {
          fail_line(name, src.line_number(), "vertex needs 3 coordinates, found " + std::to_string(n));
        }
        return true;
      });
}

template <typename P>
std::vector<P> read_off(Source& src, const std::string& name, const Progress& progress) {
  std::string_view line;
  if (!next_content_line(src, line)) fail(name, src.consumed() == 0 ? "empty file" : "no OFF header");
  std::string_view tokens[4];
  std::size_t n = tokenize(line, tokens, 4);
  if (!is_off_keyword(tokens[0])) {
    fail_line(name, src.line_number(), "expected an OFF header, found " + quote(tokens[0]));
  }
  if (n > 1 && tokens[1] == "BINARY") fail_line(name, src.line_number(), "binary OFF is not supported");
  // The counts may follow the keyword on the same line.
  std::string_view counts[3];
  std::size_t ncounts = 0;
  if (n > 1) {
    ncounts = std::min<std::size_t>(n - 1, 3);
    std::copy(tokens + 1, tokens + 1 + ncounts, counts);
  } else {
    if (!next_content_line(src, line)) fail_line(name, src.line_number(), "missing vertex and face counts");
    ncounts = std::min<std::size_t>(tokenize(line, counts, 3), 3);
  }
  std::uint64_t nv = 0, nf = 0;
  if (ncounts < 2 || !parse_count(counts[0], nv) || !parse_count(counts[1], nf)) {
    fail_line(name, src.line_number(), "expected 'vertices faces edges' counts");
  }
  if (nv == 0) fail_line(name, src.line_number(), "no vertices");
  check_count_limit(nv, name, src.line_number());

  std::vector<P> points;
  points.reserve(text_reserve(nv, 6, src));  // "0 0 0\n"
  while (points.size() < nv) {
    if (!next_content_line(src, line)) {
      fail_line(name, src.line_number(),
                "unexpected end of file: header says " + std::to_string(nv) + " vertices, found " +
                    std::to_string(points.size()));
    }
    const std::size_t k = tokenize(line, tokens, 3);
    if (k < 3) fail_line(name, src.line_number(), "expected 3 coordinates, found " + std::to_string(k));
    points.push_back(parse_xyz_tokens<P>(tokens, name, src.line_number()));
    if (progress.due(points.size())) progress.report(double(points.size()) / double(nv));
  }
  progress.report(1.0);
  return points;
}

// What `auto` picks for a PLY file: double for ascii (decimals), and for binary x, y, z of a type that float
// cannot hold exactly (double, 32-bit integers); float otherwise.
Precision ply_precision(const PlyHeader& header, const PlyElement& vertex, const std::string& name) {
  const XyzLayout layout = find_xyz(vertex, name);
  if (header.format == PlyFormat::kAscii) return Precision::kDouble;
  for (const PlyProperty* p : layout.axis) {
    if (p->type == PlyType::kFloat64 || p->type == PlyType::kInt32 || p->type == PlyType::kUint32) {
      return Precision::kDouble;
    }
  }
  return Precision::kFloat;
}

template <typename P>
std::vector<P> read_ply(Source& src, const std::string& name, const Progress& progress,
                        Precision* precision) {
  const PlyHeader header = read_ply_header(src, name);
  const bool swap = (header.format == PlyFormat::kBinaryLE) != (std::endian::native == std::endian::little);
  for (const PlyElement& e : header.elements) {
    if (e.name != "vertex") {
      if (header.format == PlyFormat::kAscii) {
        skip_ascii_element(src, e, name);
      } else {
        skip_binary_element(src, e, swap, name);
      }
      continue;
    }
    find_xyz(e, name);
    if (e.count == 0) fail_line(name, e.line, "no vertices");
    check_count_limit(e.count, name, e.line);
    if (precision != nullptr) *precision = ply_precision(header, e, name);
    // Elements after the vertices (faces, range grids) are never read.
    std::vector<P> points = header.format == PlyFormat::kAscii
                                ? read_ascii_vertices<P>(src, e, name, progress)
                                : read_binary_vertices<P>(src, e, swap, name, progress);
    progress.report(1.0);
    return points;
  }
  fail_no_vertex_element(name);
}

// Reads every point of a stream of the given format; sets *precision (if given) to what `auto` picks.
template <typename P>
std::vector<P> read_stream(std::istream& in, PointFormat format, const std::string& name,
                           const ProgressFn& progress, Precision* precision) {
  Source src(in, name);
  const Progress prog(progress);
  prog.report(0.0);
  if (precision != nullptr) *precision = Precision::kDouble;  // every text format
  switch (format) {
    case PointFormat::kObj:
      return read_obj<P>(src, name, prog);
    case PointFormat::kPly:
      return read_ply<P>(src, name, prog, precision);
    case PointFormat::kOff:
      return read_off<P>(src, name, prog);
    case PointFormat::kXyz:
      return read_xyz<P>(src, name, prog);
  }
  fail(name, "unknown point format");
}

}  // namespace

PointFormat point_format_from_path(const std::string& path) {
  if (path == "-") return PointFormat::kXyz;
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return PointFormat::kObj;
  if (ext == ".ply") return PointFormat::kPly;
  if (ext == ".off") return PointFormat::kOff;
  if (ext == ".xyz" || ext == ".txt") return PointFormat::kXyz;
  throw InputError(path + ": unknown file extension " + (ext.empty() ? std::string("(none)") : quote(ext)) +
                   " (expected .obj, .ply, .off, .xyz or .txt)");
}

std::vector<Point3> read_points(const std::string& path, const ProgressFn& progress) {
  if (path == "-") return read_points(std::cin, PointFormat::kXyz, "<stdin>", progress);
  const PointFormat format = point_format_from_path(path);
  std::ifstream in;
  open_file(path, in);
  return read_points(in, format, path, progress);
}

std::vector<Point3> read_points(std::istream& in, PointFormat format, const std::string& name,
                                const ProgressFn& progress) {
  return read_stream<Point3>(in, format, name, progress, nullptr);
}

DoublePoints read_points_double(const std::string& path, const ProgressFn& progress) {
  if (path == "-") return read_points_double(std::cin, PointFormat::kXyz, "<stdin>", progress);
  const PointFormat format = point_format_from_path(path);
  std::ifstream in;
  open_file(path, in);
  return read_points_double(in, format, path, progress);
}

DoublePoints read_points_double(std::istream& in, PointFormat format, const std::string& name,
                                const ProgressFn& progress) {
  DoublePoints result;
  result.points = read_stream<Point3d>(in, format, name, progress, &result.precision);
  return result;
}

void check_double_range(const std::vector<Point3d>& points, const std::string& name) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double v[3] = {points[i].x, points[i].y, points[i].z};
    for (int axis = 0; axis < 3; ++axis) {
      if (in_fast_exact_range(v[axis])) continue;
      char value[32];
      const auto end = std::to_chars(value, value + sizeof value, v[axis]).ptr;  // shortest round trip
      throw InputError(name + ": point " + std::to_string(i) + ": " + axis_name(axis) + " coordinate " +
                       std::string(value, end) +
                       " is outside the range of exact double arithmetic (nonzero magnitudes from 2^-250 to "
                       "2^250)");
    }
  }
}

Precision auto_precision(const std::string& path) {
  if (path == "-") return Precision::kDouble;
  const PointFormat format = point_format_from_path(path);
  std::ifstream in;
  open_file(path, in);
  return auto_precision(in, format, path);
}

Precision resolve_precision(Precision requested, const std::string& path) {
  if (requested != Precision::kAuto) return requested;
  return path.empty() ? Precision::kFloat : auto_precision(path);
}

Precision auto_precision(std::istream& in, PointFormat format, const std::string& name) {
  if (format != PointFormat::kPly) return Precision::kDouble;
  Source src(in, name);
  const PlyHeader header = read_ply_header(src, name);
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex") return ply_precision(header, e, name);
  }
  fail_no_vertex_element(name);
}

}  // namespace cudahull
