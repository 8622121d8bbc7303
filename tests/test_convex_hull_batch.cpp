// Batched hulls (issue 27): convex_hull_batch() cloud for cloud against convex_hull() on each cloud alone
// (every field), against Qhull on clouds in general position, and against an exact brute force (Caratheodory,
// exact predicates) on tiny clouds of every kind; edge cases written out; the same result on 1, 2, all and
// more threads than cores; the CUDA backend, and `cudahull bench --batch`.  What the batch refuses:
// test_convex_hull_batch_errors.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "cudahull/convex_hull.hpp"
#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/resident.hpp"
#include "qhull_reference.hpp"
#include "support/batch_clouds.hpp"
#include "support/cli_runner.hpp"

namespace cudahull {
namespace {

// --- an exact brute force for tiny clouds ------------------------------------------------------------------
//
// A point is a vertex exactly when no earlier point equals it and it is not in the convex hull of the points
// that differ from it; by Caratheodory it is in that hull exactly when it is in a closed tetrahedron, a
// closed triangle or a closed segment of them (the lower ones for the tetrahedra that are flat).  Exact
// predicates on float coordinates.

Vec3d at(const std::vector<Point3>& points, std::size_t i) {
  return to_vec3d(points[i]);
}

bool on_segment(Vec3d a, Vec3d b, Vec3d p) {
  if (!collinear3d(a, b, p)) return false;
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y) && std::min(a.z, b.z) <= p.z && p.z <= std::max(a.z, b.z);
}

bool in_triangle(Vec3d a, Vec3d b, Vec3d c, Vec3d p) {
  if (collinear3d(a, b, c) || orient3d(a, b, c, p) != 0) return false;
  // Projected on the coordinate plane where the triangle keeps an area.
  for (int drop = 0; drop < 3; ++drop) {
    auto u = [&](Vec3d v) { return drop == 0 ? v.y : v.x; };
    auto w = [&](Vec3d v) { return drop == 2 ? v.y : v.z; };
    const int turn = orient2d(u(a), w(a), u(b), w(b), u(c), w(c));
    if (turn == 0) continue;
    return orient2d(u(a), w(a), u(b), w(b), u(p), w(p)) * turn >= 0 &&
           orient2d(u(b), w(b), u(c), w(c), u(p), w(p)) * turn >= 0 &&
           orient2d(u(c), w(c), u(a), w(a), u(p), w(p)) * turn >= 0;
  }
  return false;
}

bool in_tetrahedron(Vec3d a, Vec3d b, Vec3d c, Vec3d d, Vec3d p) {
  const int o = orient3d(a, b, c, d);
  if (o == 0) return false;
  return orient3d(a, b, c, p) * o >= 0 && orient3d(a, b, d, p) * orient3d(a, b, d, c) >= 0 &&
         orient3d(a, c, d, p) * orient3d(a, c, d, b) >= 0 && orient3d(b, c, d, p) * orient3d(b, c, d, a) >= 0;
}

std::vector<PointIndex> brute_force_vertices(const std::vector<Point3>& points) {
  std::vector<PointIndex> vertices;
  const std::size_t n = points.size();
  for (std::size_t p = 0; p < n; ++p) {
    bool extreme = true;
    std::vector<std::size_t> others;
    for (std::size_t q = 0; q < n; ++q) {
      if (points[q] != points[p]) {
        others.push_back(q);
      } else if (q < p) {
        extreme = false;  // a later duplicate
      }
    }
    const Vec3d x = at(points, p);
    const std::size_t m = others.size();
    for (std::size_t i = 0; extreme && i < m; ++i) {
      for (std::size_t j = i + 1; extreme && j < m; ++j) {
        const Vec3d a = at(points, others[i]), b = at(points, others[j]);
        if (on_segment(a, b, x)) extreme = false;
        for (std::size_t k = j + 1; extreme && k < m; ++k) {
          const Vec3d c = at(points, others[k]);
          if (in_triangle(a, b, c, x)) extreme = false;
          for (std::size_t l = k + 1; extreme && l < m; ++l)
            if (in_tetrahedron(a, b, c, at(points, others[l]), x)) extreme = false;
        }
      }
    }
    if (extreme) vertices.push_back(static_cast<PointIndex>(p));
  }
  return vertices;
}

// --- tests
// ---------------------------------------------------------------------------------------------------

TEST(ConvexHullBatch, EdgeCasesWrittenOut) {
  const std::vector<std::vector<Point3d>> clouds{
      {},                                 // 0: empty
      {{1, 2, 3}},                        // 1: one point
      {{0, 0, 0}, {1, 1, 1}},             // 2: two points
      {{4, 4, 4}, {4, 4, 4}},             // 3: one point twice
      {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}},  // 4: a triangle
      {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}},  // 5: three on a line
      {{0.5, 0.5, 0.5},
       {0, 0, 0},
       {1, 0, 0},
       {0, 1, 0},
       {1, 1, 0},
       {0, 0, 1},
       {1, 0, 1},
       {0, 1, 1},
       {1, 1, 1},
       {1, 1, 1},
       {0, 0, 0},
       {0.5, 0, 0}},                                            // 6: a cube, repeats
      {{0, 0, 5}, {2, 0, 5}, {1, 1, 5}, {2, 2, 5}, {0, 2, 5}},  // 7: a flat square
      {{3, 0, 0}, {1, 0, 0}, {4, 0, 0}, {0, 0, 0}, {2, 0, 0}},  // 8: collinear
      {},                                                       // 9: empty, last
  };
  std::vector<Point3d> points;
  std::vector<std::size_t> offsets{0};
  for (const auto& cloud : clouds) {
    points.insert(points.end(), cloud.begin(), cloud.end());
    offsets.push_back(points.size());
  }
  const ConvexHullBatch batch = convex_hull_batch(points, offsets, on_cpu());
  ASSERT_EQ(batch.size(), clouds.size());
  EXPECT_EQ(batch.precision, Precision::kDouble);
  EXPECT_EQ(batch.dimensions, (std::vector<std::int32_t>{-1, 0, 1, 0, 2, 1, 3, 2, 1, -1}));
  auto vertices = [&](std::size_t c) {
    return slice(batch.vertices, batch.vertex_offsets[c], batch.vertex_offsets[c + 1]);
  };
  using V = std::vector<PointIndex>;
  EXPECT_EQ(vertices(0), V{});
  EXPECT_EQ(vertices(1), V{0});
  EXPECT_EQ(vertices(2), (V{0, 1}));
  EXPECT_EQ(vertices(3), V{0});
  EXPECT_EQ(vertices(4), (V{0, 1, 2}));
  EXPECT_EQ(vertices(5), (V{0, 2}));
  EXPECT_EQ(vertices(6), (V{1, 2, 3, 4, 5, 6, 7, 8}));  // indices into the cloud; the first of each repeat
  EXPECT_EQ(vertices(7), (V{0, 1, 3, 4}));
  EXPECT_EQ(vertices(8), (V{2, 3}));
  EXPECT_EQ(vertices(9), V{});
  EXPECT_EQ(batch.face_offsets, (std::vector<std::size_t>{0, 0, 0, 0, 0, 0, 0, 12, 12, 12, 12}));
  EXPECT_EQ(batch.volumes[6], 1.0);
  EXPECT_EQ(batch.areas[6], 6.0);
  EXPECT_EQ(batch.areas[4], 6.0);  // both sides of the triangle of area 3
  EXPECT_EQ(batch.areas[7], 8.0);  // both sides of the 2 x 2 square
  for (std::size_t c : {0, 1, 2, 3, 4, 5, 7, 8, 9})
    EXPECT_EQ(batch.volumes[c], 0.0) << c;
  for (std::size_t f = 0; f < 12; ++f) {  // the cube's planes: unit axis normals, every corner on or below
    const auto& plane = batch.planes[f];
    EXPECT_EQ(std::abs(plane[0]) + std::abs(plane[1]) + std::abs(plane[2]), 1.0);
    for (const Point3d& p : clouds[6])
      EXPECT_LE(plane[0] * p.x + plane[1] * p.y + plane[2] * p.z + plane[3], 0.0);
  }
  expect_each_cloud_is_its_own_hull(points, offsets, batch, on_cpu().hull);
}

