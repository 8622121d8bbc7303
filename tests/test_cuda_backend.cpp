// The CUDA backend against the CPU backend (label gpu: runs on the GPU machine only).  Both run the same
// routing.hpp code on the same float points, so everything must agree exactly: every iteration record
// (faces, swaps, removals, decisions, external counts), every face's count and extreme point, every point's
// face, and the final hull.  Without a usable CUDA device every test here FAILS (it never skips): the gpu
// label is only run where a GPU is expected.
//
// Environment: CUDAHULL_MODELS_DIR overrides the compiled-in folder of the shared models (the GPU machine
// gets a copy carried beside the binary).  Timings are not tests: `cudahull bench` and `cudahull hull
// --table` measure them (docs/benchmarks.md).
#include <gtest/gtest.h>

#include "support/dist_cases.hpp"
#include "support/point_sets.hpp"
#include "support/shared_models.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <cuda_runtime_api.h>

#include "cudahull/cpu_backend.hpp"
#include "cudahull/cuda/cuda_backend.hpp"
#include "cudahull/cuda/device_info.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/point_io.hpp"

namespace cudahull {
namespace {

using testing::DistCase;
using testing::grid;
using testing::scaled;

// Every test needs the device: fail (never skip) with the reason when there is none.
class Cuda : public ::testing::Test {
 protected:
  void SetUp() override {
    const CudaDeviceInfo info = query_cuda_device();
    ASSERT_TRUE(info.usable) << "no usable CUDA device (" << info.reason
                             << "): the gpu-labelled tests must run on a machine with an NVIDIA GPU";
  }
};

std::string describe(const IterationRecord& r) {
  return "iteration " + std::to_string(r.iteration);
}

void expect_same_record(const IterationRecord& c, const IterationRecord& g) {
  const std::string at = describe(c);
  EXPECT_EQ(g.iteration, c.iteration);
  EXPECT_EQ(g.faces_before, c.faces_before) << at;
  EXPECT_EQ(g.faces_after, c.faces_after) << at;
  EXPECT_EQ(g.faces_refined, c.faces_refined) << at;
  EXPECT_EQ(g.swaps_regular, c.swaps_regular) << at;
  EXPECT_EQ(g.swaps_complementary, c.swaps_complementary) << at;
  EXPECT_EQ(g.swaps_rejected, c.swaps_rejected) << at;
  EXPECT_EQ(g.vertices_removed, c.vertices_removed) << at;
  EXPECT_EQ(g.removals_rejected, c.removals_rejected) << at;
  EXPECT_EQ(g.decision_entries, c.decision_entries) << at;
  EXPECT_EQ(g.external_before, c.external_before) << at;
  EXPECT_EQ(g.external_after, c.external_after) << at;
  EXPECT_EQ(g.repairs, c.repairs) << at;
  EXPECT_EQ(g.refined_apexes, c.refined_apexes) << at;
  EXPECT_EQ(g.note, c.note) << at;
  ASSERT_EQ(g.swaps.size(), c.swaps.size()) << at;
  for (std::size_t k = 0; k < c.swaps.size(); ++k) {
    EXPECT_EQ(g.swaps[k].kind, c.swaps[k].kind) << at << " swap " << k;
    EXPECT_EQ(g.swaps[k].old_edge[0], c.swaps[k].old_edge[0]) << at << " swap " << k;
    EXPECT_EQ(g.swaps[k].old_edge[1], c.swaps[k].old_edge[1]) << at << " swap " << k;
    EXPECT_EQ(g.swaps[k].new_edge[0], c.swaps[k].new_edge[0]) << at << " swap " << k;
    EXPECT_EQ(g.swaps[k].new_edge[1], c.swaps[k].new_edge[1]) << at << " swap " << k;
  }
  ASSERT_EQ(g.removals.size(), c.removals.size()) << at;
  for (std::size_t k = 0; k < c.removals.size(); ++k) {
    EXPECT_EQ(g.removals[k].vertex, c.removals[k].vertex) << at << " removal " << k;
    EXPECT_EQ(g.removals[k].rejected, c.removals[k].rejected) << at << " removal " << k;
  }
}

template <class Point>
void expect_same_hull(const BasicHullMesh<Point>& c, const BasicHullMesh<Point>& g) {
  EXPECT_EQ(g.dimension, c.dimension);
  EXPECT_EQ(g.vertex_ids, c.vertex_ids);
  EXPECT_EQ(g.vertices, c.vertices);
  EXPECT_EQ(g.triangles, c.triangles);
  EXPECT_EQ(g.polygon, c.polygon);
}

struct CompareOptions {
  bool point_faces = false;  // compare every point's face after every step (O(points) copies)
  bool check_hull = false;   // run the exact checker on the result too
  bool restart = false;      // then restart the CUDA engine and compare its records again
};

// Runs the engine on both backends in lockstep and compares after every step, in float or double (both
// backends run the same routing.hpp code on the same points: everything must agree exactly).  Returns the
// CUDA records.
template <class Point = Point3>
std::vector<IterationRecord> compare_backends(const std::vector<Point>& points, const std::string& what,
                                              CompareOptions options = {}) {
  SCOPED_TRACE(what + (std::is_same_v<Point, Point3d> ? " (double)" : ""));
  BasicEngine<Point> cpu(points, make_cpu_backend<Point>());
  BasicEngine<Point> gpu(points, make_cuda_backend<Point>());
  std::vector<IterationRecord> records;
  while (!cpu.done()) {
    EXPECT_FALSE(gpu.done());
    if (gpu.done()) break;
    const IterationRecord c = cpu.step();
    const IterationRecord g = gpu.step();
    expect_same_record(c, g);
    records.push_back(g);
    const auto& ce = cpu.face_extremes();
    const auto& ge = gpu.face_extremes();
    EXPECT_EQ(ge.size(), ce.size()) << describe(c);
    if (ge.size() == ce.size()) {
      std::size_t differing = 0, first = 0;
      for (std::size_t f = 0; f < ce.size(); ++f) {
        if (ce[f].count != ge[f].count || ce[f].furthest != ge[f].furthest) {
          if (differing++ == 0) first = f;
        }
      }
      EXPECT_EQ(differing, 0u) << describe(c) << ": first differing face " << first << " (cpu count "
                               << ce[first].count << " furthest " << ce[first].furthest << ", cuda count "
                               << ge[first].count << " furthest " << ge[first].furthest << ")";
    }
    if (options.point_faces && cpu.dimension() == 3) {
      const auto cf = cpu.point_faces(), gf = gpu.point_faces();
      EXPECT_EQ(gf, cf) << describe(c) << ": per-point faces differ";
    }
    if (::testing::Test::HasFatalFailure()) break;
  }
  EXPECT_TRUE(gpu.done());
  const BasicHullMesh<Point>& ch = cpu.result();
  const BasicHullMesh<Point>& gh = gpu.result();
  expect_same_hull(ch, gh);
  if (options.check_hull) {
    const CheckResult check = check_hull(points, gh);
    EXPECT_TRUE(check.ok) << (check.failures.empty() ? "" : check.failures.front());
  }
  if (!options.restart || ::testing::Test::HasFatalFailure()) return records;
  // Backend::restart(): the CUDA backend keeps its double points and repeats every step.
  gpu.restart();
  std::size_t k = 0;
  while (!gpu.done() && k < records.size()) {
    const IterationRecord g = gpu.step();
    expect_same_record(records[k++], g);
    if (::testing::Test::HasFatalFailure()) break;
  }
  EXPECT_TRUE(gpu.done()) << "after restart()";
  EXPECT_EQ(k, records.size()) << "after restart()";
  EXPECT_EQ(gpu.result().vertex_ids, ch.vertex_ids) << "after restart()";
  return records;
}

std::vector<IterationRecord> compare_double_backends(const std::vector<Point3d>& points,
                                                     const std::string& what, CompareOptions options = {}) {
  options.restart = true;
  return compare_backends(points, what, options);
}

// --- The backend's own queries ------------------------------------------------------------------------

TEST_F(Cuda, BackendNameAndBadDevice) {
  auto backend = make_cuda_backend();
  EXPECT_NE(backend->name().find("cuda"), std::string::npos) << backend->name();
  try {
    make_cuda_backend(4096);
    FAIL() << "device 4096 accepted";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("4096"), std::string::npos) << e.what();
  }
}

// The furthest point from the line and the plane through five random pairs and triples of the `size`
// points, the same on both backends.
template <class Cpu, class Gpu>
void expect_same_random_queries(Cpu& cpu, Gpu& gpu, std::size_t size, std::mt19937& rng, int trial) {
  for (int k = 0; k < 5; ++k) {
    std::uniform_int_distribution<PointIndex> pick(0, static_cast<PointIndex>(size - 1));
    const PointIndex a = pick(rng), b = pick(rng), c = pick(rng);
    EXPECT_EQ(gpu.furthest_from_line(a, b), cpu.furthest_from_line(a, b)) << "trial " << trial;
    EXPECT_EQ(gpu.furthest_from_plane(a, b, c), cpu.furthest_from_plane(a, b, c)) << "trial " << trial;
  }
}

TEST_F(Cuda, QueriesMatchTheCpuWithTies) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<Point3> p;
    if (trial < 4) {
      p = generate_points(Distribution::kCube, 1000 + 77777 * trial, trial);
    } else {
      // Small integers: many equal scores, so the lowest-index rule decides.
      std::uniform_int_distribution<int> coord(-3, 3);
      p.resize(500 + 40000 * (trial - 4));
      for (auto& q : p)
        q = {float(coord(rng)), float(coord(rng)), float(coord(rng))};
      p[p.size() / 2] = {-0.0f, 3.0f, 0.0f};
      p[p.size() / 3] = {0.0f, -3.0f, -0.0f};
    }
    auto cpu = make_cpu_backend(3), gpu = make_cuda_backend();
    cpu->upload_points(p);
    gpu->upload_points(p);
    const auto cx = cpu->extremes_x(), gx = gpu->extremes_x();
    EXPECT_EQ(gx, cx) << "trial " << trial;
    expect_same_random_queries(*cpu, *gpu, p.size(), rng, trial);
  }
}

