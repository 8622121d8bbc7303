// What the OFF readers (points and faces) share, and ASCII PLY with them: content lines without comments,
// the vertex count's limit, a reserve no larger than the file, the OFF keyword.  Internal to io/.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>

#include "line_source.hpp"
#include "read_failures.hpp"
#include "text_numbers.hpp"

namespace cudahull::reading {

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

}  // namespace cudahull::reading
