// convex_hull(): the input checked, the engine run, and the hull's faces, neighbours, planes and measures
// derived from the exact mesh (in double, from the coordinates it was computed on).
#include "cudahull/convex_hull.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "cuda_backend.hpp"
#include "cudahull/cpu_backend.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/resident.hpp"
#include "device_info.hpp"
#include "device_points.hpp"
#include "resident_cuda.hpp"

namespace cudahull {

namespace {

// The range of double coordinates the exact predicates are exact on, as io's check_double_range()
// (point_io.hpp) enforces it for files; the package does not link the file readers.
constexpr double kMinExactMagnitude = 0x1p-250;
constexpr double kMaxExactMagnitude = 0x1p+250;

const char* axis_name(int axis) {
  return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

std::string shortest(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

[[noreturn]] void bad_coordinate(std::size_t point, int axis, double value, const std::string& why) {
  throw InputError("point " + std::to_string(point) + ": " + axis_name(axis) + " coordinate " +
                   shortest(value) + " " + why);
}

// Why the exact hull in Point cannot take a point whose coordinates, widened to double, are `widened`
// (the axis in `axis`), or nullptr, with the point in Point in `out`.  Every coordinate's finiteness is
// asked before any range, so that a message names a NaN before a huge neighbour.
template <class Point>
const char* rejection(const double (&widened)[3], int& axis, Point& out) {
  for (axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(widened[axis])) return "is not finite";
  }
  if constexpr (std::is_same_v<Point, Point3d>) {
    for (axis = 0; axis < 3; ++axis) {
      const double m = std::fabs(widened[axis]);
      if (m != 0 && (m < kMinExactMagnitude || m > kMaxExactMagnitude))
        return "is outside the range of exact double arithmetic (nonzero magnitudes from 2^-250 to 2^250)";
    }
    out = Point3d{widened[0], widened[1], widened[2]};
  } else {
    // Rounded once to float (a float input is unchanged); a double beyond float's range cannot be.
    const float rounded[3] = {static_cast<float>(widened[0]), static_cast<float>(widened[1]),
                              static_cast<float>(widened[2])};
    for (axis = 0; axis < 3; ++axis) {
      if (!std::isfinite(rounded[axis])) return "does not fit in float";
    }
    out = Point3{rounded[0], rounded[1], rounded[2]};
  }
  return nullptr;
}

// Throws the InputError (one line naming the point) for point `i`, if rejection() has one.  The device
// path names its first bad point with it too.
template <class Point>
void throw_if_rejected(std::size_t i, const double (&widened)[3]) {
  int axis = 0;
  Point unused;
  if (const char* why = rejection(widened, axis, unused)) bad_coordinate(i, axis, widened[axis], why);
}

void check_count(std::size_t count) {
  // PointIndex is 32 bits and the engine keeps 0xffffffff as "no point".
  if (count >= 0xffffffffu)
    throw InputError("too many points: " + std::to_string(count) + " (at most 2^32 - 2)");
}

// Copies `count` points into Point (float or double), refusing what the exact hull cannot take;
// `coordinate(i, axis)` reads the input.  On all host cores: for 10M points the copy is otherwise most of
// a resident hull's time.  Each chunk stops at its first bad point; the lowest is the one named, as a
// scan in order would.
template <class Point, class Coordinate>
std::vector<Point> copy_checked(std::size_t count, Coordinate coordinate) {
  check_count(count);
  std::vector<Point> points(count);
  const unsigned workers = hardware_workers();
  std::vector<std::size_t> first_bad(workers, count);
  parallel_chunks(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        for (std::size_t i = begin; i < end; ++i) {
          const double widened[3] = {coordinate(i, 0), coordinate(i, 1), coordinate(i, 2)};
          int axis = 0;
          if (rejection(widened, axis, points[i])) {
            first_bad[worker] = i;
            return;
          }
        }
      },
      std::size_t{1} << 16);
  const std::size_t bad = *std::min_element(first_bad.begin(), first_bad.end());
  if (bad != count) {
    const double widened[3] = {coordinate(bad, 0), coordinate(bad, 1), coordinate(bad, 2)};
    throw_if_rejected<Point>(bad, widened);
  }
  return points;
}

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct Vec {
  double x, y, z;
};
Vec operator-(Vec a, Vec b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec cross(Vec a, Vec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec a, Vec b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
double norm(Vec a) {
  return std::sqrt(dot(a, a));
}

template <class Point>
Vec as_vec(const Point& p) {
  return {static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z)};
}

// neighbors[f][k] = the face holding the reverse of the edge opposite corner k (each directed edge appears
// once in a closed 2-manifold with consistent orientation).  `triangles` index `vertex_count` vertices: the
// directed edges are grouped by their first vertex (a counting sort), so each reverse is found among a
// vertex's few edges; sorting all edges took most of a 28K-face hull's time outside the engine.
std::vector<std::array<std::int32_t, 3>> face_neighbors(const std::vector<Triangle>& triangles,
                                                        std::size_t vertex_count) {
  std::vector<std::uint32_t> start(vertex_count + 1, 0);
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k)
      ++start[t[k] + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v)
    start[v + 1] += start[v];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1), to(3 * triangles.size()),
      face(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t slot = fill[triangles[f][k]]++;
      to[slot] = triangles[f][(k + 1) % 3];
      face[slot] = static_cast<std::uint32_t>(f);
    }
  }
  std::vector<std::array<std::int32_t, 3>> neighbors(triangles.size(), {-1, -1, -1});
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      // The edge opposite corner k runs from corner k+1 to corner k+2; its neighbour holds it reversed.
      const std::uint32_t from = triangles[f][(k + 2) % 3], wanted = triangles[f][(k + 1) % 3];
      for (std::uint32_t slot = start[from]; slot < start[from + 1]; ++slot) {
        if (to[slot] == wanted) {
          neighbors[f][k] = static_cast<std::int32_t>(face[slot]);
          break;
        }
      }
      if (neighbors[f][k] < 0) throw std::logic_error("convex_hull: the mesh is not closed");
    }
  }
  return neighbors;
}

