// convex_hull(): the input checked, the engine run, and the hull's faces, neighbours, planes and measures
// derived from the exact mesh (in double, from the coordinates it was computed on).
#include "cudahull/convex_hull.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <type_traits>

#include "cuda_backend.hpp"
#include "cudahull/cpu_backend.hpp"
#include "cudahull/detail/plane_impl.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/plane.hpp"
#include "cudahull/resident.hpp"
#include "device_info.hpp"
#include "device_memory.hpp"
#include "device_points.hpp"
#include "facet_merge.hpp"
#include "host_hull.hpp"
#include "planar_filter.hpp"
#include "planar_hull.hpp"
#include "resident_cuda.hpp"

namespace cudahull {

namespace {

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
    // Every finite double: outside the engines' range (in_fast_exact_range) the hull takes the wide path.
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

// Coordinates outside the fast exact range (the wide path's hulls) are brought into it, where a whole face
// or solid allows, by a power of two: exact, and planes' directions and measures scale back exactly (a
// plane's offset by 2^k, an area by 2^2k, a volume by 2^3k, to infinity where they exceed a double).
// `scale` is 0 where every coordinate of `points` is in the range already (the device's describe computes
// there too: the same bits), else the exponent k that brings their largest magnitude into [1, 2); false
// where some coordinate, so scaled, would leave the range (magnitudes more than some 2^500 apart).
template <class PointAt>
bool fast_range_scale(std::size_t count, const PointAt& point, int* scale) {
  double largest = 0;
  bool in_range = true;
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3d p = point(k);
    in_range = in_range && in_fast_exact_range(p.x) && in_fast_exact_range(p.y) && in_fast_exact_range(p.z);
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  *scale = in_range || largest == 0 ? 0 : std::ilogb(largest);
  if (in_range) return true;
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3d p = point(k);
    for (const double v : {p.x, p.y, p.z}) {
      const double scaled = std::ldexp(v, -*scale);
      if (!in_fast_exact_range(scaled) || (scaled == 0) != (v == 0)) return false;
    }
  }
  return true;
}

Vec3d scaled_by(const Vec3d& p, int scale) {
  if (scale == 0) return p;
  return {std::ldexp(p.x, -scale), std::ldexp(p.y, -scale), std::ldexp(p.z, -scale)};
}

// (b - a) x (c - a) in long double, whose exponent range holds every product of double differences (none
// over- or underflows): for faces beyond the fast exact range even when scaled, accurate to the last place
// but where the products cancel (a sliver of such coordinates: then a few ulps of the products).
using Wide = long double;
using WideVec = std::array<Wide, 3>;
WideVec wide_cross(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Wide ux = Wide(b.x) - a.x, uy = Wide(b.y) - a.y, uz = Wide(b.z) - a.z;
  const Wide vx = Wide(c.x) - a.x, vy = Wide(c.y) - a.y, vz = Wide(c.z) - a.z;
  return {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
}
Wide wide_length(const WideVec& n) {
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// A facet's plane, accurate on slivers too (issue 25): detail::facet_plane_in_range() (plane_impl.hpp, which
// the batch kernel's device describe shares: the same bits on both), on the corners scaled into the fast
// exact range where they are not in it.
std::array<double, 4> facet_plane(Vec3d a, Vec3d b, Vec3d c) {
  const Vec3d corners[3] = {a, b, c};
  int scale = 0;
  if (fast_range_scale(
          3, [&](std::size_t k) { return corners[k]; }, &scale)) {
    std::array<double, 4> plane;
    detail::facet_plane_in_range(scaled_by(a, scale), scaled_by(b, scale), scaled_by(c, scale), plane.data());
    if (scale != 0) plane[3] = std::ldexp(plane[3], scale);  // a library call a face otherwise
    return plane;
  }
  // Corners more than 2^500 apart in magnitude: the cross product in long double (wide_cross()), rounded.
  const WideVec normal = wide_cross(a, b, c);
  const Wide length = wide_length(normal);
  if (length == 0) return {0, 0, 0, 0};
  const double n[3] = {static_cast<double>(normal[0] / length), static_cast<double>(normal[1] / length),
                       static_cast<double>(normal[2] / length)};
  auto height = [&](Vec3d p) { return Wide(n[0]) * p.x + Wide(n[1]) * p.y + Wide(n[2]) * p.z; };
  return {n[0], n[1], n[2], static_cast<double>(-std::max({height(a), height(b), height(c)}))};
}

// detail::measure_mesh() on all cores for a mesh of more than kMeasureChunk faces: each chunk of that many
// faces (fixed, whatever the core count) summed on its own, the chunks' sums added in order.  A mesh of one
// chunk, as every batch cloud's, is measure_mesh()'s own order: the device describe's bits.
constexpr std::size_t kMeasureChunk = std::size_t{1} << 20;  // a multiple of the 32 error sums

template <class Corner>
detail::SolidMeasures measure_on_cores(std::size_t faces, const Corner& corner, const Vec3d& apex) {
  if (faces <= kMeasureChunk) return detail::measure_mesh(faces, corner, apex);
  using detail::add_rn;
  using detail::SolidMeasures;
  const std::size_t chunks = (faces + kMeasureChunk - 1) / kMeasureChunk;
  std::vector<SolidMeasures> parts(chunks);
  std::vector<std::array<double, SolidMeasures::kErrorSums>> error_sums(chunks);
  const auto each_chunk = [&](const auto& pass) {
    parallel_chunks(
        chunks, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k)
            pass(k, k * kMeasureChunk, std::min(faces, (k + 1) * kMeasureChunk));
        },
        1);
  };
  each_chunk([&](std::size_t k, std::size_t begin, std::size_t end) {
    error_sums[k].fill(0);
    detail::add_face_terms(begin, end, corner, apex, parts[k], error_sums[k].data());
  });
  SolidMeasures measures;
  for (std::size_t k = 0; k < chunks; ++k) {
    measures.twice_area = add_rn(measures.twice_area, parts[k].twice_area);
    measures.six_volume = add_rn(measures.six_volume, parts[k].six_volume);
  }
  for (int l = 0; l < SolidMeasures::kErrorSums; ++l) {
    double sum = 0;
    for (std::size_t k = 0; k < chunks; ++k)
      sum = add_rn(sum, error_sums[k][l]);
    measures.six_volume_error = add_rn(measures.six_volume_error, sum);
  }
  if (measures.volume_uncertain()) {
    each_chunk([&](std::size_t k, std::size_t begin, std::size_t end) {
      parts[k].exact_volume_pass();
      detail::add_exact_terms(begin, end, corner, apex, parts[k]);
    });
    measures.exact_volume_pass();
    for (std::size_t k = 0; k < chunks; ++k)
      measures.add_exact(parts[k].six_volume);
  }
  return measures;
}

// The solid's volume and surface area into `hull`, over `triangles` (outward, indices into `vertices`):
// detail::measure_mesh() (plane_impl.hpp, as the batch's device describe: the same bits), its apex the first
// triangle's first corner; scaled into the fast exact range where the vertices are not in it.
template <class Point>
void measure_solid(const std::vector<Point>& vertices, const std::vector<Triangle>& triangles,
                   ConvexHull& hull) {
  if (triangles.empty()) return;
  const auto vertex = [&](std::size_t k) { return to_vec3d(vertices[k]); };
  int scale = 0;
  if (fast_range_scale(vertices.size(), vertex, &scale)) {
    const auto corner = [&](unsigned long long f, int k) {
      return scaled_by(vertex(triangles[f][k]), scale);
    };
    const detail::SolidMeasures measures =
        measure_on_cores(triangles.size(), corner, scaled_by(vertex(triangles[0][0]), scale));
    hull.volume = scale == 0 ? measures.volume() : std::ldexp(measures.volume(), 3 * scale);
    hull.area = scale == 0 ? measures.area() : std::ldexp(measures.area(), 2 * scale);
    return;
  }
  // Vertices more than 2^500 apart in magnitude: long double, from the same apex (no term negative).
  const Vec3d apex = vertex(triangles[0][0]);
  Wide six_volume = 0, twice_area = 0;
  for (const Triangle& t : triangles) {
    const Vec3d a = vertex(t[0]);
    const WideVec n = wide_cross(a, vertex(t[1]), vertex(t[2]));
    twice_area += wide_length(n);
    six_volume += n[0] * (Wide(a.x) - apex.x) + n[1] * (Wide(a.y) - apex.y) + n[2] * (Wide(a.z) - apex.z);
  }
  hull.volume = static_cast<double>(six_volume / 6);
  hull.area = static_cast<double>(twice_area / 2);
}

template <class Point>
ConvexHull describe_exact(const BasicHullMesh<Point>& mesh, std::string backend, bool neighbors = true) {
  ConvexHull hull;
  hull.dimension = mesh.dimension;
  hull.precision = precision_of<Point>();
  hull.backend = std::move(backend);
  hull.vertices = mesh.vertex_ids;
  std::sort(hull.vertices.begin(), hull.vertices.end());
  if (mesh.dimension == 2) {
    for (std::uint32_t corner : mesh.polygon)
      hull.polygon.push_back(mesh.vertex_ids[corner]);
    // The flat solid's surface: both sides of the polygon, each a fan of triangles from corner 0 (scaled
    // into the fast exact range as measure_solid() scales a solid).
    const auto corner = [&](std::size_t k) { return to_vec3d(mesh.vertices[mesh.polygon[k]]); };
    int scale = 0;
    if (fast_range_scale(mesh.polygon.size(), corner, &scale)) {
      // A convex polygon's fan: its triangles' normals all point one way, and their lengths add up.
      const auto at = [&](std::size_t k) { return scaled_by(corner(k), scale); };
      double twice_area = 0;
      for (std::size_t k = 1; k + 1 < mesh.polygon.size(); ++k) {
        const Vec3d o = at(0), p = at(k), q = at(k + 1);
        twice_area += detail::twice_triangle_area(o, p, q, detail::double_cross(o, p, q));
      }
      hull.area = std::ldexp(twice_area, 2 * scale);
    } else {
      WideVec sum{0, 0, 0};
      for (std::size_t k = 1; k + 1 < mesh.polygon.size(); ++k) {
        const WideVec n = wide_cross(corner(0), corner(k), corner(k + 1));
        for (int j = 0; j < 3; ++j)
          sum[j] += n[j];
      }
      hull.area = static_cast<double>(wide_length(sum));
    }
    return hull;
  }
  if (mesh.dimension != 3) return hull;

  hull.faces.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles)
    hull.faces.push_back({mesh.vertex_ids[t[0]], mesh.vertex_ids[t[1]], mesh.vertex_ids[t[2]]});
  measure_solid(mesh.vertices, mesh.triangles, hull);
  // Each face's plane on its own (on all cores: a sliver's is exact, and a hull of millions of faces has
  // some), so the result does not depend on the worker count.
  hull.planes.resize(mesh.triangles.size());
  // Vertices all in the fast exact range (every float, nearly every double): facet_plane()'s in-range path
  // without its test a face, which cost a small cloud more than its planes.
  bool in_range = true;
  if constexpr (std::is_same_v<Point, Point3d>) in_range = in_fast_exact_range(mesh.vertices);
  parallel_chunks(
      mesh.triangles.size(), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t f = begin; f < end; ++f) {
          const Triangle& t = mesh.triangles[f];
          const Vec3d a = to_vec3d(mesh.vertices[t[0]]), b = to_vec3d(mesh.vertices[t[1]]),
                      c = to_vec3d(mesh.vertices[t[2]]);
          if (in_range)
            detail::facet_plane_in_range(a, b, c, hull.planes[f].data());
          else
            hull.planes[f] = facet_plane(a, b, c);
        }
      },
      std::size_t{1} << 12);
  if (neighbors) hull.neighbors = face_neighbors(mesh.triangles, mesh.vertices.size());
  return hull;
}

