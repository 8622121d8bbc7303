// The resident engine (issue 15) on the host executor: the same operations the GPU runs, checked against the
// exact reference hull (exact_hull) and the independent checker on generated distributions, models and
// degenerate sets, in float and in double.  The gpu label runs the device executor against this one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/resident/small_hull.hpp"
#include "support/host_batch_slot.hpp"
#include "support/point_sets.hpp"
#include "support/rng.hpp"
#include "support/shared_models.hpp"

namespace cudahull {
namespace {

using testing::HostBatchSlot;

template <class Point>
void expect_exact(const std::vector<Point>& points, const std::string& what,
                  ResidentStats* stats_out = nullptr) {
  ResidentStats stats;
  const BasicHullMesh<Point> hull = resident_hull_host(points, &stats);
  const BasicHullMesh<Point> oracle = exact_hull(points);
  ASSERT_EQ(hull.dimension, oracle.dimension) << what;
  EXPECT_EQ(hull.vertex_ids, oracle.vertex_ids) << what << " (" << stats.note << ")";
  if (hull.dimension == 3) {
    const CheckResult check = check_hull(points, hull, 3);
    EXPECT_TRUE(check.ok) << what << ": " << (check.failures.empty() ? "" : check.failures.front());
  }
  // On the GPU executor's paths (the device loop with its room checks and regrowth), the same mesh, edit
  // for edit.
  ResidentStats device_path_stats;
  const BasicHullMesh<Point> device_path =
      resident_hull_host(points, &device_path_stats, ResidentPath::kDevice);
  EXPECT_EQ(device_path.vertex_ids, hull.vertex_ids) << what << " (device paths)";
  EXPECT_TRUE(device_path.triangles == hull.triangles) << what << " (device paths)";
  EXPECT_EQ(device_path_stats.rounds, stats.rounds) << what << " (device paths)";
  EXPECT_EQ(device_path_stats.edits, stats.edits) << what << " (device paths)";
  EXPECT_EQ(device_path_stats.iterations, stats.iterations) << what << " (device paths)";
  // As for points only the GPU holds (a CuPy array): the coordinates read through the executor, the
  // same hull, and the same coordinates in it.
  ResidentStats executor_stats;
  const BasicHullMesh<Point> executor_only =
      resident_hull_host(points, &executor_stats, ResidentPath::kDevice, true);
  EXPECT_EQ(executor_only.dimension, hull.dimension) << what << " (executor's points only)";
  EXPECT_EQ(executor_only.vertex_ids, hull.vertex_ids) << what << " (executor's points only)";
  EXPECT_TRUE(executor_only.triangles == hull.triangles) << what << " (executor's points only)";
  EXPECT_TRUE(executor_only.polygon == hull.polygon) << what << " (executor's points only)";
  // P's 14 points and the result's vertices, and the vertices of the patches a local repair looked at.
  if (executor_stats.polytope_first && !executor_stats.exact_finish)
    EXPECT_LE(executor_stats.points_read_back, 14 + hull.vertex_ids.size() + executor_stats.repair_vertices)
        << what;
  else if (!points.empty())
    EXPECT_GT(executor_stats.points_read_back, 0u) << what;
  ASSERT_EQ(executor_only.vertices.size(), executor_only.vertex_ids.size()) << what;
  for (std::size_t k = 0; k < executor_only.vertex_ids.size(); ++k) {
    const Point& want = points[executor_only.vertex_ids[k]];
    const Point& got = executor_only.vertices[k];
    EXPECT_TRUE(got.x == want.x && got.y == want.y && got.z == want.z) << what << " vertex " << k;
  }
  if (stats_out) *stats_out = stats;
}

std::vector<Point3d> widened(const std::vector<Point3>& p) {
  std::vector<Point3d> out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    out[i] = {p[i].x, p[i].y, p[i].z};
  return out;
}

// General position: the local edits alone reach the exact hull (no exact finish), in few host round trips.
TEST(Resident, GeneratedDistributionsInGeneralPosition) {
  for (const char* name : {"cube", "ball", "sphere", "gauss", "paraboloid"}) {
    for (std::size_t n : {50, 2000, 30000}) {
      const std::vector<Point3> points = generate_points(distribution_from_name(name), n, 7 + n);
      const std::string what = std::string(name) + " " + std::to_string(n);
      ResidentStats stats;
      expect_exact(points, what, &stats);
      EXPECT_FALSE(stats.exact_finish) << what << ": " << stats.note;
      EXPECT_GT(stats.iterations, 0u) << what;
      ResidentStats wide;
      expect_exact(widened(points), what + " in double", &wide);
      EXPECT_FALSE(wide.exact_finish) << what << " in double: " << wide.note;
    }
  }
}

// The drop filter (P, the extremes' polytope): on a cube it proves most points inside before any exact
// test, and points on P's faces or an ulp outside them are never dropped wrongly: the octahedron of the
// six axis points with points on its faces, nudged an ulp in or out, and points inside.
TEST(Resident, PolytopeFilterDropsOnlyInteriorPoints) {
  ResidentStats cube;
  expect_exact(generate_points(Distribution::kCube, 30000, 5), "cube 30000", &cube);
  EXPECT_GT(cube.dropped_by_polytope, 15000u);
  testing::Rng rng(11);
  auto uniform = [&] { return (rng.unit() + 1) / 2; };  // in [0, 1]
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Point3> points = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    for (int k = 0; k < 400; ++k) {
      // A point of the face sx x + sy y + sz z = 1, its coordinates exact in float; then an ulp in or out.
      const float a = uniform(), b = uniform() * (1 - a);
      const float c = 1 - a - b;
      const float sx = uniform() < 0.5 ? -1.f : 1.f, sy = uniform() < 0.5 ? -1.f : 1.f,
                  sz = uniform() < 0.5 ? -1.f : 1.f;
      Point3 p{sx * a, sy * b, sz * c};
      const float nudge = uniform();
      if (nudge < 0.3)
        p.z = std::nextafter(p.z, sz * 2.f);  // out
      else if (nudge < 0.6)
        p.z = std::nextafter(p.z, 0.f);  // in
      points.push_back(p);
      const float r = uniform() * 0.3f;
      points.push_back({r * sx, r * sy, r * sz});  // well inside
    }
    const std::string what = "octahedron faces, trial " + std::to_string(trial);
    ResidentStats stats;
    expect_exact(points, what, &stats);
    EXPECT_GT(stats.dropped_by_polytope, 0u) << what;
    expect_exact(widened(points), what + " in double");
  }
}

// Degenerate distributions (coplanar rings, lattices): exact through the exact finish when the local edits
// stop short on flat faces.
TEST(Resident, DegenerateDistributions) {
  for (const char* name : {"cylinder", "grid"}) {
    for (std::size_t n : {8, 1000, 20000}) {
      const std::vector<Point3> points = generate_points(distribution_from_name(name), n, 3);
      expect_exact(points, std::string(name) + " " + std::to_string(n));
    }
  }
}

// A dense cap (point_sets.hpp): flat edges inside coplanar facets are accepted, and the concave edges and
// vertices that are not extreme that the rounds leave are repaired where they are: no exact finish.
TEST(Resident, DefectsAreRepairedWhereTheyAre) {
  std::uint64_t faults = 0, repaired = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const std::string what = "cap, seed " + std::to_string(seed);
    ResidentStats stats;
    expect_exact(testing::cap_points(30000, 0.005, seed), what, &stats);
    EXPECT_FALSE(stats.exact_finish) << what << ": " << stats.note;
    faults += stats.faults;
    repaired += stats.repaired_patches;
  }
  EXPECT_GT(faults, 0u);  // the repair ran
  EXPECT_GT(repaired, 0u);
}

