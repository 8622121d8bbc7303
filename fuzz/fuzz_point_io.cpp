// libFuzzer harness for the point readers (issue 7): the bytes are a file of format CUDAHULL_FUZZ_FORMAT.  A
// reader may accept the input or throw InputError (bad input: a one-line error); anything else - a crash, a
// sanitizer report, another exception, a hang - is a bug.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size), std::ios::binary);
  try {
    const auto points = cudahull::read_points(in, cudahull::PointFormat::CUDAHULL_FUZZ_FORMAT, "fuzz");
    for (const cudahull::Point3& p : points) {  // what a reader returns is finite (README, "Input formats")
      if (!(p.x == p.x && p.y == p.y && p.z == p.z)) __builtin_trap();
    }
  } catch (const cudahull::InputError&) {
  }
  return 0;
}
