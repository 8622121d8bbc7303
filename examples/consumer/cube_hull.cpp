// The hull of a unit cube's corners and random points inside it, with the one-call API and then with the
// stepping Engine; prints what a caller of Qhull would ask for.
#include <cudahull/convex_hull.hpp>
#include <cudahull/engine.hpp>

#include <cstdio>
#include <random>
#include <vector>

int main() {
  std::vector<cudahull::Point3d> points;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> inside(0.01, 0.99);
  for (int i = 0; i < 1000; ++i)
    points.push_back({inside(random), inside(random), inside(random)});
  for (double x : {0.0, 1.0}) {
    for (double y : {0.0, 1.0}) {
      for (double z : {0.0, 1.0})
        points.push_back({x, y, z});
    }
  }

  cudahull::ConvexHullOptions options;
  options.backend = cudahull::BackendChoice::kCpu;
  const cudahull::ConvexHull hull = cudahull::convex_hull(points, options);
  std::printf("dimension %d, %zu vertices, %zu faces, volume %.17g, area %.17g\n", hull.dimension,
              hull.vertices.size(), hull.faces.size(), hull.volume, hull.area);
  std::printf("vertices:");
  for (cudahull::PointIndex v : hull.vertices)
    std::printf(" %u", v);
  std::printf("\n");

  // The same hull an iteration at a time.
  cudahull::BasicEngine<cudahull::Point3d> engine(points,
                                                  cudahull::make_backend<cudahull::Point3d>(options.backend));
  int iterations = 0;
  while (!engine.done()) {
    engine.step();
    ++iterations;
  }
  std::printf("engine: %d iterations, %zu vertices\n", iterations, engine.result().vertex_ids.size());
  return 0;
}
