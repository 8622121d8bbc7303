// A PLY writer for the reader tests: any property types and byte order, lists inside the vertex, elements
// before and after it; and a binary header alone.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace cudahull {
namespace {

enum class Enc { kAscii, kLittle, kBig };

struct Column {
  std::string type;  // PLY type name
  std::string name;
  bool list = false;  // "property list uchar <type> <name>"
};

// The short PLY name of a type ("int16" -> "short").
std::string canonical_type(const std::string& t) {
  static const char* const kPairs[][2] = {{"int8", "char"},     {"uint8", "uchar"},   {"int16", "short"},
                                          {"uint16", "ushort"}, {"int32", "int"},     {"uint32", "uint"},
                                          {"float32", "float"}, {"float64", "double"}};
  for (const auto& p : kPairs) {
    if (t == p[0]) return p[1];
  }
  return t;
}

std::size_t ply_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;
}

// Appends `v`, cast to PLY type `t`, in the given byte order.
void put_binary(std::string& out, const std::string& t, double v, Enc enc) {
  unsigned char b[8];
  std::uint64_t bits = 0;
  const std::size_t n = ply_size(t);
  if (t == "char" || t == "int8") bits = static_cast<std::uint8_t>(static_cast<std::int8_t>(v));
  if (t == "uchar" || t == "uint8") bits = static_cast<std::uint8_t>(v);
  if (t == "short" || t == "int16") bits = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
  if (t == "ushort" || t == "uint16") bits = static_cast<std::uint16_t>(v);
  if (t == "int" || t == "int32") bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(v));
  if (t == "uint" || t == "uint32") bits = static_cast<std::uint32_t>(v);
  if (t == "float" || t == "float32") bits = std::bit_cast<std::uint32_t>(static_cast<float>(v));
  if (t == "double" || t == "float64") bits = std::bit_cast<std::uint64_t>(v);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t shift = 8 * (enc == Enc::kBig ? n - 1 - i : i);
    b[i] = static_cast<unsigned char>(bits >> shift);
  }
  out.append(reinterpret_cast<const char*>(b), n);
}

void put_ascii(std::string& out, const std::string& type, double v) {
  const std::string t = canonical_type(type);
  char buf[40];
  const bool real = t == "float" || t == "float32" || t == "double" || t == "float64";
  std::snprintf(buf, sizeof buf, real ? "%.17g " : "%.0f ", v);
  out += buf;
}

// A PLY writer for the tests: `rows` holds one value per scalar column; a list column gets `i % 3` items.
// An optional element before the vertices and a face element after them exercise the skipping.
std::string make_ply(Enc enc, const std::vector<Column>& cols, const std::vector<std::vector<double>>& rows,
                     bool element_before, bool faces) {
  std::string h = "ply\nformat ";
  h += enc == Enc::kAscii ? "ascii" : enc == Enc::kLittle ? "binary_little_endian" : "binary_big_endian";
  h += " 1.0\ncomment test file\nobj_info from the test\n";
  if (element_before) h += "element camera 2\nproperty double a\nproperty list int short b\n";
  h += "element vertex " + std::to_string(rows.size()) + "\n";
  for (const Column& c : cols) {
    h += c.list ? "property list uchar " + c.type + " " + c.name + "\n"
                : "property " + c.type + " " + c.name + "\n";
  }
  if (faces) h += "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\n";
  h += "end_header\n";
  std::string body;
  const bool ascii = enc == Enc::kAscii;
  auto put = [&](const std::string& t, double v) {
    ascii ? put_ascii(body, t, v) : put_binary(body, t, v, enc);
  };
  if (element_before) {
    for (int i = 0; i < 2; ++i) {
      put("double", 0.5 + i);
      put("int", i + 1);
      for (int k = 0; k <= i; ++k)
        put("short", -k);
      if (ascii) body += "\n";
    }
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::size_t s = 0;
    for (const Column& c : cols) {
      if (c.list) {
        put("uchar", double(i % 3));
        for (std::size_t k = 0; k < i % 3; ++k)
          put(c.type, double(k + 1));
      } else {
        put(c.type, rows[i][s++]);
      }
    }
    if (ascii) body += "\n";
  }
  if (faces) {
    for (int f = 0; f < 2; ++f) {
      put("uchar", 3);
      for (int k = 0; k < 3; ++k)
        put("int", k);
      put("uchar", 1);
      if (ascii) body += "\n";
    }
  }
  return h + body;
}

std::string binary_header(const char* format, std::uint64_t count, const std::string& props) {
  return std::string("ply\nformat ") + format + " 1.0\nelement vertex " + std::to_string(count) + "\n" +
         props + "end_header\n";
}

const std::string kXyzFloat = "property float x\nproperty float y\nproperty float z\n";

}  // namespace
}  // namespace cudahull