// The absolute merge tolerance that `options` ask for, from the exact hull's vertices (the input's bounding
// box and largest magnitudes are its vertices').
template <class Point>
double merge_tolerance(const std::vector<Point>& vertices, const ConvexHullOptions& options) {
  if (options.merge == MergeMode::kQhull) return qhull_default_tolerance(vertices);
  double largest_side = 0;
  for (int axis = 0; axis < 3; ++axis) {
    double low = INFINITY, high = -INFINITY;
    for (const Point& p : vertices) {
      const double x = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
      low = std::min(low, x);
      high = std::max(high, x);
    }
    largest_side = std::max(largest_side, high - low);
  }
  return options.tolerance * largest_side;
}

// A merged hull (issue 25) from the exact one: merge_facets() works on the exact hull's vertices alone,
// since every input point is a convex combination of them, and its indices are mapped back to the input's.
template <class Point>
ConvexHull describe_merged(const BasicHullMesh<Point>& mesh, std::string backend,
                           const ConvexHullOptions& options) {
  BasicHullMesh<Point> local = mesh;
  for (std::size_t k = 0; k < local.vertex_ids.size(); ++k)
    local.vertex_ids[k] = static_cast<PointIndex>(k);
  const double cosine = std::clamp(options.angle_cosine, 0.0, 1.0);
  PhaseLaps laps("describe_merged");  // CUDAHULL_PHASE_TIMES=1
  MergedHull merged = merge_facets(mesh.vertices, local, merge_tolerance(mesh.vertices, options),
                                   std::sqrt(1 - cosine * cosine));
  ConvexHull hull;
  hull.dimension = 3;
  hull.precision = precision_of<Point>();
  hull.backend = std::move(backend);
  hull.tolerance = merged.tolerance;
  hull.max_outside = merged.max_outside;
  hull.thinnest = merged.thinnest;
  for (PointIndex v : merged.vertices)
    hull.vertices.push_back(mesh.vertex_ids[v]);
  std::sort(hull.vertices.begin(), hull.vertices.end());
  // merged's indices are positions in mesh.vertices (local's ids): its faces are the mesh's triangles.
  hull.faces.reserve(merged.faces.size());
  for (const Triangle& face : merged.faces)
    hull.faces.push_back({mesh.vertex_ids[face[0]], mesh.vertex_ids[face[1]], mesh.vertex_ids[face[2]]});
  laps.lap("merge and faces");
  measure_solid(mesh.vertices, merged.faces, hull);
  laps.lap("measures");
  hull.planes = std::move(merged.planes);
  hull.neighbors = std::move(merged.neighbors);
  laps.lap("planes and neighbours");
  for (const auto& row : merged.coplanar)
    hull.coplanar.push_back({mesh.vertex_ids[row[0]], row[1], mesh.vertex_ids[row[2]]});
  return hull;
}

