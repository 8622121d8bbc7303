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
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/hull_options.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

struct ConvexHull {
  // The input's affine dimension: 3 (2 for 2-D input), or lower: 2 (a convex polygon), 1 (a segment), 0 (one
  // point), -1 (no points).
  int dimension = -1;
  int input_dimension = 3;                  // 3, or 2 for convex_hull_2d()
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
  // normal points to (exact_hull.hpp); for 2-D input counter-clockwise in the plane, from the lowest (x, y)
  // corner.  Dimension 1: the segment's two ends.  Empty otherwise.
  std::vector<PointIndex> polygon;
  // 2-D input of dimension 2 only: the edges (polygon[k], polygon[k + 1]), counter-clockwise; the edge across
  // each end (edge_neighbors[e][k] is opposite edges[e][k], scipy's convention); each edge's line as unit
  // outward normal and offset (nx, ny, d: n . x + d <= 0 inside).
  std::vector<std::array<PointIndex, 2>> edges;
  std::vector<std::array<std::int32_t, 2>> edge_neighbors;
  std::vector<std::array<double, 3>> lines;
  // Dimension 3: the solid's volume and surface area.  Dimension 2 of 3-D input: volume 0, area both sides
  // of the polygon (the surface area of the flat solid, twice the polygon's area).  2-D input: volume is the
  // polygon's area and area its perimeter, as scipy's.  Lower: 0 and 0.
  double volume = 0, area = 0;
  // With ConvexHullOptions::box_measures, for dimension 3: Qhull's QbB volume and area, every axis mapped
  // onto [-0.5, 0.5] by the exact hull's vertices' bounds (qhull_scaling.hpp; scipy's under "QbB").  NaN
  // otherwise.
  double box_volume = std::numeric_limits<double>::quiet_NaN(),
         box_area = std::numeric_limits<double>::quiet_NaN();
  // A merged hull (ConvexHullOptions::merge): the points merging left out that the exact hull had as
  // vertices, each as {point, nearest face (or edge), nearest vertex}, as scipy's `coplanar`; the absolute
  // tolerance used; and a proven bound: every input point p lies within max_outside of every face's plane
  // (n . p + d <= max_outside, the evaluation's rounding included).  Zero for the exact hull, whose planes
  // are the exact normals rounded (every point within a few units in the last place of them).
  std::vector<std::array<PointIndex, 3>> coplanar;
  double tolerance = 0, max_outside = 0;
  // A merged hull of dimension 3: its least depth below one of its faces' planes (min over faces of max over
  // its vertices of -(n . p + d), in double), exactly where that is within 4 x the tolerance, else a lower
  // bound above it: Qhull's flatness test (QH6154) is `thinnest <= tolerance`.  Infinity otherwise.
  double thinnest = std::numeric_limits<double>::infinity();
  // The resident engine's counters (iterations, host waits, bytes each way, coordinates read back for its
  // exact checks; resident.hpp), empty for the stepping engine.  For convex_hull_device() they include
  // the input check's wait and read-back.
  std::optional<ResidentStats> resident_stats;
  // Where convex_hull_device()'s time went (host clock, ms): the engine's run, and making this result from
  // its mesh (faces, neighbours, planes, measures).  Zero on the other paths.
  double engine_ms = 0, describe_ms = 0;
  // How the hull was run, in one line: the engine, backend and precision plan_hull() chose, each with its
  // reason (HullPlan::reason), as the command line's --stats prints it.
  std::string plan;
};

// The exact convex hull of `points`.  Every finite double is taken: where a coordinate lies outside the
// engines' exact range (nonzero magnitudes 2^-250..2^250) the hull is exact_hull_any()'s, on the host
// (backend "cpu-wide"; exponent scaling, else GMP).  Throws InputError (one line naming the point index) for
// a NaN or infinite coordinate, a double that does not fit in float with kFloat, or 2^32 - 1 points or
// more; DeviceError for kCuda without a usable GPU, or a failure on the device.
ConvexHull convex_hull(const std::vector<Point3>& points, const ConvexHullOptions& options = {});
ConvexHull convex_hull(const std::vector<Point3d>& points, const ConvexHullOptions& options = {});
// The same on `count` points given as x, y, z triples in one contiguous array (e.g. a NumPy array).
ConvexHull convex_hull(const float* xyz, std::size_t count, const ConvexHullOptions& options = {});
ConvexHull convex_hull(const double* xyz, std::size_t count, const ConvexHullOptions& options = {});

// The exact convex hull of `count` 2-D points given as x, y pairs: ConvexHull's polygon, edges, lines,
// volume (area) and area (perimeter), input_dimension 2.  Exact (orient2d); the same checks and errors.
ConvexHull convex_hull_2d(const float* xy, std::size_t count, const ConvexHullOptions& options = {});
ConvexHull convex_hull_2d(const double* xy, std::size_t count, const ConvexHullOptions& options = {});
// The same on 2-D points in the current CUDA device's memory: the device checks them and drops every point
// strictly inside a polygon of extreme points, and only the survivors cross to the host (backend "cuda").
// Throws as convex_hull_device().
ConvexHull convex_hull_2d_device(const float* device_xy, std::size_t count,
                                 const ConvexHullOptions& options = {});
ConvexHull convex_hull_2d_device(const double* device_xy, std::size_t count,
                                 const ConvexHullOptions& options = {});

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

// What convex_hull() returns, for an exact hull that the Engine (result()) or exact_hull() computed, merged
// where `options` ask for it; without `neighbors` (a batch keeps none), the exact hull's are not found.
template <class Point>
ConvexHull hull_from_mesh(const BasicHullMesh<Point>& mesh, std::string backend,
                          const ConvexHullOptions& options = {}, bool neighbors = true);

// A backend for the stepping Engine, as ConvexHullOptions::backend picks it; `chosen_because` (if given)
// gets the reason in words ("as requested", "auto: no usable CUDA device: ...").  Point3 or Point3d.
template <class Point>
std::unique_ptr<BasicBackend<Point>> make_backend(BackendChoice choice,
                                                  std::string* chosen_because = nullptr);

// The memory cudahull keeps between calls on the current CUDA device and no result uses (at least 256 MiB,
// and after a batch what it used, up to a sixteenth of the device's memory, for the next batch of its size),
// back to the driver now: for memory another library (PyTorch, CuPy) needs.  The next call maps what it needs
// again.  No device: nothing.
void release_device_memory();

}  // namespace cudahull
