// Point readers: the shared models, PLY round trips over every property type and byte order, the text
// formats' variants, and one InputError per kind of malformed input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"
#include "support/temp_dir.hpp"

namespace cudahull {
namespace {

namespace fs = std::filesystem;
const fs::path kModels = CUDAHULL_MODELS_DIR;
const fs::path kData = CUDAHULL_TEST_DATA_DIR;

using ::testing::HasSubstr;
using ::testing::StartsWith;
using testing::TempDir;

void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

// The message of the InputError that `read()` throws ("" and the test failure `failure` if none is thrown).
template <class Read>
std::string input_error(Read read, const std::string& failure) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << failure;
  return "";
}

// The message of the InputError that reading `path` throws.
std::string read_error(const std::string& path) {
  return input_error([&] { read_points(path); }, path + ": no InputError");
}

std::string read_error_text(const std::string& text, PointFormat format) {
  std::istringstream in(text);
  return input_error([&] { read_points(in, format, "mem"); }, "no InputError for:\n" + text);
}

// A gtest name from a file name.
std::string test_name(std::string name) {
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

std::vector<Point3> read_text(const std::string& text, PointFormat format) {
  std::istringstream in(text);
  return read_points(in, format, "mem");
}

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

enum class Enc { kAscii, kLittle, kBig };

struct Column {
  std::string type;  // PLY type name
  std::string name;
  bool list = false;  // "property list uchar <type> <name>"
};

// The short PLY name of a type ("int16" -> "short").
std::string canonical_type(const std::string& t) {
  static const char* const kPairs[][2] = {{"int8", "char"},     {"uint8", "uchar"},   {"int16", "short"},
                                          {"uint16", "ushort"}, {"int32", "int"},     {"uint32", "uint"},
                                          {"float32", "float"}, {"float64", "double"}};
  for (const auto& p : kPairs) {
    if (t == p[0]) return p[1];
  }
  return t;
}

std::size_t ply_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;
}

// Appends `v`, cast to PLY type `t`, in the given byte order.
void put_binary(std::string& out, const std::string& t, double v, Enc enc) {
  unsigned char b[8];
  std::uint64_t bits = 0;
  const std::size_t n = ply_size(t);
  if (t == "char" || t == "int8") bits = static_cast<std::uint8_t>(static_cast<std::int8_t>(v));
  if (t == "uchar" || t == "uint8") bits = static_cast<std::uint8_t>(v);
  if (t == "short" || t == "int16") bits = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
  if (t == "ushort" || t == "uint16") bits = static_cast<std::uint16_t>(v);
  if (t == "int" || t == "int32") bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(v));
  if (t == "uint" || t == "uint32") bits = static_cast<std::uint32_t>(v);
  if (t == "float" || t == "float32") bits = std::bit_cast<std::uint32_t>(static_cast<float>(v));
  if (t == "double" || t == "float64") bits = std::bit_cast<std::uint64_t>(v);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t shift = 8 * (enc == Enc::kBig ? n - 1 - i : i);
    b[i] = static_cast<unsigned char>(bits >> shift);
  }
  out.append(reinterpret_cast<const char*>(b), n);
}

void put_ascii(std::string& out, const std::string& type, double v) {
  const std::string t = canonical_type(type);
  char buf[40];
  const bool real = t == "float" || t == "float32" || t == "double" || t == "float64";
  std::snprintf(buf, sizeof buf, real ? "%.17g " : "%.0f ", v);
  out += buf;
}

// A PLY writer for the tests: `rows` holds one value per scalar column; a list column gets `i % 3` items.
// An optional element before the vertices and a face element after them exercise the skipping.
std::string make_ply(Enc enc, const std::vector<Column>& cols, const std::vector<std::vector<double>>& rows,
                     bool element_before, bool faces) {
  std::string h = "ply\nformat ";
  h += enc == Enc::kAscii ? "ascii" : enc == Enc::kLittle ? "binary_little_endian" : "binary_big_endian";
  h += " 1.0\ncomment test file\nobj_info from the test\n";
  if (element_before) h += "element camera 2\nproperty double a\nproperty list int short b\n";
  h += "element vertex " + std::to_string(rows.size()) + "\n";
  for (const Column& c : cols) {
    h += c.list ? "property list uchar " + c.type + " " + c.name + "\n"
                : "property " + c.type + " " + c.name + "\n";
  }
  if (faces) h += "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\n";
  h += "end_header\n";
  std::string body;
  const bool ascii = enc == Enc::kAscii;
  auto put = [&](const std::string& t, double v) {
    ascii ? put_ascii(body, t, v) : put_binary(body, t, v, enc);
  };
  if (element_before) {
    for (int i = 0; i < 2; ++i) {
      put("double", 0.5 + i);
      put("int", i + 1);
      for (int k = 0; k <= i; ++k)
        put("short", -k);
      if (ascii) body += "\n";
    }
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::size_t s = 0;
    for (const Column& c : cols) {
      if (c.list) {
        put("uchar", double(i % 3));
        for (std::size_t k = 0; k < i % 3; ++k)
          put(c.type, double(k + 1));
      } else {
        put(c.type, rows[i][s++]);
      }
    }
    if (ascii) body += "\n";
  }
  if (faces) {
    for (int f = 0; f < 2; ++f) {
      put("uchar", 3);
      for (int k = 0; k < 3; ++k)
        put("int", k);
      put("uchar", 1);
      if (ascii) body += "\n";
    }
  }
  return h + body;
}

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

std::string binary_header(const char* format, std::uint64_t count, const std::string& props) {
  return std::string("ply\nformat ") + format + " 1.0\nelement vertex " + std::to_string(count) + "\n" +
         props + "end_header\n";
}

const std::string kXyzFloat = "property float x\nproperty float y\nproperty float z\n";

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

// `read_dash()` (a read of "-") with standard input from a file holding `text`, in a child process (so that
// this process's standard input is left alone): the child must exit 0, which it does when `read_dash()`
// returns true.
template <class ReadDash>
void expect_stdin_read(const std::string& text, ReadDash read_dash) {
  TempDir dir;
  write_file(dir / "in.xyz", text);
  const std::string path = (dir / "in.xyz").string();
  const auto child = [&] {
    if (std::freopen(path.c_str(), "r", stdin) == nullptr) std::_Exit(2);
    std::_Exit(read_dash() ? 0 : 1);
  };
  EXPECT_EXIT(child(), ::testing::ExitedWithCode(0), "");
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
