// `cudahull hull --precision` and `bench --precision` end to end: text input exact in double and written back
// bit for bit, points equal in float two vertices in double, doubles outside the fast exact range computed
// exactly, auto following the input, and a bad value a usage error; against a brute force on the coordinates
// as given.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/point_writer.hpp"
#include "cudahull/predicates.hpp"
#include "qhull_reference.hpp"
#include "support/cli_hull_run.hpp"
#include "support/cli_runner.hpp"

namespace cudahull {
namespace {

using ::testing::HasSubstr;

// ------------------------------------------------------------------------------------------ --precision

// The strictly extreme points of a small set by brute force, on the coordinates as given (orient3d is exact
// on floats and doubles alike): point i is a vertex iff some three other points span a plane that has every
// other point on one closed side and point i strictly on the other.  Among equal points only the lowest index
// can be a vertex.  For sets that are not planar, up to a few dozen points.
template <class Point>
std::vector<PointIndex> brute_force_vertices(const std::vector<Point>& points) {
  std::vector<PointIndex> vertices;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::vector<Vec3d> others;  // a copy of points[i] with a higher index is not a rival
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (j != i && (points[j] != points[i] || j < i)) others.push_back(to_vec3d(points[j]));
    }
    const Vec3d p = to_vec3d(points[i]);
    bool extreme = false;
    for (std::size_t a = 0; a < others.size() && !extreme; ++a) {
      for (std::size_t b = a + 1; b < others.size() && !extreme; ++b) {
        for (std::size_t c = b + 1; c < others.size() && !extreme; ++c) {
          const Vec3d &u = others[a], &v = others[b], &w = others[c];
          if (collinear3d(u, v, w)) continue;
          const int side = orient3d(u, v, w, p);
          if (side == 0) continue;
          extreme = std::none_of(others.begin(), others.end(),
                                 [&](const Vec3d& q) { return orient3d(u, v, w, q) == side; });
        }
      }
    }
    if (extreme) vertices.push_back(static_cast<PointIndex>(i));
  }
  return vertices;
}

std::vector<Point3> to_float(const std::vector<Point3d>& points) {
  std::vector<Point3> out;
  for (const Point3d& p : points)
    out.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  return out;
}

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// An .xyz file of `points` with 17 significant digits: read as doubles, exactly these values.
void write_xyz17(const fs::path& path, const std::vector<Point3d>& points) {
  std::ofstream out(path);
  char line[96];
  for (const Point3d& p : points) {
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    out << line;
  }
}

// A --vertices-out file parsed with strtod, each "index x y z" line as written.
std::vector<std::pair<PointIndex, Point3d>> read_vertices_double(const fs::path& path) {
  std::vector<std::pair<PointIndex, Point3d>> out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string id, x, y, z, rest;
    EXPECT_TRUE(ls >> id >> x >> y >> z) << line;
    EXPECT_FALSE(ls >> rest) << line;
    out.push_back({static_cast<PointIndex>(std::stoul(id)),
                   {std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr),
                    std::strtod(z.c_str(), nullptr)}});
  }
  return out;
}

// The unit cube [1, 2]^3's 8 corners, after 5 points per face 1e-12 outside it on a strictly concave cap
// through the face's corners (the face centre 1e-12 out, four points at a quarter 0.875e-12 out): every point
// strictly extreme in double.  Rounded to float, every cap point lies on its face (1 - 1e-12 and 2 + 1e-12
// are 1 and 2 in float) and only the corners remain.
std::vector<Point3d> bumped_cube() {
  std::vector<Point3d> points;
  const double uv[5][2] = {{1.5, 1.5}, {1.25, 1.5}, {1.75, 1.5}, {1.5, 1.25}, {1.5, 1.75}};
  for (int axis = 0; axis < 3; ++axis) {
    for (const double face : {1.0, 2.0}) {
      for (const auto& [u, v] : uv) {
        const double out = 2e-12 * (0.5 - ((u - 1.5) * (u - 1.5) + (v - 1.5) * (v - 1.5)));
        double c[3];
        c[axis] = face == 2.0 ? 2 + out : 1 - out;
        c[(axis + 1) % 3] = u;
        c[(axis + 2) % 3] = v;
        points.push_back({c[0], c[1], c[2]});
      }
    }
  }
  for (const double x : {1.0, 2.0})
    for (const double y : {1.0, 2.0})
      for (const double z : {1.0, 2.0})
        points.push_back({x, y, z});
  return points;
}