// The result convex_hull() returns for the exact hull `mesh`, merged where `options` ask for it (a flat hull
// has nothing to merge).
template <class Point>
ConvexHull describe(const BasicHullMesh<Point>& mesh, std::string backend, const ConvexHullOptions& options,
                    bool neighbors = true) {
  if (options.merge == MergeMode::kExact || mesh.dimension != 3)
    return describe_exact(mesh, std::move(backend), neighbors);
  return describe_merged(mesh, std::move(backend), options);
}

// The hull of checked points in Point, run as `plan` says (plan_hull(): engine and backend definite).
template <class Point>
ConvexHull run_planned(const std::vector<Point>& points, const HullPlan& plan,
                       const ConvexHullOptions& options, bool neighbors) {
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  if (plan.engine == EngineChoice::kResident) {
    ResidentStats stats;
    ConvexHull hull;
    if (plan.backend == BackendChoice::kCuda) {
      ResidentCudaHull<Point> resident;
      resident.upload(points);
      hull = describe(resident.run(&stats), "cuda-resident", options);
    } else {
      hull = describe(resident_hull_host(points, &stats), "cpu-resident", options);
    }
    hull.resident_stats = std::move(stats);
    return hull;
  }
  if (plan.small_cloud) {
    BasicHullMesh<Point> mesh;
    if (small_hull_host(points.data(), points.size(), mesh)) return describe(mesh, "cpu", options, neighbors);
  }
  std::unique_ptr<BasicBackend<Point>> backend =
      plan.backend == BackendChoice::kCuda ? make_cuda_backend<Point>() : make_cpu_backend<Point>();
  std::string name = backend->name();
  BasicEngine<Point> engine(points, std::move(backend), EngineOptions{.keep_decisions = false});
  engine.run();
  return describe(engine.result(), std::move(name), options, neighbors);
}

// run_planned(), the result saying how it ran.
template <class Point>
ConvexHull hull_in(const std::vector<Point>& points, const HullPlan& plan, const ConvexHullOptions& options,
                   bool neighbors = true) {
  ConvexHull hull = run_planned(points, plan, options, neighbors);
  hull.plan = plan.reason;
  return hull;
}

template <class Scalar>
auto array_coordinate(const Scalar* xyz) {
  return [xyz](std::size_t i, int axis) -> double { return xyz[3 * i + axis]; };
}

// Double points with a coordinate outside the engines' exact range (a subnormal, 1e300): exact_hull_any()
// on the host, exact for every finite double.  Merging needs plane_through()'s range for its heights and
// certificate: where the hull's vertices are outside it the exact hull is returned (tolerance 0).
ConvexHull wide_hull(const std::vector<Point3d>& points, const ConvexHullOptions& options) {
  const HullMeshd mesh = exact_hull_any(points);
  ConvexHullOptions exact = options;
  if (!in_fast_exact_range(mesh.vertices)) exact.merge = MergeMode::kExact;
  return describe(mesh, "cpu-wide", exact);
}