// --- Whole runs: identical on both backends -------------------------------------------------------------

class CudaGeneral : public Cuda, public ::testing::WithParamInterface<DistCase> {};

// A case's whole run, the same on both backends (restarted too in double): every point's face and the
// checker up to 100000 points, and no external point left at the end.
template <class Point>
void expect_same_whole_run(const std::vector<Point>& points, const DistCase& c) {
  CompareOptions options;
  options.point_faces = c.n <= 100000;
  options.check_hull = c.n <= 100000;
  options.restart = std::is_same_v<Point, Point3d>;
  const auto records =
      compare_backends(points, distribution_name(c.dist) + " " + std::to_string(c.n), options);
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records.back().external_after, 0u);
}

TEST_P(CudaGeneral, SameAsCpu) {
  const DistCase c = GetParam();
  expect_same_whole_run(generate_points(c.dist, c.n, 20261122 + c.n), c);
}

INSTANTIATE_TEST_SUITE_P(
    Engine, CudaGeneral,
    ::testing::ValuesIn(testing::dist_cases({{Distribution::kCube, {1000, 100000, 1000000}},
                                             {Distribution::kBall, {1000, 100000, 1000000}},
                                             {Distribution::kSphere, {1000, 100000, 1000000}},
                                             {Distribution::kGauss, {1000, 100000, 1000000}},
                                             {Distribution::kParaboloid, {20000}},
                                             {Distribution::kCylinder, {20000}},
                                             {Distribution::kGrid, {27000}}})),
    testing::dist_case_name);

