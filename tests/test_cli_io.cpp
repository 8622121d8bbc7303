// The command line's input and output behaviour, run as a separate process: `info` on the shared models,
// exit code 3 with one stderr line for every malformed input, no output file left behind by a failed or
// interrupted `hull`, `gen` determinism, and the exit codes `--help` documents.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
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

// `cudahull hull` on bad input, end to end: every case below and every file of tests/data/malformed must
// exit 3 (the code `cudahull --help` documents for "unreadable or invalid input") with one stderr line that
// names the file, the place and the problem, quickly and in little memory even when a header claims
// billions of vertices, and must leave nothing in the output folder: no -o file, no --vertices-out or
// --stats file, no temporary file.  Each case runs under every --precision it is bad in (float, and auto,
// which reads text formats and double PLY as doubles).
struct BadInput {
  std::string file;                   // its name; the message must mention it
  std::string bytes;                  // its contents
  std::vector<std::string> mentions;  // what else the message must mention: place and problem
  // The --precision values under which it is bad: a value beyond float range is a fine double (text formats
  // and double PLY are read as doubles under auto), and one outside the double range computed exactly
  // (README, "Precision") is bad in double only.
  std::vector<std::string> precisions = {"float", "auto"};
};

enum class TextFormat { kXyz, kObj, kOff, kPly };
constexpr TextFormat kTextFormats[] = {TextFormat::kXyz, TextFormat::kObj, TextFormat::kOff,
                                       TextFormat::kPly};

const char* extension(TextFormat f) {
  return f == TextFormat::kXyz   ? ".xyz"
         : f == TextFormat::kObj ? ".obj"
         : f == TextFormat::kOff ? ".off"
                                 : ".ply";
}

std::string ply_header(const std::string& format, const std::string& count, const std::string& type = "float",
                       const std::string& before_vertex = "", const std::string& after_xyz = "") {
  return "ply\nformat " + format + " 1.0\n" + before_vertex + "element vertex " + count + "\nproperty " +
         type + " x\nproperty " + type + " y\nproperty " + type + " z\n" + after_xyz + "end_header\n";
}

// A text point file whose vertex rows are `rows` ("x y z", written as given; the last one without its end of
// line when `cut`), with the count `count` in its header for OFF and PLY.  *first_row_line is the 1-based
// line of rows[0].
std::string text_file(TextFormat f, const std::vector<std::string>& rows, const std::string& count, bool cut,
                      int* first_row_line) {
  std::string head;
  switch (f) {
    case TextFormat::kXyz:
      head = "# x y z\n";
      break;
    case TextFormat::kObj:
      head = "# points\no cloud\n";
      break;
    case TextFormat::kOff:
      head = "OFF\n" + count + " 0 0\n";
      break;
    case TextFormat::kPly:
      head = ply_header("ascii", count);
      break;
  }
  *first_row_line = static_cast<int>(std::count(head.begin(), head.end(), '\n')) + 1;
  std::string text = head;
  for (std::size_t i = 0; i < rows.size(); ++i)
    text += (f == TextFormat::kObj ? "v " : "") + rows[i] + (cut && i + 1 == rows.size() ? "" : "\n");
  return text;
}

template <typename T>
std::string binary(const std::vector<T>& values, bool big_endian) {
  std::string out;
  for (T v : values) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big_endian) std::reverse(b, b + sizeof(T));
    out.append(b, sizeof(T));
  }
  return out;
}

// n points of x y z values 0, 1, 2, ...
template <typename T>
std::vector<T> ramp(std::size_t n) {
  std::vector<T> v(3 * n);
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = static_cast<T>(i);
  return v;
}

