// describe_exact() and describe() (describe.hpp): a hull's result from its exact mesh.
#include "describe.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "cudahull/detail/plane_impl.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/plane.hpp"
#include "cudahull/qhull_scaling.hpp"
#include "facet_merge.hpp"

namespace cudahull {

namespace {

// Face neighbours in two steps: neighbors[f][k] = the face holding the reverse of the edge opposite corner
// k (each directed edge appears once in a closed 2-manifold with consistent orientation).  Each face's
// corners are grouped by vertex (a counting sort, on one core: FaceCorners), with the corners after and
// before them; at vertex a, the face across f's edge a -> b is the face of a whose corner before a is b,
// found among a's few corners, read together, by selects (face_neighbors(), on all cores).  A search of b's
// edges for a, branching on each, mispredicted most of the time; sorting all edges, before that, took most
// of a 28K-face hull's time outside the engine.
struct FaceCorners {
  struct Corner {
    std::uint32_t face, k, after, before;  // face's corner k; the corners after and before it
  };
  std::vector<std::uint32_t> start;  // per vertex, into `corners`; one more at the end
  std::vector<Corner> corners;

  FaceCorners(const std::vector<Triangle>& triangles, std::size_t vertex_count) : start(vertex_count + 1, 0) {
    for (const Triangle& t : triangles) {
      for (int k = 0; k < 3; ++k)
        ++start[t[k] + 1];
    }
    for (std::size_t v = 0; v < vertex_count; ++v)
      start[v + 1] += start[v];
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    corners.resize(3 * triangles.size());
    for (std::uint32_t f = 0; f < triangles.size(); ++f) {
      for (std::uint32_t k = 0; k < 3; ++k)
        corners[fill[triangles[f][k]]++] = {f, k, triangles[f][(k + 1) % 3], triangles[f][(k + 2) % 3]};
    }
  }
};

std::vector<std::array<std::int32_t, 3>> face_neighbors(const FaceCorners& index, std::size_t faces) {
  constexpr std::uint32_t kNoFace = 0xffffffffu;
  const std::vector<std::uint32_t>& start = index.start;
  const std::vector<FaceCorners::Corner>& corners = index.corners;
  const std::size_t vertex_count = start.size() - 1;
  std::vector<std::array<std::int32_t, 3>> neighbors(faces);
  // Each corner writes its own entry: the vertices on all cores (a small mesh's on this thread, where
  // waking the workers would cost more).
  const unsigned workers = workers_from(vertex_count, 1024);
  parallel_blocks(vertex_count, workers, [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t v = begin; v < end; ++v) {
      for (std::uint32_t i = start[v]; i < start[v + 1]; ++i) {
        // Corner k's edge k -> k + 1 is opposite corner k + 2.
        std::uint32_t found = kNoFace;
        for (std::uint32_t j = start[v + 1]; j-- > start[v];) {  // last to first: the first match stays
          const std::uint32_t match = 0u - static_cast<std::uint32_t>(corners[j].before == corners[i].after);
          found = (found & ~match) | (corners[j].face & match);
        }
        if (found == kNoFace) throw std::logic_error("convex_hull: the mesh is not closed");
        neighbors[corners[i].face][(corners[i].k + 2) % 3] = static_cast<std::int32_t>(found);
      }
    }
  });
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

// A mesh of one chunk with more than this many faces has its faces' terms found on all cores and added on
// one, in measure_mesh()'s order (its bits).
constexpr std::size_t kMeasureTermsOnCores = 2048;

// measure_mesh()'s sums (the same bits) of a mesh of one chunk from its faces' terms found elsewhere (on
// all cores): added in face order on this core; the volume's exact pass, where the bounds ask for it, on all
// cores.
template <class Terms, class Corner>
detail::SolidMeasures sum_face_terms(const Terms& terms, std::size_t faces, const Corner& corner,
                                     const Vec3d& apex) {
  using detail::SolidMeasures;
  SolidMeasures measures;
  double error_sums[SolidMeasures::kErrorSums] = {};
  for (std::size_t f = 0; f < faces; ++f) {
    measures.add_terms(terms[f]);
    double& sum = error_sums[f % SolidMeasures::kErrorSums];
    sum = detail::add_rn(sum, terms[f].six_volume_error);
  }
  for (const double sum : error_sums)
    measures.six_volume_error = detail::add_rn(measures.six_volume_error, sum);
  if (measures.volume_uncertain()) {
    PassVector<double> exact(faces);
    parallel_blocks(faces, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
      for (std::size_t f = begin; f < end; ++f)
        exact[f] = SolidMeasures::exact_six_volume(corner(f, 0), corner(f, 1), corner(f, 2), apex);
    });
    measures.exact_volume_pass();
    for (const double term : exact)
      measures.add_exact(term);
  }
  return measures;
}

template <class Corner>
detail::SolidMeasures measure_on_cores(std::size_t faces, const Corner& corner, const Vec3d& apex) {
  if (faces <= kMeasureTermsOnCores) return detail::measure_mesh(faces, corner, apex);
  if (faces <= kMeasureChunk) {
    using detail::SolidMeasures;
    PassVector<SolidMeasures::FaceTerms> terms(faces);
    parallel_blocks(faces, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
      for (std::size_t f = begin; f < end; ++f)
        terms[f] = SolidMeasures::face_terms(corner(f, 0), corner(f, 1), corner(f, 2), apex);
    });
    return sum_face_terms(terms, faces, corner, apex);
  }
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

// `measures` of a solid scaled by 2^-scale (fast_range_scale()) into `hull`'s volume and area.
void set_measures(const detail::SolidMeasures& measures, int scale, ConvexHull& hull) {
  hull.volume = scale == 0 ? measures.volume() : std::ldexp(measures.volume(), 3 * scale);
  hull.area = scale == 0 ? measures.area() : std::ldexp(measures.area(), 2 * scale);
}

// The solid's volume and surface area into `hull`, over `triangles` (outward, indices into `vertices`):
// detail::measure_mesh() (plane_impl.hpp, as the batch's device describe: the same bits), its apex the first
// triangle's first corner; scaled into the fast exact range where the vertices are not in it.
template <class Point, class Triangles>
void measure_solid(const std::vector<Point>& vertices, const Triangles& triangles, ConvexHull& hull) {
  if (triangles.empty()) return;
  const auto vertex = [&](std::size_t k) { return to_vec3d(vertices[k]); };
  int scale = 0;
  if (fast_range_scale(vertices.size(), vertex, &scale)) {
    const auto corner = [&](unsigned long long f, int k) {
      return scaled_by(vertex(triangles[f][k]), scale);
    };
    set_measures(measure_on_cores(triangles.size(), corner, scaled_by(vertex(triangles[0][0]), scale)), scale,
                 hull);
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

}  // namespace

namespace detail {

template <class Point>
ConvexHull describe_exact(const BasicHullMesh<Point>& mesh, std::string backend, bool neighbors) {
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

  PhaseLaps laps("describe_exact");  // CUDAHULL_PHASE_TIMES=1
  const std::size_t faces = mesh.triangles.size();
  hull.faces.resize(faces);
  // Each face's plane on its own (on all cores: a sliver's is exact, and a hull of millions of faces has
  // some), so the result does not depend on the worker count.
  hull.planes.resize(faces);
  // Vertices all in the fast exact range (every float, nearly every double): facet_plane()'s in-range path
  // without its test a face, which cost a small cloud more than its planes.
  bool in_range = true;
  if constexpr (std::is_same_v<Point, Point3d>) in_range = in_fast_exact_range(mesh.vertices);
  // The faces and planes on all cores, the neighbours' corner index beside them on one (a small mesh all on
  // this thread, where waking the workers would cost more).
  std::unique_ptr<FaceCorners> corners;
  parallel_blocks_beside(
      faces, workers_from(faces, 2048),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t f = begin; f < end; ++f) {
          const Triangle& t = mesh.triangles[f];
          hull.faces[f] = {mesh.vertex_ids[t[0]], mesh.vertex_ids[t[1]], mesh.vertex_ids[t[2]]};
          const Vec3d a = to_vec3d(mesh.vertices[t[0]]), b = to_vec3d(mesh.vertices[t[1]]),
                      c = to_vec3d(mesh.vertices[t[2]]);
          if (in_range)
            detail::facet_plane_in_range(a, b, c, hull.planes[f].data());
          else
            hull.planes[f] = facet_plane(a, b, c);
        }
      },
      [&] {
        if (neighbors) corners = std::make_unique<FaceCorners>(mesh.triangles, mesh.vertices.size());
      },
      std::size_t{1} << 10);
  laps.lap("faces, planes and corner index");
  measure_solid(mesh.vertices, mesh.triangles, hull);
  laps.lap("measures");
  if (neighbors) hull.neighbors = face_neighbors(*corners, faces);
  laps.lap("neighbours");
  return hull;
}

}  // namespace detail

