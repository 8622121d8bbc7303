// The command line on bad input, run as a separate process: exit code 3 with one stderr line naming the file,
// the place and the problem for every malformed input, quickly and in little memory, and no output file left
// behind by a failed `hull`.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "support/cli_error_line.hpp"
#include "support/cli_runner.hpp"

using ::testing::HasSubstr;

namespace {

const fs::path kData = CUDAHULL_TEST_DATA_DIR;

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

}  // namespace
