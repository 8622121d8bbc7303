// `cudahull hull` end to end, as a user runs it: `--backend cpu --verify --vertices-out V` on generated and
// degenerate inputs, compared with Qhull and with known answers; `--stats`, `--trace`, output files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/point_writer.hpp"
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

TEST(CliHull, LowerDimensionsExitZeroWithAWarningAndAnOutputFile) {
  TempDir dir;
  std::vector<Point3> plane, line, point(5, Point3{1, 2, 3});
  for (int i = 0; i < 50; ++i) {
    plane.push_back({float(i % 7), float(i % 5), 0.5f});
    line.push_back({float(i), 1.0f, float(-i)});
  }
  for (const auto& [points, dimension] :
       std::vector<std::pair<std::vector<Point3>, int>>{{plane, 2}, {line, 1}, {point, 0}}) {
    const HullRun r = hull_of(points, {"-o", (dir / "out.obj").string()});
    EXPECT_EQ(r.stats.at("dimension"), dimension);
    EXPECT_THAT(r.run.err, HasSubstr("warning: the input is " + std::to_string(dimension) + "-dimensional"));
    EXPECT_TRUE(fs::exists(dir / "out.obj"));
    fs::remove(dir / "out.obj");
  }
  EXPECT_EQ(hull_of(plane).ids.size(), 4u);  // the 7 x 5 grid's corners
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

}  // namespace
}  // namespace cudahull
