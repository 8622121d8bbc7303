// The readers' errors: every failure is an InputError naming the file, and the line or vertex where it
// can; tokens quoted for messages; the 32-bit limit on the point count.  Internal to io/.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"

namespace cudahull::reading {

inline constexpr std::uint64_t kMaxPoints = std::numeric_limits<PointIndex>::max();  // indices are 32-bit

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

template <typename P>
void check_not_too_many(const std::vector<P>& points, const std::string& name, std::uint64_t line) {
  if (points.size() >= kMaxPoints) fail_line(name, line, "more than 4294967295 points");
}

}  // namespace cudahull::reading