TEST_F(Cuda, ManySmallSeeds) {
  for (Distribution dist : {Distribution::kCube, Distribution::kBall, Distribution::kGauss}) {
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      compare_backends(generate_points(dist, 2000, seed),
                       distribution_name(dist) + " seed " + std::to_string(seed), {true, false});
    }
  }
}

TEST_F(Cuda, DegenerateInputs) {
  compare_backends(grid(6), "integer grid 6x6x6", {true, true});
  std::vector<Point3> surface;
  for (const Point3& p : grid(9)) {
    if (p.x == 0 || p.y == 0 || p.z == 0 || p.x == 8 || p.y == 8 || p.z == 8)
      surface.push_back({p.x / 8.0f, p.y / 8.0f, p.z / 8.0f});
  }
  compare_backends(surface, "grid on a cube surface", {true, true});

  const auto base = generate_points(Distribution::kBall, 3000, 5);
  std::vector<Point3> tripled;
  for (int copy = 0; copy < 3; ++copy)
    tripled.insert(tripled.end(), base.begin(), base.end());
  compare_backends(tripled, "tripled ball", {true, true});

  compare_backends(testing::integer_paraboloid(20), "integer paraboloid", {true, true});

  auto slab = generate_points(Distribution::kCube, 50000, 11);
  for (auto& p : slab)
    p.z = (p.z + 1.0f) * 0.5e-6f;
  compare_backends(slab, "thin slab", {false, true});

  const auto ball = generate_points(Distribution::kBall, 20000, 13);
  for (float s : {0x1p100f, 0x1p-100f, 1e30f, 1e-30f}) {
    compare_backends(scaled(ball, s), "ball scaled by " + std::to_string(s), {true, true});
  }

  std::vector<Point3> coplanar, collinear, single(10, Point3{1.5f, -2.0f, 3.0f});
  for (int i = 0; i < 200; ++i) {
    coplanar.push_back({float(i % 17), float((i * 7) % 13), 4.0f});
    collinear.push_back({float(i), float(2 * i), float(-i)});
  }
  compare_backends(coplanar, "coplanar");
  compare_backends(collinear, "collinear");
  compare_backends(single, "one point ten times");
  compare_backends({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, "three points");
  compare_backends({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, "four points");
}

TEST_F(Cuda, SmallRandomIntegerSets) {
  const auto sets = testing::small_integer_sets(60);
  for (std::size_t trial = 0; trial < sets.size(); ++trial) {
    compare_backends(sets[trial], "small integer set " + std::to_string(trial), {true, false});
  }
}

TEST_F(Cuda, SharedModels) {
  const std::filesystem::path dir = testing::shared_models_dir();
  if (!std::filesystem::exists(dir))
    GTEST_SKIP() << "no models folder " << dir << " (set CUDAHULL_MODELS_DIR)";
  int found = 0;
  for (const auto& [name, count] : testing::kSharedModelCounts) {
    if (!std::filesystem::exists(dir / name)) continue;
    ++found;
    const auto points = read_points((dir / name).string());
    compare_backends(points, name, {false, true});
  }
  std::printf("compared %d shared models from %s\n", found, dir.string().c_str());
  EXPECT_GT(found, 0) << "no known model in " << dir;
}

// --- Only O(faces) data crosses per iteration ---------------------------------------------------------

TEST_F(Cuda, TrafficPerIterationIsOFaces) {
  const std::size_t n = 1000000;
  const auto points = generate_points(Distribution::kCube, n, 99);
  Engine engine(points, make_cuda_backend());
  int iterations = 0;
  engine.run([&](const IterationRecord& r) {
    ++iterations;
    const std::uint64_t from_bound = 64 * r.faces_after + 1024;
    EXPECT_LT(r.bytes_from_backend, from_bound) << describe(r) << ", faces " << r.faces_after;
    if (r.iteration == 0) {
      // The one O(points) transfer: the points themselves, once.
      EXPECT_GE(r.bytes_to_backend, n * sizeof(Point3));
      EXPECT_LT(r.bytes_to_backend, n * sizeof(Point3) + 4096);
    } else {
      const std::uint64_t to_bound =
          128 * r.faces_before + 64 * r.decision_entries + 64 * r.faces_after + 8 * r.faces_refined + 1024;
      EXPECT_LT(r.bytes_to_backend, to_bound) << describe(r);
    }
  });
  EXPECT_GT(iterations, 3);
}

// --- Limits (issue 7, item 4) --------------------------------------------------------------------------

// More points than the device can hold are a DeviceError naming the allocation (the command line's exit 4),
// not a crash or a wrong answer; once the memory is back, the same points work.  The device is filled first
// (all but about 100 MiB), so the test needs no input larger than the GPU.
TEST_F(Cuda, OutOfDeviceMemoryIsADeviceErrorThenRecovers) {
  const auto points = generate_points(Distribution::kCube, 10000000, 5);  // 240 MB on the device
  std::vector<void*> hog;
  auto free_bytes = [] {
    std::size_t free = 0, total = 0;
    cudaMemGetInfo(&free, &total);
    return free;
  };
  for (std::size_t chunk = std::size_t{1} << 30; chunk >= (std::size_t{1} << 24); chunk /= 2) {
    void* p = nullptr;
    while (free_bytes() > chunk + (std::size_t{100} << 20) && cudaMalloc(&p, chunk) == cudaSuccess)
      hog.push_back(p);
    cudaGetLastError();
  }
  ASSERT_LT(free_bytes(), std::size_t{200} << 20) << "could not fill the device";
  std::string message;
  try {
    Engine engine(points, make_cuda_backend());
    engine.run();
  } catch (const DeviceError& e) {
    message = e.what();
  }
  for (void* p : hog)
    cudaFree(p);
  EXPECT_NE(message.find("out of device memory"), std::string::npos) << "no DeviceError; got: " << message;

  Engine engine(points, make_cuda_backend());
  engine.run();
  Engine cpu(points, make_cpu_backend());
  cpu.run();
  EXPECT_EQ(engine.result().vertex_ids, cpu.result().vertex_ids);
}

// --- Double coordinates (BasicEngine<Point3d>, make_*_backend<Point3d>) ------------------------------------

std::vector<Point3d> to_double(const std::vector<Point3>& p) {
  std::vector<Point3d> d(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    d[i] = {p[i].x, p[i].y, p[i].z};
  return d;
}

std::vector<Point3> to_float(const std::vector<Point3d>& p) {
  std::vector<Point3> f(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    f[i] = {static_cast<float>(p[i].x), static_cast<float>(p[i].y), static_cast<float>(p[i].z)};
  return f;
}

// A ball of float points around (2, 2, 2) (every coordinate in [1, 3], where a float step is 1.2e-7),
// followed by a copy of each point 1e-12 further from the centre.  Rounded to float, each copy is its
// original again (a float path sees every point twice); in double every copy lies strictly outside its
// original, so the extremes in x and the hull's vertices are copies.
std::vector<Point3d> ball_with_near_copies(std::size_t n, std::uint64_t seed) {
  std::vector<Point3> ball = generate_points(Distribution::kBall, n, seed);
  for (auto& q : ball)
    q = {q.x + 2.0f, q.y + 2.0f, q.z + 2.0f};
  std::vector<Point3d> p = to_double(ball);
  p.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point3d q = p[i];
    const double dx = q.x - 2.0, dy = q.y - 2.0, dz = q.z - 2.0;
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (r == 0) {
      p.push_back({q.x, q.y, q.z + 1e-12});
    } else {
      p.push_back({q.x + 1e-12 * dx / r, q.y + 1e-12 * dy / r, q.z + 1e-12 * dz / r});
    }
  }
  return p;
}

// (1, 1, 1) + 1e-12 q for q in a ball: every point rounds to (1, 1, 1) in float (dimension 0 there), while in
// double the points span a ball of a few thousand steps of 2^-52 across (many coincidences and coplanar
// points at that resolution).
std::vector<Point3d> ball_at_1e12_scale(std::size_t n, std::uint64_t seed) {
  std::vector<Point3d> p = to_double(generate_points(Distribution::kBall, n, seed));
  for (auto& q : p)
    q = {1.0 + 1e-12 * q.x, 1.0 + 1e-12 * q.y, 1.0 + 1e-12 * q.z};
  return p;
}

TEST_F(Cuda, DoubleQueriesMatchTheCpuWhereFloatWouldTie) {
  std::mt19937 rng(17);
  const std::size_t n = 30000;
  for (int trial = 0; trial < 4; ++trial) {
    const std::vector<Point3d> p =
        trial < 2 ? ball_with_near_copies(n, 40 + trial) : ball_at_1e12_scale(2 * n, 40 + trial);
    auto cpu = make_cpu_backend<Point3d>(3);
    auto gpu = make_cuda_backend<Point3d>();
    cpu->upload_points(p);
    gpu->upload_points(p);
    EXPECT_EQ(gpu->bytes_to_backend(), p.size() * sizeof(Point3d)) << "trial " << trial;
    const auto cx = cpu->extremes_x(), gx = gpu->extremes_x();
    EXPECT_EQ(gx, cx) << "trial " << trial;
    if (trial < 2) {
      // The extremes in x are copies (the second half); in float they are originals.
      EXPECT_GE(cx[0], n) << "trial " << trial;
      EXPECT_GE(cx[1], n) << "trial " << trial;
      auto cpu_float = make_cpu_backend<Point3>(3);
      const std::vector<Point3> rounded = to_float(p);
      cpu_float->upload_points(rounded);
      const auto fx = cpu_float->extremes_x();
      EXPECT_EQ(fx[0] + n, cx[0]) << "trial " << trial;
      EXPECT_EQ(fx[1] + n, cx[1]) << "trial " << trial;
    } else {
      EXPECT_LT(p[cx[0]].x, p[cx[1]].x) << "trial " << trial;  // all one point in float
    }
    // The engine's corners (section 3.1), then random triples.
    const PointIndex c = cpu->furthest_from_line(cx[0], cx[1]);
    EXPECT_EQ(gpu->furthest_from_line(cx[0], cx[1]), c) << "trial " << trial;
    EXPECT_EQ(gpu->furthest_from_plane(cx[0], cx[1], c), cpu->furthest_from_plane(cx[0], cx[1], c))
        << "trial " << trial;
    expect_same_random_queries(*cpu, *gpu, p.size(), rng, trial);
  }
}

// The generators' float points, exactly as doubles: the same hulls as in float, through the double code.
class CudaDouble : public Cuda, public ::testing::WithParamInterface<DistCase> {};

TEST_P(CudaDouble, SameAsCpu) {
  const DistCase c = GetParam();
  expect_same_whole_run(to_double(generate_points(c.dist, c.n, 31)), c);
}

INSTANTIATE_TEST_SUITE_P(Engine, CudaDouble,
                         ::testing::ValuesIn(testing::dist_cases({{Distribution::kCube, {100000, 1000000}},
                                                                  {Distribution::kBall, {100000}},
                                                                  {Distribution::kSphere, {100000}},
                                                                  {Distribution::kGauss, {100000}}})),
                         testing::dist_case_name);

TEST_F(Cuda, DoubleDegenerateAndBeyondFloatRange) {
  compare_double_backends(to_double(grid(6)), "integer grid 6x6x6", {true, true});
  for (int e : {150, -150}) {  // beyond float's range: inf and 0 there
    std::vector<Point3d> p = to_double(testing::dyadic_ball(20000, 13));
    for (auto& q : p)
      q = {std::ldexp(q.x, e), std::ldexp(q.y, e), std::ldexp(q.z, e)};
    compare_double_backends(p, "ball scaled by 2^" + std::to_string(e), {true, true});
  }
}

// Points 1e-12 apart, which float rounding merges: the double hull has copies among its vertices, unlike the
// float hull of the rounded points; and a ball 1e-12 across, one point in float.
TEST_F(Cuda, DoubleSameAsCpuWhereFloatWouldMergePoints) {
  const std::size_t n = 20000;
  const std::vector<Point3d> copies = ball_with_near_copies(n, 7);
  compare_double_backends(copies, "ball with copies 1e-12 further out", {true, true});
  BasicEngine<Point3d> dbl(copies, make_cpu_backend<Point3d>());
  dbl.run();
  const std::vector<Point3> rounded = to_float(copies);
  Engine flt(rounded, make_cpu_backend());
  flt.run();
  EXPECT_NE(dbl.result().vertex_ids, flt.result().vertex_ids);
  std::size_t copies_on_hull = 0;
  for (PointIndex id : dbl.result().vertex_ids)
    copies_on_hull += id >= n;
  EXPECT_GT(copies_on_hull, 0u);

  const std::vector<Point3d> tiny = ball_at_1e12_scale(50000, 8);
  compare_double_backends(tiny, "ball of radius 1e-12 at (1, 1, 1)", {true, true});
  BasicEngine<Point3d> tiny_double(tiny, make_cpu_backend<Point3d>());
  tiny_double.run();
  EXPECT_EQ(tiny_double.result().dimension, 3);
  const std::vector<Point3> tiny_rounded = to_float(tiny);
  Engine tiny_float(tiny_rounded, make_cpu_backend());
  tiny_float.run();
  EXPECT_EQ(tiny_float.result().dimension, 0);  // one point in float
}

}  // namespace
}  // namespace cudahull
