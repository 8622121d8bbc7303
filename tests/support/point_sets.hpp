// Small point sets the tests build by hand (independent of cudahull's generators).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "cudahull/types.hpp"
#include "rng.hpp"

namespace cudahull::testing {

// The integer lattice {0..nx-1} x {0..ny-1} x {0..nz-1}, z fastest.
inline std::vector<Point3> lattice(int nx, int ny, int nz) {
  std::vector<Point3> p;
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y)
      for (int z = 0; z < nz; ++z)
        p.push_back({float(x), float(y), float(z)});
  return p;
}

// The integer lattice {0..side-1}^3, x fastest.
inline std::vector<Point3> grid(int side) {
  std::vector<Point3> p = lattice(side, side, side);
  for (auto& q : p)
    q = {q.z, q.y, q.x};
  return p;
}

// The lifted integer points (x, y, x^2 + y^2) for -r <= x, y <= r, y fastest: every one strictly extreme.
inline std::vector<Point3> integer_paraboloid(int r) {
  std::vector<Point3> p;
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y)
      p.push_back({float(x), float(y), float(x * x + y * y)});
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

// The kinds of seeded_set().
enum class SeededKind {
  kCube,       // general position in [-1, 1]^3
  kLattice,    // integer points in [0, side)^3: repeats, coplanar faces, collinear edges
  kFarJitter,  // a cloud 1e-3 across about (1e9, -2e9, 3e9)
  kScales,     // points 1e-6 or 1 from the origin, some lifted by 1e6 in z: wide ranges of scale
  kFlat,       // two thirds on the plane z = 0
  kRepeats,    // each point a copy of an earlier one, then a tetrahedron's three other corners
};

// `n` seeded points of one kind (`n` + 3 for kRepeats), drawn from `r`; `side` is kLattice's.
inline std::vector<Point3d> seeded_set(Rng& r, std::size_t n, SeededKind kind, int side) {
  std::vector<Point3d> p(n);
  for (auto& q : p) {
    switch (kind) {
      case SeededKind::kCube:
        q = {r.unit(), r.unit(), r.unit()};
        break;
      case SeededKind::kLattice:
        q = {double(int(r.below(side))), double(int(r.below(side))), double(int(r.below(side)))};
        break;
      case SeededKind::kFarJitter:
        q = {1e9 + r.unit() * 1e-3, -2e9 + r.unit() * 1e-3, 3e9 + r.unit() * 1e-3};
        break;
      case SeededKind::kScales: {
        const double s = r.below(2) ? 1e-6 : 1;
        q = {s * r.unit(), s * r.unit(), (r.below(2) ? 1e6 : 0) + s * r.unit()};
        break;
      }
      case SeededKind::kFlat:
        q = {r.unit(), r.unit(), r.below(3) ? 0.0 : r.unit()};
        break;
      case SeededKind::kRepeats:
        q = p[r.below(static_cast<std::size_t>(&q - p.data()) + 1)];
        break;
    }
  }
  if (kind == SeededKind::kRepeats)
    p[0] = {0, 0, 0}, p.push_back({1, 0, 0}), p.push_back({0, 1, 0}), p.push_back({0, 0, 1});
  return p;
}

// A dense cap of float points on the unit sphere: n on the cap of angular radius `angle` (radians) around
// +z, then 500 on the whole sphere.  Near the cap's centre neighbours differ in height by less than an
// ulp, so the hull has coplanar facets, and the resident engine's rounds leave concave edges over
// vertices that are not extreme: issue 26's cliff (30M sphere points on the H100), in small.
inline std::vector<Point3> cap_points(std::size_t n, double angle, std::uint64_t seed) {
  Rng r(seed);
  std::vector<Point3> points;
  auto unit01 = [&] { return (static_cast<double>(r.unit()) + 1) / 2; };
  for (std::size_t i = 0; i < n + 500; ++i) {
    const double phi = 2 * M_PI * unit01();
    const double z = i < n ? 1 - unit01() * (1 - std::cos(angle)) : 2 * unit01() - 1;
    const double s = std::sqrt(std::max(0.0, 1 - z * z));
    points.push_back({static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                      static_cast<float>(z)});
  }
  return points;
}

}  // namespace cudahull::testing
