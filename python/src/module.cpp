// cudahull._cudahull: the nanobind extension under the Python package (python/cudahull/__init__.py), which
// gives it scipy's ConvexHull interface (and convex_hull_batch, issue 27).  It takes C-contiguous (n, 3)
// float32 or float64 NumPy arrays, as the package hands them over, or such arrays in CUDA memory (DLPack:
// CuPy, PyTorch; or a raw pointer from
// __cuda_array_interface__), and returns plain dicts of NumPy arrays (a batch on the device: of PyTorch
// tensors or CuPy arrays that share the result's device memory).
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "cudahull/convex_hull.hpp"
#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/hull_runner.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/qhull_scaling.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/wide_predicates.hpp"

namespace nb = nanobind;

namespace cudahull::python {

namespace {

template <class Scalar>
using PointArray = nb::ndarray<const Scalar, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;
template <class Scalar>
using PlanarArray = nb::ndarray<const Scalar, nb::shape<-1, 2>, nb::c_contig, nb::device::cpu>;

// A NumPy array that owns `values` (moved into the array's capsule), of the given shape.
template <class T>
nb::object to_numpy(std::vector<T>&& values, std::initializer_list<std::size_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  return nb::ndarray<nb::numpy, T>(owned->data(), shape, owner).cast();
}

// A boolean array: std::vector<bool> has no data(), so one byte (0 or 1) per value, read as bool.
nb::object to_numpy(std::vector<std::uint8_t>&& values, bool /*as_bool*/) {
  auto* owned = new std::vector<std::uint8_t>(std::move(values));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<std::uint8_t>*>(p); });
  return nb::ndarray<nb::numpy, bool>(reinterpret_cast<bool*>(owned->data()), {owned->size()}, owner).cast();
}

template <class T>
nb::object to_numpy(std::vector<T>&& values) {
  const std::size_t n = values.size();
  return to_numpy(std::move(values), {n});
}

// n rows of K values each, from one std::array (or C array) per row.
template <class T, std::size_t K, class Rows, class Get>
nb::object rows_to_numpy(const Rows& rows, Get get) {
  std::vector<T> flat;
  flat.reserve(rows.size() * K);
  for (const auto& row : rows) {
    for (std::size_t k = 0; k < K; ++k)
      flat.push_back(static_cast<T>(get(row, k)));
  }
  return to_numpy(std::move(flat), {rows.size(), K});
}

// The same from rows already laid out as NumPy wants them: the vector's memory goes to NumPy uncopied (a
// large hull's copies cost milliseconds).
template <class T, std::size_t K>
nb::object take_rows(std::vector<std::array<T, K>>&& rows) {
  static_assert(sizeof(std::array<T, K>) == K * sizeof(T), "rows must be contiguous");
  auto* owned = new std::vector<std::array<T, K>>(std::move(rows));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<std::array<T, K>>*>(p); });
  return nb::ndarray<nb::numpy, T>(owned->empty() ? nullptr : owned->front().data(), {owned->size(), K},
                                   owner)
      .cast();
}

template <class T, class Rows, class Get>
nb::object column_to_numpy(const Rows& rows, Get get) {
  std::vector<T> column;
  column.reserve(rows.size());
  for (const auto& row : rows)
    column.push_back(static_cast<T>(get(row)));
  return to_numpy(std::move(column));
}

// Any array in CUDA memory; its dtype, shape and layout are checked here, with messages that say what to do.
using CudaArray = nb::ndarray<nb::ro, nb::device::cuda>;

nb::object stats_to_dict(const std::optional<ResidentStats>& stats) {
  if (!stats) return nb::none();
  nb::dict d;
  for_each_stat(*stats, [&](const char* name, const auto& value) {
    if constexpr (std::is_array_v<std::remove_reference_t<decltype(value)>>) {
      d[name] = std::vector<double>(std::begin(value), std::end(value));
    } else {
      d[name] = value;
    }
  });
  return d;
}

