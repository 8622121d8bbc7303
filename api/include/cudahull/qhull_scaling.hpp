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

// Half the sum, in face order, of the lengths of the scaled triangles' cross products; corner(f, k) is the
// index into `xyz` (x, y, z a point) of face f's corner k.  The shift cancels in the edges.  The lengths on
// all cores, their sum on one: the same bits on any number of cores.
template <class Scalar, class Corner>
double scaled_area(const Scalar* xyz, std::size_t faces, const Corner& corner, const double scale[3]) {
  const auto twice_area = [&](std::size_t f) {
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
  };
  PassVector<double> lengths(faces);
  parallel_blocks(faces, workers_from(faces, 2048), [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t f = begin; f < end; ++f)
      lengths[f] = twice_area(f);
  });
  double sum = 0;
  for (const double length : lengths)
    sum += length;
  return sum / 2;
}

// Qhull's QbB volume and area of a hull of volume `volume` whose faces' corners corner(f, k) index `xyz`:
// each axis mapped onto [-0.5, 0.5] from [low, high] (a flat axis kept), as qhull_options.scaling() maps it.
template <class Scalar, class Corner>
std::array<double, 2> box_scaled_measures(const Scalar* xyz, std::size_t faces, const Corner& corner,
                                          const double low[3], const double high[3], double volume) {
  double scale[3];
  for (int k = 0; k < 3; ++k) {
    const double width = high[k] - low[k];
    scale[k] = 1.0 / (width > 0 ? width : 1.0);
  }
  return {volume * (std::fabs(scale[0]) * std::fabs(scale[1]) * std::fabs(scale[2])),
          scaled_area(xyz, faces, corner, scale)};
}

}  // namespace cudahull
