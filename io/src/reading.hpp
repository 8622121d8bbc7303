// The point and face readers' shared parts (point_io.cpp, face_io.cpp): the line and byte source, tokens,
// correctly rounded numbers, progress, and the PLY header with its vertex records.  Internal to io/.
#pragma once

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
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull::reading {

inline constexpr std::uint64_t kMaxPoints = std::numeric_limits<PointIndex>::max();  // indices are 32-bit
inline constexpr std::size_t kChunkBytes = std::size_t{8} << 20;         // binary read granularity
inline constexpr std::size_t kMaxLineBytes = std::size_t{16} << 20;      // a longer "line" is binary garbage
inline constexpr std::uint64_t kProgressEvery = std::uint64_t{1} << 16;  // points between callbacks

[[noreturn]] inline void fail(const std::string& name, const std::string& what) {
  throw InputError(name + ": " + what);
}
[[noreturn]] inline void fail_line(const std::string& name, std::uint64_t line, const std::string& what) {
  throw InputError(name + ":" + std::to_string(line) + ": " + what);
}
[[noreturn]] inline void fail_vertex(const std::string& name, std::uint64_t index, const std::string& what) {
  throw InputError(name + ": vertex " + std::to_string(index) + ": " + what);
}

// Quotes a token for an error message: bounded, and printable, so the message stays one line.
inline std::string quote(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMax) out += "...";
  return out + "'";
}

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Splits a line at whitespace into at most `max` tokens; returns how many were found (the count may exceed
// `max`, the extra ones are only counted).
inline std::size_t tokenize(std::string_view line, std::string_view* tokens, std::size_t max) {
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

inline std::string_view strip_comment(std::string_view line) {
  const std::size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

inline bool is_blank(std::string_view line) {
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

inline const char* axis_name(int axis) {
  return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

inline std::string number_error(NumStatus status, int axis, std::string_view token, const char* type) {
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

inline bool parse_count(std::string_view token, std::uint64_t& out) {
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

// ---------------------------------------------------------------------------------------------- OFF

inline void check_count_limit(std::uint64_t count, const std::string& name, std::uint64_t line) {
  if (count > kMaxPoints) {
    fail_line(name, line, "vertex count " + std::to_string(count) + " exceeds the limit of 4294967295");
  }
}

// What to reserve for a text file whose header claims `count` vertices of at least `min_bytes` each: never
// more than the data left can hold, so that a header claiming 10^15 vertices reserves nothing absurd (the
// reading then stops at the end of the file with a clear message).  Without a known size, grow instead.
inline std::size_t text_reserve(std::uint64_t count, std::uint64_t min_bytes, const Source& src) {
  const auto left = src.remaining();
  const std::uint64_t cap = left ? *left / min_bytes + 1 : std::uint64_t{1} << 20;
  return static_cast<std::size_t>(std::min(count, cap));
}

// Returns the next line that is not blank after removing '#' comments, or false at the end.
inline bool next_content_line(Source& src, std::string_view& line) {
  while (src.next_line(line)) {
    line = strip_comment(line);
    if (!is_blank(line)) return true;
  }
  return false;
}

// "OFF" with the optional prefixes ST, C, N (texture, colour, normal); the 4D and nD variants are not 3D.
inline bool is_off_keyword(std::string_view word) {
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") return false;
  std::string_view prefix = word.substr(0, word.size() - 3);
  for (std::string_view p : {"ST", "C", "N"}) {
    if (prefix.substr(0, p.size()) == p) prefix.remove_prefix(p.size());
  }
  return prefix.empty();
}

// ---------------------------------------------------------------------------------------------- PLY

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

inline std::optional<PlyType> ply_type(std::string_view s) {
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

// Each PlyType's C++ type, in the enum's order: the one table of them (type_size, load_value).
using PlyCppTypes = std::tuple<std::int8_t, std::uint8_t, std::int16_t, std::uint16_t, std::int32_t,
                               std::uint32_t, float, double>;

// f(T{}) for t's C++ type T, as an R (R{} for a value outside the enum).  Compiles to a switch.
template <class R, class F, std::size_t... I>
R visit_ply_type(PlyType t, const F& f, std::index_sequence<I...>) {
  R r{};
  const std::size_t k = static_cast<std::size_t>(t);
  (void)((k == I && (r = f(std::tuple_element_t<I, PlyCppTypes>{}), true)) || ...);
  return r;
}
template <class R, class F>
R visit_ply_type(PlyType t, const F& f) {
  return visit_ply_type<R>(t, f, std::make_index_sequence<std::tuple_size_v<PlyCppTypes>>{});
}

inline std::size_t type_size(PlyType t) {
  return visit_ply_type<std::size_t>(t, [](auto v) { return sizeof(v); });
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

inline PlyHeader read_ply_header(Source& src, const std::string& name) {
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
inline double load_value(const char* p, PlyType t, bool swap) {
  return visit_ply_type<double>(t, [&](auto v) { return static_cast<double>(load<decltype(v)>(p, swap)); });
}

// Rounds a binary coordinate to float; "" when fine, else what is wrong with it.
inline const char* binary_coordinate_error(double v, float& out) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return "infinite";
  // Round-to-nearest sends |v| >= 2^128 - 2^103 to infinity.
  if (std::fabs(v) >= 0x1.ffffffp+127) return "beyond float range";
  out = static_cast<float>(v);
  return "";
}

// Keeps a binary coordinate as a double (every PLY type is exact in double); "" when fine.
inline const char* binary_coordinate_error(double v, double& out) {
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

[[noreturn]] inline void fail_binary_coordinate(const std::string& name, std::uint64_t index, int axis,
                                                const char* what) {
  const std::string coord = std::string(axis_name(axis)) + " coordinate";
  if (std::strcmp(what, "beyond float range") == 0)
    fail_vertex(name, index, coord + " is beyond float range");
  fail_vertex(name, index, std::string(what) + " " + coord);
}

struct XyzLayout {
  const PlyProperty* axis[3] = {nullptr, nullptr, nullptr};
};

inline XyzLayout find_xyz(const PlyElement& vertex, const std::string& name) {
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
inline std::uint64_t list_length(double v, const std::string& name, const std::string& element,
                                 std::uint64_t index) {
  if (v < 0) fail(name, element + " " + std::to_string(index) + ": negative list length");
  return static_cast<std::uint64_t>(v);
}

// Reads one binary record of an element with list properties; fills `xyz` when `layout` is given.
// Returns false when the data ends inside the record.
inline bool read_binary_record(Source& src, const PlyElement& e, bool swap, const XyzLayout* layout,
                               double* xyz, const std::string& name, std::uint64_t index) {
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

inline void skip_binary_element(Source& src, const PlyElement& e, bool swap, const std::string& name) {
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

inline void skip_ascii_element(Source& src, const PlyElement& e, const std::string& name) {
  std::string_view line;
  for (std::uint64_t i = 0; i < e.count; ++i) {
    if (!src.next_line(line)) {
      fail_line(name, src.line_number(), "unexpected end of file in element '" + e.name + "'");
    }
  }
}

[[noreturn]] inline void fail_truncated(const std::string& name, std::uint64_t index, std::uint64_t count) {
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

[[noreturn]] inline void fail_no_vertex_element(const std::string& name) {
  fail(name, "no 'vertex' element in the PLY header");
}

// Opens a point file for reading, or throws naming it.
inline void open_file(const std::string& path, std::ifstream& in) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory");
  in.open(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
}

inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace cudahull::reading