template <class Point>
ConvexHull describe(const BasicHullMesh<Point>& mesh, std::string backend) {
  ConvexHull hull;
  hull.dimension = mesh.dimension;
  hull.precision = std::is_same_v<Point, Point3d> ? Precision::kDouble : Precision::kFloat;
  hull.backend = std::move(backend);
  hull.vertices = mesh.vertex_ids;
  std::sort(hull.vertices.begin(), hull.vertices.end());
  if (mesh.dimension == 2) {
    for (std::uint32_t corner : mesh.polygon)
      hull.polygon.push_back(mesh.vertex_ids[corner]);
    // The flat solid's surface: both sides of the polygon, each a fan of triangles from corner 0.
    Vec twice_area{0, 0, 0};
    for (std::size_t k = 1; k + 1 < mesh.polygon.size(); ++k) {
      const Vec origin = as_vec(mesh.vertices[mesh.polygon[0]]);
      const Vec c = cross(as_vec(mesh.vertices[mesh.polygon[k]]) - origin,
                          as_vec(mesh.vertices[mesh.polygon[k + 1]]) - origin);
      twice_area = {twice_area.x + c.x, twice_area.y + c.y, twice_area.z + c.z};
    }
    hull.area = norm(twice_area);
    return hull;
  }
  if (mesh.dimension != 3) return hull;

  // Volumes of tetrahedra from the vertices' centroid, which lies inside: every term is positive, so the
  // sum loses nothing to cancellation.
  Vec centroid{0, 0, 0};
  for (const Point& p : mesh.vertices) {
    const Vec v = as_vec(p);
    centroid = {centroid.x + v.x, centroid.y + v.y, centroid.z + v.z};
  }
  const double n = static_cast<double>(mesh.vertices.size());
  centroid = {centroid.x / n, centroid.y / n, centroid.z / n};

  hull.faces.reserve(mesh.triangles.size());
  hull.planes.reserve(mesh.triangles.size());
  double six_volume = 0, twice_area = 0;
  for (const Triangle& t : mesh.triangles) {
    hull.faces.push_back({mesh.vertex_ids[t[0]], mesh.vertex_ids[t[1]], mesh.vertex_ids[t[2]]});
    const Vec a = as_vec(mesh.vertices[t[0]]), b = as_vec(mesh.vertices[t[1]]),
              c = as_vec(mesh.vertices[t[2]]);
    const Vec normal = cross(b - a, c - a);
    const double length = norm(normal);
    twice_area += length;
    six_volume += dot(cross(b - centroid, c - centroid), a - centroid);
    const Vec unit{normal.x / length, normal.y / length, normal.z / length};
    // The offset from the three corners' mean: the plane's rounding error shared out evenly.
    const double offset = -(dot(unit, a) + dot(unit, b) + dot(unit, c)) / 3;
    hull.planes.push_back({unit.x, unit.y, unit.z, offset});
  }
  hull.volume = six_volume / 6;
  hull.area = twice_area / 2;
  hull.neighbors = face_neighbors(mesh.triangles, mesh.vertices.size());
  return hull;
}