TEST(ConvexHullBatch, NoCloudsAndOneCloud) {
  const ConvexHullBatch none = convex_hull_batch(std::vector<Point3>{}, {0}, on_cpu());
  EXPECT_EQ(none.size(), 0u);
  EXPECT_EQ(none.vertex_offsets, std::vector<std::size_t>{0});
  EXPECT_EQ(none.face_offsets, std::vector<std::size_t>{0});
  EXPECT_TRUE(none.vertices.empty() && none.faces.empty());
  // A device result of no clouds (its columns never allocated) reads back as the same empty batch, with no
  // device touched.
  const ConvexHullBatch none_read_back = DeviceConvexHullBatch{}.to_host();
  EXPECT_EQ(none_read_back.size(), 0u);
  EXPECT_EQ(none_read_back.vertex_offsets, std::vector<std::size_t>{0});
  EXPECT_EQ(none_read_back.face_offsets, std::vector<std::size_t>{0});
  EXPECT_EQ(none_read_back.polygon_offsets, std::vector<std::size_t>{0});

  const std::vector<Point3> ball = generate_points(Distribution::kBall, 5000, 3);
  const std::vector<std::size_t> offsets{0, ball.size()};
  const ConvexHullBatch one = convex_hull_batch(ball, offsets, on_cpu());
  const ConvexHull alone = convex_hull(ball, on_cpu().hull);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one.precision, Precision::kFloat);
  EXPECT_EQ(one.backend, alone.backend);
  EXPECT_EQ(one.vertices, run_qhull(ball).vertex_ids);
  expect_each_cloud_is_its_own_hull(ball, offsets, one, on_cpu().hull);
  // The array overload is the same call.
  const ConvexHullBatch array = convex_hull_batch(&ball[0].x, ball.size(), offsets.data(), 1, on_cpu());
  EXPECT_TRUE(same_batch(array, one));
}