nb::dict hull_to_dict(ConvexHull&& hull) {
  nb::dict d;
  nb::object stats = stats_to_dict(hull.resident_stats);
  if (!stats.is_none() && hull.engine_ms > 0) {
    stats["engine_ms"] = hull.engine_ms;
    stats["describe_ms"] = hull.describe_ms;
  }
  if (!stats.is_none()) stats["plan"] = hull.plan;
  d["stats"] = stats;
  d["plan"] = hull.plan;
  d["dimension"] = hull.dimension;
  d["precision"] = precision_name(hull.precision);
  d["backend"] = hull.backend;
  d["volume"] = hull.volume;
  d["area"] = hull.area;
  d["input_dimension"] = hull.input_dimension;
  d["tolerance"] = hull.tolerance;
  d["max_outside"] = hull.max_outside;
  d["thinnest"] = hull.thinnest;
  d["vertices"] = to_numpy(std::move(hull.vertices));
  d["polygon"] = to_numpy(std::move(hull.polygon));
  d["coplanar"] = take_rows(std::move(hull.coplanar));
  if (hull.input_dimension == 2) {
    d["simplices"] = take_rows(std::move(hull.edges));
    d["neighbors"] = take_rows(std::move(hull.edge_neighbors));
    d["equations"] = take_rows(std::move(hull.lines));
  } else {
    d["simplices"] = take_rows(std::move(hull.faces));
    d["neighbors"] = take_rows(std::move(hull.neighbors));
    d["equations"] = take_rows(std::move(hull.planes));
  }
  return d;
}

// How a hull is merged, from the package's words: "exact", "qhull" or "relative" with its tolerance.
struct Merge {
  std::string mode = "exact";
  double tolerance = 0;
  double angle_cosine = 1;  // Qhull's An (1: none)
};

ConvexHullOptions options_from(const std::string& backend, const std::string& precision,
                               const std::string& engine, const Merge& merge) {
  ConvexHullOptions options;
  options.backend = backend_from_name(backend);
  options.precision = precision_from_name_strict(precision);
  options.engine = engine_from_name(engine);
  options.merge = merge_from_name(merge.mode);
  options.tolerance = merge.tolerance;
  options.angle_cosine = merge.angle_cosine;
  return options;
}

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

// Points in CUDA memory, (n, 3) or (n, 2): 3-D read in place by the resident engine, 2-D filtered on the
// device with only the possible corners read back.
template <class Scalar>
nb::dict device_hull_of(const Scalar* xyz, std::size_t count, std::size_t dimension,
                        const std::string& backend, const std::string& precision, const Merge& merge) {
  const ConvexHullOptions options = options_from(backend, precision, "resident", merge);
  ConvexHull hull;
  {
    nb::gil_scoped_release unlocked;  // the caller holds the array for the call
    hull =
        dimension == 2 ? convex_hull_2d_device(xyz, count, options) : convex_hull_device(xyz, count, options);
  }
  return hull_to_dict(std::move(hull));
}

// An (n, 3) or (n, 2) array in CUDA memory, through DLPack: C-contiguous float32 or float64, as the engine
// reads it.
nb::dict convex_hull_cuda(const CudaArray& points, const std::string& backend, const std::string& precision,
                          const std::string& merge, double tolerance, double angle) {
  const bool is_float = points.dtype() == nb::dtype<float>(),
             is_double = points.dtype() == nb::dtype<double>();
  if (!is_float && !is_double)
    throw std::invalid_argument("points in GPU memory must be float32 or float64 (convert with .astype())");
  if (points.ndim() != 2 || (points.shape(1) != 3 && points.shape(1) != 2)) {
    std::string shape;
    for (std::size_t k = 0; k < points.ndim(); ++k)
      shape += (k ? ", " : "") + std::to_string(points.shape(k));
    if (points.ndim() == 1) shape += ",";
    throw std::invalid_argument("points must be an (n, 3) or (n, 2) array, not one of shape (" + shape + ")");
  }
  // Strides count elements; a single row's first stride means nothing.
  const std::size_t n = points.shape(0), dimension = points.shape(1);
  if (n != 0 &&
      (points.stride(1) != 1 || (n > 1 && points.stride(0) != static_cast<std::int64_t>(dimension)))) {
    throw std::invalid_argument(
        "points in GPU memory must be C-contiguous: the engine reads them in place "
        "(cupy.ascontiguousarray(x) "
        "or x.contiguous() copies them on the device)");
  }
  const Merge how{merge, tolerance, angle};
  if (is_float)
    return device_hull_of(static_cast<const float*>(points.data()), n, dimension, backend, precision, how);
  return device_hull_of(static_cast<const double*>(points.data()), n, dimension, backend, precision, how);
}

