// Hull writers: each format read back through read_points, face lines, %.9g round trips, and the atomic
// writer's promises (no temporary left behind, nothing written on failure or on SIGTERM).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/mesh_io.hpp"
#include "cudahull/point_io.hpp"
#include "support/temp_dir.hpp"

namespace cudahull {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::lines_of;
using testing::slurp;
using testing::TempDir;

// Lines that start with `prefix`.
std::vector<std::string> lines_starting(const std::string& text, const std::string& prefix) {
  std::vector<std::string> out;
  for (const auto& l : lines_of(text)) {
    if (l.rfind(prefix, 0) == 0) out.push_back(l);
  }
  return out;
}

// A tetrahedron with coordinates that need all nine digits, outward counter-clockwise faces.
HullMesh tetrahedron() {
  HullMesh h;
  h.dimension = 3;
  h.vertex_ids = {5, 2, 9, 0};
  h.vertices = {{0.1f, 1.0f / 3.0f, -2.5e-7f}, {123456.789f, 0, 0}, {0, 7.0f / 9.0f, 0}, {0, 0, -1e30f}};
  h.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};
  return h;
}

TEST(WriteMesh, ObjVerticesAndOneBasedFaces) {
  TempDir dir;
  const HullMesh h = tetrahedron();
  write_mesh((dir / "t.obj").string(), h);
  EXPECT_EQ(read_points((dir / "t.obj").string()), h.vertices);
  const std::string text = slurp(dir / "t.obj");
  EXPECT_THAT(lines_starting(text, "f "), ElementsAre("f 1 3 2", "f 1 2 4", "f 1 4 3", "f 2 3 4"));
  EXPECT_THAT(lines_starting(text, "v "),
              ElementsAre("v 0.100000001 0.333333343 -2.49999999e-07", "v 123456.789 0 0",
                          "v 0 0.777777791 0", "v 0 0 -1.00000002e+30"));
  EXPECT_THAT(dir.files(), ElementsAre("t.obj"));
}

TEST(WriteMesh, OffCountsAndZeroBasedFaces) {
  TempDir dir;
  const HullMesh h = tetrahedron();
  write_mesh((dir / "t.off").string(), h);
  EXPECT_EQ(read_points((dir / "t.off").string()), h.vertices);
  const auto lines = lines_of(slurp(dir / "t.off"));
  ASSERT_EQ(lines.size(), 2u + 4u + 4u);
  EXPECT_EQ(lines[0], "OFF");
  EXPECT_EQ(lines[1], "4 4 0");
  EXPECT_THAT(std::vector<std::string>(lines.begin() + 6, lines.end()),
              ElementsAre("3 0 2 1", "3 0 1 3", "3 0 3 2", "3 1 2 3"));
}

TEST(WriteMesh, PlyHeaderAndFaces) {
  TempDir dir;
  const HullMesh h = tetrahedron();
  write_mesh((dir / "t.PLY").string(), h);  // the extension is matched without regard to case
  EXPECT_EQ(read_points((dir / "t.PLY").string()), h.vertices);
  const std::string text = slurp(dir / "t.PLY");
  EXPECT_THAT(text, HasSubstr("format ascii 1.0\n"));
  EXPECT_THAT(text, HasSubstr("element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                              "element face 4\nproperty list uchar int vertex_indices\nend_header\n"));
  const auto lines = lines_of(text);
  EXPECT_THAT(std::vector<std::string>(lines.end() - 4, lines.end()),
              ElementsAre("3 0 2 1", "3 0 1 3", "3 0 3 2", "3 1 2 3"));
}

TEST(WriteMesh, PlanarHullIsOnePolygonFace) {
  HullMesh h;
  h.dimension = 2;
  h.vertex_ids = {0, 1, 2, 3, 4};
  h.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 1.5f, 0}};
  h.polygon = {0, 1, 2, 4, 3};
  TempDir dir;
  for (const char* ext : {".obj", ".off", ".ply"}) {
    const fs::path path = dir / (std::string("p") + ext);
    write_mesh(path.string(), h);
    EXPECT_EQ(read_points(path.string()), h.vertices) << ext;
  }
  EXPECT_THAT(lines_starting(slurp(dir / "p.obj"), "f"), ElementsAre("f 1 2 3 5 4"));
  const auto off = lines_of(slurp(dir / "p.off"));
  EXPECT_EQ(off[1], "5 1 0");
  EXPECT_EQ(off.back(), "5 0 1 2 4 3");
  EXPECT_THAT(slurp(dir / "p.ply"), HasSubstr("element face 1\n"));
  EXPECT_EQ(lines_of(slurp(dir / "p.ply")).back(), "5 0 1 2 4 3");
}

