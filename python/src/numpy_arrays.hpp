// The module's array types and its C++ vectors handed to NumPy (owned by the array's capsule, mostly
// uncopied), with the STL casters every binding file needs.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace nb = nanobind;

namespace cudahull::python {

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
inline nb::object to_numpy(std::vector<std::uint8_t>&& values, bool /*as_bool*/) {
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

// An array of `rows` x `width` values (width 1: a vector) for a copy to fill, and where to write them:
// numpy.empty's, so not zeroed first, and with NumPy's huge pages for a large one (it asks the kernel for
// them where they are offered on request), whose first touch, by the copy's workers, faults a 2 MB page at
// a time rather than 4 KB.
template <class T>
struct UnfilledArray {
  T* data;
  nb::object array;
};
template <class T>
UnfilledArray<T> unfilled_numpy(std::size_t rows, std::size_t width = 1) {
  const char* dtype = std::is_same_v<T, double>          ? "float64"
                      : std::is_same_v<T, std::int64_t>  ? "int64"
                      : std::is_same_v<T, std::int32_t>  ? "int32"
                      : std::is_same_v<T, std::uint32_t> ? "uint32"
                                                         : nullptr;
  if (dtype == nullptr) throw std::logic_error("unfilled_numpy: no NumPy dtype for this type");
  nb::object empty = nb::module_::import_("numpy").attr("empty");
  nb::object array = width == 1 ? empty(rows, dtype) : empty(nb::make_tuple(rows, width), dtype);
  return {nb::cast<nb::ndarray<T, nb::c_contig>>(array).data(), std::move(array)};
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

}  // namespace cudahull::python
