// Point readers: OBJ, PLY (ascii and binary), OFF, XYZ (README, "Input formats"), and the face reader
// (face_io.hpp), which shares their line source, number parsing and PLY header.
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
#include "cudahull/face_io.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>
#include <type_traits>

#include "cudahull/errors.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull {
namespace {

constexpr std::uint64_t kMaxPoints = std::numeric_limits<PointIndex>::max();  // indices are 32-bit
constexpr std::size_t kChunkBytes = std::size_t{8} << 20;                     // binary read granularity
constexpr std::size_t kMaxLineBytes = std::size_t{16} << 20;      // a longer "line" is binary garbage
constexpr std::uint64_t kProgressEvery = std::uint64_t{1} << 16;  // points between callbacks

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw InputError(name + ": " + what);
}
[[noreturn]] void fail_line(const std::string& name, std::uint64_t line, const std::string& what) {
  throw InputError(name + ":" + std::to_string(line) + ": " + what);
}
[[noreturn]] void fail_vertex(const std::string& name, std::uint64_t index, const std::string& what) {
  throw InputError(name + ": vertex " + std::to_string(index) + ": " + what);
}

// Quotes a token for an error message: bounded, and printable, so the message stays one line.
std::string quote(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMax) out += "...";
  return out + "'";
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Splits a line at whitespace into at most `max` tokens; returns how many were found (the count may exceed
// `max`, the extra ones are only counted).
std::size_t tokenize(std::string_view line, std::string_view* tokens, std::size_t max) {
  std::size_t n = 0;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && is_space(line[i]))
      ++i;
    if (i == line.size()) return n;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i]))
      ++i;
    if (n < max) tokens[n] = line.substr(start, i - start);
    ++n;
  }
}