// A few hundred clouds of every kind, in float and in double: each cloud convex_hull()'s on it alone; the
// clouds in general position Qhull's vertices; the tiny ones the brute force's.
TEST(ConvexHullBatch, MixedCloudsAreEachTheirOwnHull) {
  const MixedBatch mixed = mixed_batch(360, 27, 150);
  const ConvexHullBatch batch = convex_hull_batch(mixed.points, mixed.offsets, on_cpu());
  EXPECT_EQ(batch.precision, Precision::kFloat);
  expect_each_cloud_is_its_own_hull(mixed.points, mixed.offsets, batch, on_cpu().hull);
  std::size_t brute_forced = 0, by_qhull = 0;
  std::vector<int> dimensions_seen(5, 0);
  for (std::size_t c = 0; c < batch.size(); ++c) {
    SCOPED_TRACE("cloud " + std::to_string(c) + " of kind " + std::to_string(mixed.kinds[c]));
    const std::vector<Point3> cloud = mixed.cloud(c);
    const std::vector<PointIndex> vertices =
        slice(batch.vertices, batch.vertex_offsets[c], batch.vertex_offsets[c + 1]);
    ++dimensions_seen[batch.dimensions[c] + 1];
    if (cloud.size() <= 10) {
      EXPECT_EQ(vertices, brute_force_vertices(cloud));
      ++brute_forced;
    }
    const Kind kind = mixed.kinds[c];
    if ((kind == kCube || kind == kBall || kind == kGauss) && cloud.size() >= 4) {
      EXPECT_EQ(vertices, run_qhull(cloud).vertex_ids);
      ++by_qhull;
    }
  }
  EXPECT_GE(brute_forced, 40u);
  EXPECT_GE(by_qhull, 100u);
  for (int d = -1; d <= 3; ++d)  // every dimension's answer met
    EXPECT_GT(dimensions_seen[d + 1], 0) << "dimension " << d;

  // In double: the same values widened, so the same vertex sets; each cloud convex_hull()'s in double.
  std::vector<Point3d> doubles;
  for (const Point3& p : mixed.points)
    doubles.push_back({p.x, p.y, p.z});
  const ConvexHullBatch in_double = convex_hull_batch(doubles, mixed.offsets, on_cpu());
  EXPECT_EQ(in_double.precision, Precision::kDouble);
  EXPECT_EQ(in_double.vertices, batch.vertices);
  EXPECT_EQ(in_double.vertex_offsets, batch.vertex_offsets);
  expect_each_cloud_is_its_own_hull(doubles, mixed.offsets, in_double, on_cpu().hull);
  // And float input asked to run in double gives the double batch.
  EXPECT_TRUE(
      same_batch(convex_hull_batch(mixed.points, mixed.offsets, on_cpu(0, Precision::kDouble)), in_double));
}

