// The resident engine stepped with records (issue 15, deliverable 3), on the host executor: the same hull
// as the fast path, and records that explain every step.  The oracle for the records is the host Mesh
// (engine/src/mesh.cpp), an independent implementation of the three local edits: replaying a step's
// refinements, swaps and removals on the mesh before it, in the recorded order, must give exactly the mesh
// after it; every rejected foldover must be a concave edge whose swap would turn a new face over as seen
// from the interior point; a swap is regular exactly when its edge was in the mesh before the step.  The
// gpu label (test_resident_cuda) checks that the device's records are these, entry for entry.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "cudahull/engine.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/resident.hpp"
#include "support/mesh_faces.hpp"
#include "support/property_cases.hpp"

namespace cudahull {
namespace {

FaceId face_with_edge(const Mesh& mesh, PointIndex a, PointIndex b, int& slot) {
  for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
    if (mesh.alive(f) && (slot = mesh.edge_index(f, a, b)) >= 0) return f;
  }
  return kNoFace;
}

FaceId face_with_corners(const Mesh& mesh, const std::array<PointIndex, 3>& corners) {
  for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
    if (mesh.alive(f) && mesh.face(f).v == corners) return f;
  }
  return kNoFace;
}

// Replays record `r` on `before` and checks it against the engine's mesh after the step.
void expect_record_explains_step(const SteppingEngine& engine, Mesh before, const IterationRecord& r,
                                 const std::string& what) {
  auto P = [&](PointIndex i) { return engine.point(i); };
  const Vec3d c = engine.interior_point();
  const Mesh old = before;
  ASSERT_EQ(r.refined_apexes.size(), r.refined_faces.size()) << what;
  EXPECT_EQ(r.faces_refined, r.refined_faces.size()) << what;
  for (std::size_t k = 0; k < r.refined_faces.size(); ++k) {
    const FaceId f = face_with_corners(before, r.refined_faces[k]);
    ASSERT_NE(f, kNoFace) << what << ": refined face " << k << " is not a face of the mesh before";
    before.split(f, r.refined_apexes[k]);
  }
  // Swaps and removals, performed and rejected, in their recorded order.
  struct Edit {
    int sequence;
    const SwapRecord* swap;
    const RemovalRecord* removal;
  };
  std::vector<Edit> edits;
  for (const SwapRecord& s : r.swaps)
    edits.push_back({s.sequence, &s, nullptr});
  for (const RemovalRecord& m : r.removals)
    edits.push_back({m.sequence, nullptr, &m});
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.sequence < b.sequence; });
  for (std::size_t k = 0; k < edits.size(); ++k)
    ASSERT_EQ(edits[k].sequence, static_cast<int>(k)) << what << ": sequence numbers are not 0, 1, 2, ...";
  std::size_t regular = 0, complementary = 0, rejected = 0, removed = 0, removals_rejected = 0;
  for (const Edit& e : edits) {
    if (e.swap) {
      const SwapRecord& s = *e.swap;
      const PointIndex u = s.old_edge[0], v = s.old_edge[1], x = s.new_edge[0], y = s.new_edge[1];
      int slot = -1;
      const FaceId f = face_with_edge(before, u, v, slot);
      ASSERT_NE(f, kNoFace) << what << ": swap " << s.sequence << " of an edge not in the mesh";
      const MeshFace& face = before.face(f);
      EXPECT_EQ(face.v[(slot + 2) % 3], x) << what << ": swap " << s.sequence;
      EXPECT_GT(orient3d(P(u), P(v), P(x), P(y)), 0)
          << what << ": swap " << s.sequence << " of a convex edge";
      if (s.kind == SwapKind::kRegular || s.kind == SwapKind::kComplementary) {
        // Regular: an edge of a face refined this step (Fig. 3b), which was an edge of the mesh before it.
        bool of_refined_face = false;
        for (const auto& t : r.refined_faces) {
          for (int k = 0; k < 3; ++k)
            of_refined_face =
                of_refined_face || (t[k] == u && t[(k + 1) % 3] == v) || (t[k] == v && t[(k + 1) % 3] == u);
        }
        EXPECT_EQ(s.kind == SwapKind::kRegular, of_refined_face) << what << ": swap " << s.sequence;
        if (s.kind == SwapKind::kRegular) EXPECT_TRUE(old.adjacent(u, v)) << what << ": swap " << s.sequence;
        (s.kind == SwapKind::kRegular ? regular : complementary) += 1;
        const std::array<FaceId, 2> made = before.swap(f, slot);
        EXPECT_TRUE(before.edge_index(made[0], x, u) >= 0 || before.edge_index(made[1], x, u) >= 0) << what;
      } else {
        ++rejected;
        if (s.kind == SwapKind::kRejectedFoldover) {
          // Seen from c, one of the new faces (x, u, y), (y, v, x) would turn over, and the recorded vertex
          // lies beneath the other.
          const bool u_turns = orient3d(c, P(x), P(u), P(y)) <= 0,
                     v_turns = orient3d(c, P(y), P(v), P(x)) <= 0;
          EXPECT_TRUE(u_turns || v_turns)
              << what << ": rejected foldover " << s.sequence << " would not fold";
          EXPECT_EQ(s.beneath_vertex, u_turns == v_turns ? kNoPoint : u_turns ? u : v) << what;
        } else {
          EXPECT_EQ(s.kind, SwapKind::kRejectedEdgeExists) << what;
        }
      }
    } else {
      const RemovalRecord& m = *e.removal;
      ASSERT_TRUE(before.has_vertex(m.vertex)) << what << ": removal of a vertex not in the mesh";
      if (m.rejected) {
        ++removals_rejected;
        continue;
      }
      ASSERT_EQ(before.degree(m.vertex, 4), 3u) << what << ": removal of a vertex of degree other than 3";
      const FaceId made = before.remove_degree3(m.vertex);
      std::array<PointIndex, 3> ring = before.face(made).v, want{m.ring[0], m.ring[1], m.ring[2]};
      std::rotate(ring.begin(), std::min_element(ring.begin(), ring.end()), ring.end());
      std::rotate(want.begin(), std::min_element(want.begin(), want.end()), want.end());
      EXPECT_EQ(ring, want) << what << ": removal " << m.sequence;
      ++removed;
    }
  }
  EXPECT_EQ(r.swaps_regular, regular) << what;
  EXPECT_EQ(r.swaps_complementary, complementary) << what;
  EXPECT_EQ(r.swaps_rejected, rejected) << what;
  EXPECT_EQ(r.vertices_removed, removed) << what;
  EXPECT_EQ(r.removals_rejected, removals_rejected) << what;
  EXPECT_EQ(testing::face_set(before), testing::face_set(engine.mesh()))
      << what << ": the replayed mesh differs";
  EXPECT_EQ(r.faces_after, engine.mesh().live_faces()) << what;
  // The decision array: one entry per performed swap and removal, each routing to a face of the new mesh
  // or a later entry.
  EXPECT_EQ(r.decisions.size(), regular + complementary + removed) << what;
  EXPECT_EQ(r.decision_entries, r.decisions.size()) << what;
  for (std::size_t k = 0; k < r.decisions.size(); ++k) {
    for (const std::int32_t code : {r.decisions[k].above, r.decisions[k].below}) {
      if (code >= 0) {
        EXPECT_LT(static_cast<std::size_t>(code), r.faces_after) << what;
      } else {
        EXPECT_GT(static_cast<std::size_t>(-code - 1), k) << what << ": a route back to an earlier entry";
        EXPECT_LT(static_cast<std::size_t>(-code - 1), r.decisions.size()) << what;
      }
    }
  }
}