// The same from __cuda_array_interface__'s pointer, for arrays that offer no DLPack (the package checks
// the interface's shape, type and strides).
nb::dict convex_hull_cuda_pointer(std::uintptr_t pointer, std::size_t count, std::size_t dimension,
                                  bool is_double, const std::string& backend, const std::string& precision,
                                  const std::string& merge, double tolerance, double angle) {
  const Merge how{merge, tolerance, angle};
  if (is_double)
    return device_hull_of(reinterpret_cast<const double*>(pointer), count, dimension, backend, precision,
                          how);
  return device_hull_of(reinterpret_cast<const float*>(pointer), count, dimension, backend, precision, how);
}

// --- batched hulls (issue 27) ---------------------------------------------------------------------------
//
// The package (convex_hull_batch in __init__.py) packs padded input and checks shapes; here the packed
// (n, 3) points and B + 1 int64 offsets (host memory) become convex_hull_batch()'s call, and its result a
// dict of NumPy arrays.

using OffsetArray = nb::ndarray<const std::int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

// The B + 1 offsets, checked non-negative, read in place as std::size_t where that is int64's unsigned
// counterpart (the same bits for these values, and an access the aliasing rules allow): a copy into fresh
// pages costs a large batch host time (docs/benchmarks.md, "The measurements behind the code's constants").
// Elsewhere, copied.  The caller must not write the
// array during the call (as for the points, read in place with the GIL released).
struct Bounds {
  const std::size_t* data = nullptr;
  std::size_t clouds = 0;
  std::vector<std::size_t> copy;  // where they could not be read in place
};
Bounds offsets_from(const OffsetArray& offsets) {
  if (offsets.shape(0) == 0)
    throw std::invalid_argument("offsets must hold B + 1 cloud boundaries ([0] for no clouds), not none");
  for (std::size_t k = 0; k < offsets.shape(0); ++k) {
    if (offsets.data()[k] < 0) throw std::invalid_argument("offsets[" + std::to_string(k) + "] is negative");
  }
  Bounds bounds;
  bounds.clouds = offsets.shape(0) - 1;
  if constexpr (std::is_same_v<std::make_unsigned_t<std::int64_t>, std::size_t>) {
    bounds.data = reinterpret_cast<const std::size_t*>(offsets.data());
  } else {
    bounds.copy.assign(offsets.data(), offsets.data() + offsets.shape(0));
    bounds.data = bounds.copy.data();
  }
  return bounds;
}

ConvexHullBatchOptions batch_options_from(const std::string& backend, const std::string& precision,
                                          const std::string& engine, unsigned threads) {
  ConvexHullBatchOptions options;
  options.hull = options_from(backend, precision, engine, {});
  options.threads = threads;
  return options;
}

nb::object offsets_to_numpy(const std::vector<std::size_t>& offsets) {
  return to_numpy(std::vector<std::int64_t>(offsets.begin(), offsets.end()));
}

// What ran (ConvexHullBatchReport), for BatchHulls.report.
nb::dict report_dict(const ConvexHullBatchReport& report) {
  nb::dict d;
  d["clouds_batched"] = report.clouds_batched;
  d["batch_launches"] = report.batch_launches;
  d["device_bytes_peak"] = report.device_bytes_peak;
  d["device_ms"] = report.device_ms;
  d["kernel_ms"] = report.kernel_ms;
  d["describe_ms"] = report.describe_ms;
  return d;
}

nb::dict batch_to_dict(ConvexHullBatch&& batch) {
  nb::dict d;
  d["report"] = report_dict(batch);
  d["vertex_offsets"] = offsets_to_numpy(batch.vertex_offsets);
  d["face_offsets"] = offsets_to_numpy(batch.face_offsets);
  d["polygon_offsets"] = offsets_to_numpy(batch.polygon_offsets);
  d["vertices"] = to_numpy(std::move(batch.vertices));
  d["faces"] = take_rows(std::move(batch.faces));
  d["planes"] = take_rows(std::move(batch.planes));
  d["polygons"] = to_numpy(std::move(batch.polygons));
  d["volumes"] = to_numpy(std::move(batch.volumes));
  d["areas"] = to_numpy(std::move(batch.areas));
  d["dimensions"] = to_numpy(std::move(batch.dimensions));
  d["precision"] = precision_name(batch.precision);
  d["backend"] = batch.backend;
  return d;
}