// Many tiny clouds, most of them degenerate (small integer boxes, flat, collinear, repeated points), against
// the brute force.
TEST(ConvexHullBatch, TinyDegenerateCloudsMatchTheBruteForce) {
  Random random(2027);
  MixedBatch tiny;
  const Kind kinds[] = {kTinyInteger, kGrid, kFlat, kCollinear, kDuplicated};
  for (std::size_t c = 0; c < 500; ++c) {
    const Kind kind = kinds[c % 5];
    tiny.add(cloud_of(kind, 4 + random.below(7), c, random), kind);
  }
  const ConvexHullBatch batch = convex_hull_batch(tiny.points, tiny.offsets, on_cpu());
  std::vector<int> dimensions_seen(5, 0);
  for (std::size_t c = 0; c < batch.size(); ++c) {
    EXPECT_EQ(slice(batch.vertices, batch.vertex_offsets[c], batch.vertex_offsets[c + 1]),
              brute_force_vertices(tiny.cloud(c)))
        << "cloud " << c;
    if (tiny.kinds[c] == kFlat) EXPECT_LE(batch.dimensions[c], 2) << "cloud " << c;
    if (tiny.kinds[c] == kCollinear) EXPECT_LE(batch.dimensions[c], 1) << "cloud " << c;
    ++dimensions_seen[batch.dimensions[c] + 1];
  }
  for (int d = 1; d <= 3; ++d)
    EXPECT_GT(dimensions_seen[d + 1], 0) << "dimension " << d;
}