TEST(Resident, LowerDimensionalAndTinyInputs) {
  expect_exact(std::vector<Point3>{}, "no points");
  expect_exact(std::vector<Point3>{{1, 2, 3}}, "one point");
  expect_exact(std::vector<Point3>{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}, "one point three times");
  expect_exact(std::vector<Point3>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0.5f, 0.5f, 0.5f}}, "collinear");
  expect_exact(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5f, 0.5f, 0}}, "square");
  expect_exact(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, "tetrahedron");
  expect_exact(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1f, 0.1f, 0.1f}},
               "tetrahedron and an inner point");
  std::vector<Point3> cube;
  for (int i = 0; i < 8; ++i)
    cube.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
  expect_exact(cube, "cube corners");
}

// Duplicates: the vertex is the lowest index of each repeated extreme point.
TEST(Resident, DuplicatesKeepTheLowestIndex) {
  std::vector<Point3> points = generate_points(Distribution::kSphere, 3000, 11);
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; i += 3)
    points.push_back(points[i]);
  for (std::size_t i = 0; i < n; i += 7)
    points.insert(points.begin(), points[n - 1 - i]);
  expect_exact(points, "sphere with repeats");
}

// Seeded random sets of every kind the property test has, small enough for a quick loop.
TEST(Resident, SeededClustersJitterAndRanges) {
  using testing::SeededKind;
  const SeededKind kinds[] = {SeededKind::kCube, SeededKind::kLattice, SeededKind::kFarJitter,
                              SeededKind::kScales};
  testing::Rng r(99);
  for (int t = 0; t < 60; ++t) {
    const std::size_t n = 4 + r.below(3000);
    const int kind = t % 4;
    expect_exact(testing::seeded_set(r, n, kinds[kind], 5),
                 "case " + std::to_string(t) + " kind " + std::to_string(kind));
  }
}

