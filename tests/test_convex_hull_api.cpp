// The one-call API (issue 16): convex_hull() against Qhull (vertices) and the exact checker (the faces as a
// mesh), its planes against every point, its neighbours against its faces, and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "cudahull/convex_hull.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/hull_plan.hpp"
#include "qhull_reference.hpp"

namespace cudahull {
namespace {

ConvexHullOptions on_cpu(Precision precision = Precision::kAuto) {
  ConvexHullOptions options;
  options.backend = BackendChoice::kCpu;
  options.precision = precision;
  return options;
}

std::vector<Point3d> widened(const std::vector<Point3>& points) {
  std::vector<Point3d> out;
  for (const Point3& p : points)
    out.push_back({p.x, p.y, p.z});
  return out;
}

// The faces as the exact checker's mesh (vertices local, triangles into them), so that it judges them.
template <class Point>
CheckResult check_faces(const std::vector<Point>& points, const ConvexHull& hull) {
  BasicHullMesh<Point> mesh;
  mesh.dimension = hull.dimension;
  mesh.vertex_ids = hull.vertices;
  std::vector<std::uint32_t> local(points.size(), 0);
  for (std::size_t i = 0; i < hull.vertices.size(); ++i) {
    local[hull.vertices[i]] = static_cast<std::uint32_t>(i);
    mesh.vertices.push_back(points[hull.vertices[i]]);
  }
  for (const auto& f : hull.faces)
    mesh.triangles.push_back({local[f[0]], local[f[1]], local[f[2]]});
  return check_hull(points, mesh);
}

template <class Point>
void expect_planes_and_neighbors(const std::vector<Point>& points, const ConvexHull& hull) {
  ASSERT_EQ(hull.planes.size(), hull.faces.size());
  ASSERT_EQ(hull.neighbors.size(), hull.faces.size());
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const auto& plane = hull.planes[f];
    EXPECT_NEAR(plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2], 1.0, 1e-14);
    for (const Point& p : points)
      EXPECT_LE(plane[0] * p.x + plane[1] * p.y + plane[2] * p.z + plane[3], 1e-12) << "face " << f;
    for (int k = 0; k < 3; ++k) {
      const auto& g = hull.faces[hull.neighbors[f][k]];
      const std::set<PointIndex> shared{g.begin(), g.end()};
      EXPECT_TRUE(shared.count(hull.faces[f][(k + 1) % 3]) && shared.count(hull.faces[f][(k + 2) % 3]));
      EXPECT_FALSE(shared.count(hull.faces[f][k]));
    }
  }
}

TEST(ConvexHullApi, BallInEitherPrecisionMatchesQhullAndTheChecker) {
  const std::vector<Point3> points = generate_points(Distribution::kBall, 5000, 16);
  const std::vector<Point3d> doubles = widened(points);
  const ConvexHull in_float = convex_hull(points, on_cpu());
  const ConvexHull in_double = convex_hull(points, on_cpu(Precision::kDouble));
  EXPECT_EQ(in_float.precision, Precision::kFloat);
  EXPECT_EQ(in_double.precision, Precision::kDouble);
  EXPECT_EQ(in_float.vertices, run_qhull(points).vertex_ids);
  EXPECT_EQ(in_double.vertices, in_float.vertices);  // the same values, widened exactly
  EXPECT_TRUE(check_faces(points, in_float).ok);
  EXPECT_TRUE(check_faces(doubles, in_double).ok);
  expect_planes_and_neighbors(points, in_float);
  // The raw-array overloads are the same call.
  const ConvexHull from_array = convex_hull(&doubles[0].x, doubles.size(), on_cpu());
  EXPECT_EQ(from_array.vertices, in_double.vertices);
  EXPECT_EQ(from_array.faces, in_double.faces);
  EXPECT_EQ(from_array.volume, in_double.volume);
}

