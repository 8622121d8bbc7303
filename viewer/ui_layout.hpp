// The window's panels, docked to its edges and sized from it (issue 17): no panel floats over another or
// over the 3-d view, and a resize moves them all.  Pure arithmetic, so tests can check it without a window.
//
//   +-----------+----------------------+-----------+
//   |           |                      | Iteration |
//   | cudahull  |      the 3-d view    |           |
//   | (controls)|                      +-----------+
//   |           +----------------------+ Over the  |
//   |           |      Debugger        | iterations|
//   +-----------+----------------------+-----------+
//
// The Debugger strip exists only while the debugger is shown; the 3-d view then takes its place.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cudahull::viewer {

struct UiRect {
  float x = 0, y = 0, width = 0, height = 0;  // logical pixels, origin top left
  bool intersects(const UiRect& o) const {
    return x < o.x + o.width && o.x < x + width && y < o.y + o.height && o.y < y + height;
  }
  bool inside(float window_width, float window_height) const {
    return x >= 0 && y >= 0 && x + width <= window_width && y + height <= window_height;
  }
};

struct UiLayout {
  UiRect controls, iteration, plots, debugger;  // debugger: zero size when hidden
  UiRect view;                                  // what is left for the 3-d view
};

// `scale` is the UI scale (1 on an ordinary screen; the content scale on a high-DPI one).
UiLayout compute_ui_layout(float window_width, float window_height, float scale, bool show_debugger);

// One panel as drawn: its rectangle, and how far its content reached to the right of what it shows (> 0:
// something is cut at the panel's right edge).
struct PanelReport {
  std::string name;
  UiRect rect;
  float overflow_x = 0;
};
// {"window": {"width", "height"}, "view": {...}, "panels": [{"name", "x", "y", "width", "height",
// "overflow_x"}]}: what `--ui-layout FILE` writes.
nlohmann::json ui_layout_json(float window_width, float window_height, const UiRect& view,
                              const std::vector<PanelReport>& panels);

}  // namespace cudahull::viewer