// The small-cloud path (small_hull_host(): what convex_hull() and so the batch take on the CPU for 4 to
// kSmallHullPoints points) against the exact reference, exact_hull(), on seeded clouds of every kind
// (coplanar faces full of points, flat, collinear, repeated points, pyramids over a flat base full of
// points, 4 points): the same vertex set, and a closed outward mesh with every point on or below every face
// (exact orient3d); a flat cloud is handed on.  Then the batch: each cloud's vertices the reference's and,
// where the small path took it, its faces that mesh's.
TEST(ConvexHullBatch, SmallCloudPathIsTheExactHull) {
  Random random(4242);
  MixedBatch small;
  std::vector<std::vector<std::array<PointIndex, 3>>> small_faces;
  std::size_t taken = 0, flat = 0;
  for (std::size_t c = 0; c < 1500; ++c) {
    const Kind kind = static_cast<Kind>(c % kKinds);
    const std::size_t n = c % 13 == 0 ? 4 : 4 + random.below(kSmallHullPoints - 4);
    std::vector<Point3> cloud = cloud_of(kind, n, 9000 + c, random);
    if (kind == kFlat && c % 2 == 0) cloud.push_back({3, -2, 500});  // a pyramid's apex over the flat base
    SCOPED_TRACE("cloud " + std::to_string(c) + " of kind " + std::to_string(kind) + ", " +
                 std::to_string(cloud.size()) + " points");
    const HullMesh exact = exact_hull(cloud);
    HullMesh mesh;
    std::vector<std::array<PointIndex, 3>> faces;
    if (small_hull_host(cloud.data(), cloud.size(), mesh)) {
      ++taken;
      ASSERT_EQ(mesh.dimension, 3);
      std::vector<PointIndex> sorted = mesh.vertex_ids;
      std::sort(sorted.begin(), sorted.end());
      EXPECT_EQ(sorted, exact.vertex_ids);
      EXPECT_EQ(mesh.triangles.size() + 4, 2 * mesh.vertices.size());  // Euler, for a closed sphere
      std::map<std::pair<PointIndex, PointIndex>, int> edges;          // each directed edge once
      for (const Triangle& t : mesh.triangles) {
        const Vec3d a = to_vec3d(mesh.vertices[t[0]]), b = to_vec3d(mesh.vertices[t[1]]),
                    c3 = to_vec3d(mesh.vertices[t[2]]);
        EXPECT_FALSE(collinear3d(a, b, c3));
        for (const Point3& p : cloud)
          EXPECT_LE(orient3d(a, b, c3, to_vec3d(p)), 0) << "a point above a face";
        faces.push_back({mesh.vertex_ids[t[0]], mesh.vertex_ids[t[1]], mesh.vertex_ids[t[2]]});
        for (int k = 0; k < 3; ++k)
          ++edges[{mesh.vertex_ids[t[k]], mesh.vertex_ids[t[(k + 1) % 3]]}];
      }
      for (const auto& [edge, count] : edges) {
        EXPECT_EQ(count, 1);
        EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << "an open edge";
      }
      for (std::size_t k = 0; k < mesh.vertices.size(); ++k)
        EXPECT_EQ(mesh.vertices[k], cloud[mesh.vertex_ids[k]]);
      // The same cloud in double: the same values, so the same mesh.
      std::vector<Point3d> wide;
      for (const Point3& p : cloud)
        wide.push_back({p.x, p.y, p.z});
      HullMeshd in_double;
      ASSERT_TRUE(small_hull_host(wide.data(), wide.size(), in_double));
      EXPECT_EQ(in_double.vertex_ids, mesh.vertex_ids);
      EXPECT_EQ(in_double.triangles, mesh.triangles);
    } else {
      // Handed on: a flat cloud always is; a cloud in general position never.
      EXPECT_FALSE(kind == kCube || kind == kBall || kind == kSphere || kind == kGauss);
    }
    if (exact.dimension < 3) {
      ++flat;
      EXPECT_TRUE(faces.empty()) << "a flat cloud taken by the small path";
    }
    small.add(cloud, kind);
    small_faces.push_back(std::move(faces));
  }
  EXPECT_GE(taken, 900u);
  EXPECT_GE(flat, 200u);

  const ConvexHullBatch batch = convex_hull_batch(small.points, small.offsets, on_cpu());
  expect_each_cloud_is_its_own_hull(small.points, small.offsets, batch, on_cpu().hull);
  for (std::size_t c = 0; c < batch.size(); ++c) {
    SCOPED_TRACE("cloud " + std::to_string(c));
    EXPECT_EQ(slice(batch.vertices, batch.vertex_offsets[c], batch.vertex_offsets[c + 1]),
              exact_hull(small.cloud(c)).vertex_ids);
    if (!small_faces[c].empty())
      EXPECT_EQ(slice(batch.faces, batch.face_offsets[c], batch.face_offsets[c + 1]), small_faces[c]);
  }
}

