// `cudahull check POINTS HULL` end to end: valid hulls pass (cudahull's own, Qhull's), and each kind of wrong
// hull is rejected with its reason: mutations of valid hulls of a ball, a lattice cube (coplanar points) and
// the bunny, and Qhull's hull of a near-coplanar set, where Qhull drops a strictly extreme point.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/face_io.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/mesh_io.hpp"
#include "cudahull/point_io.hpp"
#include "support/cli_runner.hpp"

namespace cudahull {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kData = std::string(CUDAHULL_TEST_DATA_DIR) + "/check/";

void write_xyz17(const fs::path& path, const std::vector<Point3d>& points) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  for (const Point3d& p : points)
    std::fprintf(f, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
  std::fclose(f);
}

// A hull as an OBJ of its own: vertices (as input coordinates) and triangles, written by hand so that a test
// can break it.
struct Mesh {
  std::vector<Point3d> vertices;
  std::vector<std::vector<std::uint32_t>> faces;
  std::vector<PointIndex> ids;  // each vertex's input point
};

Mesh mesh_of(const HullMeshd& h) {
  Mesh m{h.vertices, {}, h.vertex_ids};
  for (const Triangle& t : h.triangles)
    m.faces.push_back({t[0], t[1], t[2]});
  return m;
}

void write_obj(const fs::path& path, const Mesh& m) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  for (const Point3d& p : m.vertices)
    std::fprintf(f, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
  for (const auto& face : m.faces) {
    std::fprintf(f, "f");
    for (std::uint32_t v : face)
      std::fprintf(f, " %u", v + 1);
    std::fprintf(f, "\n");
  }
  std::fclose(f);
}

CliRun check(const fs::path& points, const fs::path& hull, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"check", points.string(), hull.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_cli(args);
}

// The valid hulls the mutations start from.
struct Case {
  std::string name;
  std::vector<Point3d> points;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  auto widen = [](const std::vector<Point3>& f) {
    std::vector<Point3d> d;
    for (const Point3& p : f)
      d.push_back({p.x, p.y, p.z});
    return d;
  };
  out.push_back({"ball", widen(generate_points(Distribution::kBall, 2000, 5))});
  out.push_back({"lattice cube", widen(generate_points(Distribution::kGrid, 216, 1))});  // 6x6x6
  out.push_back({"bunny", read_points_double(std::string(CUDAHULL_ASSETS_DIR) + "/bun_zipper.ply").points});
  return out;
}

// An edge (a, b) of face f and the face g across it, with their third corners c and d.
struct Flip {
  std::size_t f, g;
  std::uint32_t a, b, c, d;
};
Flip find_flip(const Mesh& m, bool want_strict_convex) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> edge;
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    for (int i = 0; i < 3; ++i)
      edge[{m.faces[f][i], m.faces[f][(i + 1) % 3]}] = f;
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = m.faces[f][i], b = m.faces[f][(i + 1) % 3], c = m.faces[f][(i + 2) % 3];
      const std::size_t g = edge.at({b, a});
      std::uint32_t d = 0;
      for (std::uint32_t v : m.faces[g])
        if (v != a && v != b) d = v;
      const Vec3d A = to_vec3d(m.vertices[a]), B = to_vec3d(m.vertices[b]), C = to_vec3d(m.vertices[c]),
                  D = to_vec3d(m.vertices[d]);
      const bool fresh = !edge.count({c, d}) && !edge.count({d, c});  // the new diagonal is no edge yet
      if (fresh && (!want_strict_convex || orient3d(A, B, C, D) < 0)) return {f, g, a, b, c, d};
    }
  ADD_FAILURE() << "no edge to flip";
  return {};
}

