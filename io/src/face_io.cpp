// The face reader (face_io.hpp): OBJ, OFF and PLY faces, with their vertices where asked, on the point
// readers' line source, numbers and PLY records (reading.hpp).  For `cudahull check` and the viewer.
#include "cudahull/face_io.hpp"

#include "reading.hpp"

namespace cudahull {
namespace {

using namespace reading;

// `where` is a message's prefix: "file:line" for text, "file: face F" for binary PLY.
[[noreturn]] void fail_at(const std::string& where, const std::string& what) {
  throw InputError(where + ": " + what);
}

template <typename P>
class FaceBuilder {
 public:
  explicit FaceBuilder(BasicFaceMesh<P>& mesh) : m_(mesh) {}
  // Ends a face of the corners added since the last one; `where` names it in messages.
  void end_face(std::uint64_t line, const std::string& where) {
    const std::size_t n = m_.corners.size() - m_.face_start.back();
    if (n < 3) fail_at(where, "a face of " + std::to_string(n) + " corners (at least 3)");
    if (m_.face_start.size() > kMaxPoints) fail_at(where, "more than 4294967295 faces");
    m_.face_start.push_back(m_.corners.size());
    m_.face_line.push_back(line);
  }
  void corner(std::uint64_t v, const std::string& where) {
    if (v >= m_.vertex_count)
      fail_at(where, "face corner " + std::to_string(v) + " is beyond the " +
                         std::to_string(m_.vertex_count) + " vertices");
    m_.corners.push_back(static_cast<std::uint32_t>(v));
  }

