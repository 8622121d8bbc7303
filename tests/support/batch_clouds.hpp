// The convex_hull_batch() tests' batches: options that keep a batch on the CPU, a cloud's slice of the
// batch's columns against convex_hull() on that cloud alone, and seeded clouds of mixed kinds (generated,
// flat, collinear, repeated points, integer boxes) packed into one batch.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "cudahull/convex_hull.hpp"
#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/generators.hpp"

namespace cudahull {
namespace {

ConvexHullBatchOptions on_cpu(unsigned threads = 0, Precision precision = Precision::kAuto) {
  ConvexHullBatchOptions options;
  options.hull.backend = BackendChoice::kCpu;
  options.hull.precision = precision;
  options.threads = threads;
  return options;
}

template <class T>
std::vector<T> slice(const std::vector<T>& values, std::size_t begin, std::size_t end) {
  return std::vector<T>(values.begin() + static_cast<std::ptrdiff_t>(begin),
                        values.begin() + static_cast<std::ptrdiff_t>(end));
}

// Cloud c of the batch against `hull`, convex_hull() on the cloud alone: every field the batch carries.
void expect_cloud_is(const ConvexHullBatch& batch, std::size_t c, const ConvexHull& hull) {
  SCOPED_TRACE("cloud " + std::to_string(c));
  EXPECT_EQ(batch.dimensions[c], hull.dimension);
  EXPECT_EQ(slice(batch.vertices, batch.vertex_offsets[c], batch.vertex_offsets[c + 1]), hull.vertices);
  EXPECT_EQ(slice(batch.faces, batch.face_offsets[c], batch.face_offsets[c + 1]), hull.faces);
  EXPECT_EQ(slice(batch.planes, batch.face_offsets[c], batch.face_offsets[c + 1]), hull.planes);
  EXPECT_EQ(slice(batch.polygons, batch.polygon_offsets[c], batch.polygon_offsets[c + 1]), hull.polygon);
  EXPECT_EQ(batch.volumes[c], hull.volume);
  EXPECT_EQ(batch.areas[c], hull.area);
}

template <class Point>
void expect_each_cloud_is_its_own_hull(const std::vector<Point>& points,
                                       const std::vector<std::size_t>& offsets, const ConvexHullBatch& batch,
                                       const ConvexHullOptions& options) {
  const std::size_t clouds = offsets.size() - 1;
  ASSERT_EQ(batch.size(), clouds);
  ASSERT_EQ(batch.vertex_offsets.size(), clouds + 1);
  ASSERT_EQ(batch.face_offsets.size(), clouds + 1);
  ASSERT_EQ(batch.polygon_offsets.size(), clouds + 1);
  EXPECT_EQ(batch.vertex_offsets.back(), batch.vertices.size());
  EXPECT_EQ(batch.face_offsets.back(), batch.faces.size());
  EXPECT_EQ(batch.planes.size(), batch.faces.size());
  for (std::size_t c = 0; c < clouds; ++c)
    expect_cloud_is(batch, c, convex_hull(slice(points, offsets[c], offsets[c + 1]), options));
}

bool same_batch(const ConvexHullBatch& a, const ConvexHullBatch& b) {
  return a.vertex_offsets == b.vertex_offsets && a.face_offsets == b.face_offsets &&
         a.vertices == b.vertices && a.faces == b.faces && a.planes == b.planes &&
         a.polygon_offsets == b.polygon_offsets && a.polygons == b.polygons && a.volumes == b.volumes &&
         a.areas == b.areas && a.dimensions == b.dimensions && a.precision == b.precision;
}

// --- clouds of mixed kinds
// ------------------------------------------------------------------------------------

enum Kind { kCube, kBall, kSphere, kGauss, kFlat, kCollinear, kDuplicated, kGrid, kTinyInteger, kKinds };

// mt19937_64's raw output (std::'s distributions differ between libraries).
struct Random {
  std::mt19937_64 engine;
  explicit Random(std::uint64_t seed) : engine(seed) {}
  std::uint64_t below(std::uint64_t n) { return engine() % n; }
  // Log-uniform in [low, high].
  std::size_t sized(std::size_t low, std::size_t high) {
    const double u = static_cast<double>(engine() >> 11) * 0x1p-53;
    return static_cast<std::size_t>(std::exp(std::log(double(low)) + u * std::log(double(high) / low)));
  }
};

std::vector<Point3> cloud_of(Kind kind, std::size_t n, std::uint64_t seed, Random& random) {
  auto integer = [&](int low, int high) {
    return static_cast<float>(low + int(random.below(high - low + 1)));
  };
  std::vector<Point3> cloud;
  switch (kind) {
    case kCube:
      return generate_points(Distribution::kCube, n, seed);
    case kBall:
      return generate_points(Distribution::kBall, n, seed);
    case kSphere:
      return generate_points(Distribution::kSphere, n, seed);
    case kGauss:
      return generate_points(Distribution::kGauss, n, seed);
    case kFlat:  // exactly on the plane z = 2x - 3y + 1
      for (std::size_t i = 0; i < n; ++i) {
        const float x = integer(-100, 100), y = integer(-100, 100);
        cloud.push_back({x, y, 2 * x - 3 * y + 1});
      }
      return cloud;
    case kCollinear:  // on the line (1, 2, 3) t + (5, -1, 2)
      for (std::size_t i = 0; i < n; ++i) {
        const float t = integer(-500, 500);
        cloud.push_back({t + 5, 2 * t - 1, 3 * t + 2});
      }
      return cloud;
    case kDuplicated: {  // a few distinct points, each many times, in any order
      const std::vector<Point3> distinct = generate_points(Distribution::kGauss, 4 + random.below(12), seed);
      for (std::size_t i = 0; i < n; ++i)
        cloud.push_back(distinct[random.below(distinct.size())]);
      return cloud;
    }
    case kGrid:  // integer points of a 9 x 9 x 9 box: faces, edges and corners full of points
      for (std::size_t i = 0; i < n; ++i)
        cloud.push_back({integer(0, 8), integer(0, 8), integer(0, 8)});
      return cloud;
    case kTinyInteger:  // a 4 x 4 x 4 box: degenerate at every turn
      for (std::size_t i = 0; i < n; ++i)
        cloud.push_back({integer(0, 3), integer(0, 3), integer(0, 3)});
      return cloud;
    default:
      return cloud;
  }
}

struct MixedBatch {
  std::vector<Point3> points;
  std::vector<std::size_t> offsets{0};
  std::vector<Kind> kinds;
  void add(const std::vector<Point3>& cloud, Kind kind) {
    points.insert(points.end(), cloud.begin(), cloud.end());
    offsets.push_back(points.size());
    kinds.push_back(kind);
  }
  std::vector<Point3> cloud(std::size_t c) const { return slice(points, offsets[c], offsets[c + 1]); }
};

// `clouds` clouds of every kind, sizes log-uniform in 4..3000 (tiny integer ones 0..10), every 50th from the
// fourth empty and from the fifth one point repeated, and one cloud of 60,000 points at `large_at` (large
// enough beside the others to run alone on every core).
MixedBatch mixed_batch(std::size_t clouds, std::uint64_t seed, std::size_t large_at) {
  Random random(seed);
  MixedBatch batch;
  for (std::size_t c = 0; c < clouds; ++c) {
    if (c == large_at) {
      batch.add(generate_points(Distribution::kBall, 60000, seed + c), kBall);
      continue;
    }
    if (c % 50 == 3 || c % 50 == 4) {
      batch.add(std::vector<Point3>(c % 50 == 3 ? 0 : 1 + random.below(5), Point3{0.5f, -1, 2}), kDuplicated);
      continue;
    }
    const Kind kind = static_cast<Kind>(c % kKinds);
    const std::size_t n = kind == kTinyInteger ? random.below(11) : random.sized(4, 3000);
    batch.add(cloud_of(kind, n, seed + c, random), kind);
  }
  return batch;
}

}  // namespace
}  // namespace cudahull
