#include "input_surface.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cudahull/errors.hpp"

namespace cudahull::viewer {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// A polygon as a fan of triangles, kept where every corner is a loaded point.
void add_polygon(const std::vector<std::int64_t>& corners, std::size_t point_count,
                 std::vector<InputTriangle>& out) {
  for (std::int64_t c : corners) {
    if (c < 0 || static_cast<std::uint64_t>(c) >= point_count) return;
  }
  for (std::size_t k = 1; k + 1 < corners.size(); ++k)
    out.push_back({static_cast<std::uint32_t>(corners[0]), static_cast<std::uint32_t>(corners[k]),
                   static_cast<std::uint32_t>(corners[k + 1])});
}

std::vector<InputTriangle> read_obj_faces(const std::string& path, std::size_t point_count) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // fans here, the same for OBJ and PLY
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) throw InputError(path + ": faces: " + reader.Error());
  std::vector<InputTriangle> out;
  std::vector<std::int64_t> corners;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t at = 0;
    for (const unsigned char n : shape.mesh.num_face_vertices) {
      corners.clear();
      for (unsigned k = 0; k < n; ++k)
        corners.push_back(shape.mesh.indices[at + k].vertex_index);
      at += n;
      add_polygon(corners, point_count, out);
    }
  }
  return out;
}

// PLY (ascii, binary_little_endian, binary_big_endian): the elements before "face" are skipped, then each
// face's vertex_indices (or vertex_index) list is read.
struct PlyProperty {
  std::string name, type, count_type;  // count_type: a list's length type, else empty
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

int type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

double read_binary(std::istream& in, const std::string& type, bool big_endian, const std::string& path) {
  unsigned char b[8] = {};
  const int size = type_size(type);
  if (size == 0 || !in.read(reinterpret_cast<char*>(b), size)) throw InputError(path + ": faces: truncated");
  if (big_endian) std::reverse(b, b + size);
  auto as = [&](auto v) {
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  };
  if (type == "char" || type == "int8") return as(std::int8_t{});
  if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
  if (type == "short" || type == "int16") return as(std::int16_t{});
  if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
  if (type == "int" || type == "int32") return as(std::int32_t{});
  if (type == "uint" || type == "uint32") return as(std::uint32_t{});
  if (type == "float" || type == "float32") return as(float{});
  return as(double{});
}

std::vector<InputTriangle> read_ply_faces(const std::string& path, std::size_t point_count) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": faces: cannot open");
  std::string line, format;
  std::vector<PlyElement> elements;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      words >> format;
    } else if (word == "element") {
      PlyElement e;
      words >> e.name >> e.count;
      elements.push_back(e);
    } else if (word == "property" && !elements.empty()) {
      PlyProperty p;
      words >> p.type;
      if (p.type == "list") words >> p.count_type >> p.type;
      words >> p.name;
      elements.back().properties.push_back(p);
    } else if (word == "end_header") {
      break;
    }
  }
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  if (!ascii && !big && format != "binary_little_endian")
    throw InputError(path + ": faces: unknown PLY format");
  std::vector<InputTriangle> out;
  std::vector<std::int64_t> corners;
  for (const PlyElement& e : elements) {
    const bool faces = e.name == "face";
    for (std::uint64_t i = 0; i < e.count; ++i) {
      std::istringstream words;
      if (ascii) {
        if (!std::getline(in, line)) throw InputError(path + ": faces: truncated");
        words.str(line);
      }
      auto value = [&](const std::string& type) {
        if (!ascii) return read_binary(in, type, big, path);
        double v = 0;
        if (!(words >> v)) throw InputError(path + ": faces: a short line in element '" + e.name + "'");
        return v;
      };
      for (const PlyProperty& p : e.properties) {
        const bool indices = faces && (p.name == "vertex_indices" || p.name == "vertex_index");
        if (p.count_type.empty()) {
          value(p.type);
          continue;
        }
        const auto n = static_cast<std::int64_t>(value(p.count_type));
        if (n < 0 || n > 1 << 20) throw InputError(path + ": faces: a bad list length");
        corners.clear();
        for (std::int64_t k = 0; k < n; ++k)
          corners.push_back(static_cast<std::int64_t>(value(p.type)));
        if (indices) add_polygon(corners, point_count, out);
      }
    }
    if (faces) break;
  }
  return out;
}

}  // namespace

std::vector<InputTriangle> read_input_surface(const std::string& path, std::size_t point_count) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return read_obj_faces(path, point_count);
  if (ext == ".ply") return read_ply_faces(path, point_count);
  return {};
}

}  // namespace cudahull::viewer