// The hull of `count` points read by `coordinate(i, axis)`, whose own precision is `own`: read in the
// plan's precision, then planned with their range known.
template <class Coordinate>
ConvexHull checked_hull(std::size_t count, Coordinate coordinate, Precision own,
                        const ConvexHullOptions& options, bool neighbors = true) {
  HullInput input;
  input.precision = own;
  input.count = count;
  if (plan_precision(options.precision, own).precision == Precision::kDouble) {
    const std::vector<Point3d> points = copy_checked<Point3d>(count, coordinate);
    input.outside_exact_range = !in_fast_exact_range(points);
    const HullPlan plan = plan_hull(options, input, cuda_presence);
    if (plan.wide_range) {
      ConvexHull hull = wide_hull(points, options);
      hull.plan = plan.reason;
      return hull;
    }
    return hull_in(points, plan, options, neighbors);
  }
  return hull_in(copy_checked<Point3>(count, coordinate), plan_hull(options, input, cuda_presence), options,
                 neighbors);
}

// The hull of points that only the current device holds, in Point: checked (and converted) there, then
// borrowed by the resident engine.
template <class Point, class Scalar>
ConvexHull device_hull_in(const Scalar* device_xyz, std::size_t count, const ConvexHullOptions& options) {
  CheckedDevicePoints<Point> checked = check_device_points<Point>(device_xyz, count);
  if (checked.first_bad != count) {
    // Named from its own coordinates by the host path's check, so the message is the same word for word.
    const std::array<double, 3> p = read_device_point(device_xyz, checked.first_bad);
    const double widened[3] = {p[0], p[1], p[2]};
    throw_if_rejected<Point>(checked.first_bad, widened);
    // Finite, but outside the engines' exact range (the device's check refuses that too): the host's wide
    // path, on a copy of every point, checked there again.
    if constexpr (std::is_same_v<Point, Point3d>) {
      const std::vector<Scalar> host = download_values(device_xyz, 3 * count);
      return checked_hull(count, array_coordinate(host.data()), Precision::kDouble, options);
    }
    throw std::logic_error("convex_hull_device: point " + std::to_string(checked.first_bad) +
                           " failed the device's check but passes the host's");
  }
  ResidentCudaHull<Point> resident;
  resident.use_device_points(checked.points, count);
  ResidentStats stats;
  const Clock::time_point run_start = Clock::now();
  const BasicHullMesh<Point> mesh = resident.run(&stats);
  const Clock::time_point describe_start = Clock::now();
  ConvexHull hull = describe(mesh, "cuda-resident", options);
  hull.engine_ms = std::chrono::duration<double, std::milli>(describe_start - run_start).count();
  hull.describe_ms = ms_since(describe_start);
  stats.host_syncs += checked.host_syncs;
  stats.bytes_from_device += checked.bytes_from_device;
  hull.resident_stats = std::move(stats);
  return hull;
}

// The plan for `count` points of `dimension` in GPU memory, whose own precision is `own`.
HullPlan device_plan(std::size_t count, int dimension, Precision own, const ConvexHullOptions& options) {
  HullInput input;
  input.precision = own;
  input.dimension = dimension;
  input.count = count;
  input.on_device = true;
  return plan_hull(options, input, cuda_presence);
}

// What points in GPU memory need before they are read: a CUDA backend, a device (plan_hull() says which is
// missing), and memory of the current device.  Throws as convex_hull_device() documents.
void require_device_points(const void* device_points, std::size_t count, const HullPlan& plan) {
  if (plan.backend == BackendChoice::kCpu) throw std::invalid_argument(plan.unavailable);
  check_count(count);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  if (count != 0) require_current_device_memory(device_points);
}

template <class Scalar>
ConvexHull device_hull(const Scalar* device_xyz, std::size_t count, Precision own,
                       const ConvexHullOptions& options) {
  const HullPlan plan = device_plan(count, 3, own, options);
  require_device_points(device_xyz, count, plan);
  ConvexHull hull = plan.precision == Precision::kDouble ? device_hull_in<Point3d>(device_xyz, count, options)
                                                         : device_hull_in<Point3>(device_xyz, count, options);
  if (hull.plan.empty()) hull.plan = plan.reason;  // the wide path's host hull says its own
  return hull;
}

// The hull of `count` x, y, z triples in host memory.  For the resident engine on the GPU they are uploaded
// as they are and checked (or converted) there, as convex_hull_device() does: the engine needs no host
// copy of them (it reads back the few coordinates its exact checks need), and the copy would cost more
// than the hull.  Otherwise they are checked into a host copy.
template <class Scalar>
ConvexHull array_hull(const Scalar* xyz, std::size_t count, Precision own, const ConvexHullOptions& options,
                      bool neighbors = true) {
  HullInput input;
  input.precision = own;
  input.count = count;
  if (plan_hull(options, input, cuda_presence).upload_first) {
    check_count(count);
    const std::shared_ptr<void> copy = upload_to_device(xyz, count * 3 * sizeof(Scalar));
    return device_hull(static_cast<const Scalar*>(copy.get()), count, own, options);
  }
  return checked_hull(count, array_coordinate(xyz), own, options, neighbors);
}

template <class Point>
auto vector_coordinate(const std::vector<Point>& points) {
  return [&points](std::size_t i, int axis) -> double {
    return axis == 0 ? points[i].x : axis == 1 ? points[i].y : points[i].z;
  };
}

