// Doubles of every magnitude for the wide-range tests (zeros, and binades from the least subnormal's to
// 2^960, with small integer or full mantissas), and the doubles one ulp either side of a value.
#pragma once

#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>

#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"

namespace cudahull {
namespace {

// ---------------------------------------------------------------------------------------------------------
// Inputs of mixed magnitudes.  Small integer mantissas make coincidences (shared coordinates, coplanar and
// collinear points) likely; full mantissas make near-cancellations.
double wide_value(std::mt19937_64& rng) {
  static constexpr int kExponents[] = {-1074, -1060, -1000, -700, -300, -250, -60, -1,
                                       0,     1,     60,    249,  300,  700,  960};
  const int e = kExponents[rng() % std::size(kExponents)];
  double m;
  switch (rng() % 4) {
    case 0:
      return 0.0;
    case 1:
      m = static_cast<double>(rng() % 8 + 1);
      break;
    case 2:
      m = static_cast<double>(rng() % 1000 + 1);
      break;
    default:
      m = std::ldexp(static_cast<double>(rng() >> 11), -52);  // in [0, 2048)
      break;
  }
  const double v = std::ldexp(m, e);  // may round (subnormal) or be rounded; any finite double will do
  return (rng() & 1) ? -v : v;
}

Vec3d wide_vec(std::mt19937_64& rng) {
  return {wide_value(rng), wide_value(rng), wide_value(rng)};
}

Point3d wide_point(std::mt19937_64& rng) {
  return {wide_value(rng), wide_value(rng), wide_value(rng)};
}

// The next double above / below.
double up(double x) {
  return std::nextafter(x, std::numeric_limits<double>::infinity());
}
double down(double x) {
  return std::nextafter(x, -std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace cudahull