// The default engine, auto: the resident engine where a GPU runs the hull, the stepping engine (backend
// "cpu (N threads)") otherwise; every engine gives Qhull's vertices.
TEST(ConvexHullApi, DefaultEngineIsResidentOnAGpuAndSteppingOnTheCpu) {
  const std::vector<Point3> points = generate_points(Distribution::kSphere, 3000, 4);
  const ConvexHull automatic = convex_hull(points);
  EXPECT_EQ(automatic.backend.substr(0, cuda_status().usable ? 13 : 4),
            cuda_status().usable ? "cuda-resident" : "cpu ");
  EXPECT_EQ(automatic.vertices, run_qhull(points).vertex_ids);
  ConvexHullOptions cpu;
  cpu.backend = BackendChoice::kCpu;
  EXPECT_EQ(convex_hull(points, cpu).backend.substr(0, 4), "cpu ");  // "cpu (N threads)": the stepping one
  cpu.engine = EngineChoice::kResident;
  const ConvexHull resident = convex_hull(points, cpu);
  EXPECT_EQ(resident.backend, "cpu-resident");
  EXPECT_EQ(resident.vertices, automatic.vertices);
  // The result says how it ran: the plan's line, as --stats prints it.
  EXPECT_EQ(resident.plan.rfind("resident engine (as requested); backend cpu (as requested)", 0), 0u)
      << resident.plan;
  EXPECT_NE(automatic.plan.find(cuda_status().usable ? "backend cuda" : "backend cpu (auto: no usable"),
            std::string::npos)
      << automatic.plan;
  EXPECT_EQ(engine_from_name("auto"), EngineChoice::kAuto);
  EXPECT_THROW(engine_from_name("fast"), std::invalid_argument);
}

TEST(ConvexHullApi, FlatInputGivesThePolygon) {
  const std::vector<Point3d> square{{0, 0, 5}, {2, 0, 5}, {1, 1, 5}, {2, 2, 5}, {0, 2, 5}};
  const ConvexHull hull = convex_hull(square, on_cpu());
  EXPECT_EQ(hull.dimension, 2);
  EXPECT_EQ(hull.vertices, (std::vector<PointIndex>{0, 1, 3, 4}));
  EXPECT_EQ(std::set<PointIndex>(hull.polygon.begin(), hull.polygon.end()),
            (std::set<PointIndex>{0, 1, 3, 4}));
  EXPECT_EQ(hull.area, 8.0);  // both sides of the 2 x 2 square
  EXPECT_EQ(hull.volume, 0.0);
  EXPECT_TRUE(hull.faces.empty() && hull.planes.empty());
}

TEST(ConvexHullApi, BadInputIsOneInputError) {
  auto message = [](auto&& call) {
    try {
      call();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no InputError");
  };
  std::vector<Point3d> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  points[2].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message([&] { convex_hull(points); }), "point 2: y coordinate nan is not finite");
  // Every finite double is taken (issue 25): 1e300 goes to the wide-range path, exactly.
  points[2].y = 1e300;
  const ConvexHull far = convex_hull(points, on_cpu());
  EXPECT_EQ(far.backend, "cpu-wide");
  EXPECT_EQ(far.vertices, (std::vector<PointIndex>{0, 1, 2, 3}));
  points[2].y = 1e39;
  EXPECT_EQ(message([&] { convex_hull(points, on_cpu(Precision::kFloat)); }),
            "point 2: y coordinate 1e+39 does not fit in float");
  std::vector<Point3> floats{{0, 0, 0}, {1, 0, 0}, {0, 0, std::numeric_limits<float>::infinity()}};
  EXPECT_EQ(message([&] { convex_hull(floats); }), "point 2: z coordinate inf is not finite");
}

// What convex_hull_device() refuses before it reads a point (its hulls are tested on the GPU through the
// Python module, python/gpu_tests).
TEST(ConvexHullApi, DevicePointsNeedTheGpu) {
  const std::vector<Point3> host{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ConvexHullOptions cpu;
  cpu.backend = BackendChoice::kCpu;
  EXPECT_THROW(convex_hull_device(&host[0].x, host.size(), cpu), std::invalid_argument);
  const CudaStatus cuda = cuda_status();
  if (cuda.usable) {
    // A host pointer is no device memory: refused, instead of faulting in the engine's first kernel.
    try {
      convex_hull_device(&host[0].x, host.size());
      ADD_FAILURE() << "a host pointer was taken as device memory";
    } catch (const DeviceError& e) {
      EXPECT_EQ(std::string(e.what()), "device points: the array is not in CUDA device memory");
    }
    return;
  }
  try {
    convex_hull_device(&host[0].x, host.size());
    ADD_FAILURE() << "no DeviceError without a GPU";
  } catch (const DeviceError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("points in GPU memory, but no usable CUDA device: ", 0), 0u)
        << e.what();
  }
}