// --- 2-D input (issue 25) ------------------------------------------------------------------------------
//
// design:
//   check the points in place (finite; rounded to float first only for kFloat on double input, a copy)
//   double input outside the exact range: wide_planar_hull() (exact_hull_any on the points lifted to z = 0)
//   else planar_hull(): the corners, counter-clockwise from the lowest (x, y)
//   merged (tolerance): drop the flattest corner while it lies within the tolerance of the line through its
//     neighbours (a heap of heights, neighbours updated); a triangle still that thin is reported flat
//   the edges, their lines (unit outward normal and offset), area and perimeter; for a merged polygon the
//     dropped corners in coplanar and max_outside, the proven bound on every point's height

// Throws the InputError naming the first point the exact hull cannot take (a NaN or an infinity); returns
// whether any double coordinate is outside the engines' exact range (the wide path's input).
template <class Input>
bool check_planar(const Input* xy, std::size_t count) {
  check_count(count);
  const unsigned workers = hardware_workers();
  std::vector<std::size_t> first_bad(workers, count);
  std::vector<char> wide(workers, 0);
  parallel_chunks(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        bool outside = false;
        for (std::size_t i = begin; i < end; ++i) {
          const double x = static_cast<double>(xy[2 * i]), y = static_cast<double>(xy[2 * i + 1]);
          if (!std::isfinite(x) || !std::isfinite(y)) {
            first_bad[worker] = i;
            break;
          }
          if constexpr (std::is_same_v<Input, double>)
            outside = outside || !in_fast_exact_range(x) || !in_fast_exact_range(y);
        }
        wide[worker] = outside;
      },
      std::size_t{1} << 16);
  const std::size_t bad = *std::min_element(first_bad.begin(), first_bad.end());
  if (bad != count) {
    const double widened[3] = {static_cast<double>(xy[2 * bad]), static_cast<double>(xy[2 * bad + 1]), 0};
    throw_if_rejected<Point3d>(bad, widened);
  }
  return std::any_of(wide.begin(), wide.end(), [](char w) { return w != 0; });
}

// Double points rounded to float once, checked as the 3-D points are (one beyond float's range named).
std::vector<float> rounded_planar(const double* xy, std::size_t count) {
  std::vector<float> out(2 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const double widened[3] = {xy[2 * i], xy[2 * i + 1], 0};
    int axis = 0;
    Point3 p;
    if (rejection(widened, axis, p)) throw_if_rejected<Point3>(i, widened);
    out[2 * i] = p.x;
    out[2 * i + 1] = p.y;
  }
  return out;
}

using Wide = long double;  // 64-bit significand, 15-bit exponent: no double difference over- or underflows

// The outward line of the counter-clockwise edge a -> b, for any finite doubles: the normal from the
// difference in long double (exact unless the coordinates' exponents are 64 apart), rounded once, and the
// offset that puts both ends on or just below the line.
std::array<double, 3> outward_line(double ax, double ay, double bx, double by) {
  const Wide dx = Wide(bx) - Wide(ax), dy = Wide(by) - Wide(ay);
  const Wide length = std::sqrt(dx * dx + dy * dy);
  const double nx = static_cast<double>(dy / length), ny = static_cast<double>(-dx / length);
  return {nx, ny,
          static_cast<double>(-std::max(Wide(nx) * ax + Wide(ny) * ay, Wide(nx) * bx + Wide(ny) * by))};
}

// Qhull's roundoff tolerance for 2-D input: its MINoutside, 4 x DISTround, with qh_distround()'s 2-D
// constants (qhull_default_tolerance() in facet_merge.hpp has the 3-D ones and the source).  The largest
// magnitudes are the corners': |x| is convex, so its maximum over the points is at a corner.
double planar_qhull_tolerance(double largest_x, double largest_y) {
  const double maxabs = std::max(largest_x, largest_y), maxsumabs = largest_x + largest_y;
  return 4 * std::numeric_limits<double>::epsilon() *
         (2 * std::min(std::sqrt(2.0) * maxabs, maxsumabs) * 1.01 + maxabs);
}

