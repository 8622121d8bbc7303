// convex_hull_2d(): 2-D input's exact (or merged) polygon, from host points or points in GPU memory (the
// device filters them first: planar_filter.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <type_traits>

#include "checked_input.hpp"
#include "cudahull/convex_hull.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/device_points.hpp"
#include "cudahull/cuda/planar_filter.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/parallel.hpp"
#include "planar_hull.hpp"

namespace cudahull {

namespace {

using detail::check_count;
using detail::device_plan;
using detail::rejection;
using detail::require_device_points;
using detail::throw_if_rejected;

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
  hull.precision = precision_of<Scalar>();
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
  const HullPlan plan = device_plan(count, 2, precision_of<Scalar>(), options);
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

}  // namespace cudahull
