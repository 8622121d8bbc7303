// `cudahull hull --backend cpu --verify --vertices-out V --stats S` on a set of points from the command-line
// tests: how it exited, the vertex ids it listed (each line's coordinates checked) and its --stats.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/point_writer.hpp"
#include "cudahull/types.hpp"

namespace cudahull {
namespace {

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

}  // namespace
}  // namespace cudahull
