// The full-precision point reader (read_points_double): decimals to the nearest double, binary doubles kept
// exactly, the same errors as the float reader but for the range, and which precision `auto` picks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"
#include "support/ply_writer.hpp"
#include "support/point_reads.hpp"
#include "support/temp_dir.hpp"

namespace cudahull {
namespace {

using ::testing::HasSubstr;

// ------------------------------------------------------------------------------------------ full precision

// read_points_double keeps what the file gives: decimals to the nearest double, binary values exactly, and
// says which precision `auto` picks.  Expected values come from strtod/strtof of the same text, or from the
// doubles written into the binary files.

DoublePoints read_text_double(const std::string& text, PointFormat format) {
  std::istringstream in(text);
  return read_points_double(in, format, "mem");
}

std::string read_error_text_double(const std::string& text, PointFormat format) {
  std::istringstream in(text);
  return input_error([&] { read_points_double(in, format, "mem"); }, "no InputError for:\n" + text);
}

double strtod_of(const std::string& s) {
  return std::strtod(s.c_str(), nullptr);
}

// The same rows of decimal tokens as a file of each text format.
std::string as_text_format(const std::vector<std::array<std::string, 3>>& rows, PointFormat format) {
  std::string body;
  for (const auto& r : rows)
    body += (format == PointFormat::kObj ? "v " : "") + r[0] + " " + r[1] + " " + r[2] + "\n";
  const std::string n = std::to_string(rows.size());
  switch (format) {
    case PointFormat::kOff:
      return "OFF\n" + n + " 0 0\n" + body;
    case PointFormat::kPly:
      return "ply\nformat ascii 1.0\nelement vertex " + n +
             "\nproperty float x\nproperty float y\nproperty float z\nend_header\n" + body;
    default:
      return body;
  }
}

TEST(DoubleText, PointsThatFloatWouldMergeStayDistinct) {
  const auto d = read_text_double("1 0 0\n1.000000000001 0 0\n0 0 1e-12\n0 0 2e-12\n", PointFormat::kXyz);
  ASSERT_EQ(d.points.size(), 4u);
  EXPECT_EQ(d.points[0], (Point3d{1, 0, 0}));
  EXPECT_EQ(d.points[1].x, strtod_of("1.000000000001"));
  EXPECT_NE(d.points[0], d.points[1]);
  EXPECT_EQ(d.points[2].z, strtod_of("1e-12"));
  EXPECT_EQ(d.points[3].z, strtod_of("2e-12"));
  EXPECT_EQ(d.precision, Precision::kDouble);
  // The float reader merges the first two (both 1.0f): what the double path is for.
  const auto f = read_text("1 0 0\n1.000000000001 0 0\n", PointFormat::kXyz);
  EXPECT_EQ(f[0], f[1]);
}

TEST(DoubleText, DecimalsGoToTheNearestDouble) {
  const auto d = read_text_double("0.1 0.2 0.3\n", PointFormat::kXyz);
  EXPECT_EQ(d.points[0], (Point3d{strtod_of("0.1"), strtod_of("0.2"), strtod_of("0.3")}));
  EXPECT_EQ(d.points[0].x, 0.1);
  EXPECT_NE(d.points[0].x, static_cast<double>(0.1f));
  // Just above the float midpoint 1 + 2^-24: the nearest double is the midpoint itself, while the float
  // reader, parsing straight to float, still rounds up (no double rounding on the float path).
  const std::string above = "1.000000059604644775390625000000000000001";
  EXPECT_EQ(read_text_double(above + " 0 0\n", PointFormat::kXyz).points[0].x, 1.0 + 0x1p-24);
  EXPECT_EQ(read_text(above + " 0 0\n", PointFormat::kXyz)[0].x, std::nextafter(1.0f, 2.0f));
  EXPECT_NE(static_cast<float>(strtod_of(above)), std::nextafter(1.0f, 2.0f));  // the trap it avoids
}

TEST(DoubleText, EveryTextFormatGivesStrtodOfItsTokens) {
  const std::vector<std::array<std::string, 3>> rows = {
      {"0.1", "-0.30000000000000004", "+1e-7"},
      {"123456789.123456789", "1.7976931348623157e308", "-4.9e-324"},
      {"2.2250738585072014e-308", "1e39", "-0"},
      {"3.14159265358979323846264338327950288", ".5", "5."},
  };
  for (PointFormat format : {PointFormat::kXyz, PointFormat::kObj, PointFormat::kOff, PointFormat::kPly}) {
    SCOPED_TRACE(static_cast<int>(format));
    const auto d = read_text_double(as_text_format(rows, format), format);
    EXPECT_EQ(d.precision, Precision::kDouble);
    ASSERT_EQ(d.points.size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Point3d expected{strtod_of(rows[i][0]), strtod_of(rows[i][1]), strtod_of(rows[i][2])};
      EXPECT_EQ(d.points[i], expected) << "row " << i;
      EXPECT_EQ(std::signbit(d.points[i].z), std::signbit(expected.z)) << "row " << i;
    }
  }
}

TEST(DoubleText, RandomDecimalsMatchStrtodAndTheFloatPathMatchesStrtof) {
  // Long random decimals across the float range: the double reader must give strtod's double, and the float
  // reader strtof's float (decimal straight to float, whatever the double reader does).
  std::mt19937_64 rng(2024);
  std::vector<std::array<std::string, 3>> rows(20000);
  for (auto& r : rows) {
    for (auto& tok : r) {
      const int digits = 1 + static_cast<int>(rng() % 30);
      tok = (rng() % 3 == 0) ? "-" : "";
      for (int k = 0; k < digits; ++k) {
        tok += static_cast<char>('0' + rng() % 10);
        if (k == 0) tok += '.';
      }
      tok += "e" + std::to_string(static_cast<int>(rng() % 70) - 40);
    }
  }
  for (PointFormat format : {PointFormat::kXyz, PointFormat::kObj, PointFormat::kOff, PointFormat::kPly}) {
    SCOPED_TRACE(static_cast<int>(format));
    const std::string text = as_text_format(rows, format);
    const auto d = read_text_double(text, format);
    const auto f = read_text(text, format);
    ASSERT_EQ(d.points.size(), rows.size());
    ASSERT_EQ(f.size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Point3d ed{strtod_of(rows[i][0]), strtod_of(rows[i][1]), strtod_of(rows[i][2])};
      const Point3 ef{std::strtof(rows[i][0].c_str(), nullptr), std::strtof(rows[i][1].c_str(), nullptr),
                      std::strtof(rows[i][2].c_str(), nullptr)};
      ASSERT_EQ(d.points[i], ed) << rows[i][0] << " " << rows[i][1] << " " << rows[i][2];
      ASSERT_EQ(f[i], ef) << rows[i][0] << " " << rows[i][1] << " " << rows[i][2];
    }
  }
}

TEST(DoubleText, RangeIsDoubleRangeAndNonFiniteIsStillAnError) {
  // Beyond float range but inside double range: the float reader refuses it, the double reader keeps it.
  EXPECT_EQ(read_text_double("1e39 -1e300 0\n", PointFormat::kXyz).points[0], (Point3d{1e39, -1e300, 0}));
  EXPECT_THAT(read_error_text_double("0 1e309 0\n", PointFormat::kXyz),
              HasSubstr("mem:1: y coordinate '1e309' is beyond double range"));
  // Underflow as IEEE rounding says: a double denormal, or a signed zero.
  const auto u = read_text_double("1e-310 -1e-400 4.9e-324\n", PointFormat::kXyz).points[0];
  EXPECT_EQ(u.x, strtod_of("1e-310"));
  EXPECT_NE(u.x, 0.0);
  EXPECT_EQ(u.y, 0.0);
  EXPECT_TRUE(std::signbit(u.y));
  EXPECT_EQ(u.z, std::numeric_limits<double>::denorm_min());
  EXPECT_THAT(read_error_text_double("0 0 inf\n", PointFormat::kXyz),
              HasSubstr("mem:1: infinite z coordinate 'inf'"));
  EXPECT_THAT(read_error_text_double("v 0 nan 0\n", PointFormat::kObj), HasSubstr("mem:1: NaN y coordinate"));
  EXPECT_THAT(read_error_text_double("1 2 x\n", PointFormat::kXyz), HasSubstr("mem:1: invalid z coordinate"));
}

// Every malformed file fails the same way through the double reader, but for the range, which is double's.
TEST(DoubleMalformed, SameErrorsAsTheFloatReader) {
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(kData / "malformed")) {
    const std::string path = entry.path().string();
    SCOPED_TRACE(path);
    ++n;
    if (entry.path().filename() == "too_big.xyz") {
      const auto d = read_points_double(path);  // 1e39 is beyond float range only
      ASSERT_EQ(d.points.size(), 2u);
      EXPECT_EQ(d.points[1], (Point3d{1e39, 0, 0}));
      continue;
    }
    EXPECT_EQ(input_error([&] { read_points_double(path); }, "no InputError"), read_error(path));
  }
  EXPECT_EQ(n, 20u);
}

std::string enc_format(Enc enc) {
  return enc == Enc::kAscii ? "ascii" : enc == Enc::kLittle ? "binary_little_endian" : "binary_big_endian";
}

// A random double that float cannot hold (so that a reader going through float would be caught).
double random_non_float(std::mt19937_64& rng) {
  while (true) {
    const double v = std::uniform_real_distribution<double>(-1, 1)(rng) *
                     std::pow(10.0, static_cast<double>(static_cast<int>(rng() % 13) - 6));
    if (static_cast<double>(static_cast<float>(v)) != v) return v;
  }
}

TEST(DoublePly, BinaryDoublesAreKeptExactly) {
  const std::vector<std::vector<Column>> layouts = {
      {{"double", "x"}, {"double", "y"}, {"double", "z"}},  // the file's bytes are the points
      {{"float", "nx"}, {"float64", "x"}, {"double", "y"}, {"double", "z"}, {"uchar", "red"}},
      {{"double", "x"}, {"int", "tags", true}, {"double", "y"}, {"double", "z"}},  // record by record
  };
  std::mt19937_64 rng(99);
  TempDir dir;
  for (Enc enc : {Enc::kLittle, Enc::kBig}) {
    for (std::size_t l = 0; l < layouts.size(); ++l) {
      SCOPED_TRACE(enc_format(enc) + " layout " + std::to_string(l));
      std::vector<std::vector<double>> rows(300);
      std::vector<Point3d> expected;
      for (auto& row : rows) {
        Point3d p;
        for (const Column& c : layouts[l]) {
          if (c.list) continue;
          const double v = c.type == "uchar" ? 7.0 : random_non_float(rng);
          row.push_back(v);
          if (c.name == "x") p.x = v;
          if (c.name == "y") p.y = v;
          if (c.name == "z") p.z = v;
        }
        expected.push_back(p);
      }
      const fs::path path = dir / ("d" + std::to_string(l) + enc_format(enc) + ".ply");
      write_file(path, make_ply(enc, layouts[l], rows, l == 1, l != 0));
      const auto d = read_points_double(path.string());
      EXPECT_EQ(d.precision, Precision::kDouble);
      EXPECT_EQ(auto_precision(path.string()), Precision::kDouble);
      ASSERT_EQ(d.points, expected);
      // The float reader still rounds each double once.
      const auto f = read_points(path.string());
      ASSERT_EQ(f.size(), expected.size());
      for (std::size_t i = 0; i < f.size(); ++i) {
        const Point3d& e = expected[i];
        ASSERT_EQ(f[i], (Point3{static_cast<float>(e.x), static_cast<float>(e.y), static_cast<float>(e.z)}));
      }
    }
  }
}

TEST(DoublePly, BinaryFloatFileReportsFloatAndKeepsTheFloats) {
  std::mt19937_64 rng(5);
  TempDir dir;
  for (Enc enc : {Enc::kLittle, Enc::kBig}) {
    SCOPED_TRACE(enc_format(enc));
    std::vector<std::vector<double>> rows(300);
    std::vector<Point3d> expected;
    for (auto& row : rows) {
      for (int a = 0; a < 3; ++a)
        row.push_back(static_cast<float>(random_non_float(rng)));
      expected.push_back({row[0], row[1], row[2]});
    }
    const fs::path path = dir / ("f_" + enc_format(enc) + ".ply");
    write_file(path, make_ply(enc, {{"float", "x"}, {"float", "y"}, {"float", "z"}}, rows, false, true));
    const auto d = read_points_double(path.string());
    EXPECT_EQ(d.precision, Precision::kFloat);
    EXPECT_EQ(auto_precision(path.string()), Precision::kFloat);
    ASSERT_EQ(d.points, expected);
  }
}

TEST(DoublePly, AutoPrecisionFollowsTheCoordinateTypes) {
  struct Case {
    Enc enc;
    std::vector<Column> cols;
    Precision expected;
  };
  const std::vector<Case> cases = {
      {Enc::kLittle, {{"float", "x"}, {"float32", "y"}, {"float", "z"}}, Precision::kFloat},
      {Enc::kBig, {{"uchar", "x"}, {"short", "y"}, {"float", "z"}}, Precision::kFloat},
      {Enc::kLittle, {{"char", "x"}, {"ushort", "y"}, {"int16", "z"}}, Precision::kFloat},
      // Only x, y, z decide: a double normal does not make a float file double.
      {Enc::kLittle, {{"float", "x"}, {"float", "y"}, {"float", "z"}, {"double", "nx"}}, Precision::kFloat},
      {Enc::kBig, {{"float", "x"}, {"float", "y"}, {"double", "z"}}, Precision::kDouble},
      {Enc::kLittle, {{"int", "x"}, {"float", "y"}, {"float", "z"}}, Precision::kDouble},
      {Enc::kLittle, {{"float", "x"}, {"uint32", "y"}, {"float", "z"}}, Precision::kDouble},
      // Ascii holds decimals, whatever type the header names.
      {Enc::kAscii, {{"float", "x"}, {"float", "y"}, {"float", "z"}}, Precision::kDouble},
      {Enc::kAscii, {{"uchar", "x"}, {"uchar", "y"}, {"uchar", "z"}}, Precision::kDouble},
  };
  TempDir dir;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    std::string types;
    for (const Column& col : c.cols)
      types += col.type + " ";
    SCOPED_TRACE(enc_format(c.enc) + ": " + types);
    std::vector<std::vector<double>> rows = {std::vector<double>(c.cols.size(), 1.0),
                                             std::vector<double>(c.cols.size(), 2.0)};
    const fs::path path = dir / ("p" + std::to_string(i) + ".ply");
    write_file(path, make_ply(c.enc, c.cols, rows, false, false));
    EXPECT_EQ(read_points_double(path.string()).precision, c.expected);
    EXPECT_EQ(auto_precision(path.string()), c.expected);
  }
  // A 32-bit integer float cannot hold is kept exactly.
  std::string ply =
      binary_header("binary_little_endian", 1, "property int x\nproperty uint y\nproperty int z\n");
  put_binary(ply, "int", 16777217, Enc::kLittle);
  put_binary(ply, "uint", 4294967295.0, Enc::kLittle);
  put_binary(ply, "int", -2147483647, Enc::kLittle);
  write_file(dir / "ints.ply", ply);
  EXPECT_EQ(read_points_double((dir / "ints.ply").string()).points[0],
            (Point3d{16777217, 4294967295.0, -2147483647}));
}

