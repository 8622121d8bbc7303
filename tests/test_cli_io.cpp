// The command line's input and output behaviour, run as a separate process: `info` on the shared models,
// `gen` determinism, and the exit codes `--help` documents.  Bad input: test_cli_bad_input.cpp; no output
// file left behind by an interrupted `hull`: test_cli_interrupt.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"
#include "support/cli_error_line.hpp"
#include "support/cli_runner.hpp"

using ::testing::HasSubstr;

namespace {

const fs::path kModels = CUDAHULL_MODELS_DIR;

TEST(CliBinary, Exists) {
  ASSERT_TRUE(fs::exists(kCli)) << kCli;
}

// ------------------------------------------------------------------------------------------ info

struct Model {
  const char* file;
  std::size_t points;
  const char* precision;  // what `--precision auto` picks: ascii PLY and OBJ double, binary float PLY float
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
  ASSERT_TRUE(j.contains("precision")) << r.out;
  EXPECT_EQ(j["precision"], GetParam().precision) << r.out;
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
                         ::testing::Values(Model{"bun_zipper.ply", 35947, "double"},
                                           Model{"stanford-bunny.obj", 35947, "double"},
                                           Model{"dragonStandRight_0.ply", 41841, "double"},
                                           Model{"dragon_scans.ply", 469193, "float"},
                                           Model{"teapot.obj", 3644, "double"},
                                           Model{"spot.obj", 2930, "double"}),
                         model_name);

// `info` says which precision `--precision auto` would pick: double for decimals (text formats) and binary
// doubles, float for binary PLY whose x, y, z are floats.
TEST(CliInfo, ReportsThePrecisionAutoWouldPick) {
  TempDir dir;
  const auto binary_ply = [](const std::string& type, int size) {
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty " + type +
                      " x\nproperty " + type + " y\nproperty " + type + " z\nend_header\n";
    const double coords[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (double c : coords) {
      const float f = static_cast<float>(c);
      ply.append(size == 4 ? reinterpret_cast<const char*>(&f) : reinterpret_cast<const char*>(&c), size);
    }
    return ply;
  };
  std::ofstream(dir / "a.xyz") << "0 0 0\n1 0 0\n0 1 0\n0 0 1.000000000001\n";
  std::ofstream(dir / "f.ply", std::ios::binary) << binary_ply("float", 4);
  std::ofstream(dir / "d.ply", std::ios::binary) << binary_ply("double", 8);
  std::ofstream(dir / "a.ply")
      << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  for (const auto& [file, precision] : std::vector<std::pair<std::string, std::string>>{
           {"a.xyz", "double"}, {"f.ply", "float"}, {"d.ply", "double"}, {"a.ply", "double"}}) {
    SCOPED_TRACE(file);
    const CliRun r = run_cli({"info", (dir / file).string()});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const auto j = nlohmann::json::parse(r.out, nullptr, /*allow_exceptions=*/false);
    ASSERT_TRUE(j.is_object()) << "not one JSON object:\n" << r.out;
    EXPECT_EQ(j["points"], 4) << r.out;
    ASSERT_TRUE(j.contains("precision")) << r.out;
    EXPECT_EQ(j["precision"], precision) << r.out;
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

// The exit codes the tests hold the CLI to (errors.hpp) are the ones `cudahull --help` and `cudahull hull
// --help` document.
TEST(CliUsage, HelpDocumentsTheExitCodes) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"--help"}, {"hull", "--help"}}) {
    const CliRun r = run_cli(args);
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    std::string text;  // whitespace runs as one space
    for (char c : r.out) {
      const bool space = std::isspace(static_cast<unsigned char>(c));
      if (!space || (!text.empty() && text.back() != ' ')) text += space ? ' ' : c;
    }
    const std::pair<int, const char*> documented[] = {
        {cudahull::kExitOk, "0 ok;"},
        {cudahull::kExitOutput, "1 cannot write output;"},
        {cudahull::kExitUsage, "2 usage;"},
        {cudahull::kExitBadInput, "3 unreadable or invalid input;"},
        {cudahull::kExitDevice, "4 out of memory or device failure;"},
        {cudahull::kExitVerifyFailed, "5 --verify found the hull wrong"}};
    for (const auto& [code, line] : documented) {
      EXPECT_THAT(text, HasSubstr(line)) << args[0];
      EXPECT_EQ(std::to_string(code), std::string(line, std::strchr(line, ' '))) << line;
    }
  }
}

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

// An -o name the hull cannot be written to is a usage error found before anything else: with an input that
// does not exist either, the answer is still the extension (exit 2), not the missing file (exit 3).
TEST(CliUsage, UnknownMeshExtensionFailsBeforeAnyWork) {
  TempDir dir;
  const fs::path out = dir / "hull.stl";
  const CliRun r = run_cli({"hull", (dir / "missing.xyz").string(), "-o", out.string(), "--backend", "cpu"});
  EXPECT_EQ(r.exit_code, cudahull::kExitUsage) << describe(r);
  expect_one_error_line(r, "unknown mesh extension '.stl'");
  EXPECT_TRUE(dir.files().empty());
}

}  // namespace