TEST(WriteMesh, PolygonWithMoreThan255CornersUsesWideListCount) {
  HullMesh h;
  h.dimension = 2;
  for (std::uint32_t i = 0; i < 300; ++i) {
    const double a = 2 * M_PI * i / 300;
    h.vertex_ids.push_back(i);
    h.vertices.push_back({static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 2});
    h.polygon.push_back(i);
  }
  TempDir dir;
  write_mesh((dir / "big.ply").string(), h);
  const std::string text = slurp(dir / "big.ply");
  EXPECT_THAT(text, HasSubstr("property list uint int vertex_indices\n"));
  EXPECT_EQ(lines_of(text).back().substr(0, 6), "300 0 ");
  EXPECT_EQ(read_points((dir / "big.ply").string()), h.vertices);
}

TEST(WriteMesh, SegmentAndPointHaveNoFaces) {
  TempDir dir;
  HullMesh seg;
  seg.dimension = 1;
  seg.vertex_ids = {3, 8};
  seg.vertices = {{1, 2, 3}, {4, 5, 6}};
  HullMesh pt;
  pt.dimension = 0;
  pt.vertex_ids = {0};
  pt.vertices = {{-1, -1, -1}};
  for (const HullMesh* h : {&seg, &pt}) {
    for (const char* ext : {".obj", ".off", ".ply"}) {
      const fs::path path = dir / (std::string("d") + std::to_string(h->dimension) + ext);
      write_mesh(path.string(), *h);
      EXPECT_EQ(read_points(path.string()), h->vertices) << path;
    }
    const std::string n = std::to_string(h->vertices.size());
    const std::string d = std::to_string(h->dimension);
    EXPECT_TRUE(lines_starting(slurp(dir / ("d" + d + ".obj")), "f").empty());
    EXPECT_EQ(lines_of(slurp(dir / ("d" + d + ".off")))[1], n + " 0 0");
    EXPECT_THAT(slurp(dir / ("d" + d + ".ply")), HasSubstr("element face 0\n"));
  }
}

TEST(WriteMesh, NineDigitsRoundTripEveryFloat) {
  std::mt19937 rng(99);
  HullMesh h;
  h.dimension = 0;  // vertices only
  const float specials[] = {std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::min(),
                            std::numeric_limits<float>::denorm_min(),
                            -0.0f,
                            0.1f,
                            16777217.0f,
                            std::nextafter(1.0f, 2.0f),
                            -3.4028233e38f};
  for (float f : specials)
    h.vertices.push_back({f, -f, f / 3});
  for (int i = 0; i < 20000; ++i) {
    // Random bit patterns that are finite floats cover every exponent.
    float v[3];
    for (float& x : v) {
      do {
        const std::uint32_t bits = rng();
        std::memcpy(&x, &bits, 4);
      } while (!std::isfinite(x));
    }
    h.vertices.push_back({v[0], v[1], v[2]});
  }
  for (std::uint32_t i = 0; i < h.vertices.size(); ++i)
    h.vertex_ids.push_back(i);
  TempDir dir;
  for (const char* ext : {".obj", ".off", ".ply"}) {
    const fs::path path = dir / (std::string("r") + ext);
    write_mesh(path.string(), h);
    const auto back = read_points(path.string());
    ASSERT_EQ(back.size(), h.vertices.size());
    for (std::size_t i = 0; i < back.size(); ++i) {
      // Bitwise, so that -0 must come back as -0.
      ASSERT_EQ(std::memcmp(&back[i], &h.vertices[i], sizeof(Point3)), 0) << ext << " vertex " << i;
    }
  }
}

TEST(WriteVertices, SortedByInputIndex) {
  TempDir dir;
  const HullMesh h = tetrahedron();
  write_vertices((dir / "v.txt").string(), h);
  EXPECT_THAT(lines_of(slurp(dir / "v.txt")),
              ElementsAre("0 0 0 -1.00000002e+30", "2 123456.789 0 0",
                          "5 0.100000001 0.333333343 -2.49999999e-07", "9 0 0.777777791 0"));
}

TEST(WriteVertices, DashWritesToStdout) {
  ::testing::internal::CaptureStdout();
  write_vertices("-", tetrahedron());
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(lines_of(out).size(), 4u);
  EXPECT_EQ(lines_of(out).front(), "0 0 0 -1.00000002e+30");
}

TEST(WriteMesh, InvalidHullAndUnknownExtensionThrowOutputError) {
  TempDir dir;
  HullMesh bad = tetrahedron();
  bad.triangles.push_back({{0, 1, 4}});
  EXPECT_THROW(write_mesh((dir / "bad.obj").string(), bad), OutputError);
  EXPECT_TRUE(dir.files().empty());
  try {
    write_mesh((dir / "x.stl").string(), tetrahedron());
    FAIL() << "no OutputError";
  } catch (const OutputError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("unknown mesh extension '.stl'"));
  }
  HullMesh mismatched = tetrahedron();
  mismatched.vertex_ids.pop_back();
  EXPECT_THROW(write_vertices((dir / "v.txt").string(), mismatched), OutputError);
  EXPECT_TRUE(dir.files().empty());
}