std::string_view strip_comment(std::string_view line) {
  const std::size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

bool is_blank(std::string_view line) {
  return std::all_of(line.begin(), line.end(), [](char c) { return is_space(c); });
}

enum class NumStatus { kOk, kBad, kNaN, kInf, kTooBig };

// The coordinate type of a point type, and its name for messages.
template <typename P>
using Scalar = std::remove_cv_t<decltype(P::x)>;
static_assert(std::is_same_v<Scalar<Point3>, float> && std::is_same_v<Scalar<Point3d>, double>);
static_assert(sizeof(Point3) == 3 * sizeof(float) && sizeof(Point3d) == 3 * sizeof(double));

template <typename T>
constexpr const char* type_name() {
  return std::is_same_v<T, float> ? "float" : "double";
}

// Decimal text to T (float or double), rounded once.  Values beyond T's range are errors; values too small
// for T underflow to a denormal or zero, as IEEE rounding says.
template <typename T>
NumStatus parse_number(std::string_view token, T& out) {
  const char* first = token.data();
  const char* last = token.data() + token.size();
  // from_chars rejects a leading '+', which other writers do emit.
  if (first != last && *first == '+' && last - first > 1 && first[1] != '-' && first[1] != '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, out);
  if (ptr != last || (ec != std::errc() && ec != std::errc::result_out_of_range)) return NumStatus::kBad;
  if (ec == std::errc::result_out_of_range) {
    // Overflow or underflow: strtof/strtod tell them apart and round an underflow correctly.
    const std::string copy(first, last);
    errno = 0;
    T value;
    if constexpr (std::is_same_v<T, float>) {
      value = std::strtof(copy.c_str(), nullptr);
    } else {
      value = std::strtod(copy.c_str(), nullptr);
    }
    if (std::isinf(value)) return NumStatus::kTooBig;
    out = value;
    return NumStatus::kOk;
  }
  if (std::isnan(out)) return NumStatus::kNaN;
  if (std::isinf(out)) return NumStatus::kInf;
  return NumStatus::kOk;
}

const char* axis_name(int axis) {
  return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

std::string number_error(NumStatus status, int axis, std::string_view token, const char* type) {
  const std::string what = std::string(axis_name(axis)) + " coordinate " + quote(token);
  switch (status) {
    case NumStatus::kNaN:
      return "NaN " + what;
    case NumStatus::kInf:
      return "infinite " + what;
    case NumStatus::kTooBig:
      return what + " is beyond " + type + " range";
    default:
      return "invalid " + what;
  }
}

// Parses three coordinate tokens of a text line into a point, or throws naming the line.
template <typename P>
P parse_xyz_tokens(const std::string_view* tokens, const std::string& name, std::uint64_t line) {
  using T = Scalar<P>;
  T v[3];
  for (int axis = 0; axis < 3; ++axis) {
    const NumStatus status = parse_number(tokens[axis], v[axis]);
    if (status != NumStatus::kOk) {
      fail_line(name, line, number_error(status, axis, tokens[axis], type_name<T>()));
    }
  }
  return {v[0], v[1], v[2]};
}

bool parse_count(std::string_view token, std::uint64_t& out) {
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && ptr == token.data() + token.size();
}

// Calls the progress callback every kProgressEvery points, never per point.
class Progress {
 public:
  explicit Progress(const ProgressFn& fn) : fn_(fn) {}
  bool enabled() const { return static_cast<bool>(fn_); }
  bool due(std::uint64_t points) const { return fn_ && points % kProgressEvery == 0; }
  void report(double fraction) const {
    if (fn_) fn_(std::clamp(fraction, 0.0, 1.0));
  }

 private:
  const ProgressFn& fn_;
};

// A buffered reader over an istream that hands out lines (as views into its buffer) and raw bytes, so one
// PLY file can be read as header lines and then binary data.
class Source {
 public:
  Source(std::istream& in, const std::string& name) : in_(in), name_(name), buffer_(std::size_t{1} << 20) {
    // The size left in the stream, where it can be seeked, bounds the counts a header may claim.
    const std::istream::pos_type start = in_.tellg();
    if (start != std::istream::pos_type(-1) && in_.seekg(0, std::ios::end)) {
      const std::istream::pos_type end = in_.tellg();
      if (end != std::istream::pos_type(-1) && end >= start) size_ = static_cast<std::uint64_t>(end - start);
    }
    in_.clear();
    in_.seekg(start);
    in_.clear();
  }

  // Bytes the stream held when the reading began, if it can tell.
  std::optional<std::uint64_t> size() const { return size_; }
  std::uint64_t consumed() const { return consumed_; }
  std::optional<std::uint64_t> remaining() const {
    if (!size_) return std::nullopt;
    return *size_ >= consumed_ ? *size_ - consumed_ : 0;
  }
  std::uint64_t line_number() const { return line_; }
  double fraction() const { return size_ && *size_ > 0 ? double(consumed_) / double(*size_) : 0.0; }

  // The next line without its end-of-line characters; false at the end of the data.
  bool next_line(std::string_view& line) {
    while (true) {
      const char* begin = buffer_.data() + pos_;
      const void* nl = std::memchr(begin, '\n', end_ - pos_);
      if (nl != nullptr) {
        const std::size_t len = static_cast<const char*>(nl) - begin;
        line = trim_cr(std::string_view(begin, len));
        pos_ += len + 1;
        consumed_ += len + 1;
        ++line_;
        return true;
      }
      if (eof_) {
        if (pos_ == end_) return false;
        line = trim_cr(std::string_view(begin, end_ - pos_));
        consumed_ += end_ - pos_;
        pos_ = end_;
        ++line_;
        return true;
      }
      if (end_ - pos_ >= kMaxLineBytes) fail_line(name_, line_ + 1, "line longer than 16 MiB (binary data?)");
      compact_and_fill();
    }
  }

  // Reads up to n bytes; returns how many were read (fewer only at the end of the data).
  std::size_t read_bytes(char* dst, std::size_t n) {
    std::size_t done = std::min(n, end_ - pos_);
    std::memcpy(dst, buffer_.data() + pos_, done);
    pos_ += done;
    while (done < n && !eof_) {
      const std::size_t want = n - done;
      if (want >= buffer_.size() / 2) {
        // Big requests bypass the buffer: one large read per chunk is what keeps this at disk speed.
        done += raw_read(dst + done, want);
      } else {
        compact_and_fill();
        const std::size_t take = std::min(want, end_ - pos_);
        std::memcpy(dst + done, buffer_.data() + pos_, take);
        pos_ += take;
        done += take;
      }
    }
    consumed_ += done;
    return done;
  }

  // Skips n bytes; returns how many were skipped.
  std::uint64_t skip_bytes(std::uint64_t n) {
    std::uint64_t done = 0;
    while (true) {
      const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(n - done, end_ - pos_));
      pos_ += take;
      done += take;
      if (done == n || eof_) break;
      pos_ = 0;
      end_ = raw_read(buffer_.data(), buffer_.size());
    }
    consumed_ += done;
    return done;
  }

 private:
  static std::string_view trim_cr(std::string_view s) {
    return !s.empty() && s.back() == '\r' ? s.substr(0, s.size() - 1) : s;
  }

  std::size_t raw_read(char* dst, std::size_t n) {
    std::size_t done = 0;
    while (done < n && !eof_) {
      in_.read(dst + done, static_cast<std::streamsize>(n - done));
      const std::size_t got = static_cast<std::size_t>(in_.gcount());
      if (in_.bad()) fail(name_, "read error");
      done += got;
      if (got == 0 || in_.eof()) eof_ = true;
    }
    return done;
  }

  void compact_and_fill() {
    if (pos_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
      end_ -= pos_;
      pos_ = 0;
    }
    if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);
    end_ += raw_read(buffer_.data() + end_, buffer_.size() - end_);
  }

  std::istream& in_;
  const std::string& name_;
  std::vector<char> buffer_;
  std::size_t pos_ = 0, end_ = 0;
  bool eof_ = false;
  std::uint64_t consumed_ = 0;
  std::uint64_t line_ = 0;
  std::optional<std::uint64_t> size_;
};

template <typename P>
void check_not_too_many(const std::vector<P>& points, const std::string& name, std::uint64_t line) {
  if (points.size() >= kMaxPoints) fail_line(name, line, "more than 4294967295 points");
}

template <typename P>
void finish(std::vector<P>& points, const Source& src, const std::string& name, const char* what,
            const Progress& progress) {
  if (points.empty()) fail(name, src.consumed() == 0 ? "empty file" : what);
  progress.report(1.0);
}

// ---------------------------------------------------------------------------------------------- XYZ

// One point per line, "x y z".  Columns after the third (normals, colours, intensities) are allowed and
// ignored without being parsed, since xyz files from scanners commonly carry them.  '#' starts a comment
// anywhere on a line; blank lines are skipped.
template <typename P>
std::vector<P> read_xyz(Source& src, const std::string& name, const Progress& progress) {
  std::vector<P> points;
  std::string_view line;
  std::string_view tokens[3];
  while (src.next_line(line)) {
    const std::size_t n = tokenize(strip_comment(line), tokens, 3);
    if (n == 0) continue;
    if (n < 3) fail_line(name, src.line_number(), "expected 3 coordinates, found " + std::to_string(n));
    check_not_too_many(points, name, src.line_number());
    points.push_back(parse_xyz_tokens<P>(tokens, name, src.line_number()));
    if (progress.due(points.size())) progress.report(src.fraction());
  }
  finish(points, src, name, "no points", progress);
  return points;
}

// ---------------------------------------------------------------------------------------------- OBJ

// `v x y z [w]` and `v x y z r g b` lines; everything else (faces, normals, groups, unknown keywords) is
// ignored, as OBJ readers do.
template <typename P>
std::vector<P> read_obj(Source& src, const std::string& name, const Progress& progress) {
  std::vector<P> points;
  std::string_view line;
  std::string_view tokens[4];
  while (src.next_line(line)) {
    std::size_t i = 0;
    while (i < line.size() && is_space(line[i]))
      ++i;
    if (i == line.size() || line[i] != 'v' || (i + 1 < line.size() && !is_space(line[i + 1]))) continue;
    const std::size_t n = tokenize(strip_comment(line.substr(i + 1)), tokens, 3);
    if (n < 3) {
      fail_line(name, src.line_number(), "vertex needs 3 coordinates, found " + std::to_string(n));
    }
    check_not_too_many(points, name, src.line_number());
    points.push_back(parse_xyz_tokens<P>(tokens, name, src.line_number()));
    if (progress.due(points.size())) progress.report(src.fraction());
  }
  finish(points, src, name, "no vertices", progress);
  return points;
}

// ---------------------------------------------------------------------------------------------- OFF

void check_count_limit(std::uint64_t count, const std::string& name, std::uint64_t line) {
  if (count > kMaxPoints) {
    fail_line(name, line, "vertex count " + std::to_string(count) + " exceeds the limit of 4294967295");
  }
}

// What to reserve for a text file whose header claims `count` vertices of at least `min_bytes` each: never
// more than the data left can hold, so that a header claiming 10^15 vertices reserves nothing absurd (the
// reading then stops at the end of the file with a clear message).  Without a known size, grow instead.
std::size_t text_reserve(std::uint64_t count, std::uint64_t min_bytes, const Source& src) {
  const auto left = src.remaining();
  const std::uint64_t cap = left ? *left / min_bytes + 1 : std::uint64_t{1} << 20;
  return static_cast<std::size_t>(std::min(count, cap));
}

// Returns the next line that is not blank after removing '#' comments, or false at the end.
bool next_content_line(Source& src, std::string_view& line) {
  while (src.next_line(line)) {
    line = strip_comment(line);
    if (!is_blank(line)) return true;
  }
  return false;
}

// "OFF" with the optional prefixes ST, C, N (texture, colour, normal); the 4D and nD variants are not 3D.
bool is_off_keyword(std::string_view word) {
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") return false;
  std::string_view prefix = word.substr(0, word.size() - 3);
  for (std::string_view p : {"ST", "C", "N"}) {
    if (prefix.substr(0, p.size()) == p) prefix.remove_prefix(p.size());
  }
  return prefix.empty();
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

// ---------------------------------------------------------------------------------------------- PLY

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

std::optional<PlyType> ply_type(std::string_view s) {
  if (s == "char" || s == "int8") return PlyType::kInt8;
  if (s == "uchar" || s == "uint8") return PlyType::kUint8;
  if (s == "short" || s == "int16") return PlyType::kInt16;
  if (s == "ushort" || s == "uint16") return PlyType::kUint16;
  if (s == "int" || s == "int32") return PlyType::kInt32;
  if (s == "uint" || s == "uint32") return PlyType::kUint32;
  if (s == "float" || s == "float32") return PlyType::kFloat32;
  if (s == "double" || s == "float64") return PlyType::kFloat64;
  return std::nullopt;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;  // lists only
  std::size_t offset = 0;                // in the fixed-size record; elements without lists only
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t line = 0;  // header line, for messages
  std::vector<PlyProperty> properties;
  bool has_list = false;
  std::size_t stride = 0;  // record size when there is no list
};

enum class PlyFormat { kAscii, kBinaryLE, kBinaryBE };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
};

PlyHeader read_ply_header(Source& src, const std::string& name) {
  std::string_view line;
  if (!src.next_line(line)) fail(name, "empty file");
  std::string_view t[6];
  if (tokenize(line, t, 6) != 1 || t[0] != "ply") {
    fail_line(name, 1, "not a PLY file (the first line must be 'ply')");
  }
  PlyHeader header;
  bool have_format = false;
  while (true) {
    if (!src.next_line(line)) fail_line(name, src.line_number(), "unexpected end of file in the header");
    const std::uint64_t ln = src.line_number();
    const std::size_t n = tokenize(line, t, 6);
    if (n == 0) continue;
    if (t[0] == "end_header") break;
    if (t[0] == "format") {
      if (n < 2) fail_line(name, ln, "format line without a format");
      if (t[1] == "ascii") {
        header.format = PlyFormat::kAscii;
      } else if (t[1] == "binary_little_endian") {
        header.format = PlyFormat::kBinaryLE;
      } else if (t[1] == "binary_big_endian") {
        header.format = PlyFormat::kBinaryBE;
      } else {
        fail_line(name, ln, "unknown PLY format " + quote(t[1]));
      }
      have_format = true;
    } else if (t[0] == "element") {
      PlyElement e;
      if (n != 3 || !parse_count(t[2], e.count)) fail_line(name, ln, "expected 'element NAME COUNT'");
      e.name = t[1];
      e.line = ln;
      header.elements.push_back(std::move(e));
    } else if (t[0] == "property") {
      if (header.elements.empty()) fail_line(name, ln, "property before any element");
      PlyProperty p;
      if (n >= 2 && t[1] == "list") {
        const auto ct = n == 5 ? ply_type(t[2]) : std::nullopt;
        const auto it = n == 5 ? ply_type(t[3]) : std::nullopt;
        if (!ct || !it) fail_line(name, ln, "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
        if (*ct == PlyType::kFloat32 || *ct == PlyType::kFloat64) {
          fail_line(name, ln, "a list count must have an integer type");
        }
        p.is_list = true;
        p.count_type = *ct;
        p.type = *it;
        p.name = t[4];
      } else {
        const auto ty = n == 3 ? ply_type(t[1]) : std::nullopt;
        if (!ty) fail_line(name, ln, "expected 'property TYPE NAME' with a known type");
        p.type = *ty;
        p.name = t[2];
      }
      header.elements.back().properties.push_back(std::move(p));
    }
    // Anything else ("comment", "obj_info", the "bye" lines of raw Stanford range scans) carries nothing
    // the points need and is skipped.
  }
  if (!have_format) fail_line(name, src.line_number(), "PLY header without a format line");
  for (PlyElement& e : header.elements) {
    for (PlyProperty& p : e.properties) {
      p.offset = e.stride;
      e.stride += type_size(p.type);
      e.has_list = e.has_list || p.is_list;
    }
  }
  return header;
}

template <typename T>
T load(const char* p, bool swap) {
  using U = std::conditional_t<
      sizeof(T) == 1, std::uint8_t,
      std::conditional_t<sizeof(T) == 2, std::uint16_t,
                         std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
  U u;
  std::memcpy(&u, p, sizeof(U));
  if (swap) {
    if constexpr (sizeof(U) == 2) u = __builtin_bswap16(u);
    if constexpr (sizeof(U) == 4) u = __builtin_bswap32(u);
    if constexpr (sizeof(U) == 8) u = __builtin_bswap64(u);
  }
  return std::bit_cast<T>(u);
}

// Reads one binary value as a double (exact for every PLY type).
double load_value(const char* p, PlyType t, bool swap) {
  switch (t) {
    case PlyType::kInt8:
      return load<std::int8_t>(p, swap);
    case PlyType::kUint8:
      return load<std::uint8_t>(p, swap);
    case PlyType::kInt16:
      return load<std::int16_t>(p, swap);
    case PlyType::kUint16:
      return load<std::uint16_t>(p, swap);
    case PlyType::kInt32:
      return load<std::int32_t>(p, swap);
    case PlyType::kUint32:
      return load<std::uint32_t>(p, swap);
    case PlyType::kFloat32:
      return load<float>(p, swap);
    case PlyType::kFloat64:
      return load<double>(p, swap);
  }
  return 0;
}

// Rounds a binary coordinate to float; "" when fine, else what is wrong with it.
const char* binary_coordinate_error(double v, float& out) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return "infinite";
  // Round-to-nearest sends |v| >= 2^128 - 2^103 to infinity.
  if (std::fabs(v) >= 0x1.ffffffp+127) return "beyond float range";
  out = static_cast<float>(v);
  return "";
}

// Keeps a binary coordinate as a double (every PLY type is exact in double); "" when fine.
const char* binary_coordinate_error(double v, double& out) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return "infinite";
  out = v;
  return "";
}

