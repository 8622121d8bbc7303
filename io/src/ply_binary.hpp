// Binary PLY data: values of either byte order, coordinates checked and rounded once, records with
// lists, elements skipped, and the vertices read a chunk at a time.  Internal to io/.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "line_source.hpp"
#include "ply_header.hpp"
#include "read_failures.hpp"
#include "text_numbers.hpp"

namespace cudahull::reading {

inline constexpr std::size_t kChunkBytes = std::size_t{8} << 20;  // binary read granularity

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

}  // namespace cudahull::reading