template <class Point>
void expect_stepped_records(const std::vector<Point>& points, const std::string& what, bool explain = false) {
  ResidentStats fast_stats;
  const BasicHullMesh<Point> fast = resident_hull_host(points, &fast_stats);
  std::unique_ptr<SteppingEngine> engine = make_resident_stepping_engine(points);
  std::size_t steps = 0;
  while (!engine->done()) {
    const Mesh before = engine->mesh();
    std::vector<std::int32_t> faces_before;
    if (explain && steps > 0) faces_before = engine->point_faces();
    const IterationRecord r = engine->step();
    EXPECT_EQ(r.iteration, static_cast<int>(steps)) << what;
    if (steps > 0 && engine->dimension() == 3 && r.faces_refined > 0)
      expect_record_explains_step(*engine, before, r, what + ", step " + std::to_string(steps));
    if (steps > 0 && r.faces_refined == 0) {
      // A stall: the mesh as it was, and the exact finish.
      EXPECT_TRUE(engine->done()) << what;
      EXPECT_EQ(r.faces_after, r.faces_before) << what;
      EXPECT_GT(r.repairs, 0u) << what;
    }
    const std::vector<std::int32_t> after = explain ? engine->point_faces() : std::vector<std::int32_t>{};
    for (PointIndex i = 0; i < after.size(); i += 7) {
      // Explain point, at every step (the first distribution, the last, a stall): its route through the
      // step's entries ends where the engine put it.
      const std::vector<std::string> lines = engine->explain_route(i, steps == 0 ? 0 : faces_before[i]);
      ASSERT_FALSE(lines.empty());
      if (steps > 0 && faces_before[i] < 0) continue;
      if (steps > 0 && r.faces_refined == 0) {
        EXPECT_EQ(lines.size(), 1u) << what;
        EXPECT_EQ(lines[0].rfind("the last step refined no face", 0), 0u) << what << ": " << lines[0];
        continue;
      }
      if (after[i] >= 0)
        EXPECT_EQ(lines.back(), "face " + std::to_string(after[i])) << what << ", point " << i;
      else
        EXPECT_TRUE(lines.back() == "internal" || lines.back() == "vertex") << what << ", point " << i;
    }
    ++steps;
    ASSERT_LT(steps, 10000u) << what;
  }
  EXPECT_EQ(engine->result_vertex_ids(), fast.vertex_ids) << what;
  EXPECT_TRUE(engine->result_triangles() == fast.triangles) << what;
  EXPECT_EQ(engine->result_vertex_ids(), exact_hull(points).vertex_ids) << what;
  if (fast.dimension == 3) {
    // The first distribution, the iterations, and a step that found no face to refine (a stall).
    const bool stalled = fast_stats.note.rfind("stalled", 0) == 0;
    EXPECT_EQ(steps, fast_stats.iterations + 1 + (stalled ? 1 : 0)) << what;
  }
}

