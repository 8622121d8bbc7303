// Small point sets the tests build by hand (independent of cudahull's generators).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "cudahull/types.hpp"
#include "rng.hpp"

namespace cudahull::testing {

// The integer lattice {0..side-1}^3, x fastest.
inline std::vector<Point3> grid(int side) {
  std::vector<Point3> p;
  for (int z = 0; z < side; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x)
        p.push_back({float(x), float(y), float(z)});
  return p;
}

inline std::vector<Point3> scaled(std::vector<Point3> p, float s) {
  for (auto& q : p)
    q = {q.x * s, q.y * s, q.z * s};
  return p;
}

// Points in the unit ball whose coordinates are multiples of 2^-23 (so power-of-two scaling is exact).
inline std::vector<Point3> dyadic_ball(std::size_t n, std::uint64_t seed) {
  Rng r(seed);
  std::vector<Point3> p;
  while (p.size() < n) {
    Point3 q{r.unit(), r.unit(), r.unit()};
    if (double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z <= 1) p.push_back(q);
  }
  return p;
}

// `count` small sets of 8..32 points with integer coordinates in [-4, 4]: full of coplanar and collinear
// coincidences and duplicates.  The same sets on every run.
inline std::vector<std::vector<Point3>> small_integer_sets(int count) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(-4, 4);
  std::vector<std::vector<Point3>> sets;
  for (int trial = 0; trial < count; ++trial) {
    std::vector<Point3> points(8 + trial % 25);
    for (auto& p : points)
      p = {float(coord(rng)), float(coord(rng)), float(coord(rng))};
    sets.push_back(std::move(points));
  }
  return sets;
}

}  // namespace cudahull::testing