// The PLY type whose bytes are a T in host order.
template <typename T>
constexpr PlyType ply_type_of() {
  return std::is_same_v<T, float> ? PlyType::kFloat32 : PlyType::kFloat64;
}

[[noreturn]] void fail_binary_coordinate(const std::string& name, std::uint64_t index, int axis,
                                         const char* what) {
  const std::string coord = std::string(axis_name(axis)) + " coordinate";
  if (std::strcmp(what, "beyond float range") == 0)
    fail_vertex(name, index, coord + " is beyond float range");
  fail_vertex(name, index, std::string(what) + " " + coord);
}

struct XyzLayout {
  const PlyProperty* axis[3] = {nullptr, nullptr, nullptr};
};

XyzLayout find_xyz(const PlyElement& vertex, const std::string& name) {
  XyzLayout layout;
  for (const PlyProperty& p : vertex.properties) {
    for (int a = 0; a < 3; ++a) {
      if (p.name == axis_name(a) && layout.axis[a] == nullptr) layout.axis[a] = &p;
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (layout.axis[a] == nullptr) {
      fail_line(name, vertex.line, std::string("vertex element has no '") + axis_name(a) + "' property");
    }
    if (layout.axis[a]->is_list) {
      fail_line(name, vertex.line, std::string("vertex property '") + axis_name(a) + "' is a list");
    }
  }
  return layout;
}

// A list length read from binary data, checked so that garbage cannot ask for a huge skip.
std::uint64_t list_length(double v, const std::string& name, const std::string& element,
                          std::uint64_t index) {
  if (v < 0) fail(name, element + " " + std::to_string(index) + ": negative list length");
  return static_cast<std::uint64_t>(v);
}

// Reads one binary record of an element with list properties; fills `xyz` when `layout` is given.
// Returns false when the data ends inside the record.
bool read_binary_record(Source& src, const PlyElement& e, bool swap, const XyzLayout* layout, double* xyz,
                        const std::string& name, std::uint64_t index) {
  char value[8];
  for (const PlyProperty& p : e.properties) {
    if (p.is_list) {
      const std::size_t cs = type_size(p.count_type);
      if (src.read_bytes(value, cs) != cs) return false;
      const std::uint64_t len = list_length(load_value(value, p.count_type, swap), name, e.name, index);
      const std::uint64_t bytes = len * type_size(p.type);
      if (src.skip_bytes(bytes) != bytes) return false;
      continue;
    }
    const std::size_t s = type_size(p.type);
    if (src.read_bytes(value, s) != s) return false;
    if (layout != nullptr) {
      for (int a = 0; a < 3; ++a) {
        if (layout->axis[a] == &p) xyz[a] = load_value(value, p.type, swap);
      }
    }
  }
  return true;
}

void skip_binary_element(Source& src, const PlyElement& e, bool swap, const std::string& name) {
  if (!e.has_list) {
    const auto left = src.remaining();
    const bool fits = e.stride == 0 || (left ? e.count <= *left / e.stride : true);
    if (!fits || src.skip_bytes(e.count * e.stride) != e.count * e.stride) {
      fail(name, "element '" + e.name + "': truncated binary data");
    }
    return;
  }
  for (std::uint64_t i = 0; i < e.count; ++i) {
    if (!read_binary_record(src, e, swap, nullptr, nullptr, name, i)) {
      fail(name, "element '" + e.name + "' " + std::to_string(i) + ": truncated binary data");
    }
  }
}

void skip_ascii_element(Source& src, const PlyElement& e, const std::string& name) {
  std::string_view line;
  for (std::uint64_t i = 0; i < e.count; ++i) {
    if (!src.next_line(line)) {
      fail_line(name, src.line_number(), "unexpected end of file in element '" + e.name + "'");
    }
  }
}

[[noreturn]] void fail_truncated(const std::string& name, std::uint64_t index, std::uint64_t count) {
  fail_vertex(name, index, "truncated binary data (header says " + std::to_string(count) + " vertices)");
}

template <typename P>
std::vector<P> read_binary_vertices(Source& src, const PlyElement& v, bool swap, const std::string& name,
                                    const Progress& progress) {
  using T = Scalar<P>;
  const XyzLayout layout = find_xyz(v, name);
  // Each record holds at least its scalars and its list lengths.
  std::size_t min_record = 0;
  for (const PlyProperty& p : v.properties)
    min_record += type_size(p.is_list ? p.count_type : p.type);
  const auto left = src.remaining();
  if (left && v.count > *left / min_record) fail_truncated(name, *left / min_record, v.count);

  std::vector<P> points;
  if (v.has_list) {
    points.reserve(left ? static_cast<std::size_t>(v.count) : std::size_t{1} << 20);
    for (std::uint64_t i = 0; i < v.count; ++i) {
      double xyz[3] = {0, 0, 0};
      if (!read_binary_record(src, v, swap, &layout, xyz, name, i)) fail_truncated(name, i, v.count);
      P p;
      T* out[3] = {&p.x, &p.y, &p.z};
      for (int a = 0; a < 3; ++a) {
        const char* err = binary_coordinate_error(xyz[a], *out[a]);
        if (*err != '\0') fail_binary_coordinate(name, i, a, err);
      }
      points.push_back(p);
      if (progress.due(points.size())) progress.report(double(points.size()) / double(v.count));
    }
    return points;
  }

  const std::size_t stride = v.stride;
  constexpr PlyType kPlain = ply_type_of<T>();
  const bool plain = std::endian::native == std::endian::little && !swap && stride == sizeof(P) &&
                     layout.axis[0]->offset == 0 && layout.axis[1]->offset == sizeof(T) &&
                     layout.axis[2]->offset == 2 * sizeof(T) && layout.axis[0]->type == kPlain &&
                     layout.axis[1]->type == kPlain && layout.axis[2]->type == kPlain;
  const std::uint64_t per_chunk = std::max<std::uint64_t>(1, kChunkBytes / stride);
  if (left) {
    points.resize(static_cast<std::size_t>(v.count));
  } else {
    points.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(v.count, std::uint64_t{1} << 20)));
  }
  std::vector<char> chunk(plain ? 0 : static_cast<std::size_t>(per_chunk * stride));
  for (std::uint64_t first = 0; first < v.count; first += per_chunk) {
    const std::uint64_t n = std::min(per_chunk, v.count - first);
    if (!left) points.resize(static_cast<std::size_t>(first + n));
    P* dst = points.data() + first;
    if (plain) {
      // x y z of the point's type in host order: the file's bytes are already the points.
      const std::size_t got = src.read_bytes(reinterpret_cast<char*>(dst), n * stride);
      if (got != n * stride) fail_truncated(name, first + got / stride, v.count);
      for (std::uint64_t i = 0; i < n; ++i) {
        const T c[3] = {dst[i].x, dst[i].y, dst[i].z};
        for (int a = 0; a < 3; ++a) {
          if (!std::isfinite(c[a]))
            fail_binary_coordinate(name, first + i, a, std::isnan(c[a]) ? "NaN" : "infinite");
        }
      }
    } else {
      const std::size_t got = src.read_bytes(chunk.data(), n * stride);
      if (got != n * stride) fail_truncated(name, first + got / stride, v.count);
      for (std::uint64_t i = 0; i < n; ++i) {
        const char* rec = chunk.data() + i * stride;
        T* out[3] = {&dst[i].x, &dst[i].y, &dst[i].z};
        for (int a = 0; a < 3; ++a) {
          const double value = load_value(rec + layout.axis[a]->offset, layout.axis[a]->type, swap);
          const char* err = binary_coordinate_error(value, *out[a]);
          if (*err != '\0') fail_binary_coordinate(name, first + i, a, err);
        }
      }
    }
    if (progress.enabled()) progress.report(double(first + n) / double(v.count));
  }
  return points;
}

