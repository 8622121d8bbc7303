#include "cudahull/point_writer.hpp"

#include <bit>
#include <cstdio>
#include <cstring>

#include "cudahull/errors.hpp"
#include "cudahull/mesh_io.hpp"
#include "cudahull/point_io.hpp"

namespace cudahull {

void write_points(const std::string& path, const std::vector<Point3>& points) {
  PointFormat format;
  try {
    format = point_format_from_path(path);
  } catch (const InputError&) {
    throw OutputError(path + ": unknown point-set extension (use .ply, .xyz, .txt, .obj or .off)");
  }
  write_file_atomically(path, [&](std::ostream& out) {
    char line[96];
    auto write_lines = [&](const char* prefix) {
      for (const Point3& p : points) {
        const int n = std::snprintf(line, sizeof line, "%s%.9g %.9g %.9g\n", prefix, p.x, p.y, p.z);
        out.write(line, n);
      }
    };
    switch (format) {
      case PointFormat::kPly: {
        out << "ply\nformat binary_little_endian 1.0\ncomment cudahull gen\nelement vertex " << points.size()
            << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        static_assert(sizeof(Point3) == 12);
        if constexpr (std::endian::native == std::endian::little) {
          out.write(reinterpret_cast<const char*>(points.data()),
                    static_cast<std::streamsize>(points.size() * sizeof(Point3)));
        } else {
          for (const Point3& p : points) {
            for (float v : {p.x, p.y, p.z}) {
              std::uint32_t bits = __builtin_bswap32(std::bit_cast<std::uint32_t>(v));
              out.write(reinterpret_cast<const char*>(&bits), 4);
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

}  // namespace cudahull