// `xy` holds the points planar_hull() saw; `original`, where given, maps their indices to the input's (the
// device filter's survivors).
template <class Scalar>
ConvexHull describe_planar(const Scalar* xy, PlanarHull planar, const ConvexHullOptions& options,
                           std::string backend, const std::vector<PointIndex>* original = nullptr) {
  ConvexHull hull;
  hull.input_dimension = 2;
  hull.dimension = planar.dimension;
  hull.precision = std::is_same_v<Scalar, double> ? Precision::kDouble : Precision::kFloat;
  hull.backend = std::move(backend);
  auto x = [&](PointIndex i) { return static_cast<double>(xy[2 * i]); };
  auto y = [&](PointIndex i) { return static_cast<double>(xy[2 * i + 1]); };
  // A corner's height over the line through its neighbours: how far the polygon moves if it is dropped.
  auto height = [&](PointIndex previous, PointIndex corner, PointIndex next) {
    const std::array<double, 3> line = outward_line(x(previous), y(previous), x(next), y(next));
    return static_cast<double>(Wide(line[0]) * x(corner) + Wide(line[1]) * y(corner) + Wide(line[2]));
  };
  const std::vector<PointIndex> exact = std::move(planar.polygon);
  std::vector<char> kept(exact.size(), 1);
  const bool merging = planar.dimension == 2 && options.merge != MergeMode::kExact;
  if (merging) {
    double largest[2] = {0, 0}, low[2] = {INFINITY, INFINITY}, high[2] = {-INFINITY, -INFINITY};
    for (PointIndex v : exact) {
      const double c[2] = {x(v), y(v)};
      for (int axis = 0; axis < 2; ++axis) {
        largest[axis] = std::max(largest[axis], std::fabs(c[axis]));
        low[axis] = std::min(low[axis], c[axis]);
        high[axis] = std::max(high[axis], c[axis]);
      }
    }
    hull.tolerance = options.merge == MergeMode::kQhull
                         ? planar_qhull_tolerance(largest[0], largest[1])
                         : options.tolerance * std::max(high[0] - low[0], high[1] - low[1]);
    // The flattest corner first; a dropped corner changes only its two neighbours' heights.
    const std::size_t m = exact.size();
    std::vector<std::size_t> previous(m), next(m);
    std::vector<double> heights(m);
    using Entry = std::pair<double, std::size_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    for (std::size_t k = 0; k < m; ++k) {
      previous[k] = (k + m - 1) % m;
      next[k] = (k + 1) % m;
      heights[k] = height(exact[previous[k]], exact[k], exact[next[k]]);
      queue.push({heights[k], k});
    }
    std::size_t left = m;
    while (!queue.empty()) {
      const auto [h, k] = queue.top();
      queue.pop();
      if (!kept[k] || h != heights[k]) continue;  // dropped, or an old height
      if (h > hull.tolerance) break;
      if (left == 3) {
        // Thinner than the tolerance: flat.  The segment's ends are the other two corners.
        hull.dimension = 1;
        break;
      }
      kept[k] = 0;
      --left;
      const std::size_t a = previous[k], b = next[k];
      next[a] = b;
      previous[b] = a;
      for (const std::size_t c : {a, b}) {
        heights[c] = height(exact[previous[c]], exact[c], exact[next[c]]);
        queue.push({heights[c], c});
      }
    }
  }
  std::vector<PointIndex> corners;
  for (std::size_t k = 0; k < exact.size(); ++k)
    if (kept[k]) corners.push_back(exact[k]);
  if (hull.dimension == 1 && planar.dimension == 2) {
    // The flattest of the last three corners dropped: the two others are the segment's ends.
    std::size_t flattest = 0;
    double lowest = INFINITY;
    for (std::size_t k = 0; k < 3; ++k) {
      const double h = height(corners[(k + 2) % 3], corners[k], corners[(k + 1) % 3]);
      if (h < lowest) lowest = h, flattest = k;
    }
    corners.erase(corners.begin() + static_cast<std::ptrdiff_t>(flattest));
  }
  hull.polygon = corners;
  hull.vertices = corners;
  std::sort(hull.vertices.begin(), hull.vertices.end());
  if (hull.dimension == 2) {
    const std::size_t m = corners.size();
    std::vector<std::size_t> edge_of(exact.size());  // the edge that covers each exact corner
    for (std::size_t k = 0, e = 0; k < exact.size(); ++k) {
      if (kept[k] && k != 0 && exact[k] != corners[0]) ++e;
      edge_of[k] = e % m;
    }
    // Corners before the first kept one lie on the last edge.
    for (std::size_t k = 0; k < exact.size() && !kept[k]; ++k)
      edge_of[k] = m - 1;
    Wide perimeter = 0, twice_area = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const PointIndex a = corners[k], b = corners[(k + 1) % m];
      hull.edges.push_back({a, b});
      // Opposite a lies the edge that goes on from b; opposite b the one that comes into a.
      hull.edge_neighbors.push_back(
          {static_cast<std::int32_t>((k + 1) % m), static_cast<std::int32_t>((k + m - 1) % m)});
      hull.lines.push_back(outward_line(x(a), y(a), x(b), y(b)));
      const Wide dx = Wide(x(b)) - x(a), dy = Wide(y(b)) - y(a);
      perimeter += std::sqrt(dx * dx + dy * dy);
      // The shoelace sum from the first corner: every term's triangle lies inside the convex polygon.
      twice_area += (Wide(x(a)) - x(corners[0])) * (Wide(y(b)) - y(corners[0])) -
                    (Wide(y(a)) - y(corners[0])) * (Wide(x(b)) - x(corners[0]));
    }
    hull.area = static_cast<double>(perimeter);
    hull.volume = static_cast<double>(twice_area / 2);
    if (merging) {
      // The certificate.  A dropped corner p lies beyond the edge that covers it: a point of that segment
      // is on or below every line (the merged polygon is convex), so p's height over any line is at most
      // its distance to the segment.  A kept corner is on its own lines and below the others, but for the
      // lines' rounding: a normal within a few ulps of the exact one, so 16u (|x| + |y| + |d|) bounds it.
      constexpr double kUnit = 0x1p-53;
      double rounding = 0;
      for (std::size_t e = 0; e < m; ++e) {
        const PointIndex a = corners[e];
        rounding = std::max(rounding,
                            16 * kUnit * (std::fabs(x(a)) + std::fabs(y(a)) + std::fabs(hull.lines[e][2])));
      }
      double beyond = 0;
      for (std::size_t k = 0; k < exact.size(); ++k) {
        if (kept[k]) continue;
        const PointIndex p = exact[k];
        const std::size_t e = edge_of[k];
        const PointIndex a = hull.edges[e][0], b = hull.edges[e][1];
        const Wide ux = Wide(x(b)) - x(a), uy = Wide(y(b)) - y(a), px = Wide(x(p)) - x(a),
                   py = Wide(y(p)) - y(a);
        const Wide t = std::clamp((px * ux + py * uy) / (ux * ux + uy * uy), Wide(0), Wide(1));
        const Wide distance = std::hypot(px - t * ux, py - t * uy);
        beyond = std::max(beyond, static_cast<double>(distance * (1 + 8 * Wide(kUnit))));
        const Wide to_a = std::hypot(px, py), to_b = std::hypot(Wide(x(p)) - x(b), Wide(y(p)) - y(b));
        hull.coplanar.push_back({p, static_cast<PointIndex>(e), to_a <= to_b ? a : b});
      }
      hull.max_outside = beyond + rounding;
    }
  }
  if (original) {
    auto map = [&](PointIndex& i) { i = (*original)[i]; };
    std::for_each(hull.polygon.begin(), hull.polygon.end(), map);
    std::for_each(hull.vertices.begin(), hull.vertices.end(), map);
    for (auto& edge : hull.edges)
      map(edge[0]), map(edge[1]);
    for (auto& row : hull.coplanar)
      map(row[0]), map(row[2]);
    std::sort(hull.vertices.begin(), hull.vertices.end());
  }
  return hull;
}

