// What describing a hull costs on the host, beside the hull itself: hull_from_mesh() of one exact mesh,
// exact (convex_hull()'s result: faces, planes, neighbours, measures) and merged as Qhull's default would
// ("qhull": the drop-in's path for qhull_options), the median and best of REPS calls each, after one to warm
// up.  The mesh: exact_hull() of N points uniform in the unit ball (a ball of 523,000 points is the GPU's
// merged row of docs/benchmarks.md) or on the unit sphere.  CUDAHULL_THREADS sets the cores;
// CUDAHULL_PHASE_TIMES=1 prints each call's laps.
//   ninja -C build describe_costs && build/describe_costs [N=523000] [REPS=30] [ball|sphere]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "cudahull/convex_hull.hpp"
#include "cudahull/exact_hull.hpp"

using namespace cudahull;

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 523000;
  const int reps = argc > 2 ? std::max(1, std::atoi(argv[2])) : 30;
  const std::string dist = argc > 3 ? argv[3] : "ball";
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  std::vector<Point3d> points(n);
  for (Point3d& p : points) {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    const double r = (dist == "sphere" ? 1.0 : std::cbrt(uniform(rng))) / std::sqrt(x * x + y * y + z * z);
    p = {x * r, y * r, z * r};
  }
  const HullMeshd mesh = exact_hull(points);
  std::printf("%zu %s points: %zu hull vertices, %zu faces\n", n, dist.c_str(), mesh.vertices.size(),
              mesh.triangles.size());
  ConvexHullOptions exact, merged;
  merged.merge = MergeMode::kQhull;
  for (const auto& [name, options] : {std::pair{"exact", exact}, std::pair{"merged", merged}}) {
    std::vector<double> ms;
    std::size_t faces = hull_from_mesh(mesh, "cpu", options).faces.size();
    for (int r = 0; r < reps; ++r) {
      const auto start = std::chrono::steady_clock::now();
      faces = hull_from_mesh(mesh, "cpu", options).faces.size();
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(ms.begin(), ms.end());
    std::printf("%-6s: %zu faces, median %.3f ms, best %.3f ms\n", name, faces, ms[ms.size() / 2], ms[0]);
  }
}
