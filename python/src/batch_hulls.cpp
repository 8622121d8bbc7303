// Batched hulls (issue 27): the package (convex_hull_batch in __init__.py) packs padded input and checks
// shapes; here the packed (n, 3) points and B + 1 int64 offsets (host memory) become convex_hull_batch()'s
// call, and its result a dict of NumPy arrays, or, for points in CUDA memory, of PyTorch tensors or CuPy
// arrays that share the result's device memory.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/convex_hull_batch_results.hpp"
#include "hull_conversions.hpp"
#include "numpy_arrays.hpp"

namespace cudahull::python {

namespace {

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

// The result's ten columns as arrays: NumPy's, or the input library's on the device.
struct ColumnArrays {
  nb::object vertex_offsets, face_offsets, polygon_offsets, vertices, faces, planes, polygons, volumes, areas,
      dimensions;
};

// The module's batch dict (BatchHulls, _batch.py): what ran, and the columns.
nb::dict batch_dict(const ConvexHullBatchReport& report, ColumnArrays&& columns) {
  nb::dict d;
  d["report"] = report_dict(report);
  d["vertex_offsets"] = std::move(columns.vertex_offsets);
  d["face_offsets"] = std::move(columns.face_offsets);
  d["polygon_offsets"] = std::move(columns.polygon_offsets);
  d["vertices"] = std::move(columns.vertices);
  d["faces"] = std::move(columns.faces);
  d["planes"] = std::move(columns.planes);
  d["polygons"] = std::move(columns.polygons);
  d["volumes"] = std::move(columns.volumes);
  d["areas"] = std::move(columns.areas);
  d["dimensions"] = std::move(columns.dimensions);
  d["precision"] = precision_name(report.precision);
  d["backend"] = report.backend;
  return d;
}

nb::dict batch_to_dict(ConvexHullBatch&& batch) {
  return batch_dict(batch, {.vertex_offsets = offsets_to_numpy(batch.vertex_offsets),
                            .face_offsets = offsets_to_numpy(batch.face_offsets),
                            .polygon_offsets = offsets_to_numpy(batch.polygon_offsets),
                            .vertices = to_numpy(std::move(batch.vertices)),
                            .faces = take_rows(std::move(batch.faces)),
                            .planes = take_rows(std::move(batch.planes)),
                            .polygons = to_numpy(std::move(batch.polygons)),
                            .volumes = to_numpy(std::move(batch.volumes)),
                            .areas = to_numpy(std::move(batch.areas)),
                            .dimensions = to_numpy(std::move(batch.dimensions))});
}

// A result in device memory as NumPy arrays, batch_to_dict()'s dtypes: read straight into arrays made for
// it (DeviceConvexHullBatch::to_host()'s vectors would be zeroed first, and copied again).
nb::dict device_batch_to_numpy(const DeviceConvexHullBatch& batch) {
  const std::size_t clouds = batch.size();
  auto vertex_offsets = unfilled_numpy<std::int64_t>(clouds + 1),
       face_offsets = unfilled_numpy<std::int64_t>(clouds + 1),
       polygon_offsets = unfilled_numpy<std::int64_t>(clouds + 1);
  auto vertices = unfilled_numpy<PointIndex>(batch.vertices.size),
       faces = unfilled_numpy<PointIndex>(batch.faces.size / 3, 3),
       polygons = unfilled_numpy<PointIndex>(batch.polygons.size);
  auto planes = unfilled_numpy<double>(batch.planes.size / 4, 4), volumes = unfilled_numpy<double>(clouds),
       areas = unfilled_numpy<double>(clouds);
  auto dimensions = unfilled_numpy<std::int32_t>(clouds);
  static_assert(sizeof(PointIndex) == sizeof(std::int32_t));  // int32 columns, PointIndex's bits
  const BatchHostColumns into{vertex_offsets.data,
                              face_offsets.data,
                              polygon_offsets.data,
                              reinterpret_cast<std::int32_t*>(vertices.data),
                              reinterpret_cast<std::int32_t*>(faces.data),
                              reinterpret_cast<std::int32_t*>(polygons.data),
                              dimensions.data,
                              planes.data,
                              volumes.data,
                              areas.data};
  {
    nb::gil_scoped_release unlocked;
    copy_to_host(batch, into);
  }
  return batch_dict(batch, {.vertex_offsets = std::move(vertex_offsets.array),
                            .face_offsets = std::move(face_offsets.array),
                            .polygon_offsets = std::move(polygon_offsets.array),
                            .vertices = std::move(vertices.array),
                            .faces = std::move(faces.array),
                            .planes = std::move(planes.array),
                            .polygons = std::move(polygons.array),
                            .volumes = std::move(volumes.array),
                            .areas = std::move(areas.array),
                            .dimensions = std::move(dimensions.array)});
}

template <class Scalar>
nb::dict convex_hull_batch_of(PointArray<Scalar> points, const OffsetArray& offsets,
                              const std::string& backend, const std::string& precision,
                              const std::string& engine, unsigned threads) {
  const Bounds bounds = offsets_from(offsets);
  const ConvexHullBatchOptions options = batch_options_from(backend, precision, engine, threads);
  std::variant<ConvexHullBatch, DeviceConvexHullBatch> result;
  {
    nb::gil_scoped_release unlocked;  // the caller's arrays stay alive: the call holds references to them
    result = convex_hull_batch_results(points.data(), points.shape(0), bounds.data, bounds.clouds, options);
  }
  if (const auto* on_device = std::get_if<DeviceConvexHullBatch>(&result))
    return device_batch_to_numpy(*on_device);
  return batch_to_dict(std::get<ConvexHullBatch>(std::move(result)));
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
  return batch_dict(batch,
                    {.vertex_offsets = column_array<Framework>(batch.device_vertex_offsets, 1, device),
                     .face_offsets = column_array<Framework>(batch.device_face_offsets, 1, device),
                     .polygon_offsets = column_array<Framework>(batch.device_polygon_offsets, 1, device),
                     .vertices = column_array<Framework>(batch.vertices, 1, device),
                     .faces = column_array<Framework>(batch.faces, 3, device),
                     .planes = column_array<Framework>(batch.planes, 4, device),
                     .polygons = column_array<Framework>(batch.polygons, 1, device),
                     .volumes = column_array<Framework>(batch.volumes, 1, device),
                     .areas = column_array<Framework>(batch.areas, 1, device),
                     .dimensions = column_array<Framework>(batch.dimensions, 1, device)});
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
  return device_batch_to_numpy(batch);
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

}  // namespace

void bind_batch_hulls(nb::module_& m) {
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
}

}  // namespace cudahull::python