std::vector<BadInput> bad_inputs() {
  std::vector<BadInput> cases;
  const char* axes[3] = {"x", "y", "z"};
  // A bad coordinate in every text format, on each axis in turn: 0 0 0 / 1 2 3 / the bad row / 4 5 6.
  struct Value {
    const char* text;
    const char* problem;
    std::vector<std::string> precisions = {"float", "auto"};
  };
  const Value values[] = {{"inf", "infinite"},
                          {"-inf", "infinite"},
                          {"+Infinity", "infinite"},
                          {"nan", "NaN"},
                          {"-NaN", "NaN"},
                          {"1e39", "beyond float range", {"float"}},
                          {"-1e39", "beyond float range", {"float"}},
                          {"3.5e38", "beyond float range", {"float"}},
                          {"1e309", "beyond double range", {"auto", "double"}}};
  int k = 0;
  for (TextFormat f : kTextFormats) {
    for (const Value& v : values) {
      const int axis = k++ % 3;
      std::string row[3] = {"7", "8", "9"};
      row[axis] = v.text;
      int first = 0;
      const std::string name = "bad_" + std::to_string(k) + extension(f);
      const std::string bytes =
          text_file(f, {"0 0 0", "1 2 3", row[0] + " " + row[1] + " " + row[2], "4 5 6"}, "4", false, &first);
      cases.push_back({name,
                       bytes,
                       {name + ":" + std::to_string(first + 2) + ": ", v.problem,
                        std::string(axes[axis]) + " coordinate '" + v.text + "'"},
                       v.precisions});
    }
  }
  // A line with only 2 coordinates; a file cut in the middle of a line or of a number; OFF and PLY files
  // that end before the header's count, and headers that claim billions of vertices over 3 rows of data.
  for (TextFormat f : kTextFormats) {
    const std::string ext = extension(f);
    const std::string short_what = f == TextFormat::kPly   ? "too few values for vertex 1 (found 2)"
                                   : f == TextFormat::kObj ? "vertex needs 3 coordinates, found 2"
                                                           : "expected 3 coordinates, found 2";
    const std::string cut_what = f == TextFormat::kPly   ? "too few values for vertex 2 (found 2)"
                                 : f == TextFormat::kObj ? "vertex needs 3 coordinates, found 2"
                                                         : "expected 3 coordinates, found 2";
    int first = 0;
    std::string bytes = text_file(f, {"0 0 0", "1 2", "4 5 6"}, "3", false, &first);
    cases.push_back(
        {"two_coords" + ext, bytes, {"two_coords" + ext + ":" + std::to_string(first + 1), short_what}});
    bytes = text_file(f, {"0 0 0", "1 2 3", "4 5"}, "3", true, &first);
    cases.push_back(
        {"cut_in_line" + ext, bytes, {"cut_in_line" + ext + ":" + std::to_string(first + 2), cut_what}});
    bytes = text_file(f, {"0 0 0", "1 2 3", "4 5 6.5e"}, "3", true, &first);
    cases.push_back(
        {"cut_in_number" + ext,
         bytes,
         {"cut_in_number" + ext + ":" + std::to_string(first + 2), "invalid z coordinate '6.5e'"}});
    if (f != TextFormat::kOff && f != TextFormat::kPly) continue;
    bytes = text_file(f, {"0 0 0", "1 2 3", "4 5 6"}, "10", false, &first);
    cases.push_back(
        {"too_few_rows" + ext, bytes, {"unexpected end of file", "header says 10 vertices, found 3"}});
    bytes = text_file(f, {"0 0 0", "1 2 3", "4 5 6"}, "4000000000", false, &first);
    cases.push_back(
        {"count_4e9" + ext, bytes, {"unexpected end of file", "header says 4000000000 vertices, found 3"}});
    bytes = text_file(f, {"0 0 0", "1 2 3", "4 5 6"}, "1000000000000000", false, &first);
    cases.push_back({"count_1e15" + ext, bytes, {"vertex count 1000000000000000 exceeds the limit"}});
  }
  cases.push_back(
      {"face_count_4e9_ascii.ply",
       ply_header("ascii", "3", "float", "element face 4000000000\nproperty list uchar int vi\n") +
           "3 0 1 2\n",
       {"unexpected end of file in element 'face'"}});

  // Binary PLY, both byte orders: a non-finite float, a double beyond float range, and data that ends before
  // the header's count (1000 vertices, 10 in the data; 3 and 4e9 in the header; a cut inside a record).
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  for (const bool be : {false, true}) {
    const std::string fmt = be ? "binary_big_endian" : "binary_little_endian", e = be ? "_be" : "_le";
    cases.push_back({"inf" + e + ".ply",
                     ply_header(fmt, "3") + binary<float>({0, 0, 0, 1, 2, inf, 4, 5, 6}, be),
                     {"vertex 1: infinite z coordinate"}});
    cases.push_back({"neg_inf" + e + ".ply",
                     ply_header(fmt, "3") + binary<float>({0, 0, 0, 1, 2, 3, -inf, 5, 6}, be),
                     {"vertex 2: infinite x coordinate"}});
    cases.push_back({"nan" + e + ".ply",
                     ply_header(fmt, "3") + binary<float>({0, nan, 0, 1, 2, 3, 4, 5, 6}, be),
                     {"vertex 0: NaN y coordinate"}});
    cases.push_back({"big_double" + e + ".ply",
                     ply_header(fmt, "3", "double") + binary<double>({0, 0, 0, 1, 1e39, 3, 4, 5, 6}, be),
                     {"vertex 1: y coordinate is beyond float range"},
                     {"float"}});
    cases.push_back({"neg_big_double" + e + ".ply",
                     ply_header(fmt, "3", "double") + binary<double>({0, 0, 0, 1, 2, 3, 4, 5, -1e39}, be),
                     {"vertex 2: z coordinate is beyond float range"},
                     {"float"}});
    cases.push_back({"truncated" + e + ".ply",
                     ply_header(fmt, "1000") + binary<float>(ramp<float>(10), be),
                     {"vertex 10: truncated", "header says 1000 vertices"}});
    cases.push_back({"truncated_double" + e + ".ply",
                     ply_header(fmt, "1000", "double") + binary<double>(ramp<double>(10), be),
                     {"vertex 10: truncated", "header says 1000 vertices"}});
    cases.push_back({"cut_in_record" + e + ".ply",
                     ply_header(fmt, "3") + binary<float>(ramp<float>(3), be).substr(0, 30),
                     {"vertex 2: truncated", "header says 3 vertices"}});
    cases.push_back({"count_4e9" + e + ".ply",
                     ply_header(fmt, "4000000000") + binary<float>(ramp<float>(3), be),
                     {"vertex 3: truncated", "header says 4000000000 vertices"}});
    cases.push_back({"count_4e9_list" + e + ".ply",
                     ply_header(fmt, "4000000000", "float", "", "property list uchar int vi\n") +
                         binary<float>({0, 0, 0}, be) + '\0' + binary<float>({1, 2, 3}, be) + '\0',
                     {"truncated", "header says 4000000000 vertices"}});
    cases.push_back({"face_count_4e9" + e + ".ply",
                     ply_header(fmt, "3", "float", "element face 4000000000\nproperty list uchar int vi\n") +
                         '\3' + binary<int>({0, 1, 2}, be),
                     {"element 'face'", "truncated"}});
  }
  return cases;
}

