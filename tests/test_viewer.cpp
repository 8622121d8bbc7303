// cudahull-viewer end to end, as a user runs it: headless (EGL; Mesa's llvmpipe in CI), screenshots read back
// and checked pixel by pixel: not blank, the hull visible in the colours of its faces' states, the picture
// changing between steps and with a layer hidden or shown (splats, cells, normals, legend, labels, the input
// surface), recordings, picking.  The debugger's views: test_viewer_debugger.cpp; errors and options:
// test_viewer_options.cpp; windowed: test_viewer_window.cpp; the parts that need no GL:
// test_viewer_parts.cpp.  Label: gl.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "renderer.hpp"
#include "support/viewer_run.hpp"

namespace cudahull::viewer {
namespace {

TEST(ViewerHeadless, BunnyHullIsVisibleInItsStateColours) {
  TempDir dir;
  const std::string script =
      dir.write("hull.txt", std::string(kHullOnly) + "run\nscreenshot " + (dir / "end.png") +
                                "\nrewind 1\nscreenshot " + (dir / "tetra.png") + "\n");
  const ViewerRun r =
      run_viewer({kBunny, "--headless", "--width", "320", "--height", "240", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("CPU upload"));  // the log says which upload path is active

  const Image end = read_png(dir / "end.png");
  ASSERT_EQ(end.width, 320);
  ASSERT_EQ(end.height, 240);
  EXPECT_GT(variance(end), 1e-3);
  EXPECT_GT(central_fraction(end, hull_colored), 0.4);
  EXPECT_TRUE(hull_colored(end.at(160, 120)));

  // Position 1 is the tetrahedron of section 3.1: every face is new, in the "refined" colour.
  const Image tetra = read_png(dir / "tetra.png");
  const glm::vec3 refined = kFaceStateColors[static_cast<int>(FaceState::kRefined)];
  EXPECT_GT(central_fraction(tetra, [&](const auto& p) { return shade_of(p, refined); }), 0.3);
  EXPECT_GT(differing_fraction(end, tetra), 0.05);
}

TEST(ViewerHeadless, PngSequenceChangesBetweenSteps) {
  TempDir dir;
  const ViewerRun r = run_viewer({"--gen", "ball", "20000", "--seed", "3", "--headless", "--width", "256",
                                  "--height", "192", "--steps", "5", "--screenshot", dir / "step_%02d.png"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  for (int k = 0; k <= 5; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "step_%02d.png", k);
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "step_06.png"));
  const Image points = read_png(dir / "step_00.png"), one = read_png(dir / "step_01.png"),
              five = read_png(dir / "step_05.png");
  EXPECT_GT(variance(points), 1e-4);  // the bare point cloud is drawn
  EXPECT_GT(variance(one), 1e-3);
  EXPECT_GT(differing_fraction(one, five), 0.05);
  // No temporary file left behind by the atomic writes.
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(fs::path(dir / "")))
    ++files;
  EXPECT_EQ(files, 6);
}

TEST(ViewerHeadless, HidingTheHullAndMovingTheCameraChangeThePicture) {
  TempDir dir;
  const std::string script =
      dir.write("layers.txt", "step 5\nscreenshot " + (dir / "shown.png") +
                                  "\nhide hull\nhide wireframe\nscreenshot " + (dir / "hidden.png") +
                                  "\nshow hull\nshow wireframe\ncamera {\"yaw\": 120, \"pitch\": 10}\n" +
                                  "screenshot " + (dir / "turned.png") + "\n");
  const ViewerRun r =
      run_viewer({kBunny, "--headless", "--width", "256", "--height", "192", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Image shown = read_png(dir / "shown.png"), hidden = read_png(dir / "hidden.png"),
              turned = read_png(dir / "turned.png");
  EXPECT_GT(differing_fraction(shown, hidden), 0.05);
  EXPECT_GT(differing_fraction(shown, turned), 0.05);
  // With the hull hidden, no pixel near the centre is a hull colour any more.
  EXPECT_LT(central_fraction(hidden, hull_colored), 0.02);
}

bool background(const std::array<float, 3>& p) {
  const glm::vec3 b = RenderSettings{}.background;
  return std::abs(p[0] - b.r) + std::abs(p[1] - b.g) + std::abs(p[2] - b.b) < 0.03f;
}

// Large clouds are drawn as compute splats (shaders/points_splat.comp.glsl); forced here on a small one,
// they must cover where GL points are drawn, in the same state colours, and sit at the right depth.
TEST(ViewerHeadless, SplatsDrawTheCloudGlPointsDraw) {
  TempDir dir;
  const std::string script = dir.write(
      "splats.txt", "step 3\nhide hull\nhide wireframe\nhide vertices\nset point-mode points\nscreenshot " +
                        (dir / "points.png") + "\nset point-mode splats\nscreenshot " + (dir / "splats.png") +
                        "\nhide external\nshow hull\nset hull-opacity 1\nscreenshot " + (dir / "hull.png") +
                        "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "20000", "--seed", "3", "--headless", "--width", "256",
                                  "--height", "192", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Image points = read_png(dir / "points.png"), splats = read_png(dir / "splats.png"),
              hull = read_png(dir / "hull.png");
  ASSERT_EQ(points.rgb.size(), splats.rgb.size());
  std::size_t drawn = 0, covered = 0, splat_pixels = 0;
  for (std::size_t i = 0; i < points.rgb.size(); ++i) {
    splat_pixels += background(splats.rgb[i]) ? 0 : 1;
    if (background(points.rgb[i])) continue;
    ++drawn;
    covered += background(splats.rgb[i]) ? 0 : 1;
  }
  ASSERT_GT(drawn, 1000u);
  EXPECT_GT(static_cast<double>(covered) / drawn, 0.9);  // squares cover the round points
  EXPECT_LT(splat_pixels, 3 * drawn);
  auto internal = [](const auto& p) { return shade_of(p, kInternalColor); };
  auto external = [](const auto& p) { return shade_of(p, kExternalColor); };
  EXPECT_GT(central_fraction(splats, internal), 0.01);
  EXPECT_GT(central_fraction(splats, external), 0.01);
  // An opaque hull hides the internal points behind its faces: the splats wrote their depth (at depth 0
  // they would cover it).
  EXPECT_GT(central_fraction(hull, hull_colored), 0.3);
}

// Issue 6, Fig. 2: selecting a face draws its three separating planes, highlights its cell's points and
// marks its extreme point; the normals layer draws every edge's normal.  Each changes the picture, and
// hiding them gives the plain picture back.
TEST(ViewerHeadless, SelectedFaceCellAndEdgeNormalsChangeThePicture) {
  TempDir dir;
  const std::string script =
      dir.write("cells.txt",
                "step 2\nhide hull\nscreenshot " + (dir / "plain.png") + "\nselect-face 0\nscreenshot " +
                    (dir / "cell.png") + "\nhide cells\nscreenshot " + (dir / "hidden.png") +
                    "\nshow normals\nscreenshot " + (dir / "normals.png") +
                    "\nselect-face 999999\nshow cells\n" + "screenshot " + (dir / "out_of_range.png") + "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "256",
                                  "--height", "192", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Image plain = read_png(dir / "plain.png"), cell = read_png(dir / "cell.png"),
              hidden = read_png(dir / "hidden.png"), normals = read_png(dir / "normals.png"),
              out_of_range = read_png(dir / "out_of_range.png");
  EXPECT_GT(differing_fraction(plain, cell), 0.01);
  // The cell's external points turn to the selection colour.
  auto selected = [](const auto& p) { return shade_of(p, kSelectedColor); };
  EXPECT_GT(central_fraction(cell, selected), central_fraction(plain, selected) + 0.001);
  EXPECT_LT(differing_fraction(plain, hidden), 0.001);
  EXPECT_GT(differing_fraction(hidden, normals), 0.003);
  EXPECT_LT(differing_fraction(normals, out_of_range), 0.001);  // an unknown face id draws no cell
}

// Issue 17: `set legend on` draws the colour key into the picture (swatches in the palette's colours, in
// the bottom left corner) and `off` gives the same picture back; `show labels` writes the vertex ids (in
// the vertices' yellow) and the face ids (light blue) in the font.
TEST(ViewerHeadless, LegendAndLabelsAppearAndGoAway) {
  TempDir dir;
  const std::string script =
      dir.write("legend.txt", "step 3\nhide internal\nhide external\nscreenshot " + (dir / "plain.png") +
                                  "\nset legend on\nscreenshot " + (dir / "legend.png") +
                                  "\nset legend off\nscreenshot " + (dir / "off.png") +
                                  "\nshow labels\nscreenshot " + (dir / "labels.png") + "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "12", "--seed", "12", "--headless", "--width", "480",
                                  "--height", "360", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("text: font "));
  const Image plain = read_png(dir / "plain.png"), legend = read_png(dir / "legend.png"),
              off = read_png(dir / "off.png"), labels = read_png(dir / "labels.png");
  EXPECT_GT(differing_fraction(plain, legend), 0.01);
  EXPECT_EQ(differing_fraction(plain, off), 0.0);
  // Each swatch of the faces' key is a square of its exact colour in the bottom left quarter.
  auto count_in_corner = [](const Image& img, const glm::vec3& c) {
    std::size_t n = 0;
    for (int y = img.height / 2; y < img.height; ++y) {
      for (int x = 0; x < img.width / 2; ++x) {
        const auto p = img.at(x, y);
        n += std::abs(p[0] - c.r) + std::abs(p[1] - c.g) + std::abs(p[2] - c.b) < 0.03f ? 1 : 0;
      }
    }
    return n;
  };
  for (const glm::vec3& c : kFaceStateColors)
    EXPECT_GE(count_in_corner(legend, c), count_in_corner(plain, c) + 60) << c.r << " " << c.g << " " << c.b;
  auto count = [](const Image& img, const glm::vec3& c) {
    std::size_t n = 0;
    for (const auto& p : img.rgb)
      n += rgba_near(p, pack_rgba(c.r, c.g, c.b, 1.0f)) ? 1 : 0;
    return n;
  };
  EXPECT_LT(count(plain, kFaceIdColor), 5u);
  EXPECT_GT(count(labels, kFaceIdColor), 40u);
  EXPECT_GT(count(labels, kVertexColor), count(plain, kVertexColor) + 40);
}

// Issue 17: recordings through ffmpeg have one frame per step (an .mp4), one per sub-step (`substep all`,
// a .gif), and --record records a whole headless run; a path that is neither .mp4 nor .gif is a usage error.
TEST(ViewerHeadless, RecordingsHaveOneFramePerStepOrSubStep) {
  TempDir dir;
  const std::string script =
      dir.write("record.txt", "record start " + (dir / "steps.mp4") +
                                  "\nstep 4\nrecord stop\nnext-removal\nrecord start " +
                                  (dir / "phases.gif") + "\nsubstep all\nrecord stop\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "161",
                                  "--height", "121", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("steps.mp4 (4 frames)"));
  EXPECT_EQ(decoded_frames(dir / "steps.mp4"), 4);
  const std::size_t played = r.err.find("played sub-steps 0 to ");
  ASSERT_NE(played, std::string::npos) << r.err;
  const int phases = std::stoi(r.err.substr(played + 22)) + 1;
  EXPECT_GE(phases, 4);
  EXPECT_EQ(decoded_frames(dir / "phases.gif"), phases);
  EXPECT_FALSE(fs::exists(dir / "phases.gif.partial"));

  // The bunny's whole run: one frame per iteration.
  const ViewerRun b =
      run_viewer({kBunny, "--headless", "--width", "96", "--height", "72", "--record", dir / "bunny.mp4",
                  "--script", dir.write("run.txt", "run\nexport-trace " + (dir / "t.jsonl") + "\n")});
  ASSERT_EQ(b.exit_code, 0) << describe(b);
  EXPECT_EQ(decoded_frames(dir / "bunny.mp4"), static_cast<int>(lines_of(dir / "t.jsonl").size()));

  const ViewerRun bad =
      run_viewer({kBunny, "--headless", "--script", dir.write("bad.txt", "record start a.avi\n")});
  EXPECT_EQ(bad.exit_code, 2) << describe(bad);
  EXPECT_THAT(bad.err, HasSubstr("bad.txt:1: 'record start' needs a .mp4 or .gif path"));
}

// Issue 17, picking: a scripted hover names the point under the mouse (its id, that it is external, its
// face and its signed distance to that face's plane, positive: outside) and a click there explains that
// same point's route, ending where the backend put it; over a face, the hover names the face and a click
// selects it and draws its cell.
TEST(ViewerHeadless, HoverAndClickNameWhatIsUnderTheMouse) {
  TempDir dir;
  const std::string script = dir.write(
      "pick.txt",
      "step 2\nhide hull\nhide internal\nhide vertices\nhover 160 120\nclick 160 120\n"
      "show hull\nhide external\nscreenshot " +
          (dir / "before.png") + "\nhover 160 120\nclick 160 120\nscreenshot " + (dir / "after.png") + "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "320",
                                  "--height", "240", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const std::string point_hover = "hover 160 120: point ";
  const std::size_t at = r.err.find(point_hover);
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string point = r.err.substr(at + point_hover.size(),
                                         r.err.find(':', at + point_hover.size()) - at - point_hover.size());
  EXPECT_THAT(r.err, HasSubstr(point_hover + point + ": external, face "));
  EXPECT_THAT(r.err, HasSubstr(", signed distance +"));
  const std::size_t explained = r.err.find("click 160 120: explain point " + point + ":");
  ASSERT_NE(explained, std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the backend agrees (face ", explained), std::string::npos) << r.err;

  const std::string face_hover = "hover 160 120: face ";
  const std::size_t f = r.err.find(face_hover);
  ASSERT_NE(f, std::string::npos) << r.err;
  const std::string face =
      r.err.substr(f + face_hover.size(), r.err.find(':', f + face_hover.size()) - f - face_hover.size());
  EXPECT_THAT(r.err, HasSubstr("click 160 120: selected face " + face + " "));
  EXPECT_GT(differing_fraction(read_png(dir / "before.png"), read_png(dir / "after.png")), 0.01);
}

// Issue 17, the input layer: the model's own surface (a PLY's face element; an OBJ's faces through
// the face reader) drawn grey under the points; a generated cloud has none, and the layer changes nothing.
TEST(ViewerHeadless, InputLayerDrawsTheModelsOwnSurface) {
  TempDir dir;
  auto grey_fraction = [](const Image& img) {
    return central_fraction(img, [](const auto& p) {
      return std::abs(p[0] - p[1]) < 0.02f && std::abs(p[1] - p[2]) < 0.02f && p[0] > 0.3f;
    });
  };
  const std::string script =
      dir.write("input.txt",
                "step 2\nhide hull\nhide wireframe\nhide internal\n"
                "hide external\nhide vertices\nscreenshot " +
                    (dir / "bare.png") + "\nshow input\nscreenshot " + (dir / "input.png") + "\n");
  for (const std::string model : {"bun_zipper.ply", "teapot.obj"}) {
    const ViewerRun r = run_viewer({std::string(CUDAHULL_ASSETS_DIR) + "/" + model, "--headless", "--width",
                                    "240", "--height", "180", "--script", script});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_LT(grey_fraction(read_png(dir / "bare.png")), 0.001) << model;
    EXPECT_GT(grey_fraction(read_png(dir / "input.png")), 0.2) << model;
  }
  const ViewerRun g = run_viewer(
      {"--gen", "ball", "500", "--headless", "--width", "240", "--height", "180", "--script", script});
  ASSERT_EQ(g.exit_code, 0) << describe(g);
  EXPECT_EQ(differing_fraction(read_png(dir / "bare.png"), read_png(dir / "input.png")), 0.0);
}

// Issue 17, no moire on the bunny at the defaults: the scan's points are drawn as large as their spacing
// on the screen, so the bare cloud is a closed surface, with (next to) no background pixel enclosed by drawn
// ones.  At the old fixed default of 3 pixels, at 960x720, the same measure finds the gaps between the scan
// lines that made the moire.
TEST(ViewerHeadless, BunnyScanDrawsAsAClosedSurfaceAtTheDefaults) {
  TempDir dir;
  auto enclosed_gaps = [](const Image& img) {  // background pixels with drawn ones 2 pixels away all round
    std::size_t drawn = 0, gaps = 0;
    for (int y = 2; y + 2 < img.height; ++y) {
      for (int x = 2; x + 2 < img.width; ++x) {
        if (!background(img.at(x, y))) {
          ++drawn;
        } else if (!background(img.at(x - 2, y)) && !background(img.at(x + 2, y)) &&
                   !background(img.at(x, y - 2)) && !background(img.at(x, y + 2))) {
          ++gaps;
        }
      }
    }
    return drawn > 0 ? static_cast<double>(gaps) / drawn : 1.0;
  };
  const std::string script =
      dir.write("bare.txt", "screenshot " + (dir / "auto.png") + "\nset point-size 3\nscreenshot " +
                                (dir / "three.png") + "\n");
  for (const auto& [width, height] : {std::pair{480, 360}, std::pair{960, 720}}) {
    const ViewerRun r = run_viewer({kBunny, "--headless", "--width", std::to_string(width), "--height",
                                    std::to_string(height), "--script", script});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_LT(enclosed_gaps(read_png(dir / "auto.png")), 0.005) << width << "x" << height;
  }
  EXPECT_GT(enclosed_gaps(read_png(dir / "three.png")), 0.02);  // 960x720, the last
}

}  // namespace
}  // namespace cudahull::viewer
