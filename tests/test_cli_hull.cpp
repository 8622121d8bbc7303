// `cudahull hull` end to end, as a user runs it: `--backend cpu --verify --vertices-out V` on generated and
// degenerate inputs, compared with Qhull and with known answers; `--stats`, `--trace`, output files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/point_writer.hpp"
#include "cudahull/predicates.hpp"
#include "qhull_reference.hpp"
#include "support/cli_runner.hpp"

namespace cudahull {
namespace {

using ::testing::HasSubstr;

// The vertex ids of a --vertices-out file ("index x y z" lines), checking each line's coordinates.
std::vector<PointIndex> read_vertex_ids(const fs::path& path, const std::vector<Point3>& points) {
  std::vector<PointIndex> ids;
  std::ifstream in(path);
  PointIndex id;
  float x, y, z;
  while (in >> id >> x >> y >> z) {
    EXPECT_LT(id, points.size());
    if (id < points.size()) EXPECT_EQ((Point3{x, y, z}), points[id]) << "vertex " << id;
    ids.push_back(id);
  }
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  return ids;
}

struct HullRun {
  CliRun run;
  std::vector<PointIndex> ids;
  nlohmann::json stats;
};

HullRun hull_of(const std::vector<Point3>& points, const std::vector<std::string>& extra = {}) {
  TempDir dir;
  const fs::path input = dir / "in.ply", vertices = dir / "v.txt", stats = dir / "stats.json";
  write_points(input.string(), points);
  std::vector<std::string> args{"hull",           input.string(),    "--backend", "cpu",         "--verify",
                                "--vertices-out", vertices.string(), "--stats",   stats.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  HullRun r;
  r.run = run_cli(args);
  EXPECT_EQ(r.run.exit_code, kExitOk) << describe(r.run);
  r.ids = read_vertex_ids(vertices, points);
  std::ifstream s(stats);
  if (s) r.stats = nlohmann::json::parse(s);
  return r;
}

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

TEST(CliHull, BackendAutoSaysWhichAndCudaNeedsADevice) {
  TempDir dir;
  write_points((dir / "in.xyz").string(), generate_points(Distribution::kCube, 100, 1));
  const CliRun automatic = run_cli({"hull", (dir / "in.xyz").string()});
  ASSERT_EQ(automatic.exit_code, kExitOk) << describe(automatic);
  EXPECT_THAT(automatic.err, HasSubstr("backend: "));
  const bool has_gpu = automatic.err.find("backend: cuda") != std::string::npos;
  // With a usable GPU, --backend cuda works; without one it is a device failure: exit 4, one line.
  const CliRun cuda = run_cli({"hull", (dir / "in.xyz").string(), "--backend", "cuda"});
  if (has_gpu) {
    EXPECT_EQ(cuda.exit_code, kExitOk) << describe(cuda);
  } else {
    EXPECT_THAT(automatic.err, HasSubstr("auto: no usable CUDA device"));
    EXPECT_EQ(cuda.exit_code, kExitDevice) << describe(cuda);
    EXPECT_THAT(cuda.err, HasSubstr("cudahull: error: --backend cuda: no usable CUDA device"));
  }
}

// --engine resident (issue 15): the same vertices as Qhull, verified, with its counts in --stats; with
// --table and --trace it steps with records, the same hull, a trace line and a table row per step.
TEST(CliHull, ResidentEngineMatchesQhullWithAndWithoutRecords) {
  for (Distribution dist : {Distribution::kBall, Distribution::kSphere, Distribution::kCylinder}) {
    const auto points = generate_points(dist, 20000, 7);
    const HullRun r = hull_of(points, {"--engine", "resident"});
    EXPECT_EQ(r.ids, run_qhull(points).vertex_ids) << distribution_name(dist);
    const nlohmann::json& stats = r.stats;
    EXPECT_EQ(stats.at("engine"), "resident");
    EXPECT_EQ(stats.at("backend"), "cpu-resident");
    EXPECT_EQ(stats.at("verified"), true);
    EXPECT_GT(stats.at("host_syncs").get<int>(), 0);
    // Every counter of the run (for_each_stat), agreeing with the summary's.
    const nlohmann::json& counters = stats.at("resident");
    EXPECT_EQ(counters.at("host_syncs"), stats.at("host_syncs"));
    EXPECT_EQ(counters.at("iterations"), stats.at("iterations"));
    EXPECT_EQ(counters.at("edits"), stats.at("swaps"));
    EXPECT_GE(counters.at("work_items").get<std::uint64_t>(), counters.at("edits").get<std::uint64_t>());
    EXPECT_EQ(counters.at("round_phase_ms").size(), 4u);  // the device's clock: zero on the host
  }
  TempDir dir;
  const auto sphere = generate_points(Distribution::kSphere, 3000, 2);
  write_points((dir / "in.xyz").string(), sphere);
  const std::string trace = (dir / "trace.jsonl").string(), vertices = (dir / "v.txt").string();
  const CliRun table = run_cli({"hull", (dir / "in.xyz").string(), "--engine", "resident", "--table",
                                "--trace", trace, "--vertices-out", vertices});
  ASSERT_EQ(table.exit_code, kExitOk) << describe(table);
  std::ifstream lines(trace);
  std::size_t steps = 0, performed = 0;
  for (std::string line; std::getline(lines, line); ++steps) {
    const nlohmann::json j = nlohmann::json::parse(line);
    EXPECT_EQ(j.at("iteration").get<std::size_t>(), steps);
    performed += j.at("swaps_regular").get<std::size_t>() + j.at("swaps_complementary").get<std::size_t>();
  }
  EXPECT_GT(steps, 3u);
  EXPECT_GT(performed, 0u);
  // A table row per step after the header.
  EXPECT_EQ(static_cast<std::size_t>(std::count(table.out.begin(), table.out.end(), '\n')), steps + 1)
      << table.out;
  std::ifstream ids(vertices);
  std::vector<PointIndex> listed;
  for (std::string line; std::getline(ids, line);)
    listed.push_back(static_cast<PointIndex>(std::stoul(line)));  // "id x y z"
  EXPECT_EQ(listed, run_qhull(sphere).vertex_ids);
  const CliRun bad = run_cli({"hull", (dir / "in.xyz").string(), "--engine", "fast"});
  EXPECT_EQ(bad.exit_code, kExitUsage) << describe(bad);
}

// CUDAHULL_THREADS sets the host threads (README); the hull and the trace do not depend on their number.
TEST(CliHull, ThreadCountFromTheEnvironmentChangesNothingButTheThreads) {
  TempDir dir;
  // Enough refinements for batched swap rounds (from 4096 candidates) to run on the threads.
  write_points((dir / "in.xyz").string(), generate_points(Distribution::kSphere, 20000, 5));
  auto run_with = [&](const char* threads, const std::string& tag) {
    if (threads != nullptr) {
      ::setenv("CUDAHULL_THREADS", threads, 1);
    } else {
      ::unsetenv("CUDAHULL_THREADS");
    }
    const CliRun r = run_cli({"hull", (dir / "in.xyz").string(), "--backend", "cpu", "--vertices-out",
                              (dir / ("v" + tag)).string(), "--trace", (dir / ("t" + tag)).string()});
    ::unsetenv("CUDAHULL_THREADS");
    EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
    return r;
  };
  EXPECT_THAT(run_with("1", "1").err, HasSubstr("backend: cpu (1 thread)"));
  EXPECT_THAT(run_with("3", "3").err, HasSubstr("backend: cpu (3 threads)"));
  const std::string vertices = slurp(dir / "v1");
  ASSERT_FALSE(vertices.empty());
  EXPECT_EQ(slurp(dir / "v3"), vertices);
  // The traces match but for their timings.
  auto without_times = [](std::string trace) {
    for (const char* key : {"\"host_ms\":", "\"backend_ms\":", "\"upload_ms\":"}) {
      for (std::size_t at = trace.find(key); at != std::string::npos; at = trace.find(key, at + 1)) {
        const std::size_t value = at + std::strlen(key);
        trace.erase(value, trace.find_first_of(",}", value) - value);
      }
    }
    return trace;
  };
  const std::string trace = without_times(slurp(dir / "t1"));
  EXPECT_NE(trace.find("\"swaps\":[{"), std::string::npos);
  EXPECT_EQ(without_times(slurp(dir / "t3")), trace);
  // Not a positive number: the hardware's count, as without the variable.
  auto backend_line = [](const std::string& err) {
    const std::size_t at = err.find("backend: cpu (");
    return at == std::string::npos ? std::string("(none)") : err.substr(at, err.find('\n', at) - at);
  };
  const std::string hardware = backend_line(run_with(nullptr, "u").err);
  EXPECT_NE(hardware, "(none)");
  EXPECT_EQ(backend_line(run_with("zero", "z").err), hardware);
  EXPECT_EQ(slurp(dir / "vz"), vertices);
}

// The command line reads the library's thresholds from its environment for A/B runs (docs/cli.md), the
// library itself none: CUDAHULL_BATCHED_SWAPS_FROM turns the stepping engine's batched swap rounds on (8) or
// off (SIZE_MAX), as scripts/compare-traces counts them (CUDAHULL_PHASE_TIMES=1), for `hull` and `bench`
// alike, and the vertices stay the same.
TEST(CliHull, BatchedSwapsFromTheEnvironmentReachTheEngine) {
  TempDir dir;
  write_points((dir / "in.xyz").string(), generate_points(Distribution::kSphere, 20000, 5));
  auto rounds_with = [&](const char* from, const std::vector<std::string>& args) {
    ::setenv("CUDAHULL_PHASE_TIMES", "1", 1);
    ::setenv("CUDAHULL_BATCHED_SWAPS_FROM", from, 1);
    const CliRun r = run_cli(args);
    ::unsetenv("CUDAHULL_BATCHED_SWAPS_FROM");
    ::unsetenv("CUDAHULL_PHASE_TIMES");
    EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
    int rounds = 0;
    for (std::size_t at = r.err.find("batched swaps: "); at != std::string::npos;
         at = r.err.find("batched swaps: ", at + 1))
      rounds += std::atoi(r.err.c_str() + at + std::strlen("batched swaps: "));
    return rounds;
  };
  const std::string input = (dir / "in.xyz").string();
  const std::string never = std::to_string(std::numeric_limits<std::size_t>::max());
  auto hull = [&](const std::string& out) {
    return std::vector<std::string>{"hull", input, "--backend", "cpu", "-q", "--vertices-out", out};
  };
  const std::string v8 = (dir / "v8").string(), vnever = (dir / "vnever").string();
  EXPECT_GT(rounds_with("8", hull(v8)), 0);
  EXPECT_EQ(rounds_with(never.c_str(), hull(vnever)), 0);
  const std::string vertices = slurp(v8);
  ASSERT_FALSE(vertices.empty());
  EXPECT_EQ(slurp(vnever), vertices);
  const std::vector<std::string> bench{"bench", input, "--backend", "cpu", "--engine", "stepping", "--json"};
  EXPECT_GT(rounds_with("8", bench), 0);
  EXPECT_EQ(rounds_with(never.c_str(), bench), 0);
}

// Every resident run reports its distance to the hardware: `bench --json` lists the phases (setup, refine,
// rounds, route, finish, host) with their time, least bytes, launches, waits and floor.  The phases' times
// add up to the run's total within 5%, no floor exceeds its phase's time, the setup reads every point once,
// and the floors come from a measured pace.
TEST(CliBench, ResidentPhasesAddUpAndNoFloorExceedsItsTime) {
  for (const char* dist : {"ball", "sphere", "cube"}) {
    const CliRun r = run_cli({"bench", "--dist", dist, "--n", "100000", "--repeat", "1", "--backend", "cpu",
                              "--engine", "resident", "--json"});
    ASSERT_EQ(r.exit_code, kExitOk) << describe(r);
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const nlohmann::json& stats = j.at("resident");
    const nlohmann::json& phases = stats.at("phases");
    std::vector<std::string> names;
    double sum = 0;
    for (const nlohmann::json& p : phases) {
      names.push_back(p.at("name"));
      const double ms = p.at("ms"), floor = p.at("floor_ms");
      sum += ms;
      EXPECT_GE(floor, 0) << dist << " " << names.back();
      EXPECT_LE(floor, ms) << dist << " " << names.back() << ": a floor above the time it bounds";
    }
    EXPECT_EQ(names, (std::vector<std::string>{"setup", "refine", "rounds", "route", "finish", "host"}));
    const double total = j.at("total_ms");
    EXPECT_NEAR(sum, total, 0.05 * total) << dist << ": the phases do not add up to the run";
    EXPECT_EQ(phases.at(0).at("bytes").get<std::uint64_t>(), 100000u * 3 * sizeof(float)) << dist;
    EXPECT_GT(phases.at(3).at("launches").get<std::uint64_t>(), 0u) << dist << ": no routing launched";
    EXPECT_GT(stats.at("pace").at("bytes_per_ms").get<double>(), 0) << dist;
  }
}

// The CLI runs with glibc's huge-page tunable unless told not to (cli/huge_pages.hpp), and a caller's own
// setting of it wins; the hull is the same either way.
TEST(CliHull, HugePagesByDefaultOffOnRequestAndTheCallersChoiceKept) {
  auto bench_with = [](const char* huge_pages, const char* tunables) {
    auto set = [](const char* name, const char* value) {
      if (value != nullptr) {
        ::setenv(name, value, 1);
      } else {
        ::unsetenv(name);
      }
    };
    set("CUDAHULL_HUGE_PAGES", huge_pages);
    set("GLIBC_TUNABLES", tunables);
    const CliRun r =
        run_cli({"bench", "--dist", "ball", "--n", "20000", "--repeat", "1", "--backend", "cpu", "--json"});
    ::unsetenv("CUDAHULL_HUGE_PAGES");
    ::unsetenv("GLIBC_TUNABLES");
    EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
    return nlohmann::json::parse(r.out.empty() ? "{}" : r.out);
  };
  const auto by_default = bench_with(nullptr, nullptr);
  const auto off = bench_with("0", nullptr);
  const auto callers = bench_with(nullptr, "glibc.malloc.hugetlb=0");
  EXPECT_EQ(by_default.value("host_huge_pages", false), true);
  EXPECT_EQ(off.value("host_huge_pages", true), false);
  EXPECT_EQ(callers.value("host_huge_pages", true), false);
  EXPECT_GT(by_default.value("hull_vertices", 0), 0);
  EXPECT_EQ(off.value("hull_vertices", -1), by_default.value("hull_vertices", -2));
  EXPECT_EQ(callers.value("hull_vertices", -1), by_default.value("hull_vertices", -2));
}

// ------------------------------------------------------------------------------------------ --precision

// The strictly extreme points of a small set by brute force, on the coordinates as given (orient3d is exact
// on floats and doubles alike): point i is a vertex iff some three other points span a plane that has every
// other point on one closed side and point i strictly on the other.  Among equal points only the lowest index
// can be a vertex.  For sets that are not planar, up to a few dozen points.
template <class Point>
std::vector<PointIndex> brute_force_vertices(const std::vector<Point>& points) {
  std::vector<PointIndex> vertices;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::vector<Vec3d> others;  // a copy of points[i] with a higher index is not a rival
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (j != i && (points[j] != points[i] || j < i)) others.push_back(to_vec3d(points[j]));
    }
    const Vec3d p = to_vec3d(points[i]);
    bool extreme = false;
    for (std::size_t a = 0; a < others.size() && !extreme; ++a) {
      for (std::size_t b = a + 1; b < others.size() && !extreme; ++b) {
        for (std::size_t c = b + 1; c < others.size() && !extreme; ++c) {
          const Vec3d &u = others[a], &v = others[b], &w = others[c];
          if (collinear3d(u, v, w)) continue;
          const int side = orient3d(u, v, w, p);
          if (side == 0) continue;
          extreme = std::none_of(others.begin(), others.end(),
                                 [&](const Vec3d& q) { return orient3d(u, v, w, q) == side; });
        }
      }
    }
    if (extreme) vertices.push_back(static_cast<PointIndex>(i));
  }
  return vertices;
}

std::vector<Point3> to_float(const std::vector<Point3d>& points) {
  std::vector<Point3> out;
  for (const Point3d& p : points)
    out.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  return out;
}

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// An .xyz file of `points` with 17 significant digits: read as doubles, exactly these values.
void write_xyz17(const fs::path& path, const std::vector<Point3d>& points) {
  std::ofstream out(path);
  char line[96];
  for (const Point3d& p : points) {
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    out << line;
  }
}

// A --vertices-out file parsed with strtod, each "index x y z" line as written.
std::vector<std::pair<PointIndex, Point3d>> read_vertices_double(const fs::path& path) {
  std::vector<std::pair<PointIndex, Point3d>> out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string id, x, y, z, rest;
    EXPECT_TRUE(ls >> id >> x >> y >> z) << line;
    EXPECT_FALSE(ls >> rest) << line;
    out.push_back({static_cast<PointIndex>(std::stoul(id)),
                   {std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr),
                    std::strtod(z.c_str(), nullptr)}});
  }
  return out;
}