namespace {

using detail::describe_exact;

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

// The exact hull's vertices' bounds (the input's).
template <class Point>
void vertex_bounds(const std::vector<Point>& vertices, double low[3], double high[3]) {
  for (int k = 0; k < 3; ++k)
    low[k] = INFINITY, high[k] = -INFINITY;
  for (const Point& p : vertices) {
    const double at[3] = {double(p.x), double(p.y), double(p.z)};
    for (int k = 0; k < 3; ++k)
      low[k] = std::min(low[k], at[k]), high[k] = std::max(high[k], at[k]);
  }
}

// ConvexHullOptions::box_measures: Qhull's QbB volume and area of the 3-D hull whose faces are `faces`
// (positions in `vertices`, the exact hull's vertices, which attain the points' bounds), summed in the
// result's face order as the Python module's general path sums them (qhull_scaling.hpp).
template <class Point, class Triangles>
void measure_box(const std::vector<Point>& vertices, const Triangles& faces, ConvexHull& hull) {
  double low[3], high[3];
  vertex_bounds(vertices, low, high);
  static_assert(sizeof(Point) == 3 * sizeof(Point::x), "a point is its three coordinates");
  const std::array<double, 2> box = box_scaled_measures(
      &vertices.data()->x, faces.size(), [&](std::size_t f, int k) { return std::size_t{faces[f][k]}; }, low,
      high, hull.volume);
  hull.box_volume = box[0];
  hull.box_area = box[1];
}

// The merged hull's measures (and QbB's), as measure_solid() and measure_box() find them (the same bits),
// with their per-face terms found in the merge's own pass over the faces (MergedFacesWork) and only their
// sums after it.  A mesh outside the fast exact range, or of more than one measuring chunk, is measured
// after the merge instead.
template <class Point>
class MergedMeasures final : public MergedFacesWork {
 public:
  MergedMeasures(const std::vector<Point>& vertices, bool box) : vertices_(vertices), box_(box) {
    in_range_ = fast_range_scale(
        vertices.size(), [&](std::size_t k) { return to_vec3d(vertices[k]); }, &scale_);
    if (box_) {
      double low[3], high[3];
      vertex_bounds(vertices, low, high);
      box_scale(low, high, box_scale_);
    }
  }
  void start(const Triangle& first_face, std::size_t faces) override {
    terms_on_faces_ = in_range_ && faces <= kMeasureChunk;
    if (terms_on_faces_) {
      apex_ = scaled_by(to_vec3d(vertices_[first_face[0]]), scale_);
      terms_.resize(faces);
    }
    if (box_) lengths_.resize(faces);
  }
  void faces(const MergedHull& merged, std::size_t begin, std::size_t end) override {
    const auto& at = merged.face_positions;
    for (std::size_t f = begin; f < end; ++f) {
      if (terms_on_faces_)
        terms_[f] =
            detail::SolidMeasures::face_terms(corner(at, f, 0), corner(at, f, 1), corner(at, f, 2), apex_);
      if (box_) lengths_[f] = scaled_twice_area(xyz(), face_corner(at), f, box_scale_);
    }
  }
  void finish(const MergedHull& merged, ConvexHull& hull) const {
    const auto& at = merged.face_positions;
    if (!terms_on_faces_) {
      measure_solid(vertices_, at, hull);
    } else if (!at.empty()) {
      set_measures(
          sum_face_terms(
              terms_, at.size(), [&](unsigned long long f, int k) { return corner(at, f, k); }, apex_),
          scale_, hull);
    }
    if (box_) {
      hull.box_volume = box_scaled_volume(hull.volume, box_scale_);
      hull.box_area = half_sum(lengths_);
    }
  }