TEST(ResidentRecords, GeneratedDistributions) {
  for (const char* name : {"cube", "ball", "sphere", "gauss", "paraboloid", "cylinder", "grid"}) {
    for (std::size_t n : {20, 3000}) {
      const std::vector<Point3> points = generate_points(distribution_from_name(name), n, 40 + n);
      expect_stepped_records(points, std::string(name) + " " + std::to_string(n), n == 3000);
      std::vector<Point3d> wide(points.size());
      for (std::size_t i = 0; i < points.size(); ++i)
        wide[i] = {points[i].x, points[i].y, points[i].z};
      expect_stepped_records(wide, std::string(name) + " " + std::to_string(n) + " in double");
    }
  }
}

// The property test's adversarial sets (tests/support/property_cases.hpp): between them they make every
// kind of edit the rounds make (regular and complementary swaps, rejected foldovers, removals), each
// replayed and checked.
TEST(ResidentRecords, PropertyCasesMakeEveryKindOfEdit) {
  std::size_t regular = 0, complementary = 0, foldovers = 0, removed = 0;
  for (std::uint64_t id = 0; id < 120; ++id) {
    const testing::Case c = testing::make_case(id);
    const std::string what = "property case " + std::to_string(id) + " (" + c.kind + ")";
    std::unique_ptr<SteppingEngine> engine = make_resident_stepping_engine(c.points);
    while (!engine->done()) {
      const Mesh before = engine->mesh();
      const IterationRecord r = engine->step();
      if (r.iteration > 0 && r.faces_refined > 0)
        expect_record_explains_step(*engine, before, r, what + ", step " + std::to_string(r.iteration));
      regular += r.swaps_regular;
      complementary += r.swaps_complementary;
      removed += r.vertices_removed;
      for (const SwapRecord& s : r.swaps)
        foldovers += s.kind == SwapKind::kRejectedFoldover;
    }
    EXPECT_EQ(engine->result_vertex_ids(), exact_hull(c.points).vertex_ids) << what;
    if (HasFailure()) break;
  }
  EXPECT_GT(regular, 0u);
  EXPECT_GT(complementary, 0u);
  EXPECT_GT(foldovers, 0u);
  EXPECT_GT(removed, 0u);
}

TEST(ResidentRecords, DegenerateAndTinyInputs) {
  expect_stepped_records(std::vector<Point3>{}, "no points");
  expect_stepped_records(std::vector<Point3>{{1, 2, 3}}, "one point");
  expect_stepped_records(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, "a square");
  expect_stepped_records(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, "a tetrahedron");
  for (std::uint64_t id = 120; id < 200; ++id) {
    const testing::Case c = testing::make_case(id);
    expect_stepped_records(c.points, "property case " + std::to_string(id) + " (" + c.kind + ")", true);
    if (HasFailure()) break;
  }
  // Cases whose local edits stall (cospherical points, a small lattice): the stall step, its record and
  // explain-point, then the exact finish.
  for (const std::uint64_t id : {2, 194, 513}) {
    const testing::Case c = testing::make_case(id);
    ResidentStats stats;
    resident_hull_host(c.points, &stats);
    EXPECT_EQ(stats.note.rfind("stalled", 0), 0u) << "property case " << id << ": " << stats.note;
    expect_stepped_records(c.points, "property case " + std::to_string(id) + " (" + c.kind + ")", true);
  }
}

// Restart repeats the same steps.
TEST(ResidentRecords, RestartRepeatsTheSteps) {
  const std::vector<Point3> points = generate_points(Distribution::kBall, 5000, 9);
  std::unique_ptr<SteppingEngine> engine = make_resident_stepping_engine(points);
  std::vector<std::size_t> first;
  engine->run([&](const IterationRecord& r) { first.push_back(r.swaps.size() * 1000003 + r.faces_after); });
  engine->restart();
  std::vector<std::size_t> again;
  engine->run([&](const IterationRecord& r) { again.push_back(r.swaps.size() * 1000003 + r.faces_after); });
  EXPECT_EQ(first, again);
  EXPECT_EQ(engine->result_vertex_ids(), exact_hull(points).vertex_ids);
}

}  // namespace
}  // namespace cudahull
