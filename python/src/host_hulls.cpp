// Hulls of NumPy points: convex_hull() in 3-D and 2-D, with the package's helpers (scaled_area, the
// visible facets, the points' check).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "bindings.hpp"
#include "cudahull/convex_hull.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/qhull_scaling.hpp"
#include "cudahull/wide_predicates.hpp"
#include "hull_conversions.hpp"
#include "numpy_arrays.hpp"

namespace cudahull::python {

namespace {

double scaled_area_of(
    nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu> points,
    nb::ndarray<const std::int64_t, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu> simplices,
    std::array<double, 3> scale) {
  const std::int64_t* s = simplices.data();
  const std::size_t n = points.shape(0), faces = simplices.shape(0);
  for (std::size_t k = 0; k < 3 * faces; ++k)
    if (s[k] < 0 || static_cast<std::size_t>(s[k]) >= n) throw std::invalid_argument("scaled_area: index");
  return scaled_area(
      points.data(), faces, [&](std::size_t f, int k) { return static_cast<std::size_t>(s[3 * f + k]); },
      scale.data());
}

// Qhull's QbB measures of a 3-D hull of `xyz` (scipy's volume and area under trimesh's "QbB Pp Qt"): each
// axis mapped onto [-0.5, 0.5] from the bounds of the exact hull's vertices (those merging kept and those it
// set aside, which attain the points' bounds), as qhull_options.scaling() maps it.  For hulls computed on
// rounded coordinates (double points in float precision); the others measure it in the call
// (ConvexHullOptions::box_measures), from the hull's own copy of its vertices.
template <class Scalar>
std::array<double, 2> box_measures_of_points(const Scalar* xyz, const ConvexHull& hull) {
  double low[3], high[3];
  for (int k = 0; k < 3; ++k)
    low[k] = std::numeric_limits<double>::infinity(), high[k] = -std::numeric_limits<double>::infinity();
  auto take = [&](PointIndex i) {
    for (int k = 0; k < 3; ++k)
      low[k] = std::min(low[k], double(xyz[3 * i + k])), high[k] = std::max(high[k], double(xyz[3 * i + k]));
  };
  for (PointIndex v : hull.vertices)
    take(v);
  for (const auto& row : hull.coplanar)
    take(row[0]);
  return box_scaled_measures(
      xyz, hull.faces.size(), [&](std::size_t f, int k) { return std::size_t{hull.faces[f][k]}; }, low, high,
      hull.volume);
}

// `box_measures`: also Qhull's QbB volume and area ("box_volume", "box_area") of a 3-D hull.
template <class Scalar>
nb::dict convex_hull_of(PointArray<Scalar> points, const std::string& backend, const std::string& precision,
                        const std::string& engine, const std::string& merge, double tolerance, double angle,
                        bool box_measures) {
  ConvexHullOptions options = options_from(backend, precision, engine, {merge, tolerance, angle});
  // Measured in the call where the hull's coordinates are the points' own (not double points rounded).
  options.box_measures =
      box_measures && !(std::is_same_v<Scalar, double> && options.precision == Precision::kFloat);
  ConvexHull hull;
  std::array<double, 2> box{0, 0};
  {
    nb::gil_scoped_release unlocked;  // the caller's array stays alive: the call holds a reference to it
    hull = convex_hull(points.data(), points.shape(0), options);
    if (box_measures && hull.dimension == 3)
      box = std::isnan(hull.box_volume) ? box_measures_of_points(points.data(), hull)
                                        : std::array<double, 2>{hull.box_volume, hull.box_area};
  }
  const int dimension = hull.dimension;
  nb::dict d = hull_to_dict(std::move(hull));
  if (box_measures && dimension == 3) {
    d["box_volume"] = box[0];
    d["box_area"] = box[1];
  }
  return d;
}

template <class Scalar>
nb::dict convex_hull_2d_of(PlanarArray<Scalar> points, const std::string& backend,
                           const std::string& precision, const std::string& merge, double tolerance,
                           double angle) {
  const ConvexHullOptions options = options_from(backend, precision, "auto", {merge, tolerance, angle});
  ConvexHull hull;
  {
    nb::gil_scoped_release unlocked;
    hull = convex_hull_2d(points.data(), points.shape(0), options);
  }
  return hull_to_dict(std::move(hull));
}

// Checks points as convex_hull() would, raising its InputError (naming the row) for the first bad one: for
// add_points, which checks a new batch alone before it changes anything.
template <class Scalar>
void check_points_of(PointArray<Scalar> points) {
  (void)checked_points<Point3d>(points.data(), points.shape(0));
}

// Which facets `query` sees: strictly above each simplex's line (2-D) or plane (3-D), decided exactly
// (the wide predicates: any finite doubles), for scipy's `good` (QGn).  The simplices are oriented as
// ConvexHull's.
nb::object facets_visible(nb::ndarray<const double, nb::c_contig, nb::device::cpu> points,
                          nb::ndarray<const std::int64_t, nb::c_contig, nb::device::cpu> simplices,
                          nb::ndarray<const double, nb::c_contig, nb::device::cpu> query) {
  const std::size_t dim = points.ndim() == 2 ? points.shape(1) : 0;
  if ((dim != 2 && dim != 3) || simplices.ndim() != 2 || simplices.shape(1) != dim || query.size() != dim)
    throw std::invalid_argument("facets_visible: points (n, d), simplices (m, d) and a point (d,), d 2 or 3");
  const double* p = points.data();
  const double* q = query.data();
  const std::size_t n = points.shape(0);
  std::vector<std::uint8_t> visible(simplices.shape(0));
  for (std::size_t f = 0; f < visible.size(); ++f) {
    const std::int64_t* s = simplices.data() + f * dim;
    for (std::size_t k = 0; k < dim; ++k)
      if (s[k] < 0 || static_cast<std::size_t>(s[k]) >= n)
        throw std::invalid_argument("facets_visible: index");
    if (dim == 2) {
      // A counter-clockwise edge a -> b: the outside is on its right.
      visible[f] = orient2d_wide(p[2 * s[0]], p[2 * s[0] + 1], p[2 * s[1]], p[2 * s[1] + 1], q[0], q[1]) < 0;
    } else {
      auto at = [&](std::int64_t i) { return Vec3d{p[3 * i], p[3 * i + 1], p[3 * i + 2]}; };
      visible[f] = orient3d_wide(at(s[0]), at(s[1]), at(s[2]), Vec3d{q[0], q[1], q[2]}) > 0;
    }
  }
  return to_numpy(std::move(visible), true);
}

}  // namespace

void bind_host_hulls(nb::module_& m) {
  m.def("convex_hull", &convex_hull_of<float>, nb::arg("points"), nb::arg("backend"), nb::arg("precision"),
        nb::arg("engine"), nb::arg("merge"), nb::arg("tolerance"), nb::arg("angle") = 1.0,
        nb::arg("box_measures") = false);
  m.def("convex_hull", &convex_hull_of<double>, nb::arg("points"), nb::arg("backend"), nb::arg("precision"),
        nb::arg("engine"), nb::arg("merge"), nb::arg("tolerance"), nb::arg("angle") = 1.0,
        nb::arg("box_measures") = false);
  m.def("scaled_area", &scaled_area_of, nb::arg("points"), nb::arg("simplices"), nb::arg("scale"));
  // 2-D input (issue 25): edges as simplices, lines as equations.
  m.def("convex_hull_2d", &convex_hull_2d_of<float>, nb::arg("points"), nb::arg("backend"),
        nb::arg("precision"), nb::arg("merge"), nb::arg("tolerance"), nb::arg("angle") = 1.0);
  m.def("convex_hull_2d", &convex_hull_2d_of<double>, nb::arg("points"), nb::arg("backend"),
        nb::arg("precision"), nb::arg("merge"), nb::arg("tolerance"), nb::arg("angle") = 1.0);
  m.def("facets_visible", &facets_visible, nb::arg("points"), nb::arg("simplices"), nb::arg("query"));
  m.def("check_points", &check_points_of<float>, nb::arg("points"));
  m.def("check_points", &check_points_of<double>, nb::arg("points"));
}

}  // namespace cudahull::python
