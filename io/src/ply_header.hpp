// The PLY header: its types (one table of their C++ types), elements and properties, the header reader,
// and where a vertex element keeps x, y and z.  Internal to io/.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "line_source.hpp"
#include "read_failures.hpp"
#include "text_numbers.hpp"

namespace cudahull::reading {

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

[[noreturn]] inline void fail_no_vertex_element(const std::string& name) {
  fail(name, "no 'vertex' element in the PLY header");
}

}  // namespace cudahull::reading