TEST(CliCheck, ValidHullsPass) {
  TempDir dir;
  for (const Case& c : cases()) {
    write_xyz17(dir / "p.xyz", c.points);
    const HullMeshd hull = exact_hull(c.points);
    write_mesh((dir / "h.obj").string(), hull);
    const CliRun r = check(dir / "p.xyz", dir / "h.obj");
    EXPECT_EQ(r.exit_code, kExitOk) << c.name << describe(r);
    EXPECT_THAT(r.out, StartsWith("OK: ")) << c.name;
    EXPECT_THAT(r.out, HasSubstr("the exact hull of the " + std::to_string(c.points.size()) + " points"));
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << c.name;
    // The same hull as OFF and PLY, and as --vertices-out's id list.
    for (const std::string ext : {".off", ".ply"}) {
      write_mesh((dir / ("h" + ext)).string(), hull);
      EXPECT_EQ(check(dir / "p.xyz", dir / ("h" + ext)).exit_code, kExitOk) << c.name << ext;
    }
    write_vertices((dir / "v.txt").string(), hull);
    const CliRun v = check(dir / "p.xyz", dir / "v.txt");
    EXPECT_EQ(v.exit_code, kExitOk) << c.name << describe(v);
    EXPECT_THAT(v.out, HasSubstr("exactly the strictly extreme points"));
  }
}

