// cudahull-viewer in a window (GLFW under Xvfb): steps, screenshots and closing after --frames, and the
// panels Dear ImGui draws docked without overlap at 1280x720 and 1920x1080.  Skipped without a display.
// Label: gl.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/viewer_run.hpp"
#include "ui_layout.hpp"

namespace cudahull::viewer {
namespace {

TEST(ViewerWindow, StepsScreenshotAndCloseAfterFrames) {
  if (!has_display()) GTEST_SKIP() << "no display (run under xvfb-run, as scripts/test does)";
  TempDir dir;
  const std::string script =
      dir.write("win.txt", std::string(kHullOnly) + "step 5\nscreenshot " + (dir / "five.png") +
                               "\nrewind 1\n" + "screenshot " + (dir / "one.png") + "\n");
  const ViewerRun r =
      run_viewer({kBunny, "--width", "320", "--height", "240", "--script", script, "--frames", "3"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("CPU upload"));
  const Image five = read_png(dir / "five.png"), one = read_png(dir / "one.png");
  EXPECT_GT(five.width, 0);
  EXPECT_GT(variance(five), 1e-3);
  EXPECT_GT(central_fraction(five, hull_colored), 0.5);
  EXPECT_GT(differing_fraction(one, five), 0.05);

  // The command-line options, windowed: --steps then --screenshot, then 2 frames more.
  const ViewerRun o = run_viewer({"--gen", "ball", "5000", "--width", "256", "--height", "192", "--steps",
                                  "3", "--screenshot", dir / "opt.png", "--frames", "2"});
  ASSERT_EQ(o.exit_code, 0) << describe(o);
  EXPECT_GT(variance(read_png(dir / "opt.png")), 1e-3);
}

UiRect rect_of(const nlohmann::json& j) {
  return {j["x"].get<float>(), j["y"].get<float>(), j["width"].get<float>(), j["height"].get<float>()};
}

// Issue 17: the panels are docked to the window's edges, sized from it, at 1280x720 and 1920x1080 with
// every panel open (the debugger too): the rectangles Dear ImGui really drew (--ui-layout) lie inside the
// window, no two intersect, none covers the 3-d view, and no panel's content runs past its right edge.
TEST(ViewerWindow, PanelsAreDockedWithoutOverlapAtBothSizes) {
  if (!has_display()) GTEST_SKIP() << "no display (run under xvfb-run, as scripts/test does)";
  TempDir dir;
  const std::string script = dir.write("ui.txt", "step 3\nselect-face 0\nshow swaps\n");
  for (const auto& [width, height] : {std::pair{1280, 720}, std::pair{1920, 1080}}) {
    const std::string json_path = dir / ("layout_" + std::to_string(width) + ".json");
    const ViewerRun r =
        run_viewer({kBunny, "--width", std::to_string(width), "--height", std::to_string(height), "--script",
                    script, "--frames", "3", "--ui-layout", json_path});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    std::ifstream in(json_path);
    const nlohmann::json layout = nlohmann::json::parse(in);
    const float w = layout["window"]["width"].get<float>(), h = layout["window"]["height"].get<float>();
    EXPECT_EQ(w, static_cast<float>(width));
    EXPECT_EQ(h, static_cast<float>(height));
    std::vector<std::string> names;
    std::vector<UiRect> rects;
    for (const auto& p : layout["panels"]) {
      names.push_back(p["name"].get<std::string>());
      rects.push_back(rect_of(p));
      EXPECT_TRUE(rects.back().inside(w, h)) << names.back() << " at " << width << "x" << height;
      EXPECT_LE(p["overflow_x"].get<float>(), 0.5f)
          << names.back() << " is cut at " << width << "x" << height;
    }
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"Debugger", "Iteration", "Over the iterations", "cudahull"}));
    const UiRect view = rect_of(layout["view"]);
    EXPECT_TRUE(view.inside(w, h));
    EXPECT_GT(view.width * view.height, 0.25f * w * h);
    for (std::size_t a = 0; a < rects.size(); ++a) {
      EXPECT_FALSE(rects[a].intersects(view)) << names[a] << " covers the view";
      for (std::size_t b = a + 1; b < rects.size(); ++b)
        EXPECT_FALSE(rects[a].intersects(rects[b]))
            << names[a] << " and " << names[b] << " overlap at " << width << "x" << height;
    }
  }
}

}  // namespace
}  // namespace cudahull::viewer
