// libFuzzer harness for the face reader (face_io.hpp): the bytes are a mesh file of format
// CUDAHULL_FUZZ_FORMAT (obj, off, ply).  The reader may accept the input or throw InputError; anything else
// - a crash, a sanitizer report, another exception, a hang - is a bug.  What it accepts must hold together:
// every face has at least three corners, each naming one of the file's vertices, the same faces with and
// without the vertices, and in float where it reads in double (or fail there alone, on a value beyond float).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "cudahull/errors.hpp"
#include "cudahull/face_io.hpp"

namespace {

constexpr cudahull::PointFormat kFormat = cudahull::PointFormat::CUDAHULL_FUZZ_FORMAT;

template <class Point>
bool read(const std::string& bytes, bool with_vertices, cudahull::BasicFaceMesh<Point>& out) {
  try {
    std::istringstream in(bytes, std::ios::binary);
    out = cudahull::read_faces<Point>(in, kFormat, "fuzz", with_vertices);
    return true;
  } catch (const cudahull::InputError&) {
    return false;
  }
}

template <class Point>
void check(const cudahull::BasicFaceMesh<Point>& m, bool with_vertices) {
  if (m.face_start.empty() || m.face_start.front() != 0 || m.face_start.back() != m.corners.size())
    __builtin_trap();
  if (m.face_line.size() != m.face_count()) __builtin_trap();
  for (std::size_t f = 0; f < m.face_count(); ++f)
    if (m.face_start[f + 1] < m.face_start[f] + 3) __builtin_trap();
  for (std::uint32_t c : m.corners)
    if (c >= m.vertex_count) __builtin_trap();
  if (with_vertices && m.vertices.size() != m.vertex_count) __builtin_trap();
  if (!with_vertices && !m.vertices.empty()) __builtin_trap();
  for (const Point& p : m.vertices)
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  cudahull::BasicFaceMesh<cudahull::Point3d> d;
  cudahull::BasicFaceMesh<cudahull::Point3> f, bare;
  const bool d_ok = read(bytes, true, d);
  const bool f_ok = read(bytes, true, f);
  if (d_ok) check(d, true);
  if (f_ok) check(f, true);
  if (f_ok && !d_ok) __builtin_trap();  // double's range holds float's
  if (f_ok && (f.corners != d.corners || f.face_start != d.face_start)) __builtin_trap();
  // Without the vertices the coordinates are not parsed, so more is accepted, with the same faces.
  const bool bare_ok = read(bytes, false, bare);
  if (bare_ok) check(bare, false);
  if (d_ok && (!bare_ok || bare.corners != d.corners || bare.vertex_count != d.vertex_count))
    __builtin_trap();
  return 0;
}