// The unit cube [1, 2]^3's 8 corners, after 5 points per face 1e-12 outside it on a strictly concave cap
// through the face's corners (the face centre 1e-12 out, four points at a quarter 0.875e-12 out): every point
// strictly extreme in double.  Rounded to float, every cap point lies on its face (1 - 1e-12 and 2 + 1e-12
// are 1 and 2 in float) and only the corners remain.
std::vector<Point3d> bumped_cube() {
  std::vector<Point3d> points;
  const double uv[5][2] = {{1.5, 1.5}, {1.25, 1.5}, {1.75, 1.5}, {1.5, 1.25}, {1.5, 1.75}};
  for (int axis = 0; axis < 3; ++axis) {
    for (const double face : {1.0, 2.0}) {
      for (const auto& [u, v] : uv) {
        const double out = 2e-12 * (0.5 - ((u - 1.5) * (u - 1.5) + (v - 1.5) * (v - 1.5)));
        double c[3];
        c[axis] = face == 2.0 ? 2 + out : 1 - out;
        c[(axis + 1) % 3] = u;
        c[(axis + 2) % 3] = v;
        points.push_back({c[0], c[1], c[2]});
      }
    }
  }
  for (const double x : {1.0, 2.0})
    for (const double y : {1.0, 2.0})
      for (const double z : {1.0, 2.0})
        points.push_back({x, y, z});
  return points;
}