template <class Scalar>
nb::dict convex_hull_batch_of(PointArray<Scalar> points, const OffsetArray& offsets,
                              const std::string& backend, const std::string& precision,
                              const std::string& engine, unsigned threads) {
  const Bounds bounds = offsets_from(offsets);
  const ConvexHullBatchOptions options = batch_options_from(backend, precision, engine, threads);
  ConvexHullBatch batch;
  {
    nb::gil_scoped_release unlocked;  // the caller's arrays stay alive: the call holds references to them
    batch = convex_hull_batch(points.data(), points.shape(0), bounds.data, bounds.clouds, options);
  }
  return batch_to_dict(std::move(batch));
}

// A result column in device memory as an array of `Framework` (PyTorch, CuPy) on its device, sharing the
// memory (DLPack): the capsule holds the column alive.  `width` values a row (1: a vector).
template <class Framework, class T>
nb::object column_array(const DeviceColumn<T>& column, std::size_t width, int device) {
  auto* owned = new std::shared_ptr<T>(column.data);
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::shared_ptr<T>*>(p); });
  const std::size_t shape[2] = {column.size / width, width};
  return nb::ndarray<Framework, T>(column.data.get(), width == 1 ? 1 : 2, shape, owner, nullptr,
                                   nb::dtype<T>(), nb::device::cuda::value, device)
      .cast();
}

template <class Framework>
nb::dict device_batch_to_dict(const DeviceConvexHullBatch& batch) {
  const int device = batch.device;
  nb::dict d;
  d["report"] = report_dict(batch);
  d["vertex_offsets"] = column_array<Framework>(batch.device_vertex_offsets, 1, device);
  d["face_offsets"] = column_array<Framework>(batch.device_face_offsets, 1, device);
  d["polygon_offsets"] = column_array<Framework>(batch.device_polygon_offsets, 1, device);
  d["vertices"] = column_array<Framework>(batch.vertices, 1, device);
  d["faces"] = column_array<Framework>(batch.faces, 3, device);
  d["planes"] = column_array<Framework>(batch.planes, 4, device);
  d["polygons"] = column_array<Framework>(batch.polygons, 1, device);
  d["volumes"] = column_array<Framework>(batch.volumes, 1, device);
  d["areas"] = column_array<Framework>(batch.areas, 1, device);
  d["dimensions"] = column_array<Framework>(batch.dimensions, 1, device);
  d["precision"] = precision_name(batch.precision);
  d["backend"] = batch.backend;
  return d;
}

// Packed points in CUDA memory, read in place: the batch kernel, and the single-cloud device path for the
// clouds it does not take (convex_hull_batch_device_results()).  The result stays on the device, as arrays
// of `library` ("torch", "cupy"), or comes back as NumPy ("numpy").
template <class Scalar>
nb::dict device_batch_of(const Scalar* xyz, std::size_t count, const OffsetArray& offsets,
                         const std::string& backend, const std::string& precision,
                         const std::string& library) {
  const Bounds bounds = offsets_from(offsets);
  const ConvexHullBatchOptions options = batch_options_from(backend, precision, "resident", 0);
  DeviceConvexHullBatch batch;
  {
    nb::gil_scoped_release unlocked;
    batch = convex_hull_batch_device_results(xyz, count, bounds.data, bounds.clouds, options);
  }
  if (library == "torch") return device_batch_to_dict<nb::pytorch>(batch);
  if (library == "cupy") return device_batch_to_dict<nb::cupy>(batch);
  ConvexHullBatch host;
  {
    nb::gil_scoped_release unlocked;
    host = batch.to_host();
  }
  return batch_to_dict(std::move(host));
}

