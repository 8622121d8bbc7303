// `cudahull hull` end to end, as a user runs it: `--backend cpu --verify --vertices-out V` on generated and
// degenerate inputs, compared with Qhull and with known answers; `--stats`, `--trace`, output files.  The
// backends, engines and environment: test_cli_hull_engines.cpp; --precision: test_cli_precision.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cudahull/generators.hpp"
#include "cudahull/point_io.hpp"
#include "qhull_reference.hpp"
#include "support/cli_hull_run.hpp"
#include "support/cli_runner.hpp"

namespace cudahull {
namespace {

using ::testing::HasSubstr;

TEST(CliHull, RandomSetsMatchQhull) {
  for (Distribution dist :
       {Distribution::kCube, Distribution::kBall, Distribution::kGauss, Distribution::kSphere}) {
    const auto points = generate_points(dist, 20000, 99);
    const HullRun r = hull_of(points);
    EXPECT_EQ(r.ids, run_qhull(points).vertex_ids) << distribution_name(dist);
    EXPECT_EQ(r.stats.at("verified"), true);
    EXPECT_EQ(r.stats.at("hull_vertices"), r.ids.size());
  }
}

TEST(CliHull, DegenerateSetsGiveTheStrictlyExtremePoints) {
  const auto grid = generate_points(Distribution::kGrid, 216, 1);  // 6 x 6 x 6
  EXPECT_EQ(hull_of(grid).ids, (std::vector<PointIndex>{0, 5, 30, 35, 180, 185, 210, 215}));

  std::vector<Point3> tripled;
  const auto ball = generate_points(Distribution::kBall, 2000, 4);
  for (int copy = 0; copy < 3; ++copy)
    tripled.insert(tripled.end(), ball.begin(), ball.end());
  const HullRun t = hull_of(tripled);
  EXPECT_EQ(t.ids, run_qhull(ball).vertex_ids);  // the first copy's indices only
  EXPECT_LT(t.ids.back(), 2000u);

  const auto cylinder = generate_points(Distribution::kCylinder, 5000, 2);
  EXPECT_EQ(hull_of(cylinder).ids, run_qhull(cylinder).vertex_ids);

  const auto paraboloid = generate_points(Distribution::kParaboloid, 3000, 8);
  const HullRun p = hull_of(paraboloid);
  EXPECT_EQ(p.ids, run_qhull(paraboloid).vertex_ids);
}

// A mesh file as `hull -o` writes it, read by this test's own small parser (not cudahull's reader): the
// vertices and the faces as 0-based vertex indices.  Any deviation from the format is a test failure.
struct MeshFile {
  std::vector<Point3> vertices;
  std::vector<std::vector<std::size_t>> faces;
};

MeshFile read_mesh_file(const fs::path& path) {
  MeshFile m;
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  const std::string ext = path.extension().string();
  std::string line;
  std::size_t nv = 0, nf = 0;
  if (ext == ".obj") {
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string key;
      ls >> key;
      if (key == "v") {
        Point3 p;
        EXPECT_TRUE(ls >> p.x >> p.y >> p.z) << line;
        m.vertices.push_back(p);
      } else if (key == "f") {
        std::vector<std::size_t> face;
        for (std::size_t v; ls >> v;) {
          EXPECT_GE(v, 1u) << line;  // OBJ counts from 1
          face.push_back(v - 1);
        }
        EXPECT_TRUE(ls.eof()) << line;
        m.faces.push_back(face);
      } else {
        EXPECT_TRUE(key.empty() || key[0] == '#') << line;
      }
    }
    return m;
  }
  if (ext == ".off") {
    std::string magic;
    std::size_t ne = 0;
    EXPECT_TRUE(in >> magic >> nv >> nf >> ne) << path;
    EXPECT_EQ(magic, "OFF");
  } else {
    EXPECT_TRUE(std::getline(in, line) && line == "ply") << path;
    while (std::getline(in, line) && line != "end_header") {
      std::istringstream ls(line);
      std::string key, what;
      ls >> key >> what;
      if (key == "format") EXPECT_EQ(what, "ascii");
      if (key == "element" && what == "vertex") ls >> nv;
      if (key == "element" && what == "face") ls >> nf;
    }
    EXPECT_EQ(line, "end_header");
  }
  m.vertices.resize(nv);
  for (Point3& p : m.vertices)
    EXPECT_TRUE(in >> p.x >> p.y >> p.z) << path;
  for (std::size_t f = 0; f < nf; ++f) {
    std::size_t corners = 0;
    EXPECT_TRUE(in >> corners) << path;
    std::vector<std::size_t> face(corners);
    for (std::size_t& v : face)
      EXPECT_TRUE(in >> v) << path;
    m.faces.push_back(face);
  }
  std::string rest;
  EXPECT_FALSE(in >> rest) << path << ": more data than the header's counts: " << rest;
  return m;
}

std::vector<Point3> sorted_points(std::vector<Point3> p) {
  std::sort(p.begin(), p.end(), [](const Point3& a, const Point3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  return p;
}

// The first index of each of `wanted` in `points`, sorted: the hull vertices a construction expects.
std::vector<PointIndex> first_indices(const std::vector<Point3>& points, const std::vector<Point3>& wanted) {
  std::vector<PointIndex> ids;
  for (const Point3& w : wanted)
    ids.push_back(static_cast<PointIndex>(std::find(points.begin(), points.end(), w) - points.begin()));
  std::sort(ids.begin(), ids.end());
  return ids;
}

// Inputs of fewer than 4 affinely independent points, each with the hull vertices its construction gives.
struct LowerDimensional {
  std::string what;
  std::vector<Point3> points;
  int dimension;
  std::vector<PointIndex> ids;  // sorted input indices of the hull vertices
};

std::vector<LowerDimensional> lower_dimensional_inputs() {
  std::vector<LowerDimensional> cases;
  const Point3 a{1.5f, -2, 3};
  cases.push_back({"1 point", {a}, 0, {0}});
  cases.push_back({"1 point 1000 times", std::vector<Point3>(1000, a), 0, {0}});
  cases.push_back({"2 equal points", {a, a}, 0, {0}});
  cases.push_back({"2 points", {a, {0, 0, 0}}, 1, {0, 1}});
  cases.push_back({"3 points", {{0, 0, 0}, {1, 2, 3}, {-1, 5, 2}}, 2, {0, 1, 2}});

  // 50 points of one line in scrambled order, then both ends again: the segment is the first copy of each
  // end.
  std::vector<Point3> line;
  auto on_line = [](int t) { return Point3{5.0f + t, 5.0f + 2 * t, 5.0f - 3 * t}; };
  for (int i = 0; i < 50; ++i)
    line.push_back(on_line(i * 17 % 50));
  line.push_back(on_line(49));
  line.push_back(on_line(0));
  cases.push_back({"collinear", line, 1, first_indices(line, {on_line(0), on_line(49)})});

  // A 7 x 5 grid in a plane (edge points included), after the centres of its cells and with its corners
  // repeated at the end: the polygon is the grid's 4 corners.  Once in z = 0, once in the plane x + y + z =
  // 0.
  for (const bool tilted : {false, true}) {
    auto at = [&](float i, float j) { return Point3{i, j, tilted ? -(i + j) : 0.0f}; };
    std::vector<Point3> plane;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 6; ++i)
        plane.push_back(at(i + 0.5f, j + 0.5f));
    for (int j = 4; j >= 0; --j)
      for (int i = 0; i < 7; ++i)
        plane.push_back(at(i, j));
    const std::vector<Point3> corners{at(0, 0), at(6, 0), at(6, 4), at(0, 4)};
    plane.insert(plane.end(), corners.begin(), corners.end());
    cases.push_back({tilted ? "tilted plane" : "plane z=0", plane, 2, first_indices(plane, corners)});
  }
  return cases;
}

// Lower-dimensional inputs exit 0 with a warning naming the dimension, and every output is written: the
// --vertices-out file lists exactly the expected input indices, and the -o mesh (each format) holds exactly
// their points, with one convex polygon face for a planar hull and no face for a segment or a point.
TEST(CliHull, LowerDimensionsExitZeroWithAWarningAndAnOutputFile) {
  TempDir dir;
  for (const LowerDimensional& c : lower_dimensional_inputs()) {
    std::vector<Point3> expected;
    for (PointIndex id : c.ids)
      expected.push_back(c.points[id]);
    for (const char* ext : {".obj", ".off", ".ply"}) {
      SCOPED_TRACE(c.what + ", -o out" + ext);
      const fs::path out = dir / (std::string("out") + ext);
      const HullRun r = hull_of(c.points, {"-o", out.string()});
      EXPECT_EQ(r.stats.at("dimension"), c.dimension);
      EXPECT_THAT(r.run.err,
                  HasSubstr("warning: the input is " + std::to_string(c.dimension) + "-dimensional"));
      EXPECT_EQ(r.ids, c.ids);

      ASSERT_TRUE(fs::exists(out));
      const MeshFile mesh = read_mesh_file(out);
      EXPECT_EQ(sorted_points(mesh.vertices), sorted_points(expected));
      EXPECT_EQ(read_points(out.string()).size(), expected.size());  // cudahull reads it back too
      const std::size_t faces = c.dimension == 2 ? 1 : 0;
      ASSERT_EQ(mesh.faces.size(), faces);
      EXPECT_EQ(r.stats.at("hull_faces"), faces);
      EXPECT_THAT(r.run.err, HasSubstr("-> " + std::to_string(expected.size()) + " vertices, " +
                                       std::to_string(faces) + " faces"));
      if (faces == 1) {
        // One face through every corner once, turning the same way at each: a convex polygon.
        std::vector<std::size_t> face = mesh.faces[0];
        ASSERT_EQ(face.size(), mesh.vertices.size());
        std::sort(face.begin(), face.end());
        for (std::size_t k = 0; k < face.size(); ++k)
          EXPECT_EQ(face[k], k);
        const auto& f = mesh.faces[0];
        std::array<double, 3> first{};
        for (std::size_t k = 0; k < f.size(); ++k) {
          const Point3 &p = mesh.vertices[f[k]], &q = mesh.vertices[f[(k + 1) % f.size()]],
                       &s = mesh.vertices[f[(k + 2) % f.size()]];
          const double u[3] = {double(q.x) - p.x, double(q.y) - p.y, double(q.z) - p.z};
          const double v[3] = {double(s.x) - q.x, double(s.y) - q.y, double(s.z) - q.z};
          const std::array<double, 3> turn{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                           u[0] * v[1] - u[1] * v[0]};
          if (k == 0) first = turn;
          EXPECT_GT(turn[0] * first[0] + turn[1] * first[1] + turn[2] * first[2], 0) << "corner " << k + 1;
        }
      }
      fs::remove(out);
    }
  }
}

TEST(CliHull, TraceHasOneLinePerIterationUntilNothingIsOutside) {
  TempDir dir;
  const auto points = generate_points(Distribution::kBall, 50000, 5);
  const HullRun r = hull_of(points, {"--trace", (dir / "trace.jsonl").string()});
  std::ifstream trace(dir / "trace.jsonl");
  std::string line;
  int iterations = 0;
  nlohmann::json last;
  while (std::getline(trace, line)) {
    last = nlohmann::json::parse(line);
    EXPECT_EQ(last.at("iteration"), iterations++);
    EXPECT_EQ(last.at("decisions").size(), last.at("decision_entries"));
    for (const auto& swap : last.at("swaps")) {
      const std::string kind = swap.at("kind");
      if (kind.rfind("rejected", 0) == 0) EXPECT_TRUE(swap.contains("reason")) << swap.dump();
    }
  }
  EXPECT_EQ(iterations, r.stats.at("iterations"));
  EXPECT_GT(iterations, 3);
  EXPECT_EQ(last.at("external_after"), 0);
}

TEST(CliHull, WritesEveryMeshFormat) {
  TempDir dir;
  const auto points = generate_points(Distribution::kCube, 3000, 3);
  for (const char* ext : {".obj", ".off", ".ply"}) {
    const fs::path out = dir / (std::string("hull") + ext);
    const HullRun r = hull_of(points, {"-o", out.string()});
    // The written mesh's vertices are exactly the hull vertices.
    const auto written = read_points(out.string());
    ASSERT_EQ(written.size(), r.ids.size()) << ext;
    for (std::size_t k = 0; k < written.size(); ++k)
      EXPECT_EQ(written[k], points[r.ids[k]]) << ext;
  }
}

}  // namespace
}  // namespace cudahull