TEST(CliBadInput, HullExitsThreeWithOneLineAndLeavesNoFile) {
  TempDir dir;
  fs::create_directories(dir / "in");
  fs::create_directories(dir / "out");
  fs::create_directories(dir / "logs");
  std::vector<BadInput> cases = bad_inputs();
  for (const fs::path& f : malformed_files()) {
    // too_big.xyz's 1e39 is beyond float range only.
    cases.push_back({f.filename().string(), slurp(f), {}});
    if (f.filename() == "too_big.xyz") cases.back().precisions = {"float"};
  }
  ASSERT_GE(cases.size(), 90u);
  for (const BadInput& c : cases) {
    for (const std::string& precision : c.precisions) {
      SCOPED_TRACE(c.file + " --precision " + precision);
      const fs::path input = dir / "in" / c.file;
      std::ofstream(input, std::ios::binary) << c.bytes;
      const CliProcess p =
          start_cli({"hull", input.string(), "-o", (dir / "out" / "out.obj").string(), "--vertices-out",
                     (dir / "out" / "v.txt").string(), "--stats", (dir / "out" / "stats.json").string(),
                     "--backend", "cpu", "--precision", precision},
                    dir / "logs");
      const CliEnd e = wait_cli(p);
      ASSERT_TRUE(e.exited()) << describe(e);  // not killed, not crashed
      EXPECT_EQ(e.exit_code(), cudahull::kExitBadInput) << describe(e);
      const CliRun r{e.exit_code(), e.out, e.err};
      expect_one_error_line(r, c.file);
      for (const std::string& m : c.mentions)
        EXPECT_THAT(e.err, HasSubstr(m));
      // A header's count never makes the reader allocate for it: a few points' worth of time and memory.
      EXPECT_LT(e.seconds, 3.0) << describe(e);
      EXPECT_LT(e.max_rss_kb, 512 * 1024) << describe(e);
      const std::vector<std::string> left = TempDir::files_in(dir / "out");
      EXPECT_TRUE(left.empty()) << "left behind: " << left.front();
      for (const std::string& name : left)
        fs::remove(dir / "out" / name);
    }
  }
}

