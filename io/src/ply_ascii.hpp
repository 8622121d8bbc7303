// ASCII PLY data: elements skipped a line a record, and the vertices read from theirs.  Internal to io/.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "line_source.hpp"
#include "off_text.hpp"
#include "ply_header.hpp"
#include "read_failures.hpp"
#include "text_numbers.hpp"

namespace cudahull::reading {

inline void skip_ascii_element(Source& src, const PlyElement& e, const std::string& name) {
  std::string_view line;
  for (std::uint64_t i = 0; i < e.count; ++i) {
    if (!src.next_line(line)) {
      fail_line(name, src.line_number(), "unexpected end of file in element '" + e.name + "'");
    }
  }
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

}  // namespace cudahull::reading