template <class Point>
ConvexHull hull_in(const std::vector<Point>& points, const ConvexHullOptions& options) {
  if (options.engine == EngineChoice::kResident) {
    if (options.backend != BackendChoice::kCpu) {
      const CudaDeviceInfo device = query_cuda_device();
      if (device.usable) {
        ResidentCudaHull<Point> resident;
        resident.upload(points);
        ResidentStats stats;
        ConvexHull hull = describe(resident.run(&stats), "cuda-resident");
        hull.resident_stats = std::move(stats);
        return hull;
      }
      if (options.backend == BackendChoice::kCuda)
        throw DeviceError("backend cuda: no usable CUDA device: " + device.reason);
    }
    ResidentStats stats;
    ConvexHull hull = describe(resident_hull_host(points, &stats), "cpu-resident");
    hull.resident_stats = std::move(stats);
    return hull;
  }
  std::unique_ptr<BasicBackend<Point>> backend = make_backend<Point>(options.backend);
  std::string name = backend->name();
  BasicEngine<Point> engine(points, std::move(backend), EngineOptions{.keep_decisions = false});
  engine.run();
  return describe(engine.result(), std::move(name));
}

// The hull of `count` points read by `coordinate(i, axis)`, whose own precision is `own`.
template <class Coordinate>
ConvexHull checked_hull(std::size_t count, Coordinate coordinate, Precision own,
                        const ConvexHullOptions& options) {
  const Precision precision = options.precision == Precision::kAuto ? own : options.precision;
  if (precision == Precision::kDouble) return hull_in(copy_checked<Point3d>(count, coordinate), options);
  return hull_in(copy_checked<Point3>(count, coordinate), options);
}

// The hull of points that only the current device holds, in Point: checked (and converted) there, then
// borrowed by the resident engine.
template <class Point, class Scalar>
ConvexHull device_hull_in(const Scalar* device_xyz, std::size_t count) {
  CheckedDevicePoints<Point> checked = check_device_points<Point>(device_xyz, count);
  if (checked.first_bad != count) {
    // Named from its own coordinates by the host path's check, so the message is the same word for word.
    const std::array<double, 3> p = read_device_point(device_xyz, checked.first_bad);
    const double widened[3] = {p[0], p[1], p[2]};
    throw_if_rejected<Point>(checked.first_bad, widened);
    throw std::logic_error("convex_hull_device: point " + std::to_string(checked.first_bad) +
                           " failed the device's check but passes the host's");
  }
  ResidentCudaHull<Point> resident;
  resident.use_device_points(checked.points, count);
  ResidentStats stats;
  const Clock::time_point run_start = Clock::now();
  const BasicHullMesh<Point> mesh = resident.run(&stats);
  const Clock::time_point describe_start = Clock::now();
  ConvexHull hull = describe(mesh, "cuda-resident");
  hull.engine_ms = std::chrono::duration<double, std::milli>(describe_start - run_start).count();
  hull.describe_ms = ms_since(describe_start);
  stats.host_syncs += checked.host_syncs;
  stats.bytes_from_device += checked.bytes_from_device;
  hull.resident_stats = std::move(stats);
  return hull;
}

template <class Scalar>
ConvexHull device_hull(const Scalar* device_xyz, std::size_t count, Precision own,
                       const ConvexHullOptions& options) {
  if (options.backend == BackendChoice::kCpu)
    throw std::invalid_argument("points in GPU memory need backend auto or cuda, not cpu");
  check_count(count);
  // Not query_cuda_device(): reading the device's properties would cost more than a small hull.
  std::string why_not;
  if (!cuda_device_present(&why_not))
    throw DeviceError("points in GPU memory, but no usable CUDA device: " + why_not);
  if (count != 0) require_current_device_memory(device_xyz);
  const Precision precision = options.precision == Precision::kAuto ? own : options.precision;
  if (precision == Precision::kDouble) return device_hull_in<Point3d>(device_xyz, count);
  return device_hull_in<Point3>(device_xyz, count);
}

template <class Scalar>
auto array_coordinate(const Scalar* xyz) {
  return [xyz](std::size_t i, int axis) -> double { return xyz[3 * i + axis]; };
}

// The hull of `count` x, y, z triples in host memory.  For the resident engine on the GPU they are uploaded
// as they are and checked (or converted) there, as convex_hull_device() does: the engine needs no host
// copy of them (it reads back the few coordinates its exact checks need), and the copy would cost more
// than the hull.  Otherwise they are checked into a host copy.
template <class Scalar>
ConvexHull array_hull(const Scalar* xyz, std::size_t count, Precision own, const ConvexHullOptions& options) {
  if (options.engine == EngineChoice::kResident && options.backend != BackendChoice::kCpu && count != 0 &&
      cuda_device_present(nullptr)) {
    check_count(count);
    const std::shared_ptr<void> copy = upload_to_device(xyz, count * 3 * sizeof(Scalar));
    return device_hull(static_cast<const Scalar*>(copy.get()), count, own, options);
  }
  return checked_hull(count, array_coordinate(xyz), own, options);
}

