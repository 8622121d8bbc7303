// The property test's point sets (issue 7), shared by test_property (the stepping engine and the resident
// engine's host executor) and test_resident_cuda (the resident engine on the GPU).
//
// Case i is always the same set (splitmix64 seeded by i), so a failure names a reproducible case.  Kinds, by
// i % 8: general position, lattices, cospherical points, coplanar subsets, duplicates, 1e-7 jitter, extreme
// coordinate ranges, clusters far apart.  The double cases (issue 14) vary them beyond float.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cudahull/types.hpp"
#include "rng.hpp"

namespace cudahull::testing {

struct Case {
  const char* kind;
  std::vector<Point3> points;
};

// Mostly small sets (fast, and where degeneracies bite), some large: 4..2000, one case in 50 up to 1e5.
inline std::size_t case_size(Rng& r, std::uint64_t id) {
  if (id % 50 == 49) return 10000 + r.below(90001);
  const double u = static_cast<double>(r.below(1 << 20)) / (1 << 20);
  return 4 + static_cast<std::size_t>(std::exp(u * u * std::log(2000.0)));
}

inline Case make_case(std::uint64_t id) {
  Rng r(id * 0x2545F4914F6CDD1Dull + 17);
  const std::size_t n = case_size(r, id);
  std::vector<Point3> p;
  p.reserve(n);
  auto lattice_point = [&](int side) {
    return Point3{float(int(r.below(side)) - side / 2), float(int(r.below(side)) - side / 2),
                  float(int(r.below(side)) - side / 2)};
  };
  switch (id % 8) {
    case 0:  // general position
      while (p.size() < n)
        p.push_back({r.unit(), r.unit(), r.unit()});
      return {"general position", p};
    case 1: {  // a lattice: coplanar faces, collinear edges, many points on the hull's faces
      const int side = 2 + static_cast<int>(r.below(10));
      while (p.size() < n)
        p.push_back(lattice_point(side));
      return {"lattice", p};
    }
    case 2: {  // exactly cospherical integer points (x^2 + y^2 + z^2 = 625) plus points inside
      static const std::vector<Point3> sphere = [] {
        std::vector<Point3> s;
        for (int x = -25; x <= 25; ++x)
          for (int y = -25; y <= 25; ++y)
            for (int z = -25; z <= 25; ++z)
              if (x * x + y * y + z * z == 625) s.push_back({float(x), float(y), float(z)});
        return s;
      }();
      while (p.size() < n) {
        if (r.below(2) == 0) {
          p.push_back(sphere[r.below(sphere.size())]);
        } else {
          p.push_back({14 * r.unit(), 14 * r.unit(), 14 * r.unit()});
        }
      }
      return {"cospherical", p};
    }
    case 3: {  // coplanar subsets: random points, many of them pushed onto a few axis and diagonal planes
      while (p.size() < n) {
        Point3 q{r.unit(), r.unit(), r.unit()};
        switch (r.below(5)) {
          case 0:
            q.z = 1;
            break;
          case 1:
            q.x = -1;
            break;
          case 2:
            q.y = q.x;
            break;  // the plane x = y
          default:
            break;
        }
        p.push_back(q);
      }
      return {"coplanar subsets", p};
    }
    case 4: {  // duplicates: few distinct points, each many times
      std::vector<Point3> distinct(4 + r.below(n / 4 + 1));
      for (auto& q : distinct)
        q = {r.unit(), r.unit(), r.unit()};
      while (p.size() < n)
        p.push_back(distinct[r.below(distinct.size())]);
      return {"duplicates", p};
    }
    case 5: {  // a lattice jittered by about 1e-7 of its size: nearly degenerate everywhere
      const int side = 3 + static_cast<int>(r.below(6));
      while (p.size() < n) {
        Point3 q = lattice_point(side);
        q = {q.x + 1e-7f * side * r.unit(), q.y + 1e-7f * side * r.unit(), q.z + 1e-7f * side * r.unit()};
        p.push_back(q);
      }
      return {"1e-7 jitter", p};
    }
    case 6: {  // extreme coordinate ranges: huge, tiny, or a tiny set far from the origin
      const int mode = static_cast<int>(r.below(3));
      while (p.size() < n) {
        const Point3 q{r.unit(), r.unit(), r.unit()};
        if (mode == 0) p.push_back({q.x * 1e30f, q.y * 1e30f, q.z * 1e30f});
        if (mode == 1) p.push_back({q.x * 1e-30f, q.y * 1e-30f, q.z * 1e-30f});
        if (mode == 2) p.push_back({1e6f + q.x * 0.5f, -3e5f + q.y * 0.5f, 7e5f + q.z * 0.5f});
      }
      return {"extreme ranges", p};
    }
    default: {  // clusters far apart: a few tiny clusters, 1e6 apart
      const std::size_t clusters = 2 + r.below(5);
      std::vector<Point3> centre(clusters);
      for (auto& c : centre)
        c = {1e6f * r.unit(), 1e6f * r.unit(), 1e6f * r.unit()};
      while (p.size() < n) {
        const Point3& c = centre[r.below(clusters)];
        p.push_back({c.x + 1e-3f * r.unit(), c.y + 1e-3f * r.unit(), c.z + 1e-3f * r.unit()});
      }
      return {"clusters far apart", p};
    }
  }
}

// The double cases (issue 14): case i's set in double, then by i % 4 (i / 8 picks among them, so every
// float kind meets every double variant): as it is (exact floats: the hull must be the float run's), jittered
// by 1e-12 of its size (below float resolution: the answer changes under rounding), scaled by 2^200 or
// 2^-200 (beyond float's range), or moved 1e9 away from the origin with a unit size (float's spacing there
// is 64).
struct DoubleCase {
  const char* kind;
  std::vector<Point3d> points;
};

inline DoubleCase make_double_case(std::uint64_t id) {
  const Case base = make_case(id);
  Rng r(id * 0x9E3779B97F4A7C15ull + 5);
  std::vector<Point3d> p(base.points.size());
  for (std::size_t k = 0; k < p.size(); ++k)
    p[k] = {base.points[k].x, base.points[k].y, base.points[k].z};
  double size = 0;
  for (const Point3d& q : p)
    size = std::max({size, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
  switch ((id / 8) % 4) {
    case 0:
      return {"exact floats", p};
    case 1:
      for (Point3d& q : p)
        q = {q.x + 1e-12 * size * r.unit(), q.y + 1e-12 * size * r.unit(), q.z + 1e-12 * size * r.unit()};
      return {"1e-12 jitter", p};
    case 2: {
      const double scale = r.below(2) ? 0x1p200 : 0x1p-200;
      for (Point3d& q : p)
        q = {q.x * scale, q.y * scale, q.z * scale};
      return {"scaled by 2^+-200", p};
    }
    default:
      for (Point3d& q : p) {
        const double k = size > 0 ? 1 / size : 1;
        q = {1e9 + q.x * k, -2e9 + q.y * k, 3e9 + q.z * k};
      }
      return {"1e9 from the origin", p};
  }
}

}  // namespace cudahull::testing