// One place decides how a hull runs (issue 26): plan_hull() against choices written out here, with the
// device's status given, so that every branch runs on any machine; then the real machine's plan against what
// convex_hull() and make_backend() did.
TEST(ConvexHullApi, PlanHullResolvesAutoAndSaysWhy) {
  const CudaStatus no_gpu{false, "", "no CUDA-capable device is detected"};
  const CudaStatus gpu{true, "NVIDIA H100 80GB HBM3", ""};
  int asked = 0;
  auto device = [&asked](const CudaStatus& status) {
    return [&asked, status] {
      ++asked;
      return status;
    };
  };
  HullInput floats;  // a float array of 1000 points
  floats.count = 1000;
  HullInput doubles = floats;
  doubles.precision = Precision::kDouble;

  // Everything auto on float input without a GPU: float, the stepping engine on the CPU, and why.
  HullPlan plan = plan_hull({}, floats, device(no_gpu));
  EXPECT_EQ(plan.precision, Precision::kFloat);
  EXPECT_EQ(plan.precision_reason, "auto");
  EXPECT_EQ(plan.engine, EngineChoice::kStepping);
  EXPECT_EQ(plan.engine_reason, "auto: no usable CUDA device");
  EXPECT_EQ(plan.backend, BackendChoice::kCpu);
  EXPECT_EQ(plan.backend_reason, "auto: no usable CUDA device: no CUDA-capable device is detected");
  EXPECT_EQ(plan.reason,
            "stepping engine (auto: no usable CUDA device); backend cpu (auto: no usable CUDA device: no "
            "CUDA-capable device is detected); precision float (auto)");
  EXPECT_TRUE(plan.unavailable.empty());
  EXPECT_FALSE(plan.wide_range || plan.upload_first);
  EXPECT_EQ(asked, 1);  // both the engine and the backend depend on it: asked once

  // With a GPU: the resident engine on it, the points uploaded as they are; none to upload for no points.
  plan = plan_hull({}, doubles, device(gpu));
  EXPECT_EQ(plan.precision, Precision::kDouble);
  EXPECT_EQ(plan.engine, EngineChoice::kResident);
  EXPECT_EQ(plan.backend, BackendChoice::kCuda);
  EXPECT_EQ(plan.device, "NVIDIA H100 80GB HBM3");
  EXPECT_EQ(plan.backend_reason, "auto: a usable CUDA device");
  EXPECT_TRUE(plan.upload_first);
  EXPECT_FALSE(plan_hull({}, HullInput{}, device(gpu)).upload_first);

  // A double 1e300 is outside the engines' range: the wide path on the host, which needs no device, so
  // backend cuda without one still runs, and the device is not asked.  Rounded to float it is no longer wide.
  const std::vector<Point3d> far{{0, 0, 0}, {1, 0, 0}, {0, 1e300, 0}, {0, 0, 1}};
  HullInput wide = doubles;
  wide.outside_exact_range = !in_fast_exact_range(far);
  ConvexHullOptions cuda_stepping;
  cuda_stepping.backend = BackendChoice::kCuda;
  cuda_stepping.engine = EngineChoice::kStepping;
  asked = 0;
  plan = plan_hull(cuda_stepping, wide, device(no_gpu));
  EXPECT_TRUE(plan.wide_range);
  EXPECT_EQ(plan.backend, BackendChoice::kCpu);
  EXPECT_EQ(plan.precision, Precision::kDouble);
  EXPECT_TRUE(plan.unavailable.empty()) << plan.unavailable;
  EXPECT_NE(plan.reason.find("outside 2^-250..2^250"), std::string::npos) << plan.reason;
  EXPECT_EQ(asked, 0);
  EXPECT_EQ(convex_hull(far, cuda_stepping).backend, "cpu-wide");
  ConvexHullOptions in_float;
  in_float.precision = Precision::kFloat;
  plan = plan_hull(in_float, wide, device(no_gpu));
  EXPECT_FALSE(plan.wide_range);
  EXPECT_EQ(plan.precision, Precision::kFloat);
  EXPECT_EQ(plan.precision_reason, "as requested");

  // An explicit request is taken as it is, and backend cpu with a definite engine asks for no device.
  ConvexHullOptions explicit_cpu;
  explicit_cpu.backend = BackendChoice::kCpu;
  explicit_cpu.engine = EngineChoice::kResident;
  explicit_cpu.precision = Precision::kDouble;
  asked = 0;
  plan = plan_hull(explicit_cpu, floats, device(gpu));
  EXPECT_EQ(asked, 0);
  EXPECT_EQ(plan.engine, EngineChoice::kResident);
  EXPECT_EQ(plan.backend, BackendChoice::kCpu);
  EXPECT_EQ(plan.precision, Precision::kDouble);
  EXPECT_EQ(plan.reason,
            "resident engine (as requested); backend cpu (as requested); precision double (as requested)");
  EXPECT_FALSE(plan.upload_first);
  // Engine auto with backend cpu: the stepping engine, still without asking.
  explicit_cpu.engine = EngineChoice::kAuto;
  EXPECT_EQ(plan_hull(explicit_cpu, floats, device(gpu)).engine, EngineChoice::kStepping);
  EXPECT_EQ(asked, 0);

  // Backend cuda without a GPU cannot run: the plan says so in DeviceError's words.
  ConvexHullOptions cuda;
  cuda.backend = BackendChoice::kCuda;
  plan = plan_hull(cuda, floats, device(no_gpu));
  EXPECT_EQ(plan.backend, BackendChoice::kCuda);
  EXPECT_EQ(plan.engine, EngineChoice::kStepping);
  EXPECT_EQ(plan.unavailable, "backend cuda: no usable CUDA device: no CUDA-capable device is detected");

  // Points in GPU memory take the resident engine on CUDA whatever the engine asked; backend cpu is a wrong
  // request and a missing GPU a missing device.
  HullInput on_device = floats;
  on_device.on_device = true;
  plan = plan_hull(cuda_stepping, on_device, device(gpu));
  EXPECT_EQ(plan.engine, EngineChoice::kResident);
  EXPECT_EQ(plan.backend, BackendChoice::kCuda);
  EXPECT_TRUE(plan.unavailable.empty());
  EXPECT_EQ(plan_hull(explicit_cpu, on_device, device(gpu)).unavailable,
            "points in GPU memory need backend auto or cuda, not cpu");
  EXPECT_EQ(plan_hull({}, on_device, device(no_gpu)).unavailable,
            "points in GPU memory, but no usable CUDA device: no CUDA-capable device is detected");

  // 2-D host input: the host's planar hull whatever the backend; backend cuda still needs the device.
  HullInput planar = doubles;
  planar.dimension = 2;
  plan = plan_hull(cuda, planar, device(gpu));
  EXPECT_EQ(plan.backend, BackendChoice::kCpu);
  EXPECT_TRUE(plan.unavailable.empty());
  EXPECT_FALSE(plan_hull(cuda, planar, device(no_gpu)).unavailable.empty());

  // This machine: convex_hull() and make_backend() run what plan_hull() (asking cuda_status()) chose.
  const std::vector<Point3> points = generate_points(Distribution::kCube, 500, 3);
  floats.count = points.size();
  plan = plan_hull({}, floats);
  EXPECT_EQ(plan.backend == BackendChoice::kCuda, cuda_status().usable);
  const std::string ran = convex_hull(points).backend;
  EXPECT_EQ(ran.substr(0, ran.find(' ')), plan.engine == EngineChoice::kResident ? "cuda-resident" : "cpu");
  std::string why;
  EXPECT_EQ(make_backend<Point3>(BackendChoice::kAuto, &why)->name().substr(0, 4),
            plan.backend == BackendChoice::kCuda ? "cuda" : "cpu ");
  EXPECT_EQ(why, plan.backend_reason);
}