// planar_hull() for double points with coordinates outside the exact range: the points lifted to z = 0
// and exact_hull_any() (exact for every finite double), its polygon turned counter-clockwise in the plane
// and started at the lowest (x, y) corner, as planar_hull() gives it.
PlanarHull wide_planar_hull(const double* xy, std::size_t count) {
  std::vector<Point3d> lifted(count);
  for (std::size_t i = 0; i < count; ++i)
    lifted[i] = {xy[2 * i], xy[2 * i + 1], 0};
  const HullMeshd mesh = exact_hull_any(lifted);
  PlanarHull planar;
  planar.dimension = mesh.dimension;
  if (mesh.dimension == 2) {
    for (std::uint32_t corner : mesh.polygon)
      planar.polygon.push_back(mesh.vertex_ids[corner]);
    const PointIndex a = planar.polygon[0], b = planar.polygon[1], c = planar.polygon[2];
    if (orient2d_wide(xy[2 * a], xy[2 * a + 1], xy[2 * b], xy[2 * b + 1], xy[2 * c], xy[2 * c + 1]) < 0)
      std::reverse(planar.polygon.begin(), planar.polygon.end());
  } else {
    planar.polygon = mesh.vertex_ids;
  }
  auto lower = [&](PointIndex a, PointIndex b) {
    return xy[2 * a] != xy[2 * b] ? xy[2 * a] < xy[2 * b] : xy[2 * a + 1] < xy[2 * b + 1];
  };
  if (!planar.polygon.empty())
    std::rotate(planar.polygon.begin(), std::min_element(planar.polygon.begin(), planar.polygon.end(), lower),
                planar.polygon.end());
  return planar;
}

template <class Input>
ConvexHull planar_hull_of(const Input* xy, std::size_t count, Precision own,
                          const ConvexHullOptions& options) {
  HullInput input;
  input.precision = own;
  input.dimension = 2;
  input.count = count;
  const HullPlan plan = plan_hull(options, input, cuda_presence);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  if constexpr (std::is_same_v<Input, double>) {
    if (plan.precision == Precision::kFloat) {
      check_planar(xy, count);  // a NaN named before a value beyond float's range, as in 3-D
      const std::vector<float> rounded = rounded_planar(xy, count);
      ConvexHull hull = describe_planar(rounded.data(), planar_hull(rounded.data(), count), options, "cpu");
      hull.plan = plan.reason;
      return hull;
    }
  }
  // In place: float input in double is the same points (widening is exact), and so the same hull.
  input.outside_exact_range = check_planar(xy, count);
  if constexpr (std::is_same_v<Input, double>) {
    if (const HullPlan wide = plan_hull(options, input, cuda_presence); wide.wide_range) {
      ConvexHullOptions exact = options;
      exact.merge = MergeMode::kExact;  // the merge's heights need the exact range: the exact hull instead
      ConvexHull hull = describe_planar(xy, wide_planar_hull(xy, count), exact, "cpu-wide");
      hull.plan = wide.reason;
      return hull;
    }
  }
  ConvexHull hull = describe_planar(xy, planar_hull(xy, count), options, "cpu");
  hull.precision = plan.precision;
  hull.plan = plan.reason;
  return hull;
}

// 2-D points in device memory: the device filters them (planar_filter.hpp) and the host finishes on the
// survivors, which keep every corner and, in input order, every duplicate of one.
template <class Scalar>
ConvexHull device_planar_hull(const Scalar* device_xy, std::size_t count, const ConvexHullOptions& options) {
  const HullPlan plan =
      device_plan(count, 2, std::is_same_v<Scalar, double> ? Precision::kDouble : Precision::kFloat, options);
  require_device_points(device_xy, count, plan);
  if (plan.precision == Precision::kFloat && std::is_same_v<Scalar, double>) {
    // Rounded to float first: on the host, which rounds as the NumPy path does.
    const std::vector<Scalar> host = download_values(device_xy, 2 * count);
    return convex_hull_2d(host.data(), count, options);
  }
  PlanarCandidates<Scalar> candidates = planar_candidates(device_xy, count);
  if (candidates.first_bad != count) {
    const std::array<double, 3> p = read_device_point_2d(device_xy, candidates.first_bad);
    const double widened[3] = {p[0], p[1], 0};
    throw_if_rejected<Point3d>(candidates.first_bad, widened);
  }
  // Finite but outside the exact range (the device refuses that too), or a degenerate input: the host's
  // path on a copy, and its backend's name.
  if (candidates.first_bad != count || candidates.degenerate) {
    const std::vector<Scalar> host = download_values(device_xy, 2 * count);
    return convex_hull_2d(host.data(), count, options);
  }
  ConvexHull hull =
      describe_planar(candidates.xy.data(), planar_hull(candidates.xy.data(), candidates.indices.size()),
                      options, "cuda", &candidates.indices);
  hull.precision = plan.precision;
  hull.plan = plan.reason;
  return hull;
}

}  // namespace