struct DoubleHullRun {
  CliRun run;
  nlohmann::json stats;
  std::vector<std::pair<PointIndex, Point3d>> vertices;  // --vertices-out, parsed with strtod
  std::vector<PointIndex> ids() const {
    std::vector<PointIndex> out;
    for (const auto& v : vertices)
      out.push_back(v.first);
    return out;
  }
};

// `cudahull hull INPUT --verify --vertices-out V --stats -` with `extra` arguments.
DoubleHullRun hull_of_file(const fs::path& input, const std::vector<std::string>& extra = {}) {
  TempDir dir;
  const fs::path vertices = dir / "v.txt";
  std::vector<std::string> args{
      "hull", input.string(), "--verify", "--vertices-out", vertices.string(), "--stats",
      "-",    "--backend",    "cpu"};
  args.insert(args.end(), extra.begin(), extra.end());
  DoubleHullRun r;
  r.run = run_cli(args);
  EXPECT_EQ(r.run.exit_code, kExitOk) << describe(r.run);
  r.stats = nlohmann::json::parse(r.run.out, nullptr, /*allow_exceptions=*/false);
  EXPECT_TRUE(r.stats.is_object()) << r.run.out;
  r.vertices = read_vertices_double(vertices);
  return r;
}

// (a) Points 1e-12 outside a cube's faces, in a text file: auto is double, and the hull's vertices are
// exactly the brute force's (every point); in float only the corners.  (b) The vertex coordinates written
// read back with strtod as the input doubles bit for bit, in --vertices-out and in every -o format.
TEST(CliPrecision, TextInputIsExactInDoubleAndRoundTrips) {
  TempDir dir;
  const std::vector<Point3d> points = bumped_cube();
  const fs::path input = dir / "bumped.xyz";
  write_xyz17(input, points);

  const std::vector<PointIndex> in_double = brute_force_vertices(points);
  ASSERT_EQ(in_double.size(), points.size()) << "the construction: every point strictly extreme";
  const std::vector<PointIndex> in_float = brute_force_vertices(to_float(points));
  ASSERT_EQ(in_float, (std::vector<PointIndex>{30, 31, 32, 33, 34, 35, 36, 37})) << "only the corners";

  const DoubleHullRun d = hull_of_file(input);
  EXPECT_EQ(d.stats.value("precision", ""), "double");
  EXPECT_EQ(d.stats.value("verified", false), true);
  EXPECT_EQ(d.ids(), in_double);
  for (const auto& [id, p] : d.vertices) {
    ASSERT_LT(id, points.size());
    for (int axis = 0; axis < 3; ++axis) {
      const double written = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
      const double given = axis == 0 ? points[id].x : axis == 1 ? points[id].y : points[id].z;
      EXPECT_EQ(bits(written), bits(given)) << "vertex " << id << " axis " << axis;
    }
  }
  EXPECT_EQ(d.stats.value("precision", ""), "double");
  EXPECT_THAT(d.run.err, HasSubstr("(double) -> 38 vertices"));

  const DoubleHullRun f = hull_of_file(input, {"--precision", "float"});
  EXPECT_EQ(f.stats.value("precision", ""), "float");
  EXPECT_EQ(f.stats.value("verified", false), true);
  EXPECT_EQ(f.ids(), in_float);
  const DoubleHullRun forced = hull_of_file(input, {"--precision", "double"});
  EXPECT_EQ(forced.ids(), in_double);

  // -o in each format: the hull's vertices, every coordinate bit for bit (PLY declares them double).
  std::vector<Point3d> expected;
  for (PointIndex id : in_double)
    expected.push_back(points[id]);
  auto key = [](const Point3d& p) { return std::make_tuple(bits(p.x), bits(p.y), bits(p.z)); };
  std::sort(expected.begin(), expected.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  for (const char* ext : {".obj", ".off", ".ply"}) {
    SCOPED_TRACE(ext);
    const fs::path out = dir / (std::string("hull") + ext);
    const CliRun r = run_cli({"hull", input.string(), "--backend", "cpu", "-q", "-o", out.string()});
    ASSERT_EQ(r.exit_code, kExitOk) << describe(r);
    std::vector<Point3d> written;
    std::istringstream text(slurp(out));
    std::size_t count = 0;
    bool in_body = std::string(ext) == ".obj";
    for (std::string line; std::getline(text, line);) {
      std::istringstream ls(line);
      std::vector<std::string> tokens;
      for (std::string t; ls >> t;)
        tokens.push_back(t);
      if (std::string(ext) == ".ply" && !in_body) {
        if (line.rfind("property", 0) == 0 && tokens.size() == 3 && tokens[2].size() == 1)
          EXPECT_EQ(tokens[1], "double") << line;
        in_body = line == "end_header";
        if (tokens.size() == 3 && tokens[0] == "element" && tokens[1] == "vertex")
          count = std::stoul(tokens[2]);
        continue;
      }
      if (std::string(ext) == ".off" && !in_body) {
        if (tokens.size() == 3) {
          count = std::stoul(tokens[0]);
          in_body = true;
        }
        continue;
      }
      if (std::string(ext) == ".obj") {
        if (tokens.empty() || tokens[0] != "v") continue;
        tokens.erase(tokens.begin());
      } else if (written.size() == count) {
        break;  // the faces
      }
      ASSERT_EQ(tokens.size(), 3u) << line;
      written.push_back({std::strtod(tokens[0].c_str(), nullptr), std::strtod(tokens[1].c_str(), nullptr),
                         std::strtod(tokens[2].c_str(), nullptr)});
    }
    std::sort(written.begin(), written.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    EXPECT_TRUE(written == expected) << written.size() << " vertices written, " << expected.size()
                                     << " expected";
  }
}

// (c) Pairs of points equal in float32 but not in double: each corner of a cube and a twin 2^-40 from it
// (across the corner's diagonal, so both are strictly extreme): 16 vertices in double, 8 in float (the
// first of each pair).
TEST(CliPrecision, PointsEqualInFloatAreTwoVerticesInDouble) {
  TempDir dir;
  std::vector<Point3d> points;
  for (const double x : {1.0, 2.0})
    for (const double y : {1.0, 2.0})
      for (const double z : {1.0, 2.0}) {
        points.push_back({x, y, z});
        // Perpendicular to the outward diagonal (sx, sy, sz): d (sy, -sx, 0).
        const double d = 0x1p-40, sx = x == 2 ? 1 : -1, sy = y == 2 ? 1 : -1;
        points.push_back({x + d * sy, y - d * sx, z});
      }
  const std::vector<Point3> narrow = to_float(points);
  for (std::size_t i = 0; i < points.size(); i += 2) {
    ASSERT_EQ(narrow[i], narrow[i + 1]);
    ASSERT_NE(points[i], points[i + 1]);
  }
  const std::vector<PointIndex> in_double = brute_force_vertices(points);
  ASSERT_EQ(in_double.size(), 16u);
  const std::vector<PointIndex> in_float = brute_force_vertices(narrow);
  ASSERT_EQ(in_float, (std::vector<PointIndex>{0, 2, 4, 6, 8, 10, 12, 14}));

  const fs::path input = dir / "twins.xyz";
  write_xyz17(input, points);
  const DoubleHullRun d = hull_of_file(input);
  EXPECT_EQ(d.stats.value("precision", ""), "double");
  EXPECT_EQ(d.ids(), in_double);
  EXPECT_EQ(d.stats.value("hull_vertices", 0), 16);
  EXPECT_EQ(hull_of_file(input, {"--precision", "float"}).ids(), in_float);

  // The same points through the double writers: binary PLY of doubles (auto: double) and .xyz.
  for (const char* name : {"twins.ply", "twins.txt"}) {
    SCOPED_TRACE(name);
    write_points((dir / name).string(), points);
    EXPECT_EQ(read_points_double((dir / name).string()).points, points);
    const DoubleHullRun w = hull_of_file(dir / name);
    EXPECT_EQ(w.stats.value("precision", ""), "double");
    EXPECT_EQ(w.ids(), in_double);
  }
  EXPECT_THAT(slurp(dir / "twins.ply"),
              HasSubstr("property double x\nproperty double y\nproperty double z\n"));

  // bench --vs qhull hands Qhull the doubles: the same 16 vertices (8 from the floats).
  for (const auto& [precision, count] :
       std::vector<std::pair<std::string, std::size_t>>{{"auto", 16}, {"float", 8}}) {
    const CliRun b = run_cli({"bench", input.string(), "--backend", "cpu", "--repeat", "1", "--vs", "qhull",
                              "--json", "--precision", precision});
    ASSERT_EQ(b.exit_code, kExitOk) << describe(b);
    const auto j = nlohmann::json::parse(b.out, nullptr, false);
    ASSERT_TRUE(j.is_object()) << b.out;
    EXPECT_EQ(j.value("precision", ""), precision == "auto" ? "double" : "float");
    EXPECT_EQ(j.value("hull_vertices", 0u), count) << precision;
    EXPECT_EQ(j.value("qhull_vertices", 0u), count) << precision;
    // Among duplicates Qhull keeps whichever it meets, not the lowest index: compare in double only.
    if (precision == "auto") EXPECT_EQ(j.value("same_vertices", false), true);
  }
}

// (d) A double coordinate outside [2^-250, 2^250] (and not 0) is taken exactly (issue 25): `hull` computes
// such an input on the wide-range path (exponent scaling, else GMP), says so, and gives the brute force's
// vertices; `bench`, which times the engines, still refuses it (exit 3, one line naming the point).
TEST(CliPrecision, DoublesOutsideTheExactRangeAreExact) {
  TempDir dir;
  // Point 5 is 1e-300 below the face z = 0 (a vertex), point 6 1e-300 above it (inside); in float both are 0.
  std::vector<Point3d> points{
      {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {0.5, 0.25, -1e-300}, {0.25, 0.25, 1e-300}};
  const fs::path tiny = dir / "tiny.xyz";
  write_xyz17(tiny, points);
  for (const std::vector<std::string>& extra :
       std::vector<std::vector<std::string>>{{}, {"--precision", "double"}}) {
    std::vector<std::string> args{
        "hull", tiny.string(), "--backend", "cpu", "--vertices-out", (dir / "v.txt").string(), "--stats",
        "-"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun r = run_cli(args);
    ASSERT_EQ(r.exit_code, kExitOk) << describe(r);
    EXPECT_THAT(r.err, HasSubstr("note: coordinates outside 2^-250..2^250"));
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.value("backend", ""), "cpu-wide");
    std::vector<PointIndex> ids;
    for (const auto& [id, p] : read_vertices_double(dir / "v.txt"))
      ids.push_back(id);
    EXPECT_EQ(ids, (std::vector<PointIndex>{0, 1, 2, 3, 4, 5}));
  }
  const CliRun f = run_cli({"hull", tiny.string(), "--backend", "cpu", "--precision", "float"});
  EXPECT_EQ(f.exit_code, kExitOk) << describe(f);

  const CliRun bench = run_cli({"bench", tiny.string(), "--backend", "cpu"});
  EXPECT_EQ(bench.exit_code, kExitBadInput) << describe(bench);
  EXPECT_EQ(bench.err, "cudahull: error: " + tiny.string() +
                           ": point 5: z coordinate -1e-300 is outside the range of exact double arithmetic "
                           "(nonzero magnitudes from 2^-250 to 2^250)\n");

  // A point at z = -2^251 below the corner at the origin: the origin falls on the segment from it to
  // (0, 0, 1) and point 5 inside the cone over the face z = 0, so the vertices are 1, 2, 3, 4 and it.
  points.back() = {0, 0, -0x1p251};
  write_xyz17(dir / "huge.xyz", points);
  const CliRun huge = run_cli(
      {"hull", (dir / "huge.xyz").string(), "--backend", "cpu", "--vertices-out", (dir / "v.txt").string()});
  EXPECT_EQ(huge.exit_code, kExitOk) << describe(huge);
  std::vector<PointIndex> ids;
  for (const auto& [id, p] : read_vertices_double(dir / "v.txt"))
    ids.push_back(id);
  EXPECT_EQ(ids, (std::vector<PointIndex>{1, 2, 3, 4, 6}));

  // The ends of the range, and zeros, are accepted and exact.
  std::vector<Point3d> ends;
  for (const double x : {-0x1p250, 0x1p250})
    for (const double y : {-0x1p250, 0x1p250})
      for (const double z : {-0x1p250, 0x1p250})
        ends.push_back({x, y, z});
  ends.push_back({0x1p-250, 0, -0x1p-250});
  write_xyz17(dir / "ends.xyz", ends);
  const DoubleHullRun e = hull_of_file(dir / "ends.xyz");
  EXPECT_EQ(e.stats.value("verified", false), true);
  EXPECT_EQ(e.ids(), (std::vector<PointIndex>{0, 1, 2, 3, 4, 5, 6, 7}));
}

// (e) --precision takes auto, float or double; anything else is a usage error (exit 2), for hull and bench.
TEST(CliPrecision, BadValueIsAUsageError) {
  TempDir dir;
  write_points((dir / "in.ply").string(), generate_points(Distribution::kCube, 100, 1));
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"hull", (dir / "in.ply").string(), "--precision", "bogus"},
           {"hull", (dir / "in.ply").string(), "--precision", "Double"},
           {"bench", "--dist", "cube", "--n", "100", "--precision", "bogus"}}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, kExitUsage) << describe(r);
    EXPECT_THAT(r.err, HasSubstr("--precision"));
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// (f) auto follows the file: a binary float PLY is computed in float, as before; generated points in float.
TEST(CliPrecision, AutoIsFloatForBinaryFloatPlyAndGeneratedPoints) {
  const auto points = generate_points(Distribution::kBall, 2000, 3);
  const HullRun r = hull_of(points);
  EXPECT_EQ(r.stats.value("precision", ""), "float");
  EXPECT_EQ(r.ids, run_qhull(points).vertex_ids);
  EXPECT_EQ(hull_of(points, {"--precision", "double"}).stats.value("precision", ""), "double");

  for (const auto& [precision, expected] :
       std::vector<std::pair<std::string, std::string>>{{"auto", "float"}, {"double", "double"}}) {
    const CliRun b = run_cli({"bench", "--dist", "ball", "--n", "5000", "--repeat", "1", "--backend", "cpu",
                              "--vs", "qhull", "--json", "--precision", precision});
    ASSERT_EQ(b.exit_code, kExitOk) << describe(b);
    const auto j = nlohmann::json::parse(b.out, nullptr, false);
    ASSERT_TRUE(j.is_object()) << b.out;
    EXPECT_EQ(j.value("precision", ""), expected);
    EXPECT_EQ(j.value("same_vertices", false), true);
  }
}

}  // namespace
}  // namespace cudahull