template <class Point>
auto vector_coordinate(const std::vector<Point>& points) {
  return [&points](std::size_t i, int axis) -> double {
    return axis == 0 ? points[i].x : axis == 1 ? points[i].y : points[i].z;
  };
}

}  // namespace

template <class Point>
std::unique_ptr<BasicBackend<Point>> make_backend(BackendChoice choice, std::string* chosen_because) {
  auto say = [&](const std::string& why) {
    if (chosen_because) *chosen_because = why;
  };
  if (choice == BackendChoice::kCpu) {
    say("as requested");
    return make_cpu_backend<Point>();
  }
  const CudaDeviceInfo device = query_cuda_device();
  if (device.usable) {
    say(choice == BackendChoice::kAuto ? "auto: a usable CUDA device" : "as requested");
    return make_cuda_backend<Point>();
  }
  if (choice == BackendChoice::kCuda)
    throw DeviceError("backend cuda: no usable CUDA device: " + device.reason);
  say("auto: no usable CUDA device: " + device.reason);
  return make_cpu_backend<Point>();
}

template <class Point, class Scalar>
std::vector<Point> checked_points(const Scalar* xyz, std::size_t count) {
  return copy_checked<Point>(count, array_coordinate(xyz));
}

template std::vector<Point3> checked_points<Point3>(const float*, std::size_t);
template std::vector<Point3> checked_points<Point3>(const double*, std::size_t);
template std::vector<Point3d> checked_points<Point3d>(const float*, std::size_t);
template std::vector<Point3d> checked_points<Point3d>(const double*, std::size_t);

template <class Point>
ConvexHull hull_from_mesh(const BasicHullMesh<Point>& mesh, std::string backend) {
  return describe(mesh, std::move(backend));
}

template ConvexHull hull_from_mesh(const HullMesh&, std::string);
template ConvexHull hull_from_mesh(const HullMeshd&, std::string);

template std::unique_ptr<BasicBackend<Point3>> make_backend(BackendChoice, std::string*);
template std::unique_ptr<BasicBackend<Point3d>> make_backend(BackendChoice, std::string*);

// EngineChoice::kAuto made definite: the resident engine where it runs on a GPU, else the stepping one.
static ConvexHullOptions resolved(ConvexHullOptions options) {
  if (options.engine == EngineChoice::kAuto)
    options.engine = options.backend != BackendChoice::kCpu && cuda_device_present(nullptr)
                         ? EngineChoice::kResident
                         : EngineChoice::kStepping;
  return options;
}

ConvexHull convex_hull(const std::vector<Point3>& points, const ConvexHullOptions& options) {
  return checked_hull(points.size(), vector_coordinate(points), Precision::kFloat, resolved(options));
}

ConvexHull convex_hull(const std::vector<Point3d>& points, const ConvexHullOptions& options) {
  return checked_hull(points.size(), vector_coordinate(points), Precision::kDouble, resolved(options));
}

ConvexHull convex_hull(const float* xyz, std::size_t count, const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kFloat, resolved(options));
}

ConvexHull convex_hull(const double* xyz, std::size_t count, const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kDouble, resolved(options));
}

ConvexHull convex_hull_device(const float* device_xyz, std::size_t count, const ConvexHullOptions& options) {
  return device_hull(device_xyz, count, Precision::kFloat, options);
}

ConvexHull convex_hull_device(const double* device_xyz, std::size_t count, const ConvexHullOptions& options) {
  return device_hull(device_xyz, count, Precision::kDouble, options);
}

CudaStatus cuda_status() {
  const CudaDeviceInfo device = query_cuda_device();
  return {device.usable, device.name, device.reason};
}

BackendChoice backend_from_name(const std::string& name) {
  if (name == "auto") return BackendChoice::kAuto;
  if (name == "cpu") return BackendChoice::kCpu;
  if (name == "cuda") return BackendChoice::kCuda;
  throw std::invalid_argument("backend must be auto, cpu or cuda, not '" + name + "'");
}

EngineChoice engine_from_name(const std::string& name) {
  if (name == "auto") return EngineChoice::kAuto;
  if (name == "stepping") return EngineChoice::kStepping;
  if (name == "resident") return EngineChoice::kResident;
  throw std::invalid_argument("engine must be auto, stepping or resident, not '" + name + "'");
}

Precision precision_from_name_strict(const std::string& name) {
  if (name == "auto" || name == "float" || name == "double") return precision_from_name(name);
  throw std::invalid_argument("precision must be auto, float or double, not '" + name + "'");
}

}  // namespace cudahull
