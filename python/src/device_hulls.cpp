// Hulls of points in CUDA memory, read in place: through DLPack (CuPy, PyTorch) or a raw pointer from
// __cuda_array_interface__; 3-D on the resident engine, 2-D filtered on the device.
#include <cstdint>
#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "cudahull/convex_hull.hpp"
#include "hull_conversions.hpp"
#include "numpy_arrays.hpp"

namespace cudahull::python {

namespace {

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

}  // namespace

void bind_device_hulls(nb::module_& m) {
  // Arrays in CUDA memory (issue 16; 2-D: issue 25): 3-D read in place by the resident engine, 2-D filtered.
  m.def("convex_hull_cuda", &convex_hull_cuda, nb::arg("points"), nb::arg("backend"), nb::arg("precision"),
        nb::arg("merge"), nb::arg("tolerance"), nb::arg("angle") = 1.0);
  m.def("convex_hull_cuda_pointer", &convex_hull_cuda_pointer, nb::arg("pointer"), nb::arg("count"),
        nb::arg("dimension"), nb::arg("is_double"), nb::arg("backend"), nb::arg("precision"),
        nb::arg("merge"), nb::arg("tolerance"), nb::arg("angle") = 1.0);
}

}  // namespace cudahull::python