TEST(AtomicWrite, LeavesOnlyTheTarget) {
  TempDir dir;
  const std::string path = (dir / "out.txt").string();
  write_file_atomically(path, [](std::ostream& os) { os << "first\n"; });
  write_file_atomically(path, [](std::ostream& os) { os << "second\n"; });  // replaces
  EXPECT_EQ(slurp(path), "second\n");
  EXPECT_THAT(dir.files(), ElementsAre("out.txt"));
}

TEST(AtomicWrite, FailingBodyLeavesNeitherTargetNorTemporary) {
  TempDir dir;
  const std::string path = (dir / "out.obj").string();
  bool temp_seen = false;
  try {
    write_file_atomically(path, [&](std::ostream& os) {
      os << "partial data\n";
      os.flush();
      // The data goes to a hidden temporary beside the target, never to the target itself.
      for (const auto& name : dir.files())
        temp_seen = temp_seen || name.find(".out.obj.tmp.") == 0;
      EXPECT_FALSE(fs::exists(path));
      throw std::runtime_error("disk on fire");
    });
    FAIL() << "no OutputError";
  } catch (const OutputError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr(path));
    EXPECT_THAT(std::string(e.what()), HasSubstr("disk on fire"));
  }
  EXPECT_TRUE(temp_seen);
  EXPECT_TRUE(dir.files().empty());
}

TEST(AtomicWrite, FailingBodyKeepsThePreviousFile) {
  TempDir dir;
  const std::string path = (dir / "out.obj").string();
  write_file_atomically(path, [](std::ostream& os) { os << "old\n"; });
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& os) {
                                       os << "new";
                                       throw std::runtime_error("stop");
                                     }),
               OutputError);
  EXPECT_EQ(slurp(path), "old\n");
  EXPECT_THAT(dir.files(), ElementsAre("out.obj"));
}

TEST(AtomicWrite, MissingDirectoryThrowsOutputError) {
  try {
    write_mesh("/nonexistent/cudahull/dir/hull.obj", tetrahedron());
    FAIL() << "no OutputError";
  } catch (const OutputError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("/nonexistent/cudahull/dir/hull.obj"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("No such file or directory"));
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

TEST(AtomicWrite, TargetIsADirectoryThrowsOutputError) {
  TempDir dir;
  fs::create_directories(dir / "taken.obj");
  EXPECT_THROW(write_mesh((dir / "taken.obj").string(), tetrahedron()), OutputError);
  EXPECT_THAT(dir.files(), ElementsAre("taken.obj"));
}

TEST(AtomicWrite, SigtermDuringWriteRemovesTheTemporary) {
  TempDir dir;
  const std::string path = (dir / "out.ply").string();
  const auto child = [&] {
    write_file_atomically(path, [](std::ostream& os) {
      os << "some data\n";
      os.flush();
      ::raise(SIGTERM);
    });
  };
  EXPECT_EXIT(child(), ::testing::KilledBySignal(SIGTERM), "");
  EXPECT_TRUE(dir.files().empty());
}

extern "C" void callers_handler(int) {}

// While a temporary file exists, SIGINT, SIGTERM and SIGHUP go to the writer's handler (which removes the
// file); afterwards the caller's handlers are back.
TEST(AtomicWrite, RestoresTheCallersSignalHandlers) {
  struct sigaction mine {};
  mine.sa_handler = callers_handler;
  sigemptyset(&mine.sa_mask);
  const int signals[] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction old[3] = {};
  for (int k = 0; k < 3; ++k)
    ASSERT_EQ(::sigaction(signals[k], &mine, &old[k]), 0);
  TempDir dir;
  struct sigaction during[3] = {};
  write_file_atomically((dir / "x.txt").string(), [&](std::ostream& os) {
    for (int k = 0; k < 3; ++k)
      ::sigaction(signals[k], nullptr, &during[k]);
    os << "x";
  });
  for (int k = 0; k < 3; ++k) {
    EXPECT_NE(during[k].sa_handler, callers_handler)
        << "no handler for signal " << signals[k] << " while writing";
    struct sigaction after {};
    ::sigaction(signals[k], nullptr, &after);
    EXPECT_EQ(after.sa_handler, callers_handler) << "signal " << signals[k] << " not restored";
    ::sigaction(signals[k], &old[k], nullptr);
  }
}

// A signal the caller ignores stays ignored while writing (a shell's background job ignores SIGINT): the
// write is not interrupted, so there is nothing to clean up.
TEST(AtomicWrite, LeavesIgnoredSignalsIgnored) {
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  struct sigaction old {};
  ASSERT_EQ(::sigaction(SIGINT, &ignore, &old), 0);
  TempDir dir;
  struct sigaction during {};
  write_file_atomically((dir / "x.txt").string(), [&](std::ostream& os) {
    ::sigaction(SIGINT, nullptr, &during);
    os << "x";
  });
  EXPECT_EQ(during.sa_handler, SIG_IGN);
  struct sigaction after {};
  ::sigaction(SIGINT, nullptr, &after);
  EXPECT_EQ(after.sa_handler, SIG_IGN);
  ::sigaction(SIGINT, &old, nullptr);
}

}  // namespace
}  // namespace cudahull
