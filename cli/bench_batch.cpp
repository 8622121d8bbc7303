// `cudahull bench --batch B` (issue 27): B generated clouds timed through convex_hull_batch(), optionally
// against a loop of Qhull or of convex_hull() over the same clouds.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "command_support.hpp"
#include "commands.hpp"
#include "cudahull/convex_hull.hpp"
#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "huge_pages.hpp"
#include "qhull_reference.hpp"

namespace cudahull::cli {

namespace {

// `cudahull bench --batch B --n N` (issue 27): B clouds of N points of --dist (cloud c from seed + c),
// packed, timed through convex_hull_batch(); with --vs qhull a loop of Qhull over the same clouds, with
// --vs loop a loop of single convex_hull() calls, each checked cloud for cloud against the batch.
template <class Point>
int bench_batch(const BenchOptions& o, const ConvexHullOptions& request) {
  if (!o.input.empty())
    throw std::invalid_argument("bench --batch takes generated clouds (--dist, --n), not INPUT");
  constexpr Precision precision = precision_of<Point>();
  const Distribution dist = distribution_from_name(o.distribution);
  std::vector<Point> points;
  points.reserve(o.batch * o.count);
  std::vector<std::size_t> offsets{0};
  for (std::uint64_t c = 0; c < o.batch; ++c) {
    for (const Point3& p : generate_points(dist, o.count, o.seed + c))
      points.push_back(Point{p.x, p.y, p.z});
    offsets.push_back(points.size());
  }
  HullInput input;
  input.precision = precision;
  input.count = points.size();
  const HullPlan plan = plan_hull(request, input);
  require_runnable(plan);
  ConvexHullBatchOptions options;
  options.hull = request;
  options.tuning = tuning_from_environment().batch;
  std::vector<double> total;
  ConvexHullBatch hulls;
  for (int r = 0; r < o.repeat; ++r) {
    const auto t0 = Clock::now();
    hulls = convex_hull_batch(points, offsets, options);
    total.push_back(ms_since(t0));
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  auto cloud_of = [&](std::size_t c) {
    return std::vector<Point>(points.begin() + static_cast<std::ptrdiff_t>(offsets[c]),
                              points.begin() + static_cast<std::ptrdiff_t>(offsets[c + 1]));
  };
  auto batch_vertices = [&](std::size_t c) {
    return std::vector<PointIndex>(
        hulls.vertices.begin() + static_cast<std::ptrdiff_t>(hulls.vertex_offsets[c]),
        hulls.vertices.begin() + static_cast<std::ptrdiff_t>(hulls.vertex_offsets[c + 1]));
  };
  const std::string label = o.distribution + " " + std::to_string(o.batch) + "x" + std::to_string(o.count);
  const double t = median(total);
  nlohmann::json j{{"input", label},
                   {"clouds", o.batch},
                   {"points_per_cloud", o.count},
                   {"points", points.size()},
                   {"hull_vertices", hulls.vertices.size()},
                   {"hull_faces", hulls.faces.size()},
                   {"backend", hulls.backend},
                   {"engine", choice_name(plan.engine)},
                   {"device", plan.backend == BackendChoice::kCuda ? plan.device : "cpu"},
                   {"precision", precision_name(precision)},
                   {"plan", plan.reason},
                   {"threads", plan.backend == BackendChoice::kCuda ? 0u : hardware_workers()},
                   {"repeat", o.repeat},
                   {"total_ms", t},
                   {"us_per_cloud", o.batch ? 1000 * t / static_cast<double>(o.batch) : 0.0},
                   {"clouds_batched", hulls.clouds_batched},
                   {"batch_launches", hulls.batch_launches},
                   {"device_bytes_peak", hulls.device_bytes_peak},
                   {"device_ms", hulls.device_ms},
                   {"describe_ms", hulls.describe_ms},
                   {"kernel_ms", hulls.kernel_ms},
                   {"host_huge_pages", huge_pages_in_use()}};
  // The same clouds one call at a time: Qhull's loop (the reference), or convex_hull()'s.
  double versus_ms = 0;
  std::size_t differ = 0;
  if (!o.versus.empty()) {
    std::vector<double> loop;
    for (int r = 0; r < o.repeat; ++r) {
      differ = 0;
      double ms = 0;
      for (std::size_t c = 0; c < o.batch; ++c) {
        const std::vector<Point> cloud = cloud_of(c);
        const auto t0 = Clock::now();
        std::vector<PointIndex> vertices;
        if (o.versus == "qhull") {
          try {
            vertices = run_qhull(cloud, "Qt").vertex_ids;
          } catch (const std::runtime_error&) {
            vertices.clear();  // a flat or too small cloud: Qhull refuses it, counted as differing
          }
        } else {
          vertices = convex_hull(cloud, request).vertices;
        }
        ms += ms_since(t0);
        differ += vertices != batch_vertices(c);
      }
      loop.push_back(ms);
    }
    versus_ms = median(loop);
    j["versus"] = o.versus;
    j["versus_ms"] = versus_ms;
    j["speedup"] = t > 0 ? versus_ms / t : 0.0;
    j["clouds_with_different_vertices"] = differ;
  }
  if (o.json) {
    std::cout << j.dump() << "\n";
    return kExitOk;
  }
  std::printf("%-28s %8s %10s %10s %12s %12s %9s %s\n", "input", "clouds", "points", "total ms", "us/cloud",
              o.versus.empty() ? "-" : (o.versus + " ms").c_str(), "speedup", "vertices");
  std::printf("%-28s %8llu %10zu %10.2f %12.2f %12s %9s %zu%s\n", label.c_str(),
              static_cast<unsigned long long>(o.batch), points.size(), t,
              o.batch ? 1000 * t / static_cast<double>(o.batch) : 0.0,
              o.versus.empty() ? "-" : std::to_string(versus_ms).substr(0, 10).c_str(),
              o.versus.empty() || t <= 0 ? "-" : (std::to_string(versus_ms / t).substr(0, 6) + "x").c_str(),
              hulls.vertices.size(),
              o.versus.empty() ? ""
              : differ == 0
                  ? (" (same vertices as " + o.versus + ", every cloud)").c_str()
                  : (" (" + std::to_string(differ) + " clouds DIFFER from " + o.versus + ")").c_str());
  std::printf("backend: %s, precision: %s\n", hulls.backend.c_str(), precision_name(precision));
  return kExitOk;
}

}  // namespace

int run_bench_batch(const BenchOptions& o) {
  const ConvexHullOptions request = request_of(o.backend, o.engine, o.precision);
  return planned_precision(request, "") == Precision::kDouble ? bench_batch<Point3d>(o, request)
                                                              : bench_batch<Point3>(o, request);
}

}  // namespace cudahull::cli
