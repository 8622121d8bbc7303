// Qhull's scaled measures (scipy's `volume` and `area` under qhull_options "QbB", "Qbb", "Qbk:n" and
// "QBk:n"): the hull's triangles with every coordinate mapped by x -> x * scale + shift per axis.  The one
// summation behind the drop-in's scaled measures, in the library (ConvexHullOptions::box_measures) and in the
// Python module, so that every path gives the same bits.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "cudahull/parallel.hpp"

namespace cudahull {

// Twice the area of face f scaled (x -> x * scale per axis; the shift cancels in the edges): the length of
// its scaled edges' cross product; corner(f, k) is the index into `xyz` (x, y, z a point) of its corner k.
template <class Scalar, class Corner>
double scaled_twice_area(const Scalar* xyz, const Corner& corner, std::size_t f, const double scale[3]) {
  const Scalar* a = xyz + 3 * corner(f, 0);
  const Scalar* b = xyz + 3 * corner(f, 1);
  const Scalar* c = xyz + 3 * corner(f, 2);
  double u[3], v[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = (double(b[k]) - double(a[k])) * scale[k];
    v[k] = (double(c[k]) - double(a[k])) * scale[k];
  }
  const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return std::sqrt(x * x + y * y + z * z);
}

// Half the sum of `lengths` in their order (scaled_area()'s).
template <class Lengths>
double half_sum(const Lengths& lengths) {
  double sum = 0;
  for (const double length : lengths)
    sum += length;
  return sum / 2;
}

// Half the sum, in face order, of scaled_twice_area() over the faces.  The lengths on all cores, their sum
// on one: the same bits on any number of cores.
template <class Scalar, class Corner>
double scaled_area(const Scalar* xyz, std::size_t faces, const Corner& corner, const double scale[3]) {
  PassVector<double> lengths(faces);
  parallel_blocks(faces, workers_from(faces, 2048), [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t f = begin; f < end; ++f)
      lengths[f] = scaled_twice_area(xyz, corner, f, scale);
  });
  return half_sum(lengths);
}

// QbB's scale per axis: [low, high] onto a unit width (a flat axis kept).
inline void box_scale(const double low[3], const double high[3], double scale[3]) {
  for (int k = 0; k < 3; ++k) {
    const double width = high[k] - low[k];
    scale[k] = 1.0 / (width > 0 ? width : 1.0);
  }
}

// QbB's volume of a hull of volume `volume`.
inline double box_scaled_volume(double volume, const double scale[3]) {
  return volume * (std::fabs(scale[0]) * std::fabs(scale[1]) * std::fabs(scale[2]));
}

// Qhull's QbB volume and area of a hull of volume `volume` whose faces' corners corner(f, k) index `xyz`:
// each axis mapped onto [-0.5, 0.5] from [low, high] (a flat axis kept), as qhull_options.scaling() maps it.
template <class Scalar, class Corner>
std::array<double, 2> box_scaled_measures(const Scalar* xyz, std::size_t faces, const Corner& corner,
                                          const double low[3], const double high[3], double volume) {
  double scale[3];
  box_scale(low, high, scale);
  return {box_scaled_volume(volume, scale), scaled_area(xyz, faces, corner, scale)};
}

}  // namespace cudahull