// The bundled models, at their known vertex counts (the exact hull agrees).
TEST(Resident, BundledModels) {
  for (const char* name : {"bun_zipper.ply", "teapot.obj"}) {
    const std::vector<Point3> points = read_points(std::string(CUDAHULL_ASSETS_DIR) + "/" + name);
    expect_exact(points, name);
  }
}

// A device loop that ended after an even number of compactions left a small spare for the one-step small
// finish, which wrote past it (found by review, 523 points; ASan in CI sees the write).
TEST(Resident, SmallFinishAfterTheDeviceLoop) {
  const std::vector<Point3> points =
      read_points(std::string(CUDAHULL_TEST_DATA_DIR) + "/resident/small_finish_after_even_loop.xyz");
  ASSERT_EQ(points.size(), 523u);
  ResidentStats stats;
  const HullMesh hull = resident_hull_host(points, &stats, ResidentPath::kDevice);
  EXPECT_GT(stats.loop_iterations, 0u);
  EXPECT_EQ(hull.vertex_ids, exact_hull(points).vertex_ids);
  expect_exact(points, "small finish after the device loop");
}

// Batched hulls (issue 27): one cloud's whole hull on a team (batch.hpp) as a block of the GPU's batch
// kernel runs it, here on the host twin, in a slot used before by other clouds: the tetrahedron, the
// iterations and the finish give exact_hull's vertices and a hull the checker passes; a cloud short of room
// says so and is done with room for every point; only flat clouds (or defects) go to the single-cloud path.
template <class Point>
void expect_batch_exact(const std::vector<Point>& points, const std::string& what, int& room_asked,
                        bool may_need_repair = false, bool small = false) {
  const BasicHullMesh<Point> oracle = exact_hull(points);
  const auto n = static_cast<resident::u32>(points.size());
  HostBatchSlot<Point> first(resident::batch_vertices(n, false), points.size(), small);
  // The slot served another cloud first (its claims, stamps and state must not leak into this one).
  const std::vector<Point3> other =
      generate_points(Distribution::kBall, std::min<std::size_t>(n, 200), 1 + n);
  std::vector<Point> previous;
  for (const Point3& q : other)
    previous.push_back(Point{q.x, q.y, q.z});
  first.run(previous, small);
  resident::BatchResult result = first.run(points, small);
  HostBatchSlot<Point>* used = &first;
  HostBatchSlot<Point> every(n, points.size(), small);
  if (result.status == resident::kBatchRoom) {
    ++room_asked;
    result = every.run(points, small);
    used = &every;
    EXPECT_NE(result.status, resident::kBatchRoom) << what << ": short of room for every point a vertex";
  }
  if (result.status == resident::kBatchSingle) {
    // Flat clouds, and defects the rounds left (the single-cloud path repairs them), only.
    if (oracle.dimension == 3)
      EXPECT_TRUE(!small && may_need_repair && used->st.loop_exit == resident::kExitDone &&
                  used->st.defects > 0)
          << what << ": sent to the single-cloud path (exit " << used->st.loop_exit << ", defects "
          << used->st.defects << ")";
    return;
  }
  ASSERT_EQ(result.status, resident::kBatchDone) << what;
  ASSERT_EQ(oracle.dimension, 3) << what << ": a flat cloud must go to the single-cloud path";
  BasicHullMesh<Point> mesh;
  const resident::u32* words = used->words.data() + result.word_at;
  for (resident::u32 f = 0; f < result.faces; ++f)
    mesh.triangles.push_back({words[3 * f], words[3 * f + 1], words[3 * f + 2]});
  mesh.vertex_ids.assign(words + 3 * result.faces, words + 3 * result.faces + result.vertices);
  mesh.vertices.assign(used->coordinates.begin() + result.point_at,
                       used->coordinates.begin() + result.point_at + result.vertices);
  EXPECT_EQ(mesh.vertex_ids, oracle.vertex_ids) << what;
  for (std::size_t k = 0; k < mesh.vertex_ids.size(); ++k)
    EXPECT_TRUE(mesh.vertices[k] == points[mesh.vertex_ids[k]]) << what << " vertex " << k;
  const CheckResult check = check_hull(points, mesh, 3);
  EXPECT_TRUE(check.ok) << what << ": " << (check.failures.empty() ? "" : check.failures.front());
}

