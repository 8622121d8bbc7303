// The one-call API (issue 16): the exact convex hull of a point array, with what callers of Qhull expect
// from it (vertices, outward faces, neighbours, planes, volume, area) and an answer for flat input.
//
//   #include <cudahull/convex_hull.hpp>
//   std::vector<cudahull::Point3d> points = ...;
//   cudahull::ConvexHull hull = cudahull::convex_hull(points);             // backend and precision: auto
//   for (const auto& face : hull.faces) ...                                // input indices, outward CCW
//
// The stepping Engine (engine.hpp) stays public beside it; make_backend() gives it the same backends.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

// kAuto: the CUDA backend when a usable device is present, else the CPU (as `cudahull --backend auto`).
enum class BackendChoice { kAuto, kCpu, kCuda };
// kAuto: kResident where the hull runs on a GPU, kStepping on the CPU (as `cudahull --engine auto`, the
// command line's default); kStepping: Algorithm 1 an iteration at a time, the host editing the mesh on all
// cores; kResident: every phase where the points are (issue 15, `cudahull --engine resident`).
enum class EngineChoice { kAuto, kStepping, kResident };

struct ConvexHullOptions {
  BackendChoice backend = BackendChoice::kAuto;
  EngineChoice engine = EngineChoice::kAuto;
  // The coordinates the hull is computed in.  kAuto: the input's own type (float stays float, double is
  // exact in double); kFloat rounds double input to float once; kDouble widens float input exactly.
  Precision precision = Precision::kAuto;
};

struct ConvexHull {
  // The input's affine dimension: 3, or 2 (a convex polygon), 1 (a segment), 0 (one point), -1 (no points).
  int dimension = -1;
  Precision precision = Precision::kFloat;  // what it was computed in (never kAuto)
  std::string backend;                      // the backend that ran, e.g. "cpu" or "cuda"
  // Input indices of the hull's vertices, ascending: exactly the strictly extreme points (a point inside a
  // face or an edge is not one; among duplicate points the lowest index is).
  std::vector<PointIndex> vertices;
  // Dimension 3: triangles of input indices, counter-clockwise seen from outside.  Empty otherwise.
  std::vector<std::array<PointIndex, 3>> faces;
  // neighbors[f][k]: the face across the edge opposite faces[f][k] (scipy's convention).
  std::vector<std::array<std::int32_t, 3>> neighbors;
  // Per face: unit outward normal (nx, ny, nz) and offset d, so that n . x + d <= 0 inside (up to the
  // rounding of the normal, computed in double from the exact corners).
  std::vector<std::array<double, 4>> planes;
  // Dimension 2: the polygon's corners (input indices) in counter-clockwise order seen from the side its
  // normal points to (exact_hull.hpp).  Empty otherwise.
  std::vector<PointIndex> polygon;
  // Dimension 3: the solid's volume and surface area.  Dimension 2: volume 0, area both sides of the
  // polygon (the surface area of the flat solid, twice the polygon's area).  Lower: 0 and 0.
  double volume = 0, area = 0;
  // The resident engine's counters (iterations, host waits, bytes each way, coordinates read back for its
  // exact checks; resident.hpp), empty for the stepping engine.  For convex_hull_device() they include
  // the input check's wait and read-back.
  std::optional<ResidentStats> resident_stats;
  // Where convex_hull_device()'s time went (host clock, ms): the engine's run, and making this result from
  // its mesh (faces, neighbours, planes, measures).  Zero on the other paths.
  double engine_ms = 0, describe_ms = 0;
};

// The exact convex hull of `points`.  Throws InputError (one line naming the point index) for a NaN or
// infinite coordinate, a double coordinate outside exact double arithmetic's range (nonzero magnitudes from
// 2^-250 to 2^250, as `cudahull hull`), a double that does not fit in float with kFloat, or 2^32 - 1 points
// or more; DeviceError for kCuda without a usable GPU, or a failure on the device.
ConvexHull convex_hull(const std::vector<Point3>& points, const ConvexHullOptions& options = {});
ConvexHull convex_hull(const std::vector<Point3d>& points, const ConvexHullOptions& options = {});
// The same on `count` points given as x, y, z triples in one contiguous array (e.g. a NumPy array).
ConvexHull convex_hull(const float* xyz, std::size_t count, const ConvexHullOptions& options = {});
ConvexHull convex_hull(const double* xyz, std::size_t count, const ConvexHullOptions& options = {});

// The same on `count` x, y, z triples already in the memory of the current CUDA device (a CuPy array, a
// PyTorch tensor), read in place: the resident engine on the CUDA backend borrows them, whatever
// options.engine says (the stepping engine needs them on the host), and reads back only the coordinates
// its exact checks need (resident_stats counts them).  The points are checked on the device first, with
// the errors above (the first bad point named); a float array with kDouble is widened, a double array
// with kFloat rounded, into a temporary device buffer.  Throws std::invalid_argument for kCpu, and
// DeviceError without a usable GPU or for memory that is not the current device's.  The array must stay
// unchanged until the call returns.
ConvexHull convex_hull_device(const float* device_xyz, std::size_t count,
                              const ConvexHullOptions& options = {});
ConvexHull convex_hull_device(const double* device_xyz, std::size_t count,
                              const ConvexHullOptions& options = {});

// The points convex_hull() computes on: `count` x, y, z triples as Point (Point3 rounds a double once,
// Point3d widens a float exactly), with the same checks and errors.  Scalar is float or double.
template <class Point, class Scalar>
std::vector<Point> checked_points(const Scalar* xyz, std::size_t count);

// What convex_hull() returns, for an exact hull that the Engine (result()) or exact_hull() computed.
template <class Point>
ConvexHull hull_from_mesh(const BasicHullMesh<Point>& mesh, std::string backend);

// A backend for the stepping Engine, as ConvexHullOptions::backend picks it; `chosen_because` (if given)
// gets the reason in words ("as requested", "auto: no usable CUDA device: ...").  Point3 or Point3d.
template <class Point>
std::unique_ptr<BasicBackend<Point>> make_backend(BackendChoice choice,
                                                  std::string* chosen_because = nullptr);

// Whether this process has a usable CUDA device (what backend auto looks for): its name, or why not.
struct CudaStatus {
  bool usable = false;
  std::string device;  // e.g. "NVIDIA H100 80GB HBM3"
  std::string reason;  // e.g. "no CUDA-capable device is detected"
};
CudaStatus cuda_status();

// "auto", "cpu", "cuda" and back; throws std::invalid_argument for another name.
BackendChoice backend_from_name(const std::string& name);
EngineChoice engine_from_name(const std::string& name);  // "auto", "stepping" or "resident"
// "auto", "float", "double"; unlike precision_from_name() (types.hpp), a bad name throws.
Precision precision_from_name_strict(const std::string& name);

}  // namespace cudahull