// ------------------------------------------------------------------------------------------ interrupt

// The contents of each file in a folder, by name.
std::map<std::string, std::string> folder_contents(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const std::string& name : TempDir::files_in(folder))
    files[name] = slurp(folder / name);
  return files;
}

void reset_folder(const fs::path& folder, const std::map<std::string, std::string>& files) {
  for (const std::string& name : TempDir::files_in(folder))
    fs::remove(folder / name);
  for (const auto& [name, bytes] : files)
    std::ofstream(folder / name, std::ios::binary) << bytes;
}

// True once `pid` has stopped or ended, without reaping it (wait_cli does that).
bool stopped_not_ended(pid_t pid) {
  siginfo_t info{};
  while (::waitid(P_PID, static_cast<id_t>(pid), &info, WSTOPPED | WEXITED | WNOWAIT) != 0) {
    if (errno != EINTR) return false;
  }
  return info.si_code == CLD_STOPPED;
}

// A `hull` run on `points` sphere points (every one a hull vertex, so the outputs take megabytes): -o
// (written first) and --vertices-out into `out`.
struct InterruptSetup {
  TempDir dir;
  fs::path out = dir / "out", logs = dir / "logs";
  std::vector<std::string> args;
  explicit InterruptSetup(int points) {
    fs::create_directories(out);
    fs::create_directories(logs);
    const std::string input = (dir / "in.ply").string();
    const CliRun gen = run_cli({"gen", "sphere", std::to_string(points), "--seed", "3", "-o", input});
    EXPECT_EQ(gen.exit_code, 0) << describe(gen);
    args = {"hull",      input, "-o", (out / "out.obj").string(), "--vertices-out", (out / "v.txt").string(),
            "--backend", "cpu", "-q"};
  }
};

// A file's lines, sorted, with face lines reduced to "f": equal for two complete hull files even if the
// engine ordered their faces or vertices differently, and different for a file cut short.
std::vector<std::string> canonical_lines(const std::string& bytes) {
  std::vector<std::string> lines;
  std::istringstream in(bytes);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line.rfind("f ", 0) == 0 ? "f" : line);
  std::sort(lines.begin(), lines.end());
  return lines;
}

// An uninterrupted run: its outputs (-o and --vertices-out) by name, and how long it took.
std::pair<std::map<std::string, std::string>, double> complete_run(const InterruptSetup& s) {
  const CliEnd whole = wait_cli(start_cli(s.args, s.logs));
  EXPECT_EQ(whole.exit_code(), 0) << describe(whole);
  const auto complete = folder_contents(s.out);
  EXPECT_EQ(complete.size(), 2u);
  return {complete, whole.seconds};
}

// Every file in `out` is one of the complete outputs, whole (the same lines), never partial or temporary.
void expect_only_whole_outputs(const fs::path& out, const std::map<std::string, std::string>& complete) {
  for (const auto& [name, bytes] : folder_contents(out)) {
    ASSERT_TRUE(complete.count(name)) << "left behind: " << name;
    EXPECT_TRUE(canonical_lines(bytes) == canonical_lines(complete.at(name)))
        << name << " is partial: " << bytes.size() << " of " << complete.at(name).size() << " bytes";
  }
}

