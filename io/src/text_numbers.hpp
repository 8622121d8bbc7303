// Text lines to tokens and tokens to numbers: whitespace splitting, '#' comments, correctly rounded
// coordinates of the point's own type, counts.  Internal to io/.
#pragma once

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

#include "cudahull/point_io.hpp"
#include "read_failures.hpp"

namespace cudahull::reading {

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

}  // namespace cudahull::reading
