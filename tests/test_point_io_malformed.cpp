// Point readers on malformed input: one InputError, on one line naming the file and the place, per kind of
// malformed file, binary data and text; absurd counts fail before allocating; missing files, folders and
// unknown extensions.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <istream>
#include <limits>
#include <streambuf>
#include <string>
#include <utility>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"
#include "support/ply_writer.hpp"
#include "support/point_reads.hpp"
#include "support/temp_dir.hpp"

namespace cudahull {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// ------------------------------------------------------------------------------------------ malformed files

struct BadCase {
  const char* file;
  const char* message;  // a part of the one-line message after "<path>"
};

class MalformedFiles : public ::testing::TestWithParam<BadCase> {};

TEST_P(MalformedFiles, ThrowsOneLineInputError) {
  const std::string path = (kData / "malformed" / GetParam().file).string();
  const std::string msg = read_error(path);
  EXPECT_THAT(msg, StartsWith(path));
  EXPECT_THAT(msg, HasSubstr(GetParam().message));
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

INSTANTIATE_TEST_SUITE_P(
    Files, MalformedFiles,
    ::testing::Values(
        BadCase{"nan.xyz", ":2: NaN y coordinate 'nan'"},
        BadCase{"inf.off", ":4: infinite y coordinate 'inf'"},
        BadCase{"too_big.xyz", ":2: x coordinate '1e39' is beyond float range"},
        BadCase{"short_line.xyz", ":2: expected 3 coordinates, found 2"},
        BadCase{"bad_number.xyz", ":1: invalid z coordinate 'abc'"}, BadCase{"garbage.obj", ": no vertices"},
        BadCase{"empty.xyz", ": empty file"},
        BadCase{"short_line.obj", ":2: vertex needs 3 coordinates, found 2"},
        BadCase{"nan.obj", ":3: NaN y coordinate"},
        BadCase{"wrong_count.off", ":5: unexpected end of file: header says 5 vertices, found 3"},
        BadCase{"wrong_count.ply", ":10: unexpected end of file: header says 10 vertices, found 3"},
        BadCase{"faces_read_as_vertices.ply", ":13: more values than the header's vertex properties"},
        BadCase{"no_xyz.ply", ":3: vertex element has no 'x' property"},
        BadCase{"huge_count.ply", ":3: vertex count 1000000000000000 exceeds the limit"},
        BadCase{"large_count.ply", ":8: unexpected end of file: header says 100000000 vertices, found 1"},
        BadCase{"bad_header.ply", ":4: expected 'property TYPE NAME' with a known type"},
        BadCase{"no_end_header.ply", ": unexpected end of file in the header"},
        BadCase{"bad_magic.ply", ":1: not a PLY file"},
        BadCase{"truncated_binary.ply", ": vertex 1: truncated binary data (header says 3 vertices)"},
        BadCase{"unknown_extension.dat", ": unknown file extension '.dat'"}),
    [](const auto& info) { return test_name(info.param.file); });

TEST(Malformed, EveryFileInTheFolderIsCovered) {
  // A file added to tests/data/malformed without a case above would otherwise go untested here.
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(kData / "malformed")) {
    (void)entry;
    ++n;
  }
  EXPECT_EQ(n, 20u);
}

TEST(MalformedBinary, NonFiniteAndOutOfRangeValuesNameTheVertex) {
  TempDir dir;
  struct Case {
    Enc enc;
    const char* type;
    double bad;
    const char* message;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Case& c : {Case{Enc::kLittle, "float", nan, ": vertex 2: NaN z coordinate"},
                        Case{Enc::kBig, "float", -inf, ": vertex 2: infinite z coordinate"},
                        Case{Enc::kLittle, "double", 1e300, ": vertex 2: z coordinate is beyond float range"},
                        Case{Enc::kBig, "double", nan, ": vertex 2: NaN z coordinate"}}) {
    std::string body;
    for (int i = 0; i < 4; ++i) {
      for (int a = 0; a < 3; ++a)
        put_binary(body, c.type, (i == 2 && a == 2) ? c.bad : 1.0, c.enc);
    }
    const std::string t = c.type;
    const std::string props = "property " + t + " x\nproperty " + t + " y\nproperty " + t + " z\n";
    const fs::path path = dir / (t + (c.enc == Enc::kBig ? "_be.ply" : "_le.ply"));
    write_file(
        path,
        binary_header(c.enc == Enc::kBig ? "binary_big_endian" : "binary_little_endian", 4, props) + body);
    const std::string msg = read_error(path.string());
    EXPECT_THAT(msg, HasSubstr(path.string() + c.message));
  }
}

TEST(MalformedBinary, TruncationNamesTheFirstMissingVertex) {
  TempDir dir;
  std::string body(12 * 3 + 5, '\0');  // three whole vertices and part of the fourth
  write_file(dir / "t.ply", binary_header("binary_little_endian", 6, kXyzFloat) + body);
  EXPECT_THAT(read_error((dir / "t.ply").string()), HasSubstr(": vertex 3: truncated binary data"));

  // A vertex element with a list: the record-by-record path.
  std::string listed = binary_header("binary_big_endian", 3, kXyzFloat + "property list uchar int l\n");
  for (int i = 0; i < 2; ++i) {
    for (int a = 0; a < 3; ++a)
      put_binary(listed, "float", 1.0, Enc::kBig);
    put_binary(listed, "uchar", 1, Enc::kBig);
    put_binary(listed, "int", 5, Enc::kBig);
  }
  for (int a = 0; a < 3; ++a)
    put_binary(listed, "float", 1.0, Enc::kBig);
  put_binary(listed, "uchar", 200, Enc::kBig);  // 200 ints promised, none there
  write_file(dir / "l.ply", listed);
  EXPECT_THAT(read_error((dir / "l.ply").string()), HasSubstr(": vertex 2: truncated binary data"));
}

TEST(MalformedBinary, AbsurdCountsFailBeforeAllocating) {
  TempDir dir;
  // 4e9 vertices fits in 32 bits, so only the file size stops it.
  write_file(dir / "a.ply",
             binary_header("binary_little_endian", 4'000'000'000ULL, kXyzFloat) + std::string(24, 'A'));
  EXPECT_THAT(read_error((dir / "a.ply").string()), HasSubstr(": vertex 2: truncated binary data"));
  write_file(dir / "b.ply", binary_header("binary_little_endian", 1'000'000'000'000'000ULL, kXyzFloat));
  EXPECT_THAT(read_error((dir / "b.ply").string()), HasSubstr("exceeds the limit"));
  // An element before the vertices that claims more data than the file has.
  write_file(dir / "c.ply",
             "ply\nformat binary_little_endian 1.0\nelement junk 99999999999\nproperty double a\n" +
                 std::string("element vertex 1\n") + kXyzFloat + "end_header\n" + std::string(12, 'A'));
  EXPECT_THAT(read_error((dir / "c.ply").string()), HasSubstr(": element 'junk': truncated binary data"));
  write_file(dir / "d.off", "OFF\n999999999999 0 0\n0 0 0\n");
  EXPECT_THAT(read_error((dir / "d.off").string()),
              HasSubstr(":2: vertex count 999999999999 exceeds the limit"));
  write_file(dir / "e.off", "OFF\n99999999 0 0\n0 0 0\n");
  EXPECT_THAT(read_error((dir / "e.off").string()),
              HasSubstr(":3: unexpected end of file: header says 99999999 vertices, found 1"));
}

// A stream that cannot seek, like a pipe: the reader cannot check counts against the size up front.
class PipeBuf : public std::streambuf {
 public:
  explicit PipeBuf(std::string data) : data_(std::move(data)) {
    setg(data_.data(), data_.data(), data_.data() + data_.size());
  }

 private:
  std::string data_;
};

TEST(MalformedBinary, AbsurdCountOnUnseekableStreamStillFailsCleanly) {
  PipeBuf buf(binary_header("binary_little_endian", 4'000'000'000ULL, kXyzFloat) + std::string(30, 'A'));
  std::istream in(&buf);
  EXPECT_THAT(input_error([&] { read_points(in, PointFormat::kPly, "pipe"); }, "no InputError"),
              HasSubstr("pipe: vertex 2: truncated binary data"));
  PipeBuf text("ply\nformat ascii 1.0\nelement vertex 4000000000\n" + kXyzFloat + "end_header\n1 2 3\n");
  std::istream in2(&text);
  EXPECT_THROW(read_points(in2, PointFormat::kPly, "pipe"), InputError);
}

TEST(MalformedText, MoreCases) {
  EXPECT_THAT(read_error_text(
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\nproperty float y\n"
                  "property float z\nend_header\n1 1 2 3\n",
                  PointFormat::kPly),
              HasSubstr("mem:3: vertex property 'x' is a list"));
  EXPECT_THAT(read_error_text("ply\nformat ascii 1.0\nelement face 1\nproperty float x\nend_header\n1\n",
                              PointFormat::kPly),
              HasSubstr("mem: no 'vertex' element"));
  EXPECT_THAT(read_error_text("ply\nformat ascii 1.0\nelement vertex 0\n" + kXyzFloat + "end_header\n",
                              PointFormat::kPly),
              HasSubstr("mem:3: no vertices"));
  EXPECT_THAT(read_error_text("ply\nformat ascii 1.0\nelement vertex 1\n" + kXyzFloat + "end_header\n1 2\n",
                              PointFormat::kPly),
              HasSubstr("mem:8: too few values for vertex 0"));
  EXPECT_THAT(
      read_error_text("ply\nformat ascii 1.0\nelement vertex 1\n" + kXyzFloat + "end_header\n1 nan 2\n",
                      PointFormat::kPly),
      HasSubstr("mem:8: NaN y coordinate"));
  EXPECT_THAT(read_error_text("ply\nformat binary_middle_endian 1.0\n", PointFormat::kPly),
              HasSubstr("mem:2: unknown PLY format"));
  EXPECT_THAT(read_error_text("ply\nelement vertex 1\n" + kXyzFloat + "end_header\n", PointFormat::kPly),
              HasSubstr("without a format line"));
  EXPECT_THAT(read_error_text("ply\nformat ascii 1.0\nproperty float x\n", PointFormat::kPly),
              HasSubstr("mem:3: property before any element"));
  EXPECT_THAT(read_error_text("OFF\n", PointFormat::kOff),
              HasSubstr("mem:1: missing vertex and face counts"));
  EXPECT_THAT(read_error_text("OFF\nthree 1 0\n", PointFormat::kOff),
              HasSubstr("mem:2: expected 'vertices faces"));
  EXPECT_THAT(read_error_text("4OFF\n1 0 0\n1 2 3 4\n", PointFormat::kOff),
              HasSubstr("mem:1: expected an OFF header"));
  EXPECT_THAT(read_error_text("OFF BINARY\n", PointFormat::kOff), HasSubstr("binary OFF is not supported"));
  EXPECT_THAT(read_error_text("# only a comment\n\n", PointFormat::kXyz), HasSubstr("mem: no points"));
  EXPECT_THAT(read_error_text("v 1 2 3\nv\n", PointFormat::kObj),
              HasSubstr("mem:2: vertex needs 3 coordinates, found 0"));
  // Garbage bytes are echoed printably, so the message stays on one line.
  const std::string msg = read_error_text(std::string("1 2 \x01\n\x7f", 7), PointFormat::kXyz);
  EXPECT_THAT(msg, HasSubstr("invalid z coordinate '?'"));
  EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(Paths, MissingFileDirectoryAndExtensions) {
  EXPECT_THAT(read_error("/nonexistent/cudahull/points.xyz"),
              HasSubstr("/nonexistent/cudahull/points.xyz: cannot open: No such file or directory"));
  TempDir dir;
  fs::create_directories(dir / "d.ply");
  EXPECT_THAT(read_error((dir / "d.ply").string()), HasSubstr("d.ply: is a directory"));
  EXPECT_EQ(cudahull::point_format_from_path("a/b.PLY"), PointFormat::kPly);
  EXPECT_EQ(cudahull::point_format_from_path("x.Obj"), PointFormat::kObj);
  EXPECT_EQ(cudahull::point_format_from_path("x.off"), PointFormat::kOff);
  EXPECT_EQ(cudahull::point_format_from_path("x.txt"), PointFormat::kXyz);
  EXPECT_EQ(cudahull::point_format_from_path("x.xyz"), PointFormat::kXyz);
  EXPECT_EQ(cudahull::point_format_from_path("-"), PointFormat::kXyz);
  EXPECT_THROW(cudahull::point_format_from_path("points"), InputError);
  EXPECT_THROW(cudahull::point_format_from_path("points.stl"), InputError);
}

}  // namespace
}  // namespace cudahull
