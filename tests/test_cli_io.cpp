// The command line's input and output behaviour, run as a separate process: `info` on the shared models,
// exit code 3 with one stderr line for every malformed input, `gen` determinism, and no output file left
// behind by a failed `hull`.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"
#include "support/cli_runner.hpp"

using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

const fs::path kModels = CUDAHULL_MODELS_DIR;
const fs::path kData = CUDAHULL_TEST_DATA_DIR;

// The CLI's error contract: one line on stderr, "cudahull: error: ...".
void expect_one_error_line(const CliRun& r, const std::string& must_mention) {
  EXPECT_THAT(r.err, StartsWith("cudahull: error: ")) << describe(r);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(r);
  EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << describe(r);
  EXPECT_THAT(r.err, HasSubstr(must_mention)) << describe(r);
}

TEST(CliBinary, Exists) {
  ASSERT_TRUE(fs::exists(kCli)) << kCli;
}

// ------------------------------------------------------------------------------------------ info

struct Model {
  const char* file;
  std::size_t points;
};

class InfoOnModels : public ::testing::TestWithParam<Model> {};

TEST_P(InfoOnModels, PrintsReadmeCountAndBoundingBox) {
  if (!fs::is_directory(kModels)) GTEST_SKIP() << "shared models folder absent: " << kModels;
  const fs::path path = kModels / GetParam().file;
  const CliRun r = run_cli({"info", path.string()});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto j = nlohmann::json::parse(r.out, nullptr, /*allow_exceptions=*/false);
  ASSERT_TRUE(j.is_object()) << "not one JSON object:\n" << r.out;
  ASSERT_TRUE(j.contains("points")) << r.out;
  EXPECT_EQ(j["points"].get<std::size_t>(), GetParam().points);
  ASSERT_TRUE(j.contains("bbox")) << r.out;
  const auto& box = j["bbox"];
  ASSERT_TRUE(box.contains("min") && box.contains("max")) << r.out;
  ASSERT_EQ(box["min"].size(), 3u);
  ASSERT_EQ(box["max"].size(), 3u);
  // The box of the points as the library reads them.
  const auto pts = cudahull::read_points(path.string());
  for (int a = 0; a < 3; ++a) {
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (const auto& p : pts) {
      const float v = a == 0 ? p.x : a == 1 ? p.y : p.z;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_NEAR(box["min"][a].get<double>(), lo, 1e-6 * (1 + std::abs(lo))) << "axis " << a;
    EXPECT_NEAR(box["max"][a].get<double>(), hi, 1e-6 * (1 + std::abs(hi))) << "axis " << a;
  }
}

std::string model_name(const ::testing::TestParamInfo<Model>& info) {
  std::string name = info.param.file;
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Models, InfoOnModels,
                         ::testing::Values(Model{"bun_zipper.ply", 35947}, Model{"stanford-bunny.obj", 35947},
                                           Model{"dragonStandRight_0.ply", 41841},
                                           Model{"dragon_scans.ply", 469193}, Model{"teapot.obj", 3644},
                                           Model{"spot.obj", 2930}),
                         model_name);

// ------------------------------------------------------------------------------------------ bad input

std::vector<fs::path> malformed_files() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kData / "malformed"))
    files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(CliBadInput, EveryMalformedFileExitsThreeWithOneLine) {
  const auto files = malformed_files();
  ASSERT_GE(files.size(), 15u);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    const CliRun r = run_cli({"info", f.string()});
    EXPECT_EQ(r.exit_code, cudahull::kExitBadInput) << describe(r);
    expect_one_error_line(r, f.filename().string());
  }
}

TEST(CliBadInput, BinaryNanAndMissingFile) {
  TempDir dir;
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  const float values[6] = {0, 0, 0, 1, std::numeric_limits<float>::quiet_NaN(), 1};
  ply.append(reinterpret_cast<const char*>(values), sizeof values);
  std::ofstream(dir / "nan.ply", std::ios::binary) << ply;
  CliRun r = run_cli({"info", (dir / "nan.ply").string()});
  EXPECT_EQ(r.exit_code, cudahull::kExitBadInput) << describe(r);
  expect_one_error_line(r, "vertex 1: NaN y coordinate");

  r = run_cli({"info", (dir / "missing.xyz").string()});
  EXPECT_EQ(r.exit_code, cudahull::kExitBadInput) << describe(r);
  expect_one_error_line(r, "missing.xyz");
}

TEST(CliBadInput, FailedHullLeavesNoOutputFile) {
  TempDir dir;
  for (const char* bad : {"nan.xyz", "truncated_binary.ply", "wrong_count.ply", "garbage.obj"}) {
    SCOPED_TRACE(bad);
    const fs::path out = dir / "out.obj";
    const CliRun r = run_cli({"hull", (kData / "malformed" / bad).string(), "-o", out.string()});
    EXPECT_EQ(r.exit_code, cudahull::kExitBadInput) << describe(r);
    expect_one_error_line(r, bad);
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(dir.files().empty()) << "left behind: " << dir.files().front();
  }
}

// ------------------------------------------------------------------------------------------ gen

TEST(CliGen, CubeIsReadableAndDeterministic) {
  TempDir dir;
  const std::string a = (dir / "a.ply").string(), b = (dir / "b.ply").string(), c = (dir / "c.ply").string();
  CliRun r = run_cli({"gen", "cube", "1000", "--seed", "7", "-o", a});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  r = run_cli({"info", a});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  EXPECT_EQ(j["points"].get<std::size_t>(), 1000u);
  EXPECT_EQ(cudahull::read_points(a).size(), 1000u);

  ASSERT_EQ(run_cli({"gen", "cube", "1000", "--seed", "7", "-o", b}).exit_code, 0);
  EXPECT_EQ(slurp(a), slurp(b)) << "same seed, different bytes";
  ASSERT_EQ(run_cli({"gen", "cube", "1000", "--seed", "8", "-o", c}).exit_code, 0);
  EXPECT_NE(slurp(a), slurp(c)) << "different seed, same bytes";
  // Only the three outputs: no temporary files.
  EXPECT_EQ(dir.files().size(), 3u);
}

TEST(CliGen, UnwritableOutputExitsWithOutputError) {
  const CliRun r = run_cli({"gen", "cube", "10", "-o", "/nonexistent/cudahull/x.ply"});
  EXPECT_EQ(r.exit_code, cudahull::kExitOutput) << describe(r);
  expect_one_error_line(r, "/nonexistent/cudahull/x.ply");
}

// ------------------------------------------------------------------------------------------ usage

TEST(CliUsage, BadCommandLinesExitTwo) {
  TempDir dir;
  const std::string out = (dir / "x.ply").string();
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"info"},                            // missing file
                                             {"no-such-command"},                 // unknown subcommand
                                             {"gen", "cube", "many", "-o", out},  // count is not a number
                                             {"info", "a.xyz", "--no-such-option"}}) {  // unknown option
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, cudahull::kExitUsage) << args[0] << " ...\n" << describe(r);
  }
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