// 2-D input (issue 25): a square with points inside and on its edges, and a duplicate of a corner.  The
// corners counter-clockwise from the lowest (x, y), the edges and their neighbours in scipy's convention,
// unit outward lines, the area as volume and the perimeter as area.
TEST(ConvexHullApi, TwoDimensionalInputGivesThePolygonsEdgesAndLines) {
  const std::vector<double> xy{0.5, 0.5, 2, 0, 2, 2, 0, 2, 1, 0, 0, 0, 2, 1, 0, 0};
  const ConvexHull hull = convex_hull_2d(xy.data(), xy.size() / 2, on_cpu());
  EXPECT_EQ(hull.input_dimension, 2);
  EXPECT_EQ(hull.dimension, 2);
  EXPECT_EQ(hull.polygon, (std::vector<PointIndex>{5, 1, 2, 3}));  // (0,0) first; the duplicate 7 is not
  EXPECT_EQ(hull.vertices, (std::vector<PointIndex>{1, 2, 3, 5}));
  ASSERT_EQ(hull.edges.size(), 4u);
  EXPECT_EQ(hull.edges[0], (std::array<PointIndex, 2>{5, 1}));
  // neighbors[e][k] is the edge opposite corner k: across from 5 lies the edge that goes on from 1.
  EXPECT_EQ(hull.edge_neighbors[0], (std::array<std::int32_t, 2>{1, 3}));
  const std::array<double, 3> bottom{0, -1, 0};
  EXPECT_EQ(hull.lines[0], bottom);
  EXPECT_EQ(hull.volume, 4.0);
  EXPECT_EQ(hull.area, 8.0);
  // float input gives the same corners, in float.
  const std::vector<float> as_float(xy.begin(), xy.end());
  const ConvexHull in_float = convex_hull_2d(as_float.data(), as_float.size() / 2, on_cpu());
  EXPECT_EQ(in_float.polygon, hull.polygon);
  EXPECT_EQ(in_float.precision, Precision::kFloat);
}