TEST(Resident, BatchHullOfOneCloudOnATeam) {
  int room_asked = 0;
  for (const char* name : {"ball", "sphere", "cube", "gauss", "grid", "cylinder"}) {
    const bool coplanar = std::string(name) == "grid" || std::string(name) == "cylinder";
    for (std::size_t n : {4, 5, 9, 60, 700, 5000}) {
      const std::vector<Point3> points = generate_points(distribution_from_name(name), n, 17 + n);
      const std::string what = std::string(name) + " " + std::to_string(n);
      expect_batch_exact(points, what, room_asked, coplanar);
      expect_batch_exact(widened(points), what + " in double", room_asked, coplanar);
    }
  }
  EXPECT_GT(room_asked, 0);  // the spheres' hulls outgrow the first pass's room
  // Flat, collinear and repeated clouds: the single-cloud path; duplicates keep the lowest index.
  expect_batch_exact(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5f, 0.5f, 0}},
                     "square", room_asked);
  expect_batch_exact(std::vector<Point3>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}, "collinear",
                     room_asked);
  expect_batch_exact(std::vector<Point3>(6, Point3{1, 2, 3}), "one point six times", room_asked);
  std::vector<Point3> repeats = generate_points(Distribution::kSphere, 300, 5);
  for (std::size_t i = 0; i < 300; i += 4)
    repeats.insert(repeats.begin(), repeats[299 - i]);
  expect_batch_exact(repeats, "sphere with repeats", room_asked);
  std::vector<Point3> inside = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}, {1, 1, 1}, {0.5f, 0.5f, 0.5f}};
  expect_batch_exact(inside, "a tetrahedron with points inside", room_asked);
}

