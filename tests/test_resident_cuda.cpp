// The resident engine on the GPU (issue 15, gpu label): the device executor must build the very mesh the
// host executor builds (the same operations, claims and prefix sums), and both the exact hull: against
// exact_hull on generated and seeded sets and the property test's adversarial sets, the stepping engine on
// the CPU backend at a million points, and the known counts of the shared models.  Run on the GPU machine
// (docs/benchmarks.md says how).
#include <cuda_runtime.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/cpu_backend.hpp"
#include "cudahull/cuda/device_info.hpp"
#include "cudahull/cuda/resident_cuda.hpp"
#include "cudahull/detail/plane_impl.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/trace.hpp"
#include "support/host_batch_slot.hpp"
#include "support/point_sets.hpp"
#include "support/property_cases.hpp"
#include "support/rng.hpp"
#include "support/shared_models.hpp"

namespace cudahull {
namespace {

template <class Point>
BasicHullMesh<Point> on_device(const std::vector<Point>& points, ResidentStats* stats) {
  ResidentCudaHull<Point> hull;
  hull.upload(points);
  return hull.run(stats);
}

// The points as a CuPy array or a PyTorch tensor holds them: already in device memory, borrowed in place.
template <class Point>
BasicHullMesh<Point> on_device_points(const std::vector<Point>& points, ResidentStats* stats) {
  Point* device = nullptr;
  const std::size_t bytes = std::max<std::size_t>(points.size(), 1) * sizeof(Point);
  if (cudaMalloc(reinterpret_cast<void**>(&device), bytes) != cudaSuccess) {
    ADD_FAILURE() << "cudaMalloc of " << bytes << " bytes";
    return {};
  }
  EXPECT_EQ(cudaMemcpy(device, points.data(), points.size() * sizeof(Point), cudaMemcpyHostToDevice),
            cudaSuccess);
  BasicHullMesh<Point> out;
  {
    ResidentCudaHull<Point> hull;
    hull.use_device_points(device, points.size());
    out = hull.run(stats);
  }
  cudaFree(device);
  return out;
}

// Device and host executors: the same mesh and the same counts; `oracle` true also checks exact_hull.
template <class Point>
void expect_same_as_host(const std::vector<Point>& points, const std::string& what, bool oracle = true) {
  ResidentStats device_stats, host_stats;
  const BasicHullMesh<Point> device = on_device(points, &device_stats);
  const BasicHullMesh<Point> host = resident_hull_host(points, &host_stats);
  EXPECT_EQ(device.vertex_ids, host.vertex_ids) << what;
  EXPECT_EQ(device.triangles, host.triangles) << what;
  EXPECT_EQ(device_stats.iterations, host_stats.iterations) << what;
  EXPECT_EQ(device_stats.rounds, host_stats.rounds) << what;
  EXPECT_EQ(device_stats.edits, host_stats.edits) << what;
  EXPECT_EQ(device_stats.exact_finish, host_stats.exact_finish) << what;
  EXPECT_EQ(device_stats.faults, host_stats.faults) << what;
  EXPECT_EQ(device_stats.repaired_patches, host_stats.repaired_patches) << what;
  // Borrowed device points: the same mesh, and no more read back than the coordinates checked.
  ResidentStats borrowed_stats;
  const BasicHullMesh<Point> borrowed = on_device_points(points, &borrowed_stats);
  EXPECT_EQ(borrowed.vertex_ids, host.vertex_ids) << what << " (device points)";
  EXPECT_EQ(borrowed.triangles, host.triangles) << what << " (device points)";
  EXPECT_TRUE(borrowed.vertices == device.vertices) << what << " (device points)";
  EXPECT_EQ(borrowed_stats.bytes_from_device,
            device_stats.bytes_from_device + borrowed_stats.points_read_back * sizeof(Point))
      << what << " (device points)";
  // As on the host (test_resident.cpp): and the vertices of the patches a local repair looked at.
  if (borrowed_stats.polytope_first && !borrowed_stats.exact_finish)
    EXPECT_LE(borrowed_stats.points_read_back,
              14 + borrowed.vertex_ids.size() + borrowed_stats.repair_vertices)
        << what << " (device points)";
  if (oracle) {
    const BasicHullMesh<Point> exact = exact_hull(points);
    EXPECT_EQ(device.vertex_ids, exact.vertex_ids) << what;
  }
  if (device.dimension == 3) {
    const CheckResult check = check_hull(points, device, 3);
    EXPECT_TRUE(check.ok) << what << ": " << (check.failures.empty() ? "" : check.failures.front());
  }
}

std::vector<Point3d> widened(const std::vector<Point3>& p) {
  std::vector<Point3d> out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    out[i] = {p[i].x, p[i].y, p[i].z};
  return out;
}

class ResidentCuda : public ::testing::Test {
 protected:
  void SetUp() override {
    const CudaDeviceInfo info = query_cuda_device();
    // Without a device every test here fails, as test_cuda_backend's do: a gpu test never passes unrun.
    ASSERT_TRUE(info.usable) << "no usable CUDA device: " << info.reason;
  }
};

// Batched hulls (issue 27): the batch kernel's clouds, from host points and from device memory, in float and
// double, equal the CPU backend's batch cloud for cloud (which is convex_hull() on each cloud alone): vertex
// sets, dimensions, face counts, volumes and areas.  Mixed clouds: every distribution, 1 to 6,000 points,
// repeats, slivers, flat and collinear ones, and one cloud too large for a block.
TEST_F(ResidentCuda, BatchEqualsTheCpuCloudForCloud) {
  testing::Rng r(27);
  const std::vector<std::string> names = distribution_names();
  std::vector<Point3> points;
  std::vector<std::size_t> offsets{0};
  for (int c = 0; c < 3000; ++c) {
    const std::size_t n = c == 1500    ? 300000
                          : c % 7 == 0 ? r.below(12)
                                       : 4 + r.below(c % 3 == 0 ? 6000 : 400);
    std::vector<Point3> cloud = generate_points(distribution_from_name(names[c % names.size()]), n, 100 + c);
    if (c % 11 == 0)  // repeats
      for (std::size_t i = 0; i < n; i += 3)
        cloud.push_back(cloud[i]);
    if (c % 19 == 0)  // a sliver, 2^-19 thick: its volume takes the exact pass (plane_impl.hpp)
      for (Point3& p : cloud)
        p.z = 0.5f + 0x1p-20f * p.z;
    if (c % 13 == 0)  // flat
      for (Point3& p : cloud)
        p.z = 0.5f;
    if (c % 17 == 0)  // collinear
      for (Point3& p : cloud)
        p = {p.x, 2 * p.x, -p.x};
    points.insert(points.end(), cloud.begin(), cloud.end());
    offsets.push_back(points.size());
  }
  for (const Precision precision : {Precision::kFloat, Precision::kDouble}) {
    ConvexHullBatchOptions cpu, cuda;
    cpu.hull.backend = BackendChoice::kCpu;
    cuda.hull.backend = BackendChoice::kCuda;
    cpu.hull.precision = cuda.hull.precision = precision;
    const ConvexHullBatch want = convex_hull_batch(points, offsets, cpu);
    Point3* device = nullptr;
    ASSERT_EQ(cudaMalloc(&device, points.size() * sizeof(Point3)), cudaSuccess);
    ASSERT_EQ(cudaMemcpy(device, points.data(), points.size() * sizeof(Point3), cudaMemcpyHostToDevice),
              cudaSuccess);
    const ConvexHullBatch from_host = convex_hull_batch(points, offsets, cuda);
    const ConvexHullBatch from_device =
        convex_hull_batch_device(&device->x, points.size(), offsets.data(), offsets.size() - 1, cuda);
    // The result left on the device: the same values, read back here.
    const DeviceConvexHullBatch left =
        convex_hull_batch_device_results(&device->x, points.size(), offsets.data(), offsets.size() - 1, cuda);
    const ConvexHullBatch from_device_result = left.to_host();
    cudaFree(device);
    EXPECT_EQ(from_device_result.faces, from_device.faces);
    EXPECT_EQ(from_device_result.planes, from_device.planes);
    EXPECT_EQ(from_device_result.volumes, from_device.volumes);
    for (const ConvexHullBatch* got : {&from_host, &from_device}) {
      const std::string what = std::string(got == &from_host ? "host points" : "device points") +
                               (precision == Precision::kDouble ? ", double" : ", float");
      EXPECT_GT(got->clouds_batched, offsets.size() / 2) << what;  // the rest: tiny, large, flat, repaired
      EXPECT_EQ(got->vertex_offsets, want.vertex_offsets) << what;
      EXPECT_EQ(got->vertices, want.vertices) << what;
      EXPECT_EQ(got->face_offsets, want.face_offsets) << what;
      EXPECT_EQ(got->dimensions, want.dimensions) << what;
      std::size_t on_warps = 0;
      for (std::size_t c = 0; c + 1 < offsets.size(); ++c) {
        const std::size_t n = offsets[c + 1] - offsets[c];
        if (n < 4 || n > 256 || got->dimensions[c] != 3) continue;
        // A warp's cloud (small_hull() on WarpTeam): the same faces in the same order as on HostTeam, the
        // team kind changes nothing.
        std::vector<Point3d> cloud;
        for (std::size_t i = offsets[c]; i < offsets[c + 1]; ++i)
          cloud.push_back(Point3d{points[i].x, points[i].y, points[i].z});
        const auto same_on_host = [&](const auto& typed) {
          testing::HostBatchSlot<typename std::decay_t<decltype(typed)>::value_type> slot(
              static_cast<resident::u32>(n), n, true);
          const resident::BatchResult result = slot.run(typed, true);
          return result.status == resident::kBatchDone &&
                 testing::host_batch_faces(slot, result) ==
                     std::vector<std::array<PointIndex, 3>>(got->faces.begin() + got->face_offsets[c],
                                                            got->faces.begin() + got->face_offsets[c + 1]);
        };
        const bool same = precision == Precision::kDouble
                              ? same_on_host(cloud)
                              : same_on_host(std::vector<Point3>(points.begin() + offsets[c],
                                                                 points.begin() + offsets[c + 1]));
        EXPECT_TRUE(same) << what << ": cloud " << c << " (" << n
                          << " points) not as small_hull() on the host";
        ++on_warps;
      }
      EXPECT_GT(on_warps, 1000u) << what;
      for (std::size_t c = 0; c + 1 < offsets.size(); ++c) {
        EXPECT_NEAR(got->volumes[c], want.volumes[c], 1e-9 * std::abs(want.volumes[c]) + 1e-30) << what << c;
        EXPECT_NEAR(got->areas[c], want.areas[c], 1e-9 * std::abs(want.areas[c]) + 1e-30) << what << c;
        if (got->dimensions[c] != 3) continue;
        // The device's describe is the host's arithmetic (plane_impl.hpp): each face's plane and the
        // measures, recomputed here from the result's own faces (in their order, from the first face's
        // first corner), are the same bits.
        // The float points widen exactly, whichever precision the hull took.
        const auto point = [&](PointIndex i) { return to_vec3d(points[offsets[c] + i]); };
        const std::size_t first = got->face_offsets[c];
        for (std::size_t f = first; f < got->face_offsets[c + 1]; ++f) {
          const auto& face = got->faces[f];
          std::array<double, 4> plane;
          detail::facet_plane_in_range(point(face[0]), point(face[1]), point(face[2]), plane.data());
          ASSERT_EQ(plane, got->planes[f]) << what << " cloud " << c << " face " << f;
        }
        const auto corner = [&](unsigned long long f, int k) { return point(got->faces[first + f][k]); };
        const detail::SolidMeasures measures =
            detail::measure_mesh(got->face_offsets[c + 1] - first, corner, corner(0, 0));
        EXPECT_EQ(got->volumes[c], measures.volume()) << what << c;
        EXPECT_EQ(got->areas[c], measures.area()) << what << c;
      }
    }
  }
}

TEST_F(ResidentCuda, GeneratedDistributionsMatchTheHostExecutor) {
  for (const char* name : {"cube", "ball", "sphere", "gauss", "paraboloid", "cylinder", "grid"}) {
    for (std::size_t n : {10, 3000, 100000}) {
      const std::vector<Point3> points = generate_points(distribution_from_name(name), n, 5 + n);
      const std::string what = std::string(name) + " " + std::to_string(n);
      expect_same_as_host(points, what);
      expect_same_as_host(widened(points), what + " in double");
    }
  }
}

TEST_F(ResidentCuda, SeededSetsMatchTheHostExecutor) {
  using testing::SeededKind;
  const SeededKind kinds[] = {SeededKind::kCube, SeededKind::kLattice, SeededKind::kFarJitter,
                              SeededKind::kFlat, SeededKind::kRepeats};
  testing::Rng r(2026);
  for (int t = 0; t < 200; ++t) {
    const std::size_t n = 4 + r.below(5000);
    expect_same_as_host(testing::seeded_set(r, n, kinds[t % 5], 6), "seeded case " + std::to_string(t));
  }
}

// Dense caps (point_sets.hpp): the defects the rounds leave are repaired on the device as on the host,
// the small ones through the one-block finish (finish_small_kernel), the larger through the full one.
// CUDAHULL_CAP_POINTS caps the sizes (compute-sanitizer runs them up to 30,000).
TEST_F(ResidentCuda, DefectsAreRepairedAsOnTheHost) {
  const char* env = std::getenv("CUDAHULL_CAP_POINTS");
  const std::size_t most = env ? std::strtoull(env, nullptr, 10) : 200000;
  std::uint64_t repaired = 0;
  for (const std::size_t n : {2000, 30000, 200000}) {
    if (n > most) continue;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const std::vector<Point3> points = testing::cap_points(n, n < 10000 ? 0.001 : 0.005, seed);
      const std::string what = "cap " + std::to_string(n) + ", seed " + std::to_string(seed);
      expect_same_as_host(points, what);
      ResidentStats stats;
      on_device(points, &stats);
      EXPECT_FALSE(stats.exact_finish) << what << ": " << stats.note;
      repaired += stats.repaired_patches;
    }
  }
  EXPECT_GT(repaired, 0u);
}

// A million points: the stepping engine on the CPU backend is the independent answer.
TEST_F(ResidentCuda, MillionPointsMatchTheSteppingEngine) {
  for (const char* name : {"ball", "sphere", "cube"}) {
    const std::vector<Point3> points = generate_points(distribution_from_name(name), 1000000, 1);
    Engine engine(points, make_cpu_backend());
    engine.run();
    ResidentStats stats;
    const HullMesh device = on_device(points, &stats);
    EXPECT_EQ(device.vertex_ids, engine.result().vertex_ids) << name;
    EXPECT_FALSE(stats.exact_finish) << name << ": " << stats.note;
  }
}

// The property test's adversarial sets (tests/support/property_cases.hpp) on the device, float and double:
// cases 0..N-1, N = CUDAHULL_PROPERTY_CASES or 1000.
TEST_F(ResidentCuda, PropertyCasesMatchTheHostExecutorAndTheExactHull) {
  const char* env = std::getenv("CUDAHULL_PROPERTY_CASES");
  const std::uint64_t cases = env ? std::strtoull(env, nullptr, 10) : 1000;
  for (std::uint64_t id = 0; id < cases; ++id) {
    const testing::Case c = testing::make_case(id);
    expect_same_as_host(c.points, "property case " + std::to_string(id) + " (" + c.kind + ")");
    const testing::DoubleCase d = testing::make_double_case(id);
    expect_same_as_host(d.points, "property case " + std::to_string(id) + " (" + d.kind + ", double)");
    if (HasFailure()) break;
  }
}

TEST_F(ResidentCuda, SharedModelsAtTheirKnownCounts) {
  testing::for_each_shared_model([](const char* name, const std::vector<Point3>& points, std::size_t count) {
    ResidentStats stats;
    const HullMesh hull = on_device(points, &stats);
    EXPECT_EQ(hull.vertex_ids.size(), count) << name;
    expect_same_as_host(points, name, false);
  });
}

// A record without what depends on the machine (times, bytes): what the records compare on.
nlohmann::json record_contents(const IterationRecord& r) {
  nlohmann::json j = iteration_to_json(r);
  for (const char* timing : {"host_ms", "backend_ms", "upload_ms", "bytes_to_backend", "bytes_from_backend"})
    j.erase(timing);
  return j;
}

// Records (deliverable 3): the device's stepping engine makes the host executor's records, entry for entry
// (swaps with their kinds, rejected foldovers with the vertex beneath, removals, the decision array), the
// same mesh after every step, the same point states (also written on the device, as for the viewer's
// interop), and the same hull.
template <class Point>
void expect_same_records(const std::vector<Point>& points, const std::string& what) {
  std::unique_ptr<SteppingEngine> host = make_resident_stepping_engine(points);
  std::unique_ptr<SteppingEngine> device = make_resident_cuda_stepping_engine(points);
  EXPECT_TRUE(device->has_device_point_states());
  std::int32_t* states = nullptr;
  ASSERT_EQ(cudaMalloc(reinterpret_cast<void**>(&states), std::max<std::size_t>(points.size(), 1) * 4),
            cudaSuccess);
  while (!host->done()) {
    ASSERT_FALSE(device->done()) << what;
    const IterationRecord a = host->step(), b = device->step();
    ASSERT_EQ(record_contents(a), record_contents(b)) << what << ", step " << a.iteration;
    if (host->dimension() != 3) continue;
    ASSERT_EQ(host->mesh().face_capacity(), device->mesh().face_capacity()) << what;
    for (FaceId f = 0; f < host->mesh().face_capacity(); ++f) {
      EXPECT_EQ(host->mesh().face(f).v, device->mesh().face(f).v) << what << ", face " << f;
      EXPECT_EQ(host->mesh().face(f).n, device->mesh().face(f).n) << what << ", face " << f;
    }
    const std::vector<std::int32_t> faces = host->point_faces();
    EXPECT_EQ(faces, device->point_faces()) << what << ", step " << a.iteration;
    const std::vector<PointIndex> vertices = device->mesh().vertices();
    ASSERT_TRUE(device->write_point_states_on_device(states, points.size(), vertices));
    std::vector<std::int32_t> written(points.size());
    ASSERT_EQ(cudaMemcpy(written.data(), states, points.size() * 4, cudaMemcpyDeviceToHost), cudaSuccess);
    for (PointIndex i = 0; i < points.size(); ++i) {
      const std::int32_t want = device->mesh().has_vertex(i) ? kPointStateVertex
                                : faces[i] >= 0              ? faces[i]
                                                             : kPointStateInternal;
      ASSERT_EQ(written[i], want) << what << ", point " << i;
    }
  }
  cudaFree(states);
  EXPECT_TRUE(device->done()) << what;
  EXPECT_EQ(host->result_vertex_ids(), device->result_vertex_ids()) << what;
  EXPECT_EQ(host->result_triangles(), device->result_triangles()) << what;
  EXPECT_EQ(device->result_vertex_ids(), exact_hull(points).vertex_ids) << what;
}

TEST_F(ResidentCuda, SteppedRecordsMatchTheHostExecutor) {
  for (const char* name : {"cube", "ball", "sphere", "gauss", "cylinder"}) {
    const std::vector<Point3> points = generate_points(distribution_from_name(name), 5000, 3);
    expect_same_records(points, name);
    expect_same_records(widened(points), std::string(name) + " in double");
  }
  const char* env = std::getenv("CUDAHULL_PROPERTY_CASES");
  const std::uint64_t cases = std::min<std::uint64_t>(env ? std::strtoull(env, nullptr, 10) : 200, 200);
  for (std::uint64_t id = 0; id < cases; ++id) {
    const testing::Case c = testing::make_case(id);
    expect_same_records(c.points, "property case " + std::to_string(id) + " (" + c.kind + ")");
    if (HasFailure()) break;
  }
}

}  // namespace
}  // namespace cudahull