// The result is the same on one thread, two, every core and more threads than cores.
TEST(ConvexHullBatch, ThreadCountChangesNothing) {
  const MixedBatch mixed = mixed_batch(240, 99, 7);
  const ConvexHullBatch one = convex_hull_batch(mixed.points, mixed.offsets, on_cpu(1));
  for (unsigned threads : {2u, hardware_workers(), 2 * hardware_workers() + 3, 0u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    EXPECT_TRUE(same_batch(convex_hull_batch(mixed.points, mixed.offsets, on_cpu(threads)), one));
  }
  expect_each_cloud_is_its_own_hull(mixed.points, mixed.offsets, one, on_cpu().hull);
}

// Without a GPU, the CUDA backend is refused as convex_hull() refuses it; points in GPU memory need one.
TEST(ConvexHullBatch, CudaNeedsTheGpu) {
  const std::vector<Point3> points = generate_points(Distribution::kCube, 100, 1);
  const std::vector<std::size_t> offsets{0, 40, 100};
  ConvexHullBatchOptions cuda;
  cuda.hull.backend = BackendChoice::kCuda;
  EXPECT_THROW(convex_hull_batch_device(&points[0].x, points.size(), offsets.data(), 2, on_cpu()),
               std::invalid_argument);
  if (cuda_status().usable) {
    // Both clouds on the batch kernel, the same vertex sets as the CPU's.
    const ConvexHullBatch on_gpu = convex_hull_batch(points, offsets, cuda);
    EXPECT_EQ(on_gpu.vertices, convex_hull_batch(points, offsets, on_cpu()).vertices);
    EXPECT_EQ(on_gpu.clouds_batched, 2u);
    return;
  }
  EXPECT_THROW(convex_hull_batch(points, offsets, cuda), DeviceError);
  EXPECT_THROW(convex_hull_batch_device(&points[0].x, points.size(), offsets.data(), 2), DeviceError);
}

// `cudahull bench --batch B --n N`: B clouds of --dist (cloud c from seed + c), timed; --vs qhull and --vs
// loop compare every cloud's vertices with Qhull's and with single convex_hull() calls.
TEST(ConvexHullBatch, BenchBatchOnTheCommandLine) {
  std::size_t qhull_vertices = 0;
  for (std::uint64_t c = 0; c < 30; ++c)
    qhull_vertices += run_qhull(generate_points(Distribution::kBall, 200, 5 + c)).vertex_ids.size();
  for (const std::string versus : {"qhull", "loop"}) {
    const CliRun r = run_cli({"bench", "--batch", "30", "--n", "200", "--dist", "ball", "--seed", "5",
                              "--backend", "cpu", "--repeat", "1", "--json", "--vs", versus});
    ASSERT_EQ(r.exit_code, kExitOk) << describe(r);
    const auto j = nlohmann::json::parse(r.out, nullptr, false);
    ASSERT_TRUE(j.is_object()) << r.out;
    EXPECT_EQ(j.value("input", ""), "ball 30x200");
    EXPECT_EQ(j.value("clouds", 0u), 30u);
    EXPECT_EQ(j.value("points", 0u), 6000u);
    EXPECT_EQ(j.value("hull_vertices", 0u), qhull_vertices);
    EXPECT_EQ(j.value("precision", ""), "float");
    EXPECT_EQ(j.value("versus", ""), versus);
    EXPECT_EQ(j.value("clouds_with_different_vertices", 99u), 0u);
    EXPECT_GT(j.value("total_ms", 0.0), 0.0);
  }
  const CliRun text = run_cli({"bench", "--batch", "3", "--n", "50", "--backend", "cpu", "--repeat", "1"});
  EXPECT_EQ(text.exit_code, kExitOk) << describe(text);
  EXPECT_NE(text.out.find("cube 3x50"), std::string::npos) << text.out;
  const CliRun help = run_cli({"bench", "--help"});
  EXPECT_NE(help.out.find("--batch"), std::string::npos) << help.out;
  EXPECT_EQ(run_cli({"bench", "--vs", "loop", "--n", "100"}).exit_code, kExitUsage);
  TempDir dir;
  EXPECT_EQ(run_cli({"bench", (dir / "none.ply").string(), "--batch", "3"}).exit_code, kExitUsage);
}

}  // namespace
}  // namespace cudahull
