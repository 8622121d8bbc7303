// The engine against independent oracles: Qhull (libqhull), the exact checker, a brute-force exact
// extreme-point finder, and the extreme counts published with the shared models.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "cudahull/cpu_backend.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/point_io.hpp"
#include "qhull_reference.hpp"
#include "support/dist_cases.hpp"
#include "support/mesh_faces.hpp"
#include "support/oracles.hpp"
#include "support/point_sets.hpp"

namespace cudahull {
namespace {

using testing::DistCase;
using testing::grid;
using testing::scaled;

struct RunResult {
  HullMesh hull;
  std::vector<IterationRecord> records;
  std::size_t repairs = 0;
};

RunResult run_engine(const std::vector<Point3>& points, unsigned threads = 2) {
  Engine engine(points, make_cpu_backend(threads));
  RunResult out;
  engine.run([&](const IterationRecord& r) {
    out.repairs += r.repairs;
    out.records.push_back(r);
  });
  out.hull = engine.result();
  return out;
}

void expect_exact(const std::vector<Point3>& points, const HullMesh& hull) {
  const CheckResult check = check_hull(points, hull);
  EXPECT_TRUE(check.ok) << (check.failures.empty() ? "" : check.failures.front());
}

// --- General position: Qhull and the checker agree, the engine needs no repair -------------------------

class GeneralPosition : public ::testing::TestWithParam<DistCase> {};

TEST_P(GeneralPosition, MatchesQhullExactlyWithoutRepair) {
  const auto [dist, n] = GetParam();
  const auto points = generate_points(dist, n, 20261122 + n);
  const RunResult r = run_engine(points);
  ASSERT_EQ(r.hull.dimension, 3);
  const QhullResult q = run_qhull(points, "Qt");
  EXPECT_EQ(r.hull.vertex_ids, q.vertex_ids);
  expect_exact(points, r.hull);
  EXPECT_EQ(r.repairs, 0u) << "general position needs no repair";
  // The trace runs until no external point remains, never growing the external set.
  ASSERT_FALSE(r.records.empty());
  EXPECT_EQ(r.records.back().external_after, 0u);
  for (std::size_t k = 0; k < r.records.size(); ++k) {
    EXPECT_EQ(r.records[k].iteration, static_cast<int>(k));
    EXPECT_LE(r.records[k].external_after, r.records[k].external_before);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Engine, GeneralPosition,
    ::testing::ValuesIn(testing::dist_cases({{Distribution::kCube, {1000, 100000, 1000000}},
                                             {Distribution::kBall, {1000, 100000, 1000000}},
                                             {Distribution::kGauss, {1000, 200000}},
                                             {Distribution::kSphere, {1000, 100000}}})),
    testing::dist_case_name);

// In general position the paper's local procedure (swaps, complementary swaps, removals) must reach the
// exact hull by itself: the exact finish repairs nothing.
TEST(Engine, NoRepairsInGeneralPosition) {
  int runs = 0, repaired = 0;
  for (Distribution dist : {Distribution::kCube, Distribution::kBall, Distribution::kGauss}) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      const auto points = generate_points(dist, 2000, seed);
      const RunResult r = run_engine(points, 1);
      expect_exact(points, r.hull);
      ++runs;
      if (r.repairs > 0) {
        ++repaired;
        std::printf("needed repair: %s, 2000 points, seed %llu\n", distribution_name(dist).c_str(),
                    static_cast<unsigned long long>(seed));
      }
    }
  }
  RecordProperty("runs_needing_repair", repaired);
  std::printf("%d of %d general-position runs needed an exact repair\n", repaired, runs);
  EXPECT_EQ(repaired, 0);
}

TEST(Engine, SmallRandomSetsMatchBruteForce) {
  const auto sets = testing::small_integer_sets(60);
  for (std::size_t trial = 0; trial < sets.size(); ++trial) {
    const std::vector<Point3>& points = sets[trial];
    const RunResult r = run_engine(points, 1);
    if (r.hull.dimension != 3) continue;
    EXPECT_EQ(r.hull.vertex_ids, testing::brute_force_extreme(points)) << "trial " << trial;
    expect_exact(points, r.hull);
  }
}

// --- Degenerate inputs (issue 3, item 8) ------------------------------------------------------------

TEST(EngineDegenerate, IntegerGridHasEightCorners) {
  const auto points = grid(6);
  const RunResult r = run_engine(points);
  ASSERT_EQ(r.hull.dimension, 3);
  EXPECT_EQ(r.hull.vertex_ids, (std::vector<PointIndex>{0, 5, 30, 35, 180, 185, 210, 215}));
  expect_exact(points, r.hull);
}

TEST(EngineDegenerate, GridOnCubeSurfaceHasEightCorners) {
  std::vector<Point3> points;
  for (const Point3& p : grid(9)) {
    const bool surface = p.x == 0 || p.y == 0 || p.z == 0 || p.x == 8 || p.y == 8 || p.z == 8;
    if (surface) points.push_back({p.x / 8.0f, p.y / 8.0f, p.z / 8.0f});
  }
  const RunResult r = run_engine(points);
  EXPECT_EQ(r.hull.vertex_ids.size(), 8u);
  EXPECT_EQ(r.hull.triangles.size(), 12u);
  expect_exact(points, r.hull);
}

TEST(EngineDegenerate, TripledPointsKeepTheLowestIndex) {
  const auto base = generate_points(Distribution::kBall, 3000, 5);
  std::vector<Point3> points;
  for (int copy = 0; copy < 3; ++copy)
    points.insert(points.end(), base.begin(), base.end());
  const RunResult single = run_engine(base), tripled = run_engine(points);
  EXPECT_EQ(tripled.hull.vertex_ids, single.hull.vertex_ids);  // the first copy, indices < 3000
  expect_exact(points, tripled.hull);
}

TEST(EngineDegenerate, CylinderRings) {
  const auto points = generate_points(Distribution::kCylinder, 20000, 3);
  const RunResult r = run_engine(points);
  expect_exact(points, r.hull);
  EXPECT_EQ(r.hull.vertex_ids, run_qhull(points, "Qt").vertex_ids);
}

TEST(EngineDegenerate, IntegerParaboloidIsAllExtreme) {
  const std::vector<Point3> points = testing::integer_paraboloid(20);
  const RunResult r = run_engine(points);
  EXPECT_EQ(r.hull.vertex_ids.size(), points.size());  // every lifted lattice point is strictly extreme
  expect_exact(points, r.hull);
}

TEST(EngineDegenerate, ThinSlab) {
  auto points = generate_points(Distribution::kCube, 50000, 11);
  for (auto& p : points)
    p.z = (p.z + 1.0f) * 0.5e-6f;
  const RunResult r = run_engine(points);
  ASSERT_EQ(r.hull.dimension, 3);
  expect_exact(points, r.hull);
}

TEST(EngineDegenerate, HugeAndTinyCoordinatesGiveTheSameHull) {
  // Scaling by a power of two is exact, so the combinatorics must not change.
  const auto base = generate_points(Distribution::kBall, 20000, 13);
  const RunResult r = run_engine(base);
  for (float s : {0x1p100f, 0x1p-100f}) {
    const auto points = scaled(base, s);
    const RunResult rs = run_engine(points);
    EXPECT_EQ(rs.hull.vertex_ids, r.hull.vertex_ids) << "scale " << s;
    expect_exact(points, rs.hull);
  }
  // And scaling by 1e30 / 1e-30 (inexact) still gives an exact hull of the scaled points.
  for (float s : {1e30f, 1e-30f}) {
    const auto points = scaled(base, s);
    const RunResult rs = run_engine(points);
    expect_exact(points, rs.hull);
  }
}

TEST(EngineDegenerate, LowerDimensionalInputs) {
  std::vector<Point3> coplanar, collinear, single(10, Point3{1.5f, -2.0f, 3.0f});
  for (int i = 0; i < 200; ++i) {
    coplanar.push_back({float(i % 17), float((i * 7) % 13), 4.0f});
    collinear.push_back({float(i), float(2 * i), float(-i)});
  }
  const RunResult plane = run_engine(coplanar), line = run_engine(collinear), point = run_engine(single);
  EXPECT_EQ(plane.hull.dimension, 2);
  expect_exact(coplanar, plane.hull);
  EXPECT_EQ(line.hull.dimension, 1);
  EXPECT_EQ(line.hull.vertex_ids, (std::vector<PointIndex>{0, 199}));
  EXPECT_EQ(point.hull.dimension, 0);
  EXPECT_EQ(point.hull.vertex_ids, (std::vector<PointIndex>{0}));
  const RunResult three = run_engine({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  EXPECT_EQ(three.hull.dimension, 2);
  EXPECT_EQ(three.hull.vertex_ids.size(), 3u);
}

// --- The shared models: their published exact extreme counts -----------------------------------------

TEST(EngineModels, ExtremeCountsMatchTheModelsReadme) {
  const std::filesystem::path dir = CUDAHULL_MODELS_DIR;
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no ../shared/models beside the checkout";
  const std::map<std::string, std::size_t> expected{
      {"bun_zipper.ply", 1564},  {"stanford-bunny.obj", 1562}, {"dragonStandRight_0.ply", 439},
      {"dragon_scans.ply", 207}, {"teapot.obj", 878},          {"spot.obj", 305}};
  for (const auto& [name, count] : expected) {
    const auto points = read_points((dir / name).string());
    const RunResult r = run_engine(points);
    EXPECT_EQ(r.hull.vertex_ids.size(), count) << name;
    expect_exact(points, r.hull);
  }
}

// --- The step API and the decision array ----------------------------------------------------------

TEST(EngineSteps, DecisionArrayMatchesTheSwapsAndRemovals) {
  const auto points = generate_points(Distribution::kBall, 20000, 17);
  Engine engine(points, make_cpu_backend(2));
  std::size_t iterations = 0;
  while (!engine.done()) {
    const IterationRecord r = engine.step();
    ++iterations;
    // One decision entry per performed swap and per removal (Fig. 7).
    EXPECT_EQ(r.decisions.size(), r.swaps_regular + r.swaps_complementary + r.vertices_removed);
    std::size_t rejected = 0;
    for (const SwapRecord& s : r.swaps) {
      const bool is_rejected = s.kind != SwapKind::kRegular && s.kind != SwapKind::kComplementary;
      rejected += is_rejected;
      if (!is_rejected) {
        ASSERT_GE(s.decision_index, 0);
        EXPECT_EQ(r.decisions[s.decision_index].kind, kDecisionSwap);
      }
    }
    EXPECT_EQ(rejected, r.swaps_rejected);
    // Each refinement makes 1 face into 3; swaps keep the count; each removal takes away 2.
    if (r.iteration > 0) {
      EXPECT_EQ(r.faces_after, r.faces_before + 2 * r.faces_refined - 2 * r.vertices_removed);
    }
    // The mesh stays a closed triangulated sphere: F = 2V - 4.
    EXPECT_EQ(engine.mesh().live_faces(), 2 * engine.mesh().vertex_count() - 4);
  }
  EXPECT_GT(iterations, 3u);
  // Every remaining point state is consistent: after the last step nothing is external.
  for (std::int32_t f : engine.point_faces())
    EXPECT_EQ(f, -1);
}

TEST(EngineSteps, FaceCellsSeparateNeighbours) {
  const auto points = generate_points(Distribution::kBall, 5000, 19);
  Engine engine(points, make_cpu_backend(1));
  engine.step();
  engine.step();
  const Mesh& mesh = engine.mesh();
  for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
    const FaceCell cell = engine.face_cell(f);
    const MeshFace& face = mesh.face(f);
    // The face's own centroid is inside its cell; its neighbour's centroid is outside the shared plane.
    Point3 c{};
    for (PointIndex v : face.v)
      c = {c.x + points[v].x / 3, c.y + points[v].y / 3, c.z + points[v].z / 3};
    for (int i = 0; i < 3; ++i) {
      EXPECT_GT(plane_value(cell.edge_plane[i], c), 0);
      const MeshFace& nb = mesh.face(face.n[i]);
      Point3 d{};
      for (PointIndex v : nb.v)
        d = {d.x + points[v].x / 3, d.y + points[v].y / 3, d.z + points[v].z / 3};
      EXPECT_LT(plane_value(cell.edge_plane[i], d), 0);
    }
  }
}

TEST(EngineSteps, ThreadCountDoesNotChangeTheHull) {
  const auto points = generate_points(Distribution::kGauss, 300000, 23);
  const RunResult one = run_engine(points, 1), four = run_engine(points, 4);
  EXPECT_EQ(one.hull.vertex_ids, four.hull.vertex_ids);
  EXPECT_EQ(one.hull.triangles, four.hull.triangles);
  ASSERT_EQ(one.records.size(), four.records.size());
}

// --- Engine::restart(): the same run again, on the points the backend already holds ----------------------

// The first field in which two runs' records differ ("" when none does), so that a test can also check
// that a difference is seen.
std::string first_difference(const std::vector<IterationRecord>& a, const std::vector<IterationRecord>& b) {
  if (a.size() != b.size())
    return "record count " + std::to_string(a.size()) + " vs " + std::to_string(b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    const IterationRecord &x = a[k], &y = b[k];
    std::ostringstream where;
    where << "record " << k << ": ";
    const auto differs = [&](const char* field) { return where.str() + field; };
    if (x.iteration != y.iteration) return differs("iteration");
    if (x.faces_before != y.faces_before || x.faces_after != y.faces_after ||
        x.faces_refined != y.faces_refined)
      return differs("face counts");
    if (x.swaps_regular != y.swaps_regular || x.swaps_complementary != y.swaps_complementary ||
        x.swaps_rejected != y.swaps_rejected)
      return differs("swap counts");
    if (x.vertices_removed != y.vertices_removed || x.removals_rejected != y.removals_rejected)
      return differs("removal counts");
    if (x.decision_entries != y.decision_entries) return differs("decision_entries");
    if (x.external_before != y.external_before || x.external_after != y.external_after)
      return differs("external counts");
    if (x.repairs != y.repairs) return differs("repairs");
    if (x.swaps.size() != y.swaps.size()) return differs("swaps.size()");
    for (std::size_t i = 0; i < x.swaps.size(); ++i) {
      const SwapRecord &s = x.swaps[i], &t = y.swaps[i];
      if (s.kind != t.kind || s.sequence != t.sequence || s.old_edge[0] != t.old_edge[0] ||
          s.old_edge[1] != t.old_edge[1] || s.new_edge[0] != t.new_edge[0] ||
          s.new_edge[1] != t.new_edge[1] || s.decision_index != t.decision_index)
        return differs("swap ") + std::to_string(i);
    }
    if (x.removals.size() != y.removals.size()) return differs("removals.size()");
    for (std::size_t i = 0; i < x.removals.size(); ++i) {
      const RemovalRecord &r = x.removals[i], &s = y.removals[i];
      if (r.sequence != s.sequence || r.vertex != s.vertex || r.rejected != s.rejected ||
          !std::equal(std::begin(r.ring), std::end(r.ring), std::begin(s.ring)) ||
          r.decision_index != s.decision_index)
        return differs("removal ") + std::to_string(i);
    }
    if (x.refined_apexes != y.refined_apexes) return differs("refined_apexes");
    if (x.refined_faces != y.refined_faces) return differs("refined_faces");
    if (x.decisions.size() != y.decisions.size()) return differs("decisions.size()");
    for (std::size_t i = 0; i < x.decisions.size(); ++i) {
      const DecisionEntry &d = x.decisions[i], &e = y.decisions[i];
      if (d.above != e.above || d.below != e.below || d.kind != e.kind)
        return differs("decision ") + std::to_string(i);
    }
  }
  return "";
}

// Forwards every call to a CPU backend and counts upload_points() and restart().
struct BackendCalls {
  int uploads = 0, restarts = 0;
};

class CountingBackend final : public Backend {
 public:
  CountingBackend(std::unique_ptr<Backend> inner, BackendCalls& calls)
      : inner_(std::move(inner)), calls_(calls) {}

  std::string name() const override { return "counting " + inner_->name(); }
  void upload_points(const std::vector<Point3>& points) override {
    ++calls_.uploads;
    inner_->upload_points(points);
  }
  void restart() override {
    ++calls_.restarts;
    inner_->restart();
  }
  std::array<PointIndex, 2> extremes_x() override { return inner_->extremes_x(); }
  PointIndex furthest_from_line(PointIndex a, PointIndex b) override {
    return inner_->furthest_from_line(a, b);
  }
  PointIndex furthest_from_plane(PointIndex a, PointIndex b, PointIndex c) override {
    return inner_->furthest_from_plane(a, b, c);
  }
  void distribute_points(const IterationTables& tables) override { inner_->distribute_points(tables); }
  std::size_t compact_index_array() override { return inner_->compact_index_array(); }
  void get_extreme_points(std::vector<FaceExtreme>& out) override { inner_->get_extreme_points(out); }
  void point_faces(std::vector<std::int32_t>& out) override { inner_->point_faces(out); }
  bool has_device_point_states() const override { return inner_->has_device_point_states(); }
  bool write_point_states_on_device(std::int32_t* device_out, std::size_t count,
                                    const std::vector<PointIndex>& vertices) override {
    return inner_->write_point_states_on_device(device_out, count, vertices);
  }
  std::uint64_t bytes_to_backend() const override { return inner_->bytes_to_backend(); }
  std::uint64_t bytes_from_backend() const override { return inner_->bytes_from_backend(); }

 private:
  std::unique_ptr<Backend> inner_;
  BackendCalls& calls_;
};

std::vector<IterationRecord> step_to_end(Engine& engine) {
  std::vector<IterationRecord> records;
  while (!engine.done())
    records.push_back(engine.step());
  return records;
}

TEST(EngineRestart, RepeatsTheRunWithoutUploadingAgain) {
  const auto points = generate_points(Distribution::kBall, 20000, 31);
  BackendCalls calls;
  Engine engine(points, std::make_unique<CountingBackend>(make_cpu_backend(2), calls));
  EXPECT_EQ(calls.uploads, 0) << "the engine uploads on its first step";

  const std::vector<IterationRecord> first = step_to_end(engine);
  const HullMesh first_hull = engine.result();
  ASSERT_GT(first.size(), 3u);
  ASSERT_EQ(first_hull.dimension, 3);
  ASSERT_FALSE(first_hull.vertex_ids.empty());
  EXPECT_EQ(calls.uploads, 1);
  EXPECT_EQ(calls.restarts, 0);
  // The comparison sees a difference where there is one.
  std::vector<IterationRecord> altered = first;
  IterationRecord& changed = altered[altered.size() / 2];
  ASSERT_FALSE(changed.decisions.empty());
  ++changed.decisions.back().above;
  EXPECT_NE(first_difference(first, altered), "");
  EXPECT_NE(first_difference(first, {first.begin(), first.end() - 1}), "");

  // Restarted at the end: the same steps again.
  engine.restart();
  EXPECT_FALSE(engine.done());
  EXPECT_EQ(engine.mesh().live_faces(), 0u);
  EXPECT_EQ(calls.restarts, 1);
  const std::vector<IterationRecord> second = step_to_end(engine);
  EXPECT_EQ(first_difference(first, second), "");
  EXPECT_EQ(engine.result().vertex_ids, first_hull.vertex_ids);
  EXPECT_EQ(engine.result().triangles, first_hull.triangles);

  // Restarted in the middle (after 3 steps): the full sequence again, from its start.
  engine.restart();
  for (int k = 0; k < 3; ++k)
    engine.step();
  engine.restart();
  EXPECT_EQ(calls.restarts, 3);
  const std::vector<IterationRecord> third = step_to_end(engine);
  EXPECT_EQ(first_difference(first, third), "");
  EXPECT_EQ(engine.result().vertex_ids, first_hull.vertex_ids);
  EXPECT_EQ(engine.result().triangles, first_hull.triangles);

  // The points went to the backend once, across all three runs.
  EXPECT_EQ(calls.uploads, 1);
}

// With batched swap rounds (from 8 candidates) the edge claims' hash table grows with the rounds a run has
// seen, and its collisions delay swaps: a restart must start from a fresh table to repeat the records.
TEST(EngineRestart, RepeatsABatchedRun) {
  const auto points = generate_points(Distribution::kSphere, 20000, 31);
  EngineOptions batched;
  batched.batched_swaps_from = 8;
  Engine engine(points, make_cpu_backend(2), batched);
  const std::vector<IterationRecord> first = step_to_end(engine);
  engine.restart();
  const std::vector<IterationRecord> second = step_to_end(engine);
  EXPECT_EQ(first_difference(first, second), "");
  EXPECT_EQ(engine.result().triangles, [&] {
    Engine fresh(points, make_cpu_backend(2), batched);
    fresh.run();
    return fresh.result().triangles;
  }());
}

// Batched swap rounds (phases/swaps.cpp, swap_edges()) make many swaps at once; their sequence numbers must
// still be an order in which one swap at a time gives the same mesh (the viewer's sub-steps replay them so).
// The same points, batched and not, give the same hull; the batched run needs no repair either.
using testing::face_set;

// The host's parallel helpers: every byte copied and every order sorted, for sizes around their chunking
// (a trailing empty chunk once made parallel_memcpy copy a negative length).
TEST(Parallel, MemcpyCopiesEveryByteForAnySize) {
  std::mt19937 rng(5);
  const std::size_t block = 1000;
  for (std::size_t bytes : {std::size_t{0}, std::size_t{1}, block - 1, block, block + 1, 4 * block,
                            4 * block + 7, 17 * block + 123, 64 * block, 100 * block + 999}) {
    // 64 guard bytes after each buffer, different in source and destination: nothing past `bytes` moves.
    std::vector<unsigned char> src(bytes + 64, 0xAA), dst(bytes + 64);
    for (std::size_t k = 0; k < bytes; ++k)
      src[k] = static_cast<unsigned char>(rng());
    for (unsigned workers : {1u, 2u, 16u}) {  // 16 on any machine: more workers than blocks leaves some empty
      std::fill(dst.begin(), dst.end(), 0x55);
      parallel_memcpy(dst.data(), src.data(), bytes, block, workers);
      EXPECT_TRUE(std::equal(src.begin(), src.begin() + static_cast<std::ptrdiff_t>(bytes), dst.begin()))
          << bytes << " bytes, " << workers << " workers";
      EXPECT_TRUE(std::all_of(dst.begin() + static_cast<std::ptrdiff_t>(bytes), dst.end(),
                              [](unsigned char c) { return c == 0x55; }))
          << "wrote past the end: " << bytes << " bytes, " << workers << " workers";
    }
  }
}

TEST(Parallel, SortMatchesStdSort) {
  std::mt19937 rng(6);
  for (std::size_t n : {std::size_t{0}, std::size_t{5}, std::size_t{65535}, std::size_t{65536 * 3 + 17},
                        std::size_t{1000003}}) {
    std::vector<std::uint32_t> values(n);
    for (auto& v : values)
      v = static_cast<std::uint32_t>(rng() % (n + 1));  // repeats included
    std::vector<std::uint32_t> expected = values;
    std::sort(expected.begin(), expected.end());
    parallel_sort(values);
    EXPECT_EQ(values, expected) << n << " values";
  }
}

// Mesh::split_batch() promises exactly what split() one face at a time gives: ids, links and each vertex's
// starting face (which orders its ring, and so the engine's later choices).
TEST(MeshBatches, SplitBatchEqualsSplitInOrder) {
  const auto points = generate_points(Distribution::kBall, 5000, 31);
  Engine engine(points, make_cpu_backend(1));
  for (int k = 0; k < 4; ++k)
    engine.step();
  Mesh one_by_one = engine.mesh(), batched = engine.mesh();
  std::vector<FaceId> faces;
  std::vector<PointIndex> apexes;
  for (FaceId f = 0; f < one_by_one.face_capacity(); f += 2) {
    faces.push_back(f);
    apexes.push_back(static_cast<PointIndex>(points.size() + f));  // combinatorial: no coordinates needed
  }
  ASSERT_GT(faces.size(), 50u);
  for (std::size_t k = 0; k < faces.size(); ++k)
    one_by_one.split(faces[k], apexes[k]);
  batched.split_batch(faces, apexes, 4);
  ASSERT_EQ(batched.face_capacity(), one_by_one.face_capacity());
  EXPECT_EQ(batched.live_faces(), one_by_one.live_faces());
  EXPECT_EQ(batched.vertex_count(), one_by_one.vertex_count());
  for (FaceId f = 0; f < one_by_one.face_capacity(); ++f) {
    ASSERT_EQ(batched.alive(f), one_by_one.alive(f)) << "face " << f;
    if (!one_by_one.alive(f)) continue;
    EXPECT_EQ(batched.face(f).v, one_by_one.face(f).v) << "face " << f;
    EXPECT_EQ(batched.face(f).n, one_by_one.face(f).n) << "face " << f;
  }
  std::vector<PointIndex> ring_a, ring_b;
  std::vector<FaceId> faces_a, faces_b;
  for (PointIndex v : one_by_one.vertices()) {
    one_by_one.ring(v, ring_a, faces_a);
    batched.ring(v, ring_b, faces_b);
    EXPECT_EQ(ring_a, ring_b) << "vertex " << v;
    EXPECT_EQ(faces_a, faces_b) << "vertex " << v;
  }
}

TEST(EngineSteps, BatchedSwapsReplayOneAtATimeInSequenceOrder) {
  const auto points = generate_points(Distribution::kSphere, 30000, 29);
  EngineOptions options;
  options.batched_swaps_from = 64;
  Engine engine(points, make_cpu_backend(2), options);
  std::size_t batched_iterations = 0, repairs = 0;
  while (!engine.done()) {
    Mesh replay = engine.mesh();
    const IterationRecord r = engine.step();
    repairs += r.repairs;
    if (r.iteration == 0 || engine.done())
      continue;  // the tetrahedron; the last step may be finished exactly
    for (const RefinementEntry& e : engine.last_refinement())
      replay.split(e.face, e.apex);
    for (const KeptEdit& e : kept_edits(r)) {
      if (e.removal) {
        ASSERT_TRUE(replay.has_vertex(e.removal->vertex));
        replay.remove_degree3(e.removal->vertex);
        continue;
      }
      const auto made = redo_swap(replay, *e.swap);
      ASSERT_TRUE(made.has_value()) << "iteration " << r.iteration << ": swap #" << e.sequence << " ("
                                    << e.swap->old_edge[0] << "-" << e.swap->old_edge[1]
                                    << ") does not replay";
      const MeshFace& n1 = replay.face((*made)[0]);
      // The swap made the recorded edge x - y.
      EXPECT_EQ(n1.v[0], e.swap->new_edge[0]) << "swap #" << e.sequence;
      EXPECT_EQ(n1.v[2], e.swap->new_edge[1]) << "swap #" << e.sequence;
    }
    EXPECT_EQ(face_set(replay), face_set(engine.mesh())) << "iteration " << r.iteration;
    if (r.swaps_regular + r.swaps_complementary >= 64) ++batched_iterations;
  }
  EXPECT_GE(batched_iterations, 5u);
  EXPECT_EQ(repairs, 0u);
  const QhullResult q = run_qhull(points, "Qt");
  EXPECT_EQ(engine.result().vertex_ids, q.vertex_ids);
  expect_exact(points, engine.result());

  // One at a time: the same hull, face for face (no four of these points are coplanar).
  EngineOptions single;
  single.batched_swaps_from = SIZE_MAX;
  Engine unbatched(points, make_cpu_backend(2), single);
  unbatched.run();
  EXPECT_EQ(unbatched.result().vertex_ids, engine.result().vertex_ids);
  EXPECT_EQ(face_set(unbatched.mesh()), face_set(engine.mesh()));
}

}  // namespace
}  // namespace cudahull