// Eight kinds of wrong hull, each on each valid hull, each rejected (exit 5) for its own reason.
TEST(CliCheck, MutationsAreRejectedWithTheirReason) {
  TempDir dir;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const HullMeshd hull = exact_hull(c.points);
    const Mesh valid = mesh_of(hull);
    write_xyz17(dir / "p.xyz", c.points);
    auto expect = [&](const Mesh& m, const std::string& reason, const std::string& what) {
      write_obj(dir / "m.obj", m);
      const CliRun r = check(dir / "p.xyz", dir / "m.obj");
      EXPECT_EQ(r.exit_code, kExitVerifyFailed) << what << describe(r);
      EXPECT_THAT(r.err, HasSubstr(reason)) << what << describe(r);
      EXPECT_THAT(r.err, HasSubstr("cudahull: error: check failed")) << what;
    };

    // 1. A dropped vertex: the hull of the points without one of its vertices.
    {
      const PointIndex gone = hull.vertex_ids[hull.vertex_ids.size() / 2];
      std::vector<PointIndex> rest;
      for (PointIndex i = 0; i < c.points.size(); ++i)
        if (!(c.points[i] == c.points[gone])) rest.push_back(i);
      const Mesh dropped = mesh_of(exact_hull(c.points, rest));
      expect(dropped, "point " + std::to_string(gone) + " (", "dropped vertex");
      expect(dropped, "is above face", "dropped vertex");
    }
    // 2. An interior point as a vertex: one face split in three at a point inside the hull.
    {
      Mesh m = valid;
      const std::uint32_t q = static_cast<std::uint32_t>(m.vertices.size());
      // The input point nearest the vertex centroid, not a vertex of the hull.
      Point3d centre{0, 0, 0};
      for (const Point3d& p : hull.vertices)
        centre = {centre.x + p.x / hull.vertices.size(), centre.y + p.y / hull.vertices.size(),
                  centre.z + p.z / hull.vertices.size()};
      std::size_t best = 0;
      double best_d = 1e300;
      for (std::size_t i = 0; i < c.points.size(); ++i) {
        const double d =
            std::hypot(c.points[i].x - centre.x, c.points[i].y - centre.y, c.points[i].z - centre.z);
        if (d < best_d) best_d = d, best = i;
      }
      m.vertices.push_back(c.points[best]);
      const auto t = m.faces[0];
      m.faces[0] = {t[0], t[1], q};
      m.faces.push_back({t[1], t[2], q});
      m.faces.push_back({t[2], t[0], q});
      expect(m, "is concave", "interior point as a vertex");
    }
    // 3. A flipped face.
    {
      Mesh m = valid;
      std::swap(m.faces[3][1], m.faces[3][2]);
      expect(m, "not an oriented 2-manifold", "flipped face");
    }
    // 4. A swapped edge: the diagonal of two faces across a convex edge, which turns concave.
    {
      Mesh m = valid;
      const Flip e = find_flip(m, true);
      m.faces[e.f] = {e.a, e.d, e.c};
      m.faces[e.g] = {e.d, e.b, e.c};
      expect(m, "is concave: vertex", "swapped edge");
    }
    // 5. A missing face.
    {
      Mesh m = valid;
      m.faces.erase(m.faces.begin() + 5);
      expect(m, "the mesh is not closed", "missing face");
    }
    // 6. A duplicated face.
    {
      Mesh m = valid;
      m.faces.push_back(m.faces[7]);
      expect(m, "is used in the same direction", "duplicated face");
    }
    // 7. A point moved outside: the hull unchanged, one point of the point file pushed out.
    {
      std::vector<Point3d> moved = c.points;
      std::size_t inner = 0;
      while (std::binary_search(hull.vertex_ids.begin(), hull.vertex_ids.end(), inner))
        ++inner;
      moved[inner] = {1e6, 1e6, 1e6};
      write_xyz17(dir / "moved.xyz", moved);
      write_obj(dir / "m.obj", valid);
      const CliRun r = check(dir / "moved.xyz", dir / "m.obj");
      EXPECT_EQ(r.exit_code, kExitVerifyFailed) << describe(r);
      EXPECT_THAT(r.err,
                  HasSubstr("point " + std::to_string(inner) + " (1000000 1000000 1000000) is above face"))
          << describe(r);
    }
    // 8. An id out of range, in a list of ids; and a face corner beyond the file's vertices (bad input).
    {
      std::ofstream ids(dir / "ids.txt");
      for (PointIndex v : hull.vertex_ids)
        ids << v << "\n";
      ids << c.points.size() + 3 << "\n";
      ids.close();
      const CliRun r = check(dir / "p.xyz", dir / "ids.txt");
      EXPECT_EQ(r.exit_code, kExitVerifyFailed) << describe(r);
      EXPECT_THAT(r.err, HasSubstr("id " + std::to_string(c.points.size() + 3) + " is beyond the " +
                                   std::to_string(c.points.size()) + " input points"));
      Mesh m = valid;
      m.faces[2][1] = static_cast<std::uint32_t>(m.vertices.size() + 7);
      write_obj(dir / "m.obj", m);
      const CliRun bad = check(dir / "p.xyz", dir / "m.obj");
      EXPECT_EQ(bad.exit_code, kExitBadInput) << describe(bad);
      EXPECT_THAT(bad.err, HasSubstr("is beyond the " + std::to_string(m.vertices.size()) + " vertices"));
      EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << describe(bad);
    }
    // And in the id list: an interior point listed, a vertex left out.
    {
      std::ofstream ids(dir / "ids.txt");
      for (std::size_t k = 1; k < hull.vertex_ids.size(); ++k)
        ids << hull.vertex_ids[k] << "\n";
      std::size_t inner = 0;
      while (std::binary_search(hull.vertex_ids.begin(), hull.vertex_ids.end(), inner))
        ++inner;
      ids << inner << "\n";
      ids.close();
      const CliRun r = check(dir / "p.xyz", dir / "ids.txt");
      EXPECT_EQ(r.exit_code, kExitVerifyFailed) << describe(r);
      EXPECT_THAT(r.err, HasSubstr("point " + std::to_string(inner) + " ("));
      EXPECT_THAT(r.err, HasSubstr("is listed but is not strictly extreme"));
      EXPECT_THAT(r.err, HasSubstr("point " + std::to_string(hull.vertex_ids[0]) + " ("));
      EXPECT_THAT(r.err, HasSubstr("is strictly extreme but is not listed"));
    }
  }
}