nb::dict convex_hull_batch_cuda(const CudaArray& points, const OffsetArray& offsets,
                                const std::string& backend, const std::string& precision,
                                const std::string& library) {
  const bool is_float = points.dtype() == nb::dtype<float>(),
             is_double = points.dtype() == nb::dtype<double>();
  if (!is_float && !is_double)
    throw std::invalid_argument("points in GPU memory must be float32 or float64 (convert with .astype())");
  if (points.ndim() != 2 || points.shape(1) != 3)
    throw std::invalid_argument("packed points in GPU memory must be an (n, 3) array");
  const std::size_t n = points.shape(0);
  if (n != 0 && (points.stride(1) != 1 || (n > 1 && points.stride(0) != 3)))
    throw std::invalid_argument(
        "points in GPU memory must be C-contiguous: the engine reads them in place "
        "(cupy.ascontiguousarray(x) "
        "or x.contiguous() copies them on the device)");
  if (is_float)
    return device_batch_of(static_cast<const float*>(points.data()), n, offsets, backend, precision, library);
  return device_batch_of(static_cast<const double*>(points.data()), n, offsets, backend, precision, library);
}

nb::dict convex_hull_batch_cuda_pointer(std::uintptr_t pointer, std::size_t count, bool is_double,
                                        const OffsetArray& offsets, const std::string& backend,
                                        const std::string& precision, const std::string& library) {
  if (is_double)
    return device_batch_of(reinterpret_cast<const double*>(pointer), count, offsets, backend, precision,
                           library);
  return device_batch_of(reinterpret_cast<const float*>(pointer), count, offsets, backend, precision,
                         library);
}

// The stepping engine for notebooks: one iteration per step(), its record as a dict of NumPy arrays.
class StepEngine {
 public:
  template <class Scalar>
  StepEngine(PointArray<Scalar> points, const std::string& backend, const std::string& precision) {
    ConvexHullOptions request;
    request.precision = precision_from_name_strict(precision);
    request.backend = backend_from_name(backend);
    request.engine = EngineChoice::kStepping;  // what this class steps
    HullInput input;
    input.precision = std::is_same_v<Scalar, double> ? Precision::kDouble : Precision::kFloat;
    input.count = points.shape(0);
    const HullPlan plan = plan_hull(request, input);
    // The engine borrows its points: they live on the heap, owned here, for as long as it does.  The
    // points are checked before the plan's DeviceError, where it has one; the backend is the plan's
    // (hull_runner.hpp).
    if (plan.precision == Precision::kDouble) {
      double_points_ =
          std::make_unique<std::vector<Point3d>>(checked_points<Point3d>(points.data(), points.shape(0)));
      if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
      double_engine_ =
          std::make_unique<BasicEngine<Point3d>>(*double_points_, planned_backend<Point3d>(plan));
      engine_ = double_engine_.get();
    } else {
      float_points_ =
          std::make_unique<std::vector<Point3>>(checked_points<Point3>(points.data(), points.shape(0)));
      if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
      float_engine_ = std::make_unique<BasicEngine<Point3>>(*float_points_, planned_backend<Point3>(plan));
      engine_ = float_engine_.get();
    }
  }

  bool done() const { return engine_->done(); }
  int dimension() const { return engine_->dimension(); }
  std::string precision() const { return precision_name(engine_->precision()); }
  std::string backend() const { return engine_->backend_name(); }
  std::size_t point_count() const { return engine_->point_count(); }
  void restart() { engine_->restart(); }

  nb::dict step() {
    if (engine_->done()) throw std::logic_error("the engine is done: restart() it to step again");
    IterationRecord record;
    {
      nb::gil_scoped_release unlocked;
      record = engine_->step();
    }
    return record_to_dict(record);
  }