struct DoubleHullRun {
  CliRun run;
  nlohmann::json stats;
  std::vector<std::pair<PointIndex, Point3d>> vertices;  // --vertices-out, parsed with strtod
  std::vector<PointIndex> ids() const {
    std::vector<PointIndex> out;
    for (const auto& v : vertices)
      out.push_back(v.first);
    return out;
  }
};

// `cudahull hull INPUT --verify --vertices-out V --stats -` with `extra` arguments.
DoubleHullRun hull_of_file(const fs::path& input, const std::vector<std::string>& extra = {}) {
  TempDir dir;
  const fs::path vertices = dir / "v.txt";
  std::vector<std::string> args{
      "hull", input.string(), "--verify", "--vertices-out", vertices.string(), "--stats",
      "-",    "--backend",    "cpu"};
  args.insert(args.end(), extra.begin(), extra.end());
  DoubleHullRun r;
  r.run = run_cli(args);
  EXPECT_EQ(r.run.exit_code, kExitOk) << describe(r.run);
  r.stats = nlohmann::json::parse(r.run.out, nullptr, /*allow_exceptions=*/false);
  EXPECT_TRUE(r.stats.is_object()) << r.run.out;
  r.vertices = read_vertices_double(vertices);
  return r;
}

// (a) Points 1e-12 outside a cube's faces, in a text file: auto is double, and the hull's vertices are
// exactly the brute force's (every point); in float only the corners.  (b) The vertex coordinates written
// read back with strtod as the input doubles bit for bit, in --vertices-out and in every -o format.
TEST(CliPrecision, TextInputIsExactInDoubleAndRoundTrips) {
  TempDir dir;
  const std::vector<Point3d> points = bumped_cube();
  const fs::path input = dir / "bumped.xyz";
  write_xyz17(input, points);

  const std::vector<PointIndex> in_double = brute_force_vertices(points);
  ASSERT_EQ(in_double.size(), points.size()) << "the construction: every point strictly extreme";
  const std::vector<PointIndex> in_float = brute_force_vertices(to_float(points));
  ASSERT_EQ(in_float, (std::vector<PointIndex>{30, 31, 32, 33, 34, 35, 36, 37})) << "only the corners";

  const DoubleHullRun d = hull_of_file(input);
  EXPECT_EQ(d.stats.value("precision", ""), "double");
  EXPECT_EQ(d.stats.value("verified", false), true);
  EXPECT_EQ(d.ids(), in_double);
  for (const auto& [id, p] : d.vertices) {
    ASSERT_LT(id, points.size());
    for (int axis = 0; axis < 3; ++axis) {
      const double written = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
      const double given = axis == 0 ? points[id].x : axis == 1 ? points[id].y : points[id].z;
      EXPECT_EQ(bits(written), bits(given)) << "vertex " << id << " axis " << axis;
    }
  }
  EXPECT_EQ(d.stats.value("precision", ""), "double");
  EXPECT_THAT(d.run.err, HasSubstr("(double) -> 38 vertices"));

  const DoubleHullRun f = hull_of_file(input, {"--precision", "float"});
  EXPECT_EQ(f.stats.value("precision", ""), "float");
  EXPECT_EQ(f.stats.value("verified", false), true);
  EXPECT_EQ(f.ids(), in_float);
  const DoubleHullRun forced = hull_of_file(input, {"--precision", "double"});
  EXPECT_EQ(forced.ids(), in_double);

  // -o in each format: the hull's vertices, every coordinate bit for bit (PLY declares them double).
  std::vector<Point3d> expected;
  for (PointIndex id : in_double)
    expected.push_back(points[id]);
  auto key = [](const Point3d& p) { return std::make_tuple(bits(p.x), bits(p.y), bits(p.z)); };
  std::sort(expected.begin(), expected.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  for (const char* ext : {".obj", ".off", ".ply"}) {
    SCOPED_TRACE(ext);
    const fs::path out = dir / (std::string("hull") + ext);
    const CliRun r = run_cli({"hull", input.string(), "--backend", "cpu", "-q", "-o", out.string()});
    ASSERT_EQ(r.exit_code, kExitOk) << describe(r);
    std::vector<Point3d> written;
    std::istringstream text(slurp(out));
    std::size_t count = 0;
    bool in_body = std::string(ext) == ".obj";
    for (std::string line; std::getline(text, line);) {
      std::istringstream ls(line);
      std::vector<std::string> tokens;
      for (std::string t; ls >> t;)
        tokens.push_back(t);
      if (std::string(ext) == ".ply" && !in_body) {
        if (line.rfind("property", 0) == 0 && tokens.size() == 3 && tokens[2].size() == 1)
          EXPECT_EQ(tokens[1], "double") << line;
        in_body = line == "end_header";
        if (tokens.size() == 3 && tokens[0] == "element" && tokens[1] == "vertex")
          count = std::stoul(tokens[2]);
        continue;
      }
      if (std::string(ext) == ".off" && !in_body) {
        if (tokens.size() == 3) {
          count = std::stoul(tokens[0]);
          in_body = true;
        }
        continue;
      }
      if (std::string(ext) == ".obj") {
        if (tokens.empty() || tokens[0] != "v") continue;
        tokens.erase(tokens.begin());
      } else if (written.size() == count) {
        break;  // the faces
      }
      ASSERT_EQ(tokens.size(), 3u) << line;
      written.push_back({std::strtod(tokens[0].c_str(), nullptr), std::strtod(tokens[1].c_str(), nullptr),
                         std::strtod(tokens[2].c_str(), nullptr)});
    }
    std::sort(written.begin(), written.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    EXPECT_TRUE(written == expected) << written.size() << " vertices written, " << expected.size()
                                     << " expected";
  }
}

// (c) Pairs of points equal in float32 but not in double: each corner of a cube and a twin 2^-40 from it
// (across the corner's diagonal, so both are strictly extreme): 16 vertices in double, 8 in float (the
// first of each pair).
TEST(CliPrecision, PointsEqualInFloatAreTwoVerticesInDouble) {
  TempDir dir;
  std::vector<Point3d> points;
  for (const double x : {1.0, 2.0})
    for (const double y : {1.0, 2.0})
      for (const double z : {1.0, 2.0}) {
        points.push_back({x, y, z});
        // Perpendicular to the outward diagonal (sx, sy, sz): d (sy, -sx, 0).
        const double d = 0x1p-40, sx = x == 2 ? 1 : -1, sy = y == 2 ? 1 : -1;
        points.push_back({x + d * sy, y - d * sx, z});
      }
  const std::vector<Point3> narrow = to_float(points);
  for (std::size_t i = 0; i < points.size(); i += 2) {
    ASSERT_EQ(narrow[i], narrow[i + 1]);
    ASSERT_NE(points[i], points[i + 1]);
  }
  const std::vector<PointIndex> in_double = brute_force_vertices(points);
  ASSERT_EQ(in_double.size(), 16u);
  const std::vector<PointIndex> in_float = brute_force_vertices(narrow);
  ASSERT_EQ(in_float, (std::vector<PointIndex>{0, 2, 4, 6, 8, 10, 12, 14}));

  const fs::path input = dir / "twins.xyz";
  write_xyz17(input, points);
  const DoubleHullRun d = hull_of_file(input);
  EXPECT_EQ(d.stats.value("precision", ""), "double");
  EXPECT_EQ(d.ids(), in_double);
  EXPECT_EQ(d.stats.value("hull_vertices", 0), 16);
  EXPECT_EQ(hull_of_file(input, {"--precision", "float"}).ids(), in_float);

  // The same points through the double writers: binary PLY of doubles (auto: double) and .xyz.
  for (const char* name : {"twins.ply", "twins.txt"}) {
    SCOPED_TRACE(name);
    write_points((dir / name).string(), points);
    EXPECT_EQ(read_points_double((dir / name).string()).points, points);
    const DoubleHullRun w = hull_of_file(dir / name);
    EXPECT_EQ(w.stats.value("precision", ""), "double");
    EXPECT_EQ(w.ids(), in_double);
  }
  EXPECT_THAT(slurp(dir / "twins.ply"),
              HasSubstr("property double x\nproperty double y\nproperty double z\n"));

  // bench --vs qhull hands Qhull the doubles: the same 16 vertices (8 from the floats).
  for (const auto& [precision, count] :
       std::vector<std::pair<std::string, std::size_t>>{{"auto", 16}, {"float", 8}}) {
    const CliRun b = run_cli({"bench", input.string(), "--backend", "cpu", "--repeat", "1", "--vs", "qhull",
                              "--json", "--precision", precision});
    ASSERT_EQ(b.exit_code, kExitOk) << describe(b);
    const auto j = nlohmann::json::parse(b.out, nullptr, false);
    ASSERT_TRUE(j.is_object()) << b.out;
    EXPECT_EQ(j.value("precision", ""), precision == "auto" ? "double" : "float");
    EXPECT_EQ(j.value("hull_vertices", 0u), count) << precision;
    EXPECT_EQ(j.value("qhull_vertices", 0u), count) << precision;
    // Among duplicates Qhull keeps whichever it meets, not the lowest index: compare in double only.
    if (precision == "auto") EXPECT_EQ(j.value("same_vertices", false), true);
  }
}

// (d) A double coordinate outside [2^-250, 2^250] (and not 0) is taken exactly (issue 25): `hull` computes
// such an input on the wide-range path (exponent scaling, else GMP), says so, and gives the brute force's
// vertices; `bench`, which times the engines, still refuses it (exit 3, one line naming the point).
TEST(CliPrecision, DoublesOutsideTheExactRangeAreExact) {
  TempDir dir;
  // Point 5 is 1e-300 below the face z = 0 (a vertex), point 6 1e-300 above it (inside); in float both are 0.
  std::vector<Point3d> points{
      {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {0.5, 0.25, -1e-300}, {0.25, 0.25, 1e-300}};
  const fs::path tiny = dir / "tiny.xyz";
  write_xyz17(tiny, points);
  for (const std::vector<std::string>& extra :
       std::vector<std::vector<std::string>>{{}, {"--precision", "double"}}) {
    std::vector<std::string> args{
        "hull", tiny.string(), "--backend", "cpu", "--vertices-out", (dir / "v.txt").string(), "--stats",
        "-"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun r = run_cli(args);
    ASSERT_EQ(r.exit_code, kExitOk) << describe(r);
    EXPECT_THAT(r.err, HasSubstr("note: coordinates outside 2^-250..2^250"));
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.value("backend", ""), "cpu-wide");
    std::vector<PointIndex> ids;
    for (const auto& [id, p] : read_vertices_double(dir / "v.txt"))
      ids.push_back(id);
    EXPECT_EQ(ids, (std::vector<PointIndex>{0, 1, 2, 3, 4, 5}));
  }
  const CliRun f = run_cli({"hull", tiny.string(), "--backend", "cpu", "--precision", "float"});
  EXPECT_EQ(f.exit_code, kExitOk) << describe(f);

  const CliRun bench = run_cli({"bench", tiny.string(), "--backend", "cpu"});
  EXPECT_EQ(bench.exit_code, kExitBadInput) << describe(bench);
  EXPECT_EQ(bench.err, "cudahull: error: " + tiny.string() +
                           ": point 5: z coordinate -1e-300 is outside the range of exact double arithmetic "
                           "(nonzero magnitudes from 2^-250 to 2^250)\n");

  // A point at z = -2^251 below the corner at the origin: the origin falls on the segment from it to
  // (0, 0, 1) and point 5 inside the cone over the face z = 0, so the vertices are 1, 2, 3, 4 and it.
  points.back() = {0, 0, -0x1p251};
  write_xyz17(dir / "huge.xyz", points);
  const CliRun huge = run_cli(
      {"hull", (dir / "huge.xyz").string(), "--backend", "cpu", "--vertices-out", (dir / "v.txt").string()});
  EXPECT_EQ(huge.exit_code, kExitOk) << describe(huge);
  std::vector<PointIndex> ids;
  for (const auto& [id, p] : read_vertices_double(dir / "v.txt"))
    ids.push_back(id);
  EXPECT_EQ(ids, (std::vector<PointIndex>{1, 2, 3, 4, 6}));

  // The ends of the range, and zeros, are accepted and exact.
  std::vector<Point3d> ends;
  for (const double x : {-0x1p250, 0x1p250})
    for (const double y : {-0x1p250, 0x1p250})
      for (const double z : {-0x1p250, 0x1p250})
        ends.push_back({x, y, z});
  ends.push_back({0x1p-250, 0, -0x1p-250});
  write_xyz17(dir / "ends.xyz", ends);
  const DoubleHullRun e = hull_of_file(dir / "ends.xyz");
  EXPECT_EQ(e.stats.value("verified", false), true);
  EXPECT_EQ(e.ids(), (std::vector<PointIndex>{0, 1, 2, 3, 4, 5, 6, 7}));
}

// (e) --precision takes auto, float or double; anything else is a usage error (exit 2), for hull and bench.
TEST(CliPrecision, BadValueIsAUsageError) {
  TempDir dir;
  write_points((dir / "in.ply").string(), generate_points(Distribution::kCube, 100, 1));
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"hull", (dir / "in.ply").string(), "--precision", "bogus"},
           {"hull", (dir / "in.ply").string(), "--precision", "Double"},
           {"bench", "--dist", "cube", "--n", "100", "--precision", "bogus"}}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, kExitUsage) << describe(r);
    EXPECT_THAT(r.err, HasSubstr("--precision"));
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// (f) auto follows the file: a binary float PLY is computed in float, as before; generated points in float.
TEST(CliPrecision, AutoIsFloatForBinaryFloatPlyAndGeneratedPoints) {
  const auto points = generate_points(Distribution::kBall, 2000, 3);
  const HullRun r = hull_of(points);
  EXPECT_EQ(r.stats.value("precision", ""), "float");
  EXPECT_EQ(r.ids, run_qhull(points).vertex_ids);
  EXPECT_EQ(hull_of(points, {"--precision", "double"}).stats.value("precision", ""), "double");

  for (const auto& [precision, expected] :
       std::vector<std::pair<std::string, std::string>>{{"auto", "float"}, {"double", "double"}}) {
    const CliRun b = run_cli({"bench", "--dist", "ball", "--n", "5000", "--repeat", "1", "--backend", "cpu",
                              "--vs", "qhull", "--json", "--precision", precision});
    ASSERT_EQ(b.exit_code, kExitOk) << describe(b);
    const auto j = nlohmann::json::parse(b.out, nullptr, false);
    ASSERT_TRUE(j.is_object()) << b.out;
    EXPECT_EQ(j.value("precision", ""), expected);
    EXPECT_EQ(j.value("same_vertices", false), true);
  }
}

}  // namespace
}  // namespace cudahull