// Merging through the API (issue 25): a cube whose face centres stand 1 and 2 units in the last place
// proud of their faces.  The exact hull keeps them; Qhull's tolerance merges them away, lists them as
// coplanar and bounds their height; an explicit relative tolerance does the same.
TEST(ConvexHullApi, MergingDropsPointsWithinTheToleranceAndBoundsThem) {
  std::vector<Point3d> points;
  for (double x : {0.0, 1.0})
    for (double y : {0.0, 1.0})
      for (double z : {0.0, 1.0})
        points.push_back({x, y, z});
  points.push_back({0.5, 0.5, std::nextafter(1.0, 2.0)});
  points.push_back({0.5, std::nextafter(std::nextafter(1.0, 2.0), 2.0), 0.5});
  EXPECT_EQ(convex_hull(points, on_cpu()).vertices.size(), 10u);
  for (const MergeMode mode : {MergeMode::kQhull, MergeMode::kRelative}) {
    ConvexHullOptions options = on_cpu();
    options.merge = mode;
    options.tolerance = 1e-12;
    const ConvexHull merged = convex_hull(points, options);
    EXPECT_EQ(merged.vertices, (std::vector<PointIndex>{0, 1, 2, 3, 4, 5, 6, 7}));
    ASSERT_EQ(merged.coplanar.size(), 2u);
    EXPECT_EQ(merged.coplanar[0][0], 8u);
    EXPECT_EQ(merged.coplanar[1][0], 9u);
    EXPECT_GT(merged.tolerance, 0);
    for (const auto& plane : merged.planes)
      for (const Point3d& p : points)
        EXPECT_LE(plane[0] * p.x + plane[1] * p.y + plane[2] * p.z + plane[3], merged.max_outside);
    EXPECT_NEAR(merged.volume, 1.0, 1e-15);
  }
}

}  // namespace
}  // namespace cudahull