template <typename P>
std::vector<P> read_ascii_vertices(Source& src, const PlyElement& v, const std::string& name,
                                   const Progress& progress) {
  using T = Scalar<P>;
  const XyzLayout layout = find_xyz(v, name);
  std::vector<P> points;
  // Every value takes at least a digit and a separator.
  points.reserve(text_reserve(v.count, 2 * v.properties.size(), src));
  std::string_view line;
  while (points.size() < v.count) {
    if (!src.next_line(line)) {
      fail_line(name, src.line_number(),
                "unexpected end of file: header says " + std::to_string(v.count) + " vertices, found " +
                    std::to_string(points.size()));
    }
    if (is_blank(line)) continue;
    const std::uint64_t ln = src.line_number();
    std::size_t pos = 0;
    std::size_t found = 0;
    // Returns the next token of the line, or fails naming how many values the header asked for.
    auto next_token = [&]() {
      while (pos < line.size() && is_space(line[pos]))
        ++pos;
      if (pos == line.size()) {
        fail_line(name, ln,
                  "too few values for vertex " + std::to_string(points.size()) + " (found " +
                      std::to_string(found) + ")");
      }
      const std::size_t start = pos;
      while (pos < line.size() && !is_space(line[pos]))
        ++pos;
      ++found;
      return line.substr(start, pos - start);
    };
    T xyz[3] = {0, 0, 0};
    for (const PlyProperty& p : v.properties) {
      if (p.is_list) {
        const std::string_view tok = next_token();
        std::uint64_t len = 0;
        if (!parse_count(tok, len)) fail_line(name, ln, "invalid list length " + quote(tok));
        for (std::uint64_t k = 0; k < len; ++k)
          next_token();
        continue;
      }
      const std::string_view tok = next_token();
      for (int a = 0; a < 3; ++a) {
        if (layout.axis[a] != &p) continue;
        const NumStatus status = parse_number(tok, xyz[a]);
        if (status != NumStatus::kOk) fail_line(name, ln, number_error(status, a, tok, type_name<T>()));
      }
    }
    // Extra values mean the header does not describe the data (e.g. face lines read as vertices).
    if (!is_blank(line.substr(pos))) {
      fail_line(name, ln, "more values than the header's vertex properties (" + std::to_string(found) + ")");
    }
    points.push_back({xyz[0], xyz[1], xyz[2]});
    if (progress.due(points.size())) progress.report(double(points.size()) / double(v.count));
  }
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

[[noreturn]] void fail_no_vertex_element(const std::string& name) {
  fail(name, "no 'vertex' element in the PLY header");
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

// Opens a point file for reading, or throws naming it.
void open_file(const std::string& path, std::ifstream& in) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory");
  in.open(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// ---------------------------------------------------------------------------------------------- faces

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