template <class Point>
std::unique_ptr<BasicBackend<Point>> make_backend(BackendChoice choice, std::string* chosen_because) {
  ConvexHullOptions request;
  request.backend = choice;
  request.engine = EngineChoice::kStepping;  // the backends are the stepping engine's
  HullInput input;
  input.precision = precision_of<Point>();
  const HullPlan plan = plan_hull(request, input);
  if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
  if (chosen_because) *chosen_because = plan.backend_reason;
  if (plan.backend == BackendChoice::kCuda) return make_cuda_backend<Point>();
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
ConvexHull hull_from_mesh(const BasicHullMesh<Point>& mesh, std::string backend,
                          const ConvexHullOptions& options, bool neighbors) {
  if (!neighbors && options.merge == MergeMode::kExact)
    return describe_exact(mesh, std::move(backend), false);
  return describe(mesh, std::move(backend), options);
}

template ConvexHull hull_from_mesh(const HullMesh&, std::string, const ConvexHullOptions&, bool);
template ConvexHull hull_from_mesh(const HullMeshd&, std::string, const ConvexHullOptions&, bool);

template std::unique_ptr<BasicBackend<Point3>> make_backend(BackendChoice, std::string*);
template std::unique_ptr<BasicBackend<Point3d>> make_backend(BackendChoice, std::string*);

ConvexHull convex_hull(const std::vector<Point3>& points, const ConvexHullOptions& options) {
  return checked_hull(points.size(), vector_coordinate(points), Precision::kFloat, options);
}

ConvexHull convex_hull(const std::vector<Point3d>& points, const ConvexHullOptions& options) {
  return checked_hull(points.size(), vector_coordinate(points), Precision::kDouble, options);
}

ConvexHull convex_hull(const float* xyz, std::size_t count, const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kFloat, options);
}

ConvexHull convex_hull(const double* xyz, std::size_t count, const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kDouble, options);
}

namespace {

// small_cloud_hull() in Point: the points read into this thread's buffer (rejection() converts them as
// copy_checked() does), the small hull into this thread's mesh, described as hull_in() describes it.
template <class Point, class Scalar>
bool small_cloud_in(const Scalar* xyz, std::size_t count, ConvexHull& hull) {
  thread_local std::vector<Point> points;
  thread_local BasicHullMesh<Point> mesh;
  points.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double widened[3] = {static_cast<double>(xyz[3 * i]), static_cast<double>(xyz[3 * i + 1]),
                               static_cast<double>(xyz[3 * i + 2])};
    int axis = 0;
    if (rejection(widened, axis, points[i])) return false;
  }
  if constexpr (std::is_same_v<Point, Point3d>) {
    if (!in_fast_exact_range(points.data(), count)) return false;
  }
  if (!small_hull_host(points.data(), count, mesh)) return false;
  hull = describe_exact(mesh, "cpu", false);
  return true;
}

}  // namespace

template <class Scalar>
bool small_cloud_hull(const Scalar* xyz, std::size_t count, const ConvexHullOptions& options,
                      ConvexHull& hull) {
  // As plan_hull() sets small_cloud, for a request whose backend and precision the batch has resolved.
  if (options.merge != MergeMode::kExact || options.engine != EngineChoice::kAuto ||
      options.backend != BackendChoice::kCpu || count < 4 || count > kSmallHullPoints)
    return false;
  const Precision own = std::is_same_v<Scalar, double> ? Precision::kDouble : Precision::kFloat;
  if (plan_precision(options.precision, own).precision == Precision::kDouble)
    return small_cloud_in<Point3d>(xyz, count, hull);
  return small_cloud_in<Point3>(xyz, count, hull);
}

template bool small_cloud_hull(const float*, std::size_t, const ConvexHullOptions&, ConvexHull&);
template bool small_cloud_hull(const double*, std::size_t, const ConvexHullOptions&, ConvexHull&);

ConvexHull convex_hull_without_neighbors(const float* xyz, std::size_t count,
                                         const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kFloat, options, false);
}

ConvexHull convex_hull_without_neighbors(const double* xyz, std::size_t count,
                                         const ConvexHullOptions& options) {
  return array_hull(xyz, count, Precision::kDouble, options, false);
}

ConvexHull convex_hull_device(const float* device_xyz, std::size_t count, const ConvexHullOptions& options) {
  return device_hull(device_xyz, count, Precision::kFloat, options);
}

ConvexHull convex_hull_device(const double* device_xyz, std::size_t count, const ConvexHullOptions& options) {
  return device_hull(device_xyz, count, Precision::kDouble, options);
}

ConvexHull convex_hull_2d(const float* xy, std::size_t count, const ConvexHullOptions& options) {
  return planar_hull_of(xy, count, Precision::kFloat, options);
}

ConvexHull convex_hull_2d(const double* xy, std::size_t count, const ConvexHullOptions& options) {
  return planar_hull_of(xy, count, Precision::kDouble, options);
}

ConvexHull convex_hull_2d_device(const float* device_xy, std::size_t count,
                                 const ConvexHullOptions& options) {
  return device_planar_hull(device_xy, count, options);
}

ConvexHull convex_hull_2d_device(const double* device_xy, std::size_t count,
                                 const ConvexHullOptions& options) {
  return device_planar_hull(device_xy, count, options);
}

CudaStatus cuda_presence() {
  CudaStatus status;
  status.usable = cuda_device_present(&status.reason);
  return status;
}

CudaStatus cuda_status() {
  const CudaDeviceInfo device = query_cuda_device();
  return {device.usable, device.name, device.reason};
}

void release_device_memory() {
  release_device_memory_now();  // no device, or none cudahull allocated on: nothing
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

const char* choice_name(BackendChoice choice) {
  return choice == BackendChoice::kCpu ? "cpu" : choice == BackendChoice::kCuda ? "cuda" : "auto";
}

const char* choice_name(EngineChoice choice) {
  return choice == EngineChoice::kStepping   ? "stepping"
         : choice == EngineChoice::kResident ? "resident"
                                             : "auto";
}

MergeMode merge_from_name(const std::string& name) {
  if (name == "exact") return MergeMode::kExact;
  if (name == "qhull") return MergeMode::kQhull;
  if (name == "relative") return MergeMode::kRelative;
  throw std::invalid_argument("merge must be exact, qhull or relative, not '" + name + "'");
}

Precision precision_from_name_strict(const std::string& name) {
  if (name == "auto" || name == "float" || name == "double") return precision_from_name(name);
  throw std::invalid_argument("precision must be auto, float or double, not '" + name + "'");
}

}  // namespace cudahull