 private:
  BasicFaceMesh<P>& m_;
};

std::string line_ref(const std::string& name, std::uint64_t line) {
  return name + ":" + std::to_string(line);
}

// OBJ: `v` lines as read_obj reads them, `f` lines as polygons.  A positive index counts from 1; a negative
// one back from the last vertex read so far.  Positive indices are checked once every vertex is known.
template <typename P>
void read_obj_faces(Source& src, const std::string& name, bool with_vertices, BasicFaceMesh<P>& m) {
  std::string_view line;
  std::string_view tokens[4];
  std::vector<std::int64_t> raw;  // 0-based corners, checked at the end
  while (src.next_line(line)) {
    std::size_t i = 0;
    while (i < line.size() && is_space(line[i]))
      ++i;
    if (i == line.size() || (line[i] != 'v' && line[i] != 'f')) continue;
    if (i + 1 < line.size() && !is_space(line[i + 1])) continue;  // vn, vt, fo, ...
    const std::string_view rest = strip_comment(line.substr(i + 1));
    if (line[i] == 'v') {
      if (tokenize(rest, tokens, 3) < 3) fail_line(name, src.line_number(), "vertex needs 3 coordinates");
      if (m.vertex_count >= kMaxPoints) fail_line(name, src.line_number(), "more than 4294967295 points");
      if (with_vertices) m.vertices.push_back(parse_xyz_tokens<P>(tokens, name, src.line_number()));
      ++m.vertex_count;
      continue;
    }
    std::size_t k = 0, corners = 0;
    while (true) {
      while (k < rest.size() && is_space(rest[k]))
        ++k;
      if (k == rest.size()) break;
      const std::size_t start = k;
      while (k < rest.size() && !is_space(rest[k]))
        ++k;
      const std::string_view tok = rest.substr(start, k - start);
      const std::string_view index = tok.substr(0, tok.find('/'));  // v, v/vt, v//vn, v/vt/vn
      std::int64_t v = 0;
      const auto [ptr, ec] = std::from_chars(index.data(), index.data() + index.size(), v);
      if (ec != std::errc() || ptr != index.data() + index.size() || v == 0)
        fail_line(name, src.line_number(), "invalid face corner " + quote(tok));
      if (v < 0) {
        v += static_cast<std::int64_t>(m.vertex_count);
        if (v < 0)
          fail_line(name, src.line_number(), "face corner " + quote(tok) + " is before the first vertex");
      } else {
        --v;
      }
      raw.push_back(v);
      ++corners;
    }
    if (corners < 3)
      fail_line(name, src.line_number(), "a face of " + std::to_string(corners) + " corners (at least 3)");
    if (m.face_start.size() > kMaxPoints) fail_line(name, src.line_number(), "more than 4294967295 faces");
    m.face_start.push_back(raw.size());
    m.face_line.push_back(src.line_number());
  }
  m.corners.reserve(raw.size());
  for (std::size_t f = 0; f + 1 < m.face_start.size(); ++f)
    for (std::size_t c = m.face_start[f]; c < m.face_start[f + 1]; ++c) {
      if (static_cast<std::uint64_t>(raw[c]) >= m.vertex_count)
        fail_line(name, m.face_line[f],
                  "face corner " + std::to_string(raw[c] + 1) + " is beyond the " +
                      std::to_string(m.vertex_count) + " vertices");
      m.corners.push_back(static_cast<std::uint32_t>(raw[c]));
    }
}

// OFF, and Qhull's `o` output (the same without the keyword: a first line "3", the dimension).
template <typename P>
void read_off_faces(Source& src, const std::string& name, bool with_vertices, BasicFaceMesh<P>& m) {
  std::string_view line;
  if (!next_content_line(src, line)) fail(name, src.consumed() == 0 ? "empty file" : "no OFF header");
  std::string_view tokens[4];
  std::size_t n = tokenize(line, tokens, 4);
  std::string_view counts[3];
  std::size_t ncounts = 0;
  if (n == 1 && tokens[0] == "3") {
    m.qhull_off = true;
  } else if (!is_off_keyword(tokens[0])) {
    fail_line(name, src.line_number(), "expected an OFF header, found " + quote(tokens[0]));
  } else if (n > 1 && tokens[1] == "BINARY") {
    fail_line(name, src.line_number(), "binary OFF is not supported");
  } else if (n > 1) {
    ncounts = std::min<std::size_t>(n - 1, 3);
    std::copy(tokens + 1, tokens + 1 + ncounts, counts);
  }
  if (ncounts == 0) {
    if (!next_content_line(src, line)) fail_line(name, src.line_number(), "missing vertex and face counts");
    ncounts = std::min<std::size_t>(tokenize(line, counts, 3), 3);
  }
  std::uint64_t nv = 0, nf = 0;
  if (ncounts < 2 || !parse_count(counts[0], nv) || !parse_count(counts[1], nf))
    fail_line(name, src.line_number(), "expected 'vertices faces edges' counts");
  check_count_limit(nv, name, src.line_number());
  m.vertex_count = nv;
  if (with_vertices) m.vertices.reserve(text_reserve(nv, 6, src));
  for (std::uint64_t i = 0; i < nv; ++i) {
    if (!next_content_line(src, line))
      fail_line(name, src.line_number(),
                "unexpected end of file: header says " + std::to_string(nv) + " vertices, found " +
                    std::to_string(i));
    const std::size_t k = tokenize(line, tokens, 3);
    if (k < 3) fail_line(name, src.line_number(), "expected 3 coordinates, found " + std::to_string(k));
    if (with_vertices) m.vertices.push_back(parse_xyz_tokens<P>(tokens, name, src.line_number()));
  }
  FaceBuilder<P> faces(m);
  m.face_start.reserve(text_reserve(nf, 8, src) + 1);  // "3 0 1 2\n"
  for (std::uint64_t f = 0; f < nf; ++f) {
    if (!next_content_line(src, line))
      fail_line(
          name, src.line_number(),
          "unexpected end of file: header says " + std::to_string(nf) + " faces, found " + std::to_string(f));
    const std::string where = line_ref(name, src.line_number());
    std::size_t pos = 0;
    auto next = [&](std::uint64_t& out, const char* what) {
      while (pos < line.size() && is_space(line[pos]))
        ++pos;
      const std::size_t start = pos;
      while (pos < line.size() && !is_space(line[pos]))
        ++pos;
      if (!parse_count(line.substr(start, pos - start), out))
        fail_at(where, std::string("expected ") + what + ", found " + quote(line.substr(start, pos - start)));
    };
    std::uint64_t k = 0;
    next(k, "a corner count");
    for (std::uint64_t c = 0; c < k; ++c) {
      std::uint64_t v = 0;
      next(v, "a vertex index");
      faces.corner(v, where);
    }
    faces.end_face(src.line_number(), where);  // anything after the corners is a colour
  }
}

// PLY: the vertex element as read_ply reads it, the face element's vertex_indices lists.
template <typename P>
void read_ply_faces(Source& src, const std::string& name, bool with_vertices, BasicFaceMesh<P>& m) {
  const PlyHeader header = read_ply_header(src, name);
  const bool ascii = header.format == PlyFormat::kAscii;
  const bool swap = (header.format == PlyFormat::kBinaryLE) != (std::endian::native == std::endian::little);
  const PlyElement* vertex = nullptr;
  for (const PlyElement& e : header.elements)
    if (e.name == "vertex" && vertex == nullptr) vertex = &e;
  if (vertex == nullptr) fail_no_vertex_element(name);
  check_count_limit(vertex->count, name, vertex->line);
  m.vertex_count = vertex->count;
  FaceBuilder<P> faces(m);
  const ProgressFn none;
  const Progress quiet(none);
  for (const PlyElement& e : header.elements) {
    const bool is_face = e.name == "face";
    if (&e == vertex && with_vertices) {
      m.vertices = ascii ? read_ascii_vertices<P>(src, e, name, quiet)
                         : read_binary_vertices<P>(src, e, swap, name, quiet);
      continue;
    }
    if (&e == vertex && ascii) {  // skipped as read_ascii_vertices reads it: blank lines are no vertices
      std::string_view line;
      for (std::uint64_t i = 0; i < e.count; ++i)
        do {
          if (!src.next_line(line))
            fail_line(name, src.line_number(), "unexpected end of file in element 'vertex'");
        } while (is_blank(line));
      continue;
    }
    if (!is_face) {
      ascii ? skip_ascii_element(src, e, name) : skip_binary_element(src, e, swap, name);
      continue;
    }
    const PlyProperty* list = nullptr;
    for (const PlyProperty& p : e.properties)
      if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index") && list == nullptr) list = &p;
    if (list == nullptr) fail_line(name, e.line, "face element without a 'vertex_indices' list");
    if (list->type == PlyType::kFloat32 || list->type == PlyType::kFloat64)
      fail_line(name, e.line, "face indices must have an integer type");
    std::string_view line;
    for (std::uint64_t f = 0; f < e.count; ++f) {
      std::string where = name + ": face " + std::to_string(f);
      std::uint64_t ln = 0;
      std::size_t pos = 0;
      if (ascii) {
        do {
          if (!src.next_line(line))
            fail_line(name, src.line_number(), "unexpected end of file in element 'face'");
        } while (is_blank(line));
        ln = src.line_number();
        where = line_ref(name, ln);
      }
      // The next value: a token of the line, or bytes of the data; integers only where `integer`.
      auto value = [&](PlyType type) -> double {
        if (ascii) {
          while (pos < line.size() && is_space(line[pos]))
            ++pos;
          const std::size_t start = pos;
          while (pos < line.size() && !is_space(line[pos]))
            ++pos;
          const std::string_view tok = line.substr(start, pos - start);
          double v = 0;
          if (tok.empty()) fail_at(where, "too few values for the face's properties");
          if (parse_number(tok, v) != NumStatus::kOk) fail_at(where, "invalid value " + quote(tok));
          return v;
        }
        char bytes[8];
        const std::size_t s = type_size(type);
        if (src.read_bytes(bytes, s) != s) fail_at(where, "truncated binary data");
        return load_value(bytes, type, swap);
      };
      for (const PlyProperty& p : e.properties) {
        if (!p.is_list) {
          value(p.type);
          continue;
        }
        const double len = value(p.count_type);
        if (!(len >= 0 && len == std::floor(len) && len <= 4294967295.0))
          fail_at(where, "invalid list length");
        for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(len); ++k) {
          const double v = value(p.type);
          if (&p != list) continue;
          if (!(v >= 0 && v == std::floor(v) && v < 18446744073709551616.0))
            fail_at(where, "invalid vertex index");
          faces.corner(static_cast<std::uint64_t>(v), where);
        }
        if (&p == list) faces.end_face(ln, where);
      }
      if (ascii && !is_blank(line.substr(pos)))
        fail_at(where, "more values than the header's face properties");
    }
  }
}

template <typename P>
BasicFaceMesh<P> read_faces_stream(std::istream& in, PointFormat format, const std::string& name,
                                   bool with_vertices) {
  Source src(in, name);
  BasicFaceMesh<P> m;
  switch (format) {
    case PointFormat::kObj:
      read_obj_faces(src, name, with_vertices, m);
      break;
    case PointFormat::kOff:
      read_off_faces(src, name, with_vertices, m);
      break;
    case PointFormat::kPly:
      read_ply_faces(src, name, with_vertices, m);
      break;
    case PointFormat::kXyz:
      fail(name, "an xyz file has no faces (expected .obj, .off or .ply)");
  }
  return m;
}

}  // namespace

template <class Point>
BasicFaceMesh<Point> read_faces(const std::string& path, bool with_vertices) {
  const PointFormat format = point_format_from_path(path);
  std::ifstream in;
  open_file(path, in);
  return read_faces<Point>(in, format, path, with_vertices);
}

template <class Point>
BasicFaceMesh<Point> read_faces(std::istream& in, PointFormat format, const std::string& name,
                                bool with_vertices) {
  return read_faces_stream<Point>(in, format, name, with_vertices);
}

template BasicFaceMesh<Point3> read_faces(const std::string&, bool);
template BasicFaceMesh<Point3d> read_faces(const std::string&, bool);
template BasicFaceMesh<Point3> read_faces(std::istream&, PointFormat, const std::string&, bool);
template BasicFaceMesh<Point3d> read_faces(std::istream&, PointFormat, const std::string&, bool);

}  // namespace cudahull