TEST(DoublePly, LargeDoubleFileCrossesChunks) {
  std::mt19937_64 rng(11);
  std::vector<Point3d> expected(400'000);  // 9.6 MB, more than one 8 MiB read chunk
  for (auto& p : expected)
    p = {random_non_float(rng), random_non_float(rng), random_non_float(rng)};
  TempDir dir;
  for (Enc enc : {Enc::kLittle, Enc::kBig}) {
    SCOPED_TRACE(enc_format(enc));
    std::string body;
    for (const auto& p : expected) {
      for (double v : {p.x, p.y, p.z})
        put_binary(body, "double", v, enc);
    }
    const std::string header = binary_header(enc_format(enc).c_str(), expected.size(),
                                             "property double x\nproperty double y\nproperty double z\n");
    write_file(dir / "big.ply", header + body);
    std::vector<double> fractions;
    const auto d = read_points_double((dir / "big.ply").string(), [&](double f) { fractions.push_back(f); });
    ASSERT_EQ(d.points, expected);
    ASSERT_GE(fractions.size(), 2u);
    EXPECT_EQ(fractions.back(), 1.0);
  }
}

TEST(DoublePly, BinaryRangeIsDoubleRange) {
  std::string ply =
      binary_header("binary_little_endian", 2, "property double x\nproperty double y\nproperty double z\n");
  for (double v : {1e300, -1e-320, 0.0, 1.0, std::numeric_limits<double>::quiet_NaN(), 2.0})
    put_binary(ply, "double", v, Enc::kLittle);
  TempDir dir;
  write_file(dir / "r.ply", ply);
  EXPECT_THAT(read_error((dir / "r.ply").string()),
              HasSubstr(": vertex 0: x coordinate is beyond float range"));
  EXPECT_THAT(input_error([&] { read_points_double((dir / "r.ply").string()); }, "no InputError"),
              HasSubstr(": vertex 1: NaN y coordinate"));
}

TEST(AutoPrecision, FromTheFormatAndThePlyHeaderAlone) {
  TempDir dir;
  for (const char* name : {"a.xyz", "a.txt", "a.obj", "a.off"}) {
    write_file(dir / name, "not even read");
    EXPECT_EQ(auto_precision((dir / name).string()), Precision::kDouble) << name;
  }
  EXPECT_EQ(auto_precision("-"), Precision::kDouble);
  // No vertex is read: a header without its data is enough.
  write_file(dir / "h.ply", binary_header("binary_big_endian", 1000, kXyzFloat));
  EXPECT_EQ(auto_precision((dir / "h.ply").string()), Precision::kFloat);
  std::istringstream in(
      binary_header("binary_little_endian", 5, "property double x\n" + kXyzFloat.substr(17)));
  EXPECT_EQ(auto_precision(in, PointFormat::kPly, "mem"), Precision::kDouble);
  // The errors are the readers'.
  EXPECT_THROW(auto_precision((dir / "missing.ply").string()), InputError);
  EXPECT_THROW(auto_precision((dir / "a.stl").string()), InputError);
  write_file(dir / "nov.ply",
             "ply\nformat binary_little_endian 1.0\nelement face 0\nproperty float x\nend_header\n");
  EXPECT_THAT(read_error((dir / "nov.ply").string()), HasSubstr("no 'vertex' element"));
  EXPECT_THROW(auto_precision((dir / "nov.ply").string()), InputError);
  write_file(dir / "noz.ply",
             binary_header("binary_little_endian", 1, "property float x\nproperty float y\n"));
  EXPECT_THROW(auto_precision((dir / "noz.ply").string()), InputError);
  EXPECT_THROW(auto_precision((kData / "malformed" / "bad_magic.ply").string()), InputError);
}

TEST(AutoPrecision, Names) {
  EXPECT_STREQ(precision_name(Precision::kAuto), "auto");
  EXPECT_STREQ(precision_name(Precision::kFloat), "float");
  EXPECT_STREQ(precision_name(Precision::kDouble), "double");
}

TEST(Stdin, DashReadsDoublesFromStandardInput) {
  expect_stdin_read("0.1 2 3\n1.000000000001 5 6\n", [] {
    const auto d = read_points_double("-");
    const std::vector<Point3d> expected = {{0.1, 2, 3}, {strtod_of("1.000000000001"), 5, 6}};
    return d.points == expected && d.precision == Precision::kDouble;
  });
}

}  // namespace
}  // namespace cudahull
