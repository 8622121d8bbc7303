#include "cudahull/point_writer.hpp"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <type_traits>

#include "cudahull/errors.hpp"
#include "cudahull/mesh_io.hpp"
#include "cudahull/point_io.hpp"

namespace cudahull {
namespace {

// The text and PLY spelling of a coordinate type: float as today (%.9g, `float`), double with 17 digits.
template <class Point>
struct Coordinate {
  using Scalar = decltype(Point{}.x);
  static constexpr bool kDouble = std::is_same_v<Scalar, double>;
  using Bits = std::conditional_t<kDouble, std::uint64_t, std::uint32_t>;
  static constexpr const char* kLine = kDouble ? "%s%.17g %.17g %.17g\n" : "%s%.9g %.9g %.9g\n";
  static constexpr const char* kPlyType = kDouble ? "double" : "float";
  static Bits swapped(Scalar v) {
    const Bits bits = std::bit_cast<Bits>(v);
    if constexpr (kDouble)
      return __builtin_bswap64(bits);
    else
      return __builtin_bswap32(bits);
  }
};

}  // namespace

template <class Point>
void write_points(const std::string& path, const std::vector<Point>& points) {
  using C = Coordinate<Point>;
  using Scalar = typename C::Scalar;
  PointFormat format;
  try {
    format = point_format_from_path(path);
  } catch (const InputError&) {
    throw OutputError(path + ": unknown point-set extension (use .ply, .xyz, .txt, .obj or .off)");
  }
  write_file_atomically(path, [&](std::ostream& out) {
    char line[160];
    auto write_lines = [&](const char* prefix) {
      for (const Point& p : points) {
        const int n = std::snprintf(line, sizeof line, C::kLine, prefix, static_cast<double>(p.x),
                                    static_cast<double>(p.y), static_cast<double>(p.z));
        out.write(line, n);
      }
    };
    switch (format) {
      case PointFormat::kPly: {
        const std::string type = C::kPlyType;
        out << "ply\nformat binary_little_endian 1.0\ncomment cudahull gen\nelement vertex " << points.size()
            << "\nproperty " << type << " x\nproperty " << type << " y\nproperty " << type
            << " z\nend_header\n";
        static_assert(sizeof(Point) == 3 * sizeof(Scalar));
        if constexpr (std::endian::native == std::endian::little) {
          out.write(reinterpret_cast<const char*>(points.data()),
                    static_cast<std::streamsize>(points.size() * sizeof(Point)));
        } else {
          for (const Point& p : points) {
            for (Scalar v : {p.x, p.y, p.z}) {
              const typename C::Bits bits = C::swapped(v);
              out.write(reinterpret_cast<const char*>(&bits), sizeof bits);
            }
          }
        }
        break;
      }
      case PointFormat::kOff:
        out << "OFF\n" << points.size() << " 0 0\n";
        write_lines("");
        break;
      case PointFormat::kObj:
        out << "# cudahull gen\n";
        write_lines("v ");
        break;
      case PointFormat::kXyz:
        write_lines("");
        break;
    }
  });
}

template void write_points(const std::string&, const std::vector<Point3>&);
template void write_points(const std::string&, const std::vector<Point3d>&);

}  // namespace cudahull