 private:
  Vec3d corner(const PassVector<Triangle>& at, std::size_t f, int k) const {
    return scaled_by(to_vec3d(vertices_[at[f][k]]), scale_);
  }
  static auto face_corner(const PassVector<Triangle>& at) {
    return [&at](std::size_t f, int k) { return std::size_t{at[f][k]}; };
  }
  const decltype(Point::x)* xyz() const {
    static_assert(sizeof(Point) == 3 * sizeof(Point::x), "a point is its three coordinates");
    return &vertices_.data()->x;
  }

  const std::vector<Point>& vertices_;
  const bool box_;
  bool in_range_ = false, terms_on_faces_ = false;
  int scale_ = 0;
  double box_scale_[3] = {1, 1, 1};
  Vec3d apex_;
  PassVector<detail::SolidMeasures::FaceTerms> terms_;
  PassVector<double> lengths_;
};

// A merged hull from the exact one: merge_facets() works on the exact hull's vertices alone, since every
// input point is a convex combination of them; its faces come both as input indices and as positions in
// mesh.vertices, which the measures read.
template <class Point>
ConvexHull describe_merged(const BasicHullMesh<Point>& mesh, std::string backend,
                           const ConvexHullOptions& options) {
  // The merge's passes follow one another closely: woken now, the workers share its first passes, which
  // otherwise run on the caller alone while they wake (after a device's hull they have slept for
  // milliseconds).
  wake_workers(std::chrono::microseconds(1000));
  const double cosine = std::clamp(options.angle_cosine, 0.0, 1.0);
  PhaseLaps laps("describe_merged");  // CUDAHULL_PHASE_TIMES=1
  MergedMeasures<Point> measures(mesh.vertices, options.box_measures);
  MergedHull merged = merge_facets(mesh.vertices, mesh, merge_tolerance(mesh.vertices, options),
                                   std::sqrt(1 - cosine * cosine), &measures);
  ConvexHull hull;
  hull.dimension = 3;
  hull.precision = precision_of<Point>();
  hull.backend = std::move(backend);
  hull.tolerance = merged.tolerance;
  hull.max_outside = merged.max_outside;
  hull.thinnest = merged.thinnest;
  hull.vertices = std::move(merged.vertices);
  hull.faces = std::move(merged.faces);
  laps.lap("merge");
  measures.finish(merged, hull);
  laps.lap("measures' sums");
  hull.planes = std::move(merged.planes);
  hull.neighbors = std::move(merged.neighbors);
  hull.coplanar = std::move(merged.coplanar);
  return hull;
}

}  // namespace

