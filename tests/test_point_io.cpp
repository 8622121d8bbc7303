// Point readers: the shared models, PLY round trips over every property type and byte order, the text
// formats' variants, standard input and progress.  One InputError per kind of malformed input:
// test_point_io_malformed.cpp; the full-precision reader: test_point_io_double.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cudahull/point_io.hpp"
#include "support/ply_writer.hpp"
#include "support/point_reads.hpp"
#include "support/temp_dir.hpp"

namespace cudahull {
namespace {

const fs::path kModels = CUDAHULL_MODELS_DIR;

using ::testing::HasSubstr;

// ------------------------------------------------------------------------------------------ shared models

struct ModelCase {
  const char* file;
  std::size_t count;
  Point3 first, last;  // read by hand from the files
};

class SharedModels : public ::testing::TestWithParam<ModelCase> {};

TEST_P(SharedModels, ReadsReadmeCountAndCoordinates) {
  if (!fs::is_directory(kModels)) GTEST_SKIP() << "shared models folder absent: " << kModels;
  const ModelCase& c = GetParam();
  const auto points = read_points((kModels / c.file).string());
  ASSERT_EQ(points.size(), c.count);
  EXPECT_EQ(points.front(), c.first);
  EXPECT_EQ(points.back(), c.last);
}

TEST_P(SharedModels, DoubleReaderAgreesWithTheFloatReader) {
  if (!fs::is_directory(kModels)) GTEST_SKIP() << "shared models folder absent: " << kModels;
  const std::string path = (kModels / GetParam().file).string();
  const auto f = read_points(path);
  const auto d = cudahull::read_points_double(path);
  ASSERT_EQ(d.points.size(), f.size());
  // Only dragon_scans.ply is binary (float); the others are text.
  const bool binary_float = std::string(GetParam().file) == "dragon_scans.ply";
  EXPECT_EQ(d.precision, binary_float ? cudahull::Precision::kFloat : cudahull::Precision::kDouble);
  // Binary floats are kept exactly; these files' short decimals round to the same float either way.
  for (std::size_t i = 0; i < f.size(); ++i) {
    const auto& p = d.points[i];
    ASSERT_EQ(f[i], (Point3{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)}))
        << "vertex " << i;
    if (binary_float) {
      ASSERT_EQ(p, (cudahull::Point3d{f[i].x, f[i].y, f[i].z})) << "vertex " << i;
    }
  }
}

const ModelCase kModelCases[] = {
    {"bun_zipper.ply", 35947, {-0.0378297f, 0.12794f, 0.00447467f}, {-0.0400442f, 0.15362f, -0.00816685f}},
    {"stanford-bunny.obj", 35947, {-0.037830f, 0.127940f, 0.004475f}, {-0.040044f, 0.153620f, -0.008167f}},
    {"dragonStandRight_0.ply",
     41841,
     {-0.0570643f, 0.0534662f, 0.0326335f},
     {-0.0330614f, 0.197932f, -0.0201442f}},
    // Binary: %.9g of the stored floats, which reads back as the same floats.
    {"dragon_scans.ply",
     469193,
     {-0.0574304536f, 0.0534693226f, 0.0317070112f},
     {-0.0359619223f, 0.197838485f, 0.00969995931f}},
    {"teapot.obj", 3644, {-3.0f, 1.8f, 0.0f}, {3.434f, 2.4729f, 0.0f}},
    {"spot.obj", 2930, {0.348799f, -0.334989f, -0.0832331f}, {-0.0137291f, -0.0795664f, 1.04692f}}};

INSTANTIATE_TEST_SUITE_P(Models, SharedModels, ::testing::ValuesIn(kModelCases),
                         [](const auto& info) { return test_name(info.param.file); });

// ------------------------------------------------------------------------------------------ PLY round trips

// A value that type `type` holds exactly (and, for ascii, that %.17g reproduces).
double random_value(const std::string& type, std::mt19937_64& rng, bool ascii) {
  const std::string t = canonical_type(type);
  auto in = [&](double lo, double hi) {
    return std::floor(std::uniform_real_distribution<double>(lo, hi + 1)(rng));
  };
  if (t == "char") return in(-128, 127);
  if (t == "uchar") return in(0, 255);
  if (t == "short") return in(-32768, 32767);
  if (t == "ushort") return in(0, 65535);
  if (t == "int") return in(-2147483648.0, 2147483647.0);
  if (t == "uint") return in(0, 4294967295.0);
  const double mag = std::pow(10.0, in(-6, 6));
  const double v = std::uniform_real_distribution<double>(-1, 1)(rng) * mag;
  // Doubles in ascii are written from float values: decimal -> float and double -> float must agree.
  return (t == "float" || ascii) ? static_cast<double>(static_cast<float>(v)) : v;
}

struct RoundTripCase {
  Enc enc;
  std::vector<Column> cols;
  bool element_before;
  bool faces;
};

class PlyRoundTrip : public ::testing::TestWithParam<RoundTripCase> {};

TEST_P(PlyRoundTrip, ReadsBackExactly) {
  const RoundTripCase& c = GetParam();
  std::mt19937_64 rng(12345);
  std::vector<std::vector<double>> rows(500);
  std::vector<Point3> expected;
  for (auto& row : rows) {
    Point3 p;
    for (const Column& col : c.cols) {
      if (col.list) continue;
      const double v = random_value(col.type, rng, c.enc == Enc::kAscii);
      row.push_back(v);
      // The reader rounds each value to float once.
      if (col.name == "x") p.x = static_cast<float>(v);
      if (col.name == "y") p.y = static_cast<float>(v);
      if (col.name == "z") p.z = static_cast<float>(v);
    }
    expected.push_back(p);
  }
  TempDir dir;
  const fs::path path = dir / "round.ply";
  write_file(path, make_ply(c.enc, c.cols, rows, c.element_before, c.faces));
  const auto points = read_points(path.string());
  ASSERT_EQ(points.size(), expected.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    ASSERT_EQ(points[i], expected[i]) << "vertex " << i;
}

std::vector<RoundTripCase> round_trip_cases() {
  const std::vector<std::vector<Column>> layouts = {
      {{"float", "x"}, {"float", "y"}, {"float", "z"}},
      {{"double", "x"}, {"double", "y"}, {"double", "z"}},
      {{"uchar", "z"}, {"short", "y"}, {"int", "x"}, {"float", "confidence"}},
      {{"char", "x"}, {"ushort", "y"}, {"uint", "z"}, {"uchar", "red"}, {"double", "nx"}},
      {{"float32", "nx"}, {"float64", "x"}, {"int16", "y"}, {"uint8", "alpha"}, {"int32", "z"}},
      {{"float", "x"}, {"int", "tags", true}, {"double", "y"}, {"float", "z"}},  // a list inside the vertex
  };
  std::vector<RoundTripCase> cases;
  for (Enc enc : {Enc::kAscii, Enc::kLittle, Enc::kBig}) {
    for (std::size_t i = 0; i < layouts.size(); ++i) {
      cases.push_back({enc, layouts[i], i % 2 == 1, i != 1});
    }
  }
  return cases;
}

std::string round_trip_name(const ::testing::TestParamInfo<RoundTripCase>& info) {
  static const char* const kEnc[] = {"ascii", "le", "be"};
  return std::string(kEnc[static_cast<int>(info.param.enc)]) + "_" + std::to_string(info.index);
}

INSTANTIATE_TEST_SUITE_P(Layouts, PlyRoundTrip, ::testing::ValuesIn(round_trip_cases()), round_trip_name);

TEST(PlyBinary, LargeFloatFileReadsEveryPoint) {
  // More than one read chunk (8 MiB), so the chunk boundaries are crossed.
  std::mt19937_64 rng(7);
  std::vector<Point3> expected(1'500'000);
  std::string body;
  for (auto& p : expected) {
    p = {static_cast<float>(rng() % 100000) / 7.0f, -static_cast<float>(rng() % 1000),
         1.0f / float(1 + rng() % 9)};
    for (float v : {p.x, p.y, p.z})
      put_binary(body, "float", v, Enc::kLittle);
  }
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                             std::to_string(expected.size()) +
                             "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  TempDir dir;
  write_file(dir / "big.ply", header + body);
  std::vector<double> fractions;
  const auto points = read_points((dir / "big.ply").string(), [&](double f) { fractions.push_back(f); });
  ASSERT_EQ(points, expected);
  ASSERT_GE(fractions.size(), 2u);
  EXPECT_LT(fractions.size(), 1000u) << "progress must not be reported per point";
  EXPECT_EQ(fractions.back(), 1.0);
  for (std::size_t i = 1; i < fractions.size(); ++i)
    EXPECT_GE(fractions[i], fractions[i - 1]);
}

// ------------------------------------------------------------------------------------------ valid text files

TEST(ValidFiles, XyzCommentsBlankLinesCrlfExtraColumns) {
  const auto p = read_points((kData / "valid" / "comments.xyz").string());
  const std::vector<Point3> expected = {{1, 2, 3}, {-4.5f, 5.25f, 0.6f}, {7, 8, 9}, {0, -0.0f, 1.5f}};
  EXPECT_EQ(p, expected);
}

TEST(ValidFiles, OffVariants) {
  const std::vector<Point3> coff = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_EQ(read_points((kData / "valid" / "coff.off").string()), coff);
  const std::vector<Point3> inline_counts = {{0.5f, 0.25f, 0.125f}, {-1, -2, -3}, {10, 20, 30}};
  EXPECT_EQ(read_points((kData / "valid" / "inline_counts.off").string()), inline_counts);
  EXPECT_EQ(read_text("NOFF\n1 0 0\n1 2 3 0 0 1\n", PointFormat::kOff), (std::vector<Point3>{{1, 2, 3}}));
  EXPECT_EQ(read_text("STCOFF\n1 0\n1 2 3\n", PointFormat::kOff), (std::vector<Point3>{{1, 2, 3}}));
}

TEST(ValidFiles, StanfordRangeScanHeader) {
  const std::vector<Point3> expected = {{-0.0570643f, 0.0534662f, 0.0326335f}, {1, 2, 3}, {4, 5, 6}};
  EXPECT_EQ(read_points((kData / "valid" / "stanford_scan.ply").string()), expected);
}

TEST(ValidFiles, AsciiPlyElementBeforeVertexAndMixedTypes) {
  const std::vector<Point3> expected = {{100000, -7, 0.1f}, {-5, 32767, -2.5f}};
  EXPECT_EQ(read_points((kData / "valid" / "element_before_vertex.ply").string()), expected);
}

TEST(ValidFiles, ObjIgnoresEverythingButVertices) {
  const std::vector<Point3> expected = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  EXPECT_EQ(read_points((kData / "valid" / "mixed.obj").string()), expected);
}

TEST(Numbers, RoundedOnceToFloat) {
  // Decimal straight to float: 0.1 must be the float nearest 0.1, and a decimal just above a float
  // midpoint must round up even though its nearest double is the midpoint itself.
  EXPECT_EQ(read_text("0.1 0.2 0.3\n", PointFormat::kXyz)[0], (Point3{0.1f, 0.2f, 0.3f}));
  // 1 + 2^-24 (the midpoint between 1 and its float successor) plus 1e-30: rounds up to 1 + 2^-23.
  const auto p = read_text("1.000000059604644775390625000000000000001 0 0\n", PointFormat::kXyz);
  EXPECT_EQ(p[0].x, std::nextafter(1.0f, 2.0f));
}

TEST(Numbers, UnderflowIsAcceptedOverflowIsNot) {
  const auto p = read_text("1e-50 -1e-50 1e-40\n", PointFormat::kXyz);
  EXPECT_EQ(p[0].x, 0.0f);
  EXPECT_EQ(p[0].y, 0.0f);
  EXPECT_TRUE(std::signbit(p[0].y));
  EXPECT_EQ(p[0].z, 1e-40f);  // a float denormal
  // The largest decimal that still rounds to FLT_MAX, and the first that rounds to infinity.
  EXPECT_EQ(read_text("3.4028235e38 -3.4028235e38 0\n", PointFormat::kXyz)[0].x,
            std::numeric_limits<float>::max());
  EXPECT_THAT(read_error_text("3.4028236e38 0 0\n", PointFormat::kXyz), HasSubstr("beyond float range"));
  EXPECT_THAT(read_error_text("0 -1e39 0\n", PointFormat::kXyz),
              HasSubstr("mem:1: y coordinate '-1e39' is beyond float range"));
}

TEST(Numbers, SignsAndRejectedForms) {
  EXPECT_EQ(read_text("+1 -2 +.5\n", PointFormat::kXyz)[0], (Point3{1, -2, 0.5f}));
  for (const char* bad : {"0x10 0 0\n", "1,5 0 0\n", "1.2.3 0 0\n", "++1 0 0\n", "- 0 0\n", "1e 0 0\n"}) {
    EXPECT_THAT(read_error_text(bad, PointFormat::kXyz), HasSubstr("mem:1: invalid x coordinate")) << bad;
  }
  EXPECT_THAT(read_error_text("0 0 inf\n", PointFormat::kXyz),
              HasSubstr("mem:1: infinite z coordinate 'inf'"));
  EXPECT_THAT(read_error_text("0 -nan 0\n", PointFormat::kXyz), HasSubstr("mem:1: NaN y coordinate"));
}

TEST(Stdin, DashReadsXyzFromStandardInput) {
  expect_stdin_read("1 2 3\n# c\n4 5 6\n", [] {
    const auto p = read_points("-");
    const std::vector<Point3> expected = {{1, 2, 3}, {4, 5, 6}};
    return p == expected;
  });
}

TEST(Progress, TextReaderReportsOccasionallyAndEndsAtOne) {
  std::string text;
  for (int i = 0; i < 300000; ++i)
    text += std::to_string(i) + " 1 2\n";
  std::istringstream in(text);
  std::vector<double> f;
  const auto p = read_points(in, PointFormat::kXyz, "mem", [&](double x) { f.push_back(x); });
  EXPECT_EQ(p.size(), 300000u);
  EXPECT_EQ(p.back(), (Point3{299999, 1, 2}));
  ASSERT_GE(f.size(), 3u);
  EXPECT_LT(f.size(), 100u);
  EXPECT_EQ(f.front(), 0.0);
  EXPECT_EQ(f.back(), 1.0);
  for (std::size_t i = 1; i < f.size(); ++i)
    EXPECT_GE(f[i], f[i - 1]);
}

}  // namespace
}  // namespace cudahull