// A vertex on a flat facet (the lattice cube's face centre) used as a corner: not strictly extreme.
TEST(CliCheck, AFacetPointAsAVertexIsRejected) {
  TempDir dir;
  std::vector<Point3d> pts;
  for (int x = 0; x <= 2; ++x)
    for (int y = 0; y <= 2; ++y)
      for (int z = 0; z <= 2; ++z)
        pts.push_back({double(x), double(y), double(z)});
  write_xyz17(dir / "p.xyz", pts);
  // The cube's 8 corners, and the centre of its top face (1, 1, 2) fanning that face.
  Mesh m;
  m.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2},
                {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 1, 2}};
  m.faces = {{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7},
             {4, 5, 8},    {5, 6, 8},    {6, 7, 8},    {7, 4, 8}};
  write_obj(dir / "h.obj", m);
  const CliRun r = check(dir / "p.xyz", dir / "h.obj");
  EXPECT_EQ(r.exit_code, kExitVerifyFailed) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("vertex 14 (1 1 2) is not strictly extreme: it lies inside the facet"));
  // Without it the quads pass; a quad with a corner off its plane does not.
  m.vertices.pop_back();
  m.faces.resize(5);
  m.faces.push_back({4, 5, 6, 7});
  write_obj(dir / "h.obj", m);
  EXPECT_EQ(check(dir / "p.xyz", dir / "h.obj").exit_code, kExitOk);
  pts.push_back({2, 2, 2.5});
  write_xyz17(dir / "p.xyz", pts);
  m.vertices[6] = {2, 2, 2.5};
  write_obj(dir / "h.obj", m);
  const CliRun bent = check(dir / "p.xyz", dir / "h.obj");
  EXPECT_EQ(bent.exit_code, kExitVerifyFailed) << describe(bent);
  EXPECT_THAT(bent.err, HasSubstr("face 5 (4 corners) is no convex polygon: it is not planar"));
}

// Qhull's own output (`qhull o`, tests/data/check/README.md): a ball's hull passes; the hull of a cube with
// a point 1e-15 above its top face does not: Qhull merged the point into the face though it is strictly
// extreme.
TEST(CliCheck, QhullsHullOfABallPasses) {
  const CliRun r = check(kData + "ball.xyz", kData + "ball_qhull.off");
  EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
  EXPECT_THAT(r.out, HasSubstr("the exact hull of the 200 points"));
}

TEST(CliCheck, QhullsHullOfANearCoplanarSetIsRejected) {
  const CliRun r = check(kData + "near_coplanar.xyz", kData + "near_coplanar_qhull.off");
  EXPECT_EQ(r.exit_code, kExitVerifyFailed) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("check: point 8 (0.5 0.5 1.0000000000000011) is above face 3 (ids "));
  // The same square facets are the cube's exact hull without that point.
  TempDir dir;
  std::vector<Point3d> cube;
  for (const Point3d& p : read_points_double(kData + "near_coplanar.xyz").points)
    cube.push_back(p);
  cube.pop_back();
  write_xyz17(dir / "cube.xyz", cube);
  const CliRun ok = check(dir / "cube.xyz", kData + "near_coplanar_qhull.off");
  EXPECT_EQ(ok.exit_code, kExitOk) << describe(ok);
  EXPECT_THAT(ok.out, HasSubstr("8 vertices, 6 faces (12 triangles)"));
}

