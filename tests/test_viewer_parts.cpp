// The viewer's parts that need no GL: the panel layout's arithmetic at any window size, camera JSON, script
// parsing, numbered paths and layer names.  Label: gl.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "camera.hpp"
#include "png.hpp"
#include "renderer.hpp"
#include "script.hpp"
#include "ui_layout.hpp"

namespace cudahull::viewer {
namespace {

using ::testing::HasSubstr;

// The same arithmetic over sizes the window test does not open: small, wide, high-DPI, debugger hidden.
TEST(ViewerParts, LayoutTilesTheWindowAtAnySize) {
  for (const auto& [w, h, scale] :
       {std::tuple{1280.f, 720.f, 1.f}, std::tuple{1920.f, 1080.f, 1.f}, std::tuple{800.f, 600.f, 1.f},
        std::tuple{3840.f, 2160.f, 2.f}, std::tuple{2560.f, 1080.f, 1.f}}) {
    for (bool debugger : {true, false}) {
      const UiLayout l = compute_ui_layout(w, h, scale, debugger);
      std::vector<UiRect> rects{l.controls, l.iteration, l.plots, l.view};
      if (debugger) rects.push_back(l.debugger);
      float area = 0;
      for (std::size_t a = 0; a < rects.size(); ++a) {
        EXPECT_TRUE(rects[a].inside(w, h)) << a << " at " << w << "x" << h;
        EXPECT_GT(rects[a].width, 0);
        area += rects[a].width * rects[a].height;
        for (std::size_t b = a + 1; b < rects.size(); ++b)
          EXPECT_FALSE(rects[a].intersects(rects[b])) << a << " and " << b << " at " << w << "x" << h;
      }
      EXPECT_FLOAT_EQ(area, w * h);  // the panels and the view tile the window
    }
  }
}

TEST(ViewerParts, CameraJsonRoundTripsAndRejectsBadValues) {
  Camera a;
  a.fit({-1, -2, -3}, {1, 2, 3});
  a.orbit(40, -25, 600);
  a.pan(10, 5, 600);
  a.zoom(2);
  Camera b;
  b.from_json(nlohmann::json::parse(a.to_json().dump()));
  EXPECT_EQ(a.to_json(), b.to_json());
  EXPECT_FLOAT_EQ(b.yaw(), a.yaw());

  Camera c = b;
  c.from_json({{"yaw", 10}});  // a subset changes only those keys
  EXPECT_FLOAT_EQ(c.yaw(), 10.0f);
  EXPECT_FLOAT_EQ(c.distance(), b.distance());
  EXPECT_THROW(c.from_json({{"distance", -1}}), std::invalid_argument);
  EXPECT_THROW(c.from_json({{"target", {1, 2}}}), std::invalid_argument);
  EXPECT_THROW(c.from_json({{"zoom", 2}}), std::invalid_argument);
  EXPECT_THROW(c.from_json(nlohmann::json::array()), std::invalid_argument);
  EXPECT_FLOAT_EQ(c.yaw(), 10.0f);  // unchanged by the failures

  a.reset();  // back to the view fit() chose
  Camera fitted;
  fitted.fit({-1, -2, -3}, {1, 2, 3});
  EXPECT_EQ(a.to_json(), fitted.to_json());
}

TEST(ViewerParts, ScriptParsing) {
  std::istringstream ok(
      "step\nstep 3  # three\n\n  run\nrewind 0\nselect-face 7\nshow cells\nhide hull\n"
      "camera {\"yaw\": 1}\nscreenshot out/a b.png\nset point-colors face\n");
  const auto commands = parse_script(ok, "ok.txt");
  ASSERT_EQ(commands.size(), 10u);
  EXPECT_EQ(commands[0].number, 1);
  EXPECT_EQ(commands[1].number, 3);
  EXPECT_EQ(commands[2].kind, ScriptCommand::Kind::kRun);
  EXPECT_EQ(commands[2].where, "ok.txt:4");
  EXPECT_EQ(commands[8].text, "out/a b.png");

  auto error_of = [](const std::string& text) {
    std::istringstream in(text);
    try {
      parse_script(in, "s");
    } catch (const ScriptError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error_of("step -1\n"), HasSubstr("s:1: 'step' needs a count"));
  EXPECT_THAT(error_of("step\nrewind\n"), HasSubstr("s:2: 'rewind' needs"));
  EXPECT_THAT(error_of("run 3\n"), HasSubstr("s:1: 'run' takes no argument"));
  EXPECT_THAT(error_of("camera {yaw}\n"), HasSubstr("s:1: 'camera' needs a JSON object"));
  EXPECT_THAT(error_of("set hull-opacity 2\n"), HasSubstr("s:1: hull-opacity must be a number in [0, 1]"));
  EXPECT_THAT(error_of("screenshot\n"), HasSubstr("s:1: 'screenshot' needs a PNG path"));
}

TEST(ViewerParts, NumberedPaths) {
  EXPECT_EQ(format_numbered_path("a/%d.png", 7), "a/7.png");
  EXPECT_EQ(format_numbered_path("a/s_%03d.png", 7), "a/s_007.png");
  EXPECT_EQ(format_numbered_path("a/plain.png", 7), "a/plain.png");
  EXPECT_EQ(format_numbered_path("100%_%d.png", 2), "100%_2.png");
  EXPECT_FALSE(has_number_field("a/%s.png"));
  EXPECT_TRUE(layer_from_name("wireframe").has_value());
  EXPECT_FALSE(layer_from_name("cell").has_value());
}

}  // namespace
}  // namespace cudahull::viewer