// Starts the run, waits for a new name in the output folder (the temporary file of -o), stops the process
// there (SIGSTOP) and, if out.obj is still as `before`, queues `sig` and lets it go on (SIGCONT), so that
// the signal lands inside the write.  A run that got past out.obj before it could be stopped is killed and
// run again.  Returns how the caught run ended, or nothing after five misses.
std::optional<CliEnd> signal_during_the_write(const InterruptSetup& s,
                                              const std::map<std::string, std::string>& before, int sig,
                                              bool ignore_sigint = false) {
  for (int attempt = 0; attempt < 5; ++attempt) {
    reset_folder(s.out, before);
    const CliProcess p = start_cli(s.args, s.logs, ignore_sigint);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    bool new_name = false;
    while (!new_name && std::chrono::steady_clock::now() < deadline) {
      new_name = TempDir::files_in(s.out).size() > before.size();
      siginfo_t info{};
      if (!new_name && ::waitid(P_PID, static_cast<id_t>(p.pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
          info.si_pid == p.pid) {
        break;  // it ended without writing anything we saw
      }
      if (!new_name) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    bool caught = false;
    if (new_name && ::kill(p.pid, SIGSTOP) == 0 && stopped_not_ended(p.pid)) {
      const auto now = folder_contents(s.out);
      const auto obj = now.find("out.obj");
      const auto was = before.find("out.obj");
      const bool obj_as_before =
          was == before.end() ? obj == now.end() : obj != now.end() && obj->second == was->second;
      caught = obj_as_before && now.size() > before.size();  // a temporary file, out.obj not renamed
      ::kill(p.pid, caught ? sig : SIGKILL);
      ::kill(p.pid, SIGCONT);
    } else {
      ::kill(p.pid, SIGKILL);
    }
    const CliEnd e = wait_cli(p);
    if (caught) return e;
  }
  return std::nullopt;
}

// Ctrl-C, or the terminal closing (SIGHUP), in the middle of writing -o: the process dies by the signal and
// the output folder holds exactly what it held before, byte for byte: no partial out.obj, no
// --vertices-out file, no temporary file; earlier outputs survive.
TEST(CliInterrupt, SignalDuringTheWriteLeavesNothingPartial) {
  InterruptSetup s(50000);
  const std::map<std::string, std::string> earlier{{"out.obj", "# an earlier hull\nv 0 0 0\n"},
                                                   {"v.txt", "0 0 0 0\n"}};
  for (const int sig : {SIGINT, SIGHUP}) {
    for (const auto& before : {std::map<std::string, std::string>{}, earlier}) {
      SCOPED_TRACE(std::string(sig == SIGINT ? "SIGINT, " : "SIGHUP, ") +
                   (before.empty() ? "empty output folder" : "earlier outputs in the folder"));
      const std::optional<CliEnd> e = signal_during_the_write(s, before, sig);
      ASSERT_TRUE(e.has_value()) << "never caught the process while it wrote out.obj";
      EXPECT_EQ(e->signal(), sig) << describe(*e);
      EXPECT_EQ(folder_contents(s.out), before);
    }
  }
}

// A SIGINT that the caller ignores (a background job of a shell) stays ignored while -o is written: the
// run goes on and writes both outputs whole.
TEST(CliInterrupt, IgnoredSigintStaysIgnoredDuringTheWrite) {
  InterruptSetup s(50000);
  const auto [complete, seconds] = complete_run(s);
  ASSERT_EQ(complete.size(), 2u);
  const std::optional<CliEnd> e = signal_during_the_write(s, {}, SIGINT, /*ignore_sigint=*/true);
  ASSERT_TRUE(e.has_value()) << "never caught the process while it wrote out.obj";
  EXPECT_EQ(e->exit_code(), 0) << describe(*e);
  EXPECT_EQ(folder_contents(s.out).size(), complete.size());
  expect_only_whole_outputs(s.out, complete);
}

// SIGINT at a spread of moments, from the start to past the end: whenever it lands, the process either
// dies by it or has finished (exit 0), and each output is either absent or complete (as an uninterrupted
// run writes it), with no temporary file.
TEST(CliInterrupt, SigintAtAnyMomentLeavesCompleteFilesOrNone) {
  InterruptSetup s(20000);
  const auto [complete, seconds] = complete_run(s);
  ASSERT_EQ(complete.size(), 2u);
  const double run_ms = seconds * 1000;
  for (const double fraction : {0.0, 0.5, 0.8, 0.9, 1.0, 1.2}) {
    SCOPED_TRACE("SIGINT at " + std::to_string(fraction) + " of a run");
    reset_folder(s.out, {});
    const CliProcess p = start_cli(s.args, s.logs);
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(fraction * run_ms));
    ::kill(p.pid, SIGINT);
    const CliEnd e = wait_cli(p);
    EXPECT_TRUE(e.signal() == SIGINT || e.exit_code() == 0) << describe(e);
    expect_only_whole_outputs(s.out, complete);
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