// small_hull(), the batch's warps' hull: every cloud in space done on the team (coplanar facets, repeats and
// points on the hull's faces included), the exact vertex set, a valid hull; flat ones to the single path.
TEST(Resident, SmallHullOfOneCloudOnATeam) {
  int room_asked = 0;
  for (const char* name : {"ball", "sphere", "cube", "gauss", "grid", "cylinder"}) {
    for (std::size_t n : {4, 5, 9, 60, 100, 256, 700, 3000}) {
      const std::vector<Point3> points = generate_points(distribution_from_name(name), n, 29 + n);
      const std::string what = std::string(name) + " " + std::to_string(n);
      expect_batch_exact(points, what, room_asked, false, true);
      expect_batch_exact(widened(points), what + " in double", room_asked, false, true);
    }
  }
  EXPECT_GT(room_asked, 0);  // the spheres' hulls outgrow the first pass's room
  expect_batch_exact(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5f, 0.5f, 0}},
                     "square", room_asked, false, true);
  expect_batch_exact(std::vector<Point3>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}, "collinear", room_asked,
                     false, true);
  expect_batch_exact(std::vector<Point3>(6, Point3{1, 2, 3}), "one point six times", room_asked, false, true);
  std::vector<Point3> repeats = generate_points(Distribution::kSphere, 300, 5);
  for (std::size_t i = 0; i < 300; i += 4)
    repeats.insert(repeats.begin(), repeats[299 - i]);
  expect_batch_exact(repeats, "sphere with repeats", room_asked, false, true);
  // A cube's corners, its edges' and faces' midpoints and its centre, in every order the seeds give: the
  // points on faces and edges taken first must leave the mesh when the corners come.
  const std::vector<Point3> lattice = testing::lattice(3, 3, 3);
  for (unsigned seed = 0; seed < 40; ++seed) {
    std::vector<Point3> shuffled = lattice;
    std::mt19937 rng(seed);
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    expect_batch_exact(shuffled, "3x3x3 lattice, order " + std::to_string(seed), room_asked, false, true);
  }
  std::vector<Point3> inside = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}, {1, 1, 1}, {0.5f, 0.5f, 0.5f}};
  expect_batch_exact(inside, "a tetrahedron with points inside", room_asked, false, true);
}

// HostTeam finds a step's seen faces by a walk from the furthest point's face; a team that is not in order
// (the device's) tests every face.  A host team that scans, as they do, must build the same mesh face for
// face on clouds full of coplanar faces, repeats and points on faces, or the CPU's batch would differ from
// the GPU's.
struct ScanningHostTeam : resident::HostTeam {};

TEST(Resident, SmallHullWalkFindsTheFacesTheScanFinds) {
  std::vector<std::vector<Point3>> clouds;
  for (const char* name : {"ball", "sphere", "cube", "gauss", "grid", "cylinder"})
    for (std::size_t n : {5, 12, 23, 40, 128})
      for (unsigned seed = 0; seed < 6; ++seed)
        clouds.push_back(generate_points(distribution_from_name(name), n, 1000 * seed + n));
  const std::vector<Point3> lattice = testing::lattice(4, 4, 3);
  for (unsigned seed = 0; seed < 60; ++seed) {
    std::vector<Point3> shuffled = lattice;
    std::mt19937 rng(seed);
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    shuffled.resize(12 + seed % 37);                       // partial lattices: coplanar faces of every shape
    shuffled.push_back(shuffled[seed % shuffled.size()]);  // and a repeat
    clouds.push_back(shuffled);
  }
  int compared = 0;
  for (std::size_t c = 0; c < clouds.size(); ++c) {
    const std::vector<Point3d> points = widened(clouds[c]);
    const auto n = static_cast<resident::u32>(points.size());
    HostBatchSlot<Point3d> walked(n, n, true), scanned(n, n, true);
    const resident::BatchResult a = walked.run(points, true);
    const resident::BatchResult b = scanned.run(points, true, ScanningHostTeam{});
    ASSERT_EQ(a.status, b.status) << "cloud " << c;
    if (a.status != resident::kBatchDone) continue;
    ASSERT_EQ(a.faces, b.faces) << "cloud " << c;
    ASSERT_EQ(a.vertices, b.vertices) << "cloud " << c;
    const std::size_t words = 3 * std::size_t{a.faces} + a.vertices;
    EXPECT_TRUE(std::equal(walked.words.begin() + a.word_at, walked.words.begin() + a.word_at + words,
                           scanned.words.begin() + b.word_at))
        << "cloud " << c;
    ++compared;
  }
  EXPECT_GT(compared, 200);
}

TEST(Resident, SharedModelsAtTheirKnownCounts) {
  testing::for_each_shared_model([](const char* name, const std::vector<Point3>& points, std::size_t count) {
    ResidentStats stats;
    const HullMesh hull = resident_hull_host(points, &stats);
    EXPECT_EQ(hull.vertex_ids.size(), count) << name << " (" << stats.note << ")";
    const CheckResult check = check_hull(points, hull, 3);
    EXPECT_TRUE(check.ok) << name << ": " << (check.failures.empty() ? "" : check.failures.front());
  });
}

}  // namespace
}  // namespace cudahull
