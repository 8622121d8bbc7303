// libFuzzer harness for the point readers (issue 7): the bytes are a file of format CUDAHULL_FUZZ_FORMAT.  A
// reader may accept the input or throw InputError (bad input: a one-line error); anything else - a crash, a
// sanitizer report, another exception, a hang - is a bug.  Each input goes through both entry points, the
// float one (read_points) and the full-precision one (read_points_double), and through auto_precision.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"

namespace {

constexpr cudahull::PointFormat kFormat = cudahull::PointFormat::CUDAHULL_FUZZ_FORMAT;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  bool float_ok = false;
  std::vector<cudahull::Point3> floats;
  try {
    std::istringstream in(bytes, std::ios::binary);
    floats = cudahull::read_points(in, kFormat, "fuzz");
    for (const cudahull::Point3& p : floats) {  // what a reader returns is finite (README, "Input formats")
      if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) __builtin_trap();
    }
    float_ok = true;
  } catch (const cudahull::InputError&) {
  }
  try {
    std::istringstream in(bytes, std::ios::binary);
    const cudahull::DoublePoints result = cudahull::read_points_double(in, kFormat, "fuzz");
    for (const cudahull::Point3d& p : result.points) {
      if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) __builtin_trap();
    }
    if (result.precision != cudahull::Precision::kFloat && result.precision != cudahull::Precision::kDouble) {
      __builtin_trap();
    }
    // Double's range holds float's: what the float reader accepts the double reader accepts, point for point,
    // and where `auto` picks float (binary float or small integer coordinates) the values are the same.
    if (float_ok && result.points.size() != floats.size()) __builtin_trap();
    if (float_ok && result.precision == cudahull::Precision::kFloat) {
      for (std::size_t i = 0; i < floats.size(); ++i) {
        const cudahull::Point3d& d = result.points[i];
        if (d != cudahull::Point3d{floats[i].x, floats[i].y, floats[i].z}) __builtin_trap();
      }
    }
    // auto_precision reads only the header, and agrees with the reader.
    std::istringstream header(bytes, std::ios::binary);
    try {
      if (cudahull::auto_precision(header, kFormat, "fuzz") != result.precision) __builtin_trap();
    } catch (const cudahull::InputError&) {
      __builtin_trap();
    }
  } catch (const cudahull::InputError&) {
    if (float_ok) __builtin_trap();
  }
  return 0;
}
