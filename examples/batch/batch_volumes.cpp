// The volumes of 10,000 small polyhedra in one call: clouds of 6 to 40 random points packed one after the
// other, with their boundaries in `offsets`, through convex_hull_batch() (on the GPU where there is one, else
// on every core).  Cloud 0 is a unit cube's corners and its centre, whose hull's volume is exactly 1.  Each
// cloud's hull is convex_hull()'s on that cloud alone: checked here on the first 100 clouds.
#include <cudahull/convex_hull.hpp>
#include <cudahull/convex_hull_batch.hpp>

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <random>
#include <vector>

int main() {
  constexpr std::size_t kClouds = 10000;
  std::vector<cudahull::Point3d> points;
  std::vector<std::size_t> offsets = {0};  // cloud c is points[offsets[c] .. offsets[c + 1])

  for (double x : {0.0, 1.0}) {
    for (double y : {0.0, 1.0}) {
      for (double z : {0.0, 1.0})
        points.push_back({x, y, z});
    }
  }
  points.push_back({0.5, 0.5, 0.5});
  offsets.push_back(points.size());

  std::mt19937 random(20118);
  std::uniform_int_distribution<std::size_t> size(6, 40);
  std::normal_distribution<double> coordinate;
  while (offsets.size() <= kClouds) {
    for (std::size_t n = size(random); n > 0; --n)
      points.push_back({coordinate(random), coordinate(random), coordinate(random)});
    offsets.push_back(points.size());
  }

  const auto start = std::chrono::steady_clock::now();
  const cudahull::ConvexHullBatch hulls = cudahull::convex_hull_batch(points, offsets);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  double total = 0;
  for (double volume : hulls.volumes)
    total += volume;
  std::printf("%zu clouds, their volumes in one call: %.1f ms (backend %s)\n", hulls.size(), ms,
              hulls.backend.c_str());
  std::printf("cloud 0 (a unit cube): volume %.17g, area %.17g, %zu vertices\n", hulls.volumes[0],
              hulls.areas[0], hulls.vertex_offsets[1] - hulls.vertex_offsets[0]);
  std::printf("total volume %.17g\n", total);

  // The same as convex_hull() on each cloud alone: its vertex set and its volume.
  std::size_t same = 0;
  for (std::size_t c = 0; c < 100; ++c) {
    const std::vector<cudahull::Point3d> cloud(points.begin() + offsets[c], points.begin() + offsets[c + 1]);
    const cudahull::ConvexHull alone = cudahull::convex_hull(cloud);
    const std::vector<cudahull::PointIndex> vertices(hulls.vertices.begin() + hulls.vertex_offsets[c],
                                                     hulls.vertices.begin() + hulls.vertex_offsets[c + 1]);
    if (vertices == alone.vertices && hulls.volumes[c] == alone.volume) ++same;
  }
  std::printf("clouds 0 to 99: %zu of 100 the same as convex_hull() on the cloud alone\n", same);
  return same == 100 ? 0 : 1;
}