  // The current mesh: live faces as input indices (counter-clockwise from outside), and each face's
  // neighbours in scipy's convention (the k-th across the edge opposite corner k).
  nb::dict mesh() const {
    const Mesh& mesh = engine_->mesh();
    std::vector<FaceId> live;
    std::vector<FaceId> new_id(mesh.face_capacity(), kNoFace);
    for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
      if (!mesh.alive(f)) continue;
      new_id[f] = static_cast<FaceId>(live.size());
      live.push_back(f);
    }
    nb::dict d;
    d["faces"] =
        rows_to_numpy<std::uint32_t, 3>(live, [&](FaceId f, std::size_t k) { return mesh.face(f).v[k]; });
    // Mesh::n[i] lies across the edge v[i] -> v[i+1], which is opposite corner i + 2.
    d["neighbors"] = rows_to_numpy<std::int32_t, 3>(live, [&](FaceId f, std::size_t k) {
      const FaceId across = mesh.face(f).n[(k + 1) % 3];
      return across == kNoFace ? -1 : static_cast<std::int32_t>(new_id[across]);
    });
    d["vertices"] = to_numpy(mesh.vertices());
    return d;
  }

  // The exact hull, as cudahull.convex_hull returns it; once done.
  nb::dict result() const {
    if (!engine_->done()) throw std::logic_error("the engine is not done: step() until done");
    if (float_engine_) return hull_to_dict(hull_from_mesh(float_engine_->result(), engine_->backend_name()));
    return hull_to_dict(hull_from_mesh(double_engine_->result(), engine_->backend_name()));
  }

 private:
  static nb::dict record_to_dict(const IterationRecord& r) {
    nb::dict d;
    for_each_count(r, [&](const char* name, const auto& value) { d[name] = value; });
    d["note"] = r.note;
    // Fig. 3a: each refined face's corners and the apex it split at.
    d["refined_apexes"] = to_numpy(std::vector<PointIndex>(r.refined_apexes));
    d["refined_faces"] =
        rows_to_numpy<std::uint32_t, 3>(r.refined_faces, [](const auto& f, std::size_t k) { return f[k]; });
    // Figs. 3b, 4, 5: every swap tried, in order; swap_kind indexes cudahull.SWAP_KINDS.
    const auto& s = r.swaps;
    d["swap_kind"] = column_to_numpy<std::uint8_t>(s, [](const SwapRecord& w) { return w.kind; });
    d["swap_sequence"] = column_to_numpy<std::int32_t>(s, [](const SwapRecord& w) { return w.sequence; });
    d["swap_old_edge"] =
        rows_to_numpy<std::uint32_t, 2>(s, [](const SwapRecord& w, std::size_t k) { return w.old_edge[k]; });
    d["swap_new_edge"] =
        rows_to_numpy<std::uint32_t, 2>(s, [](const SwapRecord& w, std::size_t k) { return w.new_edge[k]; });
    d["swap_beneath_vertex"] =
        column_to_numpy<std::uint32_t>(s, [](const SwapRecord& w) { return w.beneath_vertex; });
    d["swap_beneath_triangle"] = rows_to_numpy<std::uint32_t, 3>(
        s, [](const SwapRecord& w, std::size_t k) { return w.beneath_triangle[k]; });
    d["swap_decision_index"] =
        column_to_numpy<std::int32_t>(s, [](const SwapRecord& w) { return w.decision_index; });
    // Fig. 4: degree-3 vertices removed (or, rejected, left), with the face that replaced them.
    const auto& m = r.removals;
    d["removal_sequence"] =
        column_to_numpy<std::int32_t>(m, [](const RemovalRecord& v) { return v.sequence; });
    d["removal_vertex"] = column_to_numpy<std::uint32_t>(m, [](const RemovalRecord& v) { return v.vertex; });
    d["removal_ring"] =
        rows_to_numpy<std::uint32_t, 3>(m, [](const RemovalRecord& v, std::size_t k) { return v.ring[k]; });
    d["removal_decision_index"] =
        column_to_numpy<std::int32_t>(m, [](const RemovalRecord& v) { return v.decision_index; });
    std::vector<std::uint8_t> rejected;
    for (const RemovalRecord& v : m)
      rejected.push_back(v.rejected ? 1 : 0);
    d["removal_rejected"] = to_numpy(std::move(rejected), true);
    // Fig. 7: the decision array sent to the backend (plane: nx, ny, nz, d; above/below: route codes).
    const auto& e = r.decisions;
    d["decision_kind"] = column_to_numpy<std::uint8_t>(e, [](const DecisionEntry& x) { return x.kind; });
    d["decision_plane"] = rows_to_numpy<double, 4>(e, [](const DecisionEntry& x, std::size_t k) {
      const double plane[4] = {x.plane.nx, x.plane.ny, x.plane.nz, x.plane.d};
      return plane[k];
    });
    d["decision_above"] = column_to_numpy<std::int32_t>(e, [](const DecisionEntry& x) { return x.above; });
    d["decision_below"] = column_to_numpy<std::int32_t>(e, [](const DecisionEntry& x) { return x.below; });
    return d;
  }

  std::unique_ptr<std::vector<Point3>> float_points_;
  std::unique_ptr<std::vector<Point3d>> double_points_;
  std::unique_ptr<BasicEngine<Point3>> float_engine_;
  std::unique_ptr<BasicEngine<Point3d>> double_engine_;
  SteppingEngine* engine_ = nullptr;
};

}  // namespace

}  // namespace cudahull::python

