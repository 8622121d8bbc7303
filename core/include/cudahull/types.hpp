// Basic value types shared by every part of cudahull.
//
// Points are Point3 (float) or Point3d (double), as the input's precision or --precision picks (README,
// "Precision"); every exact decision is exact on the coordinates as given.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace cudahull {

struct Point3 {
  float x = 0, y = 0, z = 0;
  // Written out (not "= default") so that CUDA sources, compiled as C++17, can include this header.
  friend bool operator==(const Point3& a, const Point3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
  friend bool operator!=(const Point3& a, const Point3& b) { return !(a == b); }
};

// A point in double precision, as read_points_double (io) returns it: text coordinates to the nearest double,
// binary float, double and integer values exactly.
struct Point3d {
  double x = 0, y = 0, z = 0;
  friend bool operator==(const Point3d& a, const Point3d& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
  }
  friend bool operator!=(const Point3d& a, const Point3d& b) { return !(a == b); }
};

// The coordinate type a computation runs in.  kAuto picks, per input file, the narrowest type that holds
// every coordinate as the file gives it: kFloat for binary PLY whose x, y, z are float (or 8- or 16-bit
// integers), kDouble for text formats and for binary PLY whose x, y, z include a double or a 32-bit integer.
enum class Precision { kAuto, kFloat, kDouble };

// The precision of a point type or of its coordinates: kFloat for Point3 and float, kDouble for Point3d and
// double.
template <class PointOrScalar>
constexpr Precision precision_of() {
  static_assert(std::is_same_v<PointOrScalar, Point3> || std::is_same_v<PointOrScalar, Point3d> ||
                    std::is_same_v<PointOrScalar, float> || std::is_same_v<PointOrScalar, double>,
                "precision_of: Point3, Point3d, float or double");
  return std::is_same_v<PointOrScalar, Point3d> || std::is_same_v<PointOrScalar, double> ? Precision::kDouble
                                                                                         : Precision::kFloat;
}

// "auto", "float" or "double".
inline const char* precision_name(Precision p) {
  switch (p) {
    case Precision::kFloat:
      return "float";
    case Precision::kDouble:
      return "double";
    default:
      return "auto";
  }
}

// The inverse of precision_name(): "float" or "double", anything else (the command lines validate it) auto.
inline Precision precision_from_name(const std::string& name) {
  if (name == "float") return Precision::kFloat;
  if (name == "double") return Precision::kDouble;
  return Precision::kAuto;
}

using PointIndex = std::uint32_t;
using Triangle = std::array<std::uint32_t, 3>;

// A convex hull as it leaves the engine: vertices are input points (by input index), faces are outward,
// counter-clockwise triangles seen from outside.  For a lower-dimensional input, `dimension` is 0, 1 or 2:
// dimension 0 has one vertex, 1 has the two segment ends, 2 has the polygon's corners in counter-clockwise
// order (seen from the side the polygon's normal points to) in `polygon` and no triangles.
// `Point` is the input's point type, Point3 or Point3d: the vertices keep the input's coordinates exactly.
template <class Point>
struct BasicHullMesh {
  int dimension = 3;
  std::vector<PointIndex> vertex_ids;  // input indices, one per hull vertex
  std::vector<Point> vertices;         // coordinates of vertex_ids, same order
  std::vector<Triangle> triangles;     // indices into `vertices`
  std::vector<std::uint32_t> polygon;  // dimension 2 only: indices into `vertices`, in order
};
using HullMesh = BasicHullMesh<Point3>;
using HullMeshd = BasicHullMesh<Point3d>;

}  // namespace cudahull
