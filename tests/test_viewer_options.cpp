// cudahull-viewer's command line and scripts, headless: --engine auto picks as `cudahull hull` does, a bad
// script line exits 2 naming the line, errors exit with the CLI's codes, and --precision double keeps points
// that float rounds away.  Label: gl.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "support/viewer_run.hpp"

namespace cudahull::viewer {
namespace {

// --engine auto picks as `cudahull hull` does (plan_hull()): on the CPU backend, the stepping engine.
TEST(ViewerHeadless, EngineAutoPicksAsTheCommandLine) {
  TempDir dir;
  ViewerRun r = run_viewer({"--gen", "ball", "2000", "--seed", "3", "--engine", "auto", "--backend", "cpu",
                            "--headless", "--width", "64", "--height", "48", "--steps", "2", "--screenshot",
                            dir / "shot.png"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("cpu"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("resident engine"))) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "shot.png"));
  ViewerRun bad = run_viewer({"--gen", "ball", "20", "--engine", "fastest", "--headless"});
  EXPECT_NE(bad.exit_code, 0) << describe(bad);
}

TEST(ViewerHeadless, BadScriptLineExits2NamingTheLine) {
  TempDir dir;
  const std::string script =
      dir.write("bad.txt", "# a demo\nstep 2\njump 4\nscreenshot " + (dir / "x.png") + "\n");
  const ViewerRun r = run_viewer({kBunny, "--headless", "--script", script});
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("bad.txt:3: unknown command 'jump'"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
  EXPECT_FALSE(fs::exists(dir / "x.png"));                              // checked before anything ran

  const std::string layer = dir.write("layer.txt", "hide hulls\n");
  const ViewerRun l = run_viewer({kBunny, "--headless", "--script", layer});
  EXPECT_EQ(l.exit_code, 2) << describe(l);
  EXPECT_THAT(l.err, HasSubstr("layer.txt:1:"));
  EXPECT_THAT(l.err, HasSubstr("wireframe"));  // lists the layers

  const std::string camera = dir.write("camera.txt", "step\ncamera {\"pitch\": 95}\n");
  const ViewerRun c = run_viewer({kBunny, "--headless", "--script", camera});
  EXPECT_EQ(c.exit_code, 2) << describe(c);
  EXPECT_THAT(c.err, HasSubstr("camera.txt:2: camera: \"pitch\" must be in [-89, 89]"));
}

TEST(ViewerHeadless, ErrorsHaveTheCliExitCodes) {
  TempDir dir;
  EXPECT_EQ(run_viewer({dir / "missing.ply", "--headless", "--screenshot", dir / "x.png"}).exit_code, 3);
  const std::string bad = dir.write("bad.xyz", "1 2 3\n4 nan 6\n");
  const ViewerRun b = run_viewer({bad, "--headless", "--screenshot", dir / "x.png"});
  EXPECT_EQ(b.exit_code, 3) << describe(b);
  EXPECT_THAT(b.err, HasSubstr("bad.xyz"));
  EXPECT_EQ(run_viewer({kBunny, "--headless"}).exit_code, 2);  // nothing to write
  EXPECT_EQ(run_viewer({"--headless", "--screenshot", dir / "x.png"}).exit_code, 2);
  EXPECT_EQ(run_viewer({"--gen", "donut", "10", "--headless", "--screenshot", dir / "x.png"}).exit_code, 2);
  EXPECT_EQ(
      run_viewer({kBunny, "--gen", "ball", "10", "--headless", "--screenshot", dir / "x.png"}).exit_code, 2);
  EXPECT_EQ(run_viewer({kBunny, "--headless", "--script", dir / "none.txt"}).exit_code, 3);
  EXPECT_EQ(run_viewer({kBunny, "--backend", "cuda", "--headless", "--screenshot", dir / "x.png"}).exit_code,
            4);
  const ViewerRun w =
      run_viewer({kBunny, "--headless", "--steps", "1", "--screenshot", dir / "no/such/dir/x.png"});
  EXPECT_EQ(w.exit_code, 1) << describe(w);
}

// --precision: the cube [-1,1]^3's corners plus a point 1e-12 outside each face's centre.  In double every
// one of those six is a hull vertex (14 vertices); in float they round onto the faces (8); auto is double for
// .xyz.  A bad value exits 2.
TEST(ViewerHeadless, PrecisionDoubleKeepsPointsThatFloatRoundsAway) {
  TempDir dir;
  std::string text;
  auto add = [&text](double x, double y, double z) {
    char line[128];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", x, y, z);
    text += line;
  };
  for (int k = 0; k < 8; ++k)
    add(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
  const double out = 1 + 1e-12;
  add(out, 0.1, 0.2);
  add(-out, 0.2, 0.1);
  add(0.1, out, 0.2);
  add(0.2, -out, 0.1);
  add(0.1, 0.2, out);
  add(0.2, 0.1, -out);
  const std::string input = dir.write("cube.xyz", text);
  auto vertices = [&](const std::vector<std::string>& precision, const std::string& name) {
    const std::string mesh = dir / (name + ".obj");
    std::vector<std::string> args{input, "--headless", "--script",
                                  dir.write(name + ".txt", "run\nexport-mesh " + mesh + "\n")};
    args.insert(args.end(), precision.begin(), precision.end());
    const ViewerRun r = run_viewer(args);
    EXPECT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_THAT(r.err, HasSubstr("; precision " + (precision.empty() ? std::string("double (auto)")
                                                                     : precision[1] + " (as requested)")));
    int count = 0;
    for (const std::string& line : lines_of(mesh))
      count += line.rfind("v ", 0) == 0;
    return count;
  };
  EXPECT_EQ(vertices({"--precision", "double"}, "double"), 14);
  EXPECT_EQ(vertices({"--precision", "float"}, "float"), 8);
  EXPECT_EQ(vertices({}, "auto"), 14);

  const ViewerRun bad =
      run_viewer({input, "--headless", "--script", dir / "auto.txt", "--precision", "half"});
  EXPECT_EQ(bad.exit_code, 2) << describe(bad);
  EXPECT_THAT(bad.err, HasSubstr("--precision"));
}

}  // namespace
}  // namespace cudahull::viewer