NB_MODULE(_cudahull, m) {
  using namespace cudahull;
  using namespace cudahull::python;
  m.doc() = "cudahull's C++ core; use the cudahull package (ConvexHull, Engine) rather than this module.";
  // The C++ errors keep their messages; bad input is a ValueError, as scipy raises for it.
  nb::exception<InputError>(m, "InputError", PyExc_ValueError);
  nb::exception<DeviceError>(m, "DeviceError", PyExc_RuntimeError);

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

  // Arrays in CUDA memory (issue 16; 2-D: issue 25): 3-D read in place by the resident engine, 2-D filtered.
  m.def("convex_hull_cuda", &convex_hull_cuda, nb::arg("points"), nb::arg("backend"), nb::arg("precision"),
        nb::arg("merge"), nb::arg("tolerance"), nb::arg("angle") = 1.0);
  m.def("convex_hull_cuda_pointer", &convex_hull_cuda_pointer, nb::arg("pointer"), nb::arg("count"),
        nb::arg("dimension"), nb::arg("is_double"), nb::arg("backend"), nb::arg("precision"),
        nb::arg("merge"), nb::arg("tolerance"), nb::arg("angle") = 1.0);
  // Batched hulls (issue 27): packed points and B + 1 offsets; the package packs padded input.
  m.def("convex_hull_batch", &convex_hull_batch_of<float>, nb::arg("points"), nb::arg("offsets"),
        nb::arg("backend"), nb::arg("precision"), nb::arg("engine"), nb::arg("threads") = 0);
  m.def("convex_hull_batch", &convex_hull_batch_of<double>, nb::arg("points"), nb::arg("offsets"),
        nb::arg("backend"), nb::arg("precision"), nb::arg("engine"), nb::arg("threads") = 0);
  m.def("convex_hull_batch_cuda", &convex_hull_batch_cuda, nb::arg("points"), nb::arg("offsets"),
        nb::arg("backend"), nb::arg("precision"), nb::arg("library"));
  m.def("convex_hull_batch_cuda_pointer", &convex_hull_batch_cuda_pointer, nb::arg("pointer"),
        nb::arg("count"), nb::arg("is_double"), nb::arg("offsets"), nb::arg("backend"), nb::arg("precision"),
        nb::arg("library"));
  m.def("release_device_memory", []() {
    nb::gil_scoped_release unlocked;
    release_device_memory();
  });
  // Whether a CUDA array can be taken here at all: (usable, why not), before its data is touched.
  m.def("cuda_device", []() {
    const CudaStatus cuda = cuda_status();
    return nb::make_tuple(cuda.usable, cuda.usable ? cuda.device : cuda.reason);
  });

  nb::list kinds;
  for (SwapKind kind : {SwapKind::kRegular, SwapKind::kComplementary, SwapKind::kRejectedFoldover,
                        SwapKind::kRejectedEdgeExists, SwapKind::kRejectedDegenerate})
    kinds.append(swap_kind_name(kind));
  m.attr("SWAP_KINDS") = nb::tuple(kinds);

  nb::class_<StepEngine>(m, "Engine")
      .def(nb::init<PointArray<float>, const std::string&, const std::string&>(), nb::arg("points"),
           nb::arg("backend"), nb::arg("precision"))
      .def(nb::init<PointArray<double>, const std::string&, const std::string&>(), nb::arg("points"),
           nb::arg("backend"), nb::arg("precision"))
      .def_prop_ro("done", &StepEngine::done)
      .def_prop_ro("dimension", &StepEngine::dimension)
      .def_prop_ro("precision", &StepEngine::precision)
      .def_prop_ro("backend", &StepEngine::backend)
      .def_prop_ro("npoints", &StepEngine::point_count)
      .def("restart", &StepEngine::restart)
      .def("step", &StepEngine::step)
      .def("mesh", &StepEngine::mesh)
      .def("result", &StepEngine::result);
}