// Qhull prints 16 significant digits: its vertices match the input point they round from, and only in
// Qhull's format.
TEST(CliCheck, QhullsRoundedCoordinatesMatchTheirPoints) {
  TempDir dir;
  const std::vector<Point3d> pts{{0.12345678901234568, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  write_xyz17(dir / "p.xyz", pts);
  const std::string faces = "3 1 3 2\n3 0 1 2\n3 3 0 2\n3 0 3 1\n";  // as `qhull o` gives them
  std::ofstream(dir / "q.off") << "3\n4 4 6\n0.1234567890123457 0 0\n1 0 0\n0 1 0\n0 0 1\n" << faces;
  const CliRun r = check(dir / "p.xyz", dir / "q.off");
  EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
  EXPECT_THAT(r.out, HasSubstr("1 vertices matched their input point within Qhull's 16 printed digits"));
  std::ofstream(dir / "o.off") << "OFF\n4 4 6\n0.1234567890123457 0 0\n1 0 0\n0 1 0\n0 0 1\n" << faces;
  const CliRun exact = check(dir / "p.xyz", dir / "o.off");
  EXPECT_EQ(exact.exit_code, kExitVerifyFailed) << describe(exact);
  EXPECT_THAT(exact.err, HasSubstr("hull vertex 0 (0.12345678901234571 0 0) of"));
  EXPECT_THAT(exact.err, HasSubstr("is not an input point"));
}

// Float input is checked in float; bad input and usage have their own exit codes.
TEST(CliCheck, PrecisionBadInputAndUsage) {
  TempDir dir;
  ASSERT_EQ(run_cli({"gen", "ball", "3000", "--seed", "4", "-o", (dir / "b.ply").string()}).exit_code,
            kExitOk);
  ASSERT_EQ(run_cli({"hull", (dir / "b.ply").string(), "-o", (dir / "h.ply").string(), "-q"}).exit_code,
            kExitOk);
  const CliRun r = check(dir / "b.ply", dir / "h.ply");
  EXPECT_EQ(r.exit_code, kExitOk) << describe(r);
  EXPECT_THAT(r.out, HasSubstr("(float)"));
  // In double the hull's 9-digit decimals are not the points' floats: the precision is the points' to keep.
  EXPECT_EQ(check(dir / "b.ply", dir / "h.ply", {"--precision", "double"}).exit_code, kExitVerifyFailed);
  EXPECT_EQ(check(dir / "b.ply", dir / "h.ply", {"--precision", "half"}).exit_code, kExitUsage);
  EXPECT_EQ(run_cli({"check", (dir / "b.ply").string()}).exit_code, kExitUsage);
  const CliRun missing = check(dir / "b.ply", dir / "nope.obj");
  EXPECT_EQ(missing.exit_code, kExitBadInput) << describe(missing);
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << describe(missing);
  std::ofstream(dir / "bad.txt") << "12\nabc\n";
  const CliRun bad = check(dir / "b.ply", dir / "bad.txt");
  EXPECT_EQ(bad.exit_code, kExitBadInput) << describe(bad);
  EXPECT_THAT(bad.err, HasSubstr("bad.txt:2: expected a point id"));
  const CliRun help = run_cli({"check", "--help"});
  EXPECT_EQ(help.exit_code, kExitOk);
  EXPECT_THAT(help.out, HasSubstr("qhull o"));
}

// Coplanar points: the hull is one polygon face; collinear ones: a segment, its two ends and no face.
TEST(CliCheck, LowerDimensions) {
  TempDir dir;
  write_xyz17(dir / "flat.xyz", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.25, 0.25, 0}, {0.5, 0.5, 0}});
  std::ofstream(dir / "flat.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const CliRun flat = check(dir / "flat.xyz", dir / "flat.off");
  EXPECT_EQ(flat.exit_code, kExitOk) << describe(flat);
  EXPECT_THAT(flat.out, HasSubstr("which are coplanar (a convex polygon)"));
  std::ofstream(dir / "flat4.off") << "OFF\n4 1 0\n0 0 0\n1 0 0\n0.5 0.5 0\n0 1 0\n4 0 1 2 3\n";
  const CliRun corner = check(dir / "flat.xyz", dir / "flat4.off");
  EXPECT_EQ(corner.exit_code, kExitVerifyFailed) << describe(corner);
  EXPECT_THAT(corner.err, HasSubstr("is not strictly extreme: it is collinear with its neighbours"));

  write_xyz17(dir / "line.xyz", {{0, 0, 0}, {2, 2, 2}, {1, 1, 1}});
  std::ofstream(dir / "line.obj") << "v 0 0 0\nv 2 2 2\n";
  EXPECT_EQ(check(dir / "line.xyz", dir / "line.obj").exit_code, kExitOk);
  std::ofstream(dir / "short.obj") << "v 0 0 0\nv 1 1 1\n";
  const CliRun s = check(dir / "line.xyz", dir / "short.obj");
  EXPECT_EQ(s.exit_code, kExitVerifyFailed) << describe(s);
  EXPECT_THAT(s.err, HasSubstr("point 1 (2 2 2) lies on the line beyond the segment's ends"));
}

// The face reader itself (face_io.hpp), on what the tools write.
FaceMesh faces_of(const std::string& text, PointFormat format) {
  std::istringstream in(text);
  return read_faces<Point3d>(in, format, "mem");
}
std::vector<std::vector<std::uint32_t>> polygons(const FaceMesh& m) {
  std::vector<std::vector<std::uint32_t>> out;
  for (std::size_t f = 0; f < m.face_count(); ++f)
    out.emplace_back(m.corners.begin() + m.face_start[f], m.corners.begin() + m.face_start[f + 1]);
  return out;
}

TEST(FaceReader, ObjOffPlyAndQhull) {
  const FaceMesh obj = faces_of(
      "v 0 0 0\nv 1 0 0\nvt 0 0\nv 0 1 0\nv 0 0 1\nf 1/1/1 3//1 2\nf -4 -3 -1 # c\n"
      "vn 0 0 1\nl 1 2\nfo 1 2 3\n",
      PointFormat::kObj);
  EXPECT_EQ(obj.vertex_count, 4u);
  EXPECT_EQ(polygons(obj), (std::vector<std::vector<std::uint32_t>>{{0, 2, 1}, {0, 1, 3}}));
  EXPECT_EQ(obj.face_line, (std::vector<std::uint64_t>{6, 7}));
  const FaceMesh off =
      faces_of("OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n4 0 1 2 3 255 0 0\n3 3 2 1\n", PointFormat::kOff);
  EXPECT_FALSE(off.qhull_off);
  EXPECT_EQ(polygons(off), (std::vector<std::vector<std::uint32_t>>{{0, 1, 2, 3}, {3, 2, 1}}));
  const FaceMesh qh = faces_of("3\n4 1 6\n0.1 0 0\n1 0 0\n0 1 0\n0 0 1\n3 1 3 2\n", PointFormat::kOff);
  EXPECT_TRUE(qh.qhull_off);
  EXPECT_EQ(qh.vertices[0], (Point3d{0.1, 0, 0}));
  const FaceMesh ply = faces_of(
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty uchar flags\nproperty list uchar uint vertex_indices\nend_header\n"
      "0 0 0\n\n1 0 0\n0 1 0\n7 3 2 1 0\n",
      PointFormat::kPly);
  EXPECT_EQ(polygons(ply), (std::vector<std::vector<std::uint32_t>>{{2, 1, 0}}));
  EXPECT_EQ(ply.vertices.size(), 3u);
  for (const auto& [text, format, message] : std::vector<std::tuple<std::string, PointFormat, std::string>>{
           {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", PointFormat::kObj,
            "mem:4: face corner 4 is beyond the 3 vertices"},
           {"v 0 0 0\nv 1 0 0\nf 1 2\n", PointFormat::kObj, "mem:3: a face of 2 corners (at least 3)"},
           {"v 0 0 0\nf 1 2 x\n", PointFormat::kObj, "mem:2: invalid face corner 'x'"},
           {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", PointFormat::kOff,
            "mem:6: face corner 3 is beyond the 3 vertices"},
           {"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", PointFormat::kOff,
            "mem:6: unexpected end of file: header says 2 faces, found 1"},
           {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 "
            "1 2\n",
            PointFormat::kPly, "mem:7: face indices must have an integer type"},
           {"0 0 0\n", PointFormat::kXyz, "mem: an xyz file has no faces"}}) {
    try {
      faces_of(text, format);
      ADD_FAILURE() << "accepted: " << message;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  }
}

}  // namespace
}  // namespace cudahull