namespace detail {

template <class Point>
ConvexHull describe(const BasicHullMesh<Point>& mesh, std::string backend, const ConvexHullOptions& options,
                    bool neighbors) {
  if (options.merge == MergeMode::kExact || mesh.dimension != 3) {
    ConvexHull hull = describe_exact(mesh, std::move(backend), neighbors);
    if (options.box_measures && mesh.dimension == 3) measure_box(mesh.vertices, mesh.triangles, hull);
    return hull;
  }
  return describe_merged(mesh, std::move(backend), options);
}

template ConvexHull describe_exact(const HullMesh&, std::string, bool);
template ConvexHull describe_exact(const HullMeshd&, std::string, bool);
template ConvexHull describe(const HullMesh&, std::string, const ConvexHullOptions&, bool);
template ConvexHull describe(const HullMeshd&, std::string, const ConvexHullOptions&, bool);

}  // namespace detail

template <class Point>
ConvexHull hull_from_mesh(const BasicHullMesh<Point>& mesh, std::string backend,
                          const ConvexHullOptions& options, bool neighbors) {
  if (!neighbors && options.merge == MergeMode::kExact)
    return detail::describe_exact(mesh, std::move(backend), false);
  return detail::describe(mesh, std::move(backend), options);
}

template ConvexHull hull_from_mesh(const HullMesh&, std::string, const ConvexHullOptions&, bool);
template ConvexHull hull_from_mesh(const HullMeshd&, std::string, const ConvexHullOptions&, bool);

}  // namespace cudahull
