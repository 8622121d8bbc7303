#include "ui_layout.hpp"

#include <algorithm>
#include <cmath>

namespace cudahull::viewer {

UiLayout compute_ui_layout(float window_width, float window_height, float scale, bool show_debugger) {
  const float w = std::max(window_width, 1.0f), h = std::max(window_height, 1.0f);
  // The side columns take a share of the width, between what their widest rows need (at 1280 wide) and
  // what keeps the view large (at 1920); on a window too narrow for both, they split it.
  float left = std::clamp(0.27f * w, 340.0f * scale, 470.0f * scale);
  float right = std::clamp(0.25f * w, 320.0f * scale, 460.0f * scale);
  if (left + right > 0.8f * w) {
    left = 0.45f * w;
    right = 0.35f * w;
  }
  // Whole pixels, as Dear ImGui places windows: neighbours then share an edge exactly.
  left = std::floor(left);
  right = std::floor(right);
  UiLayout l;
  l.controls = {0, 0, left, h};
  const float iteration_height = std::round(0.56f * h);
  l.iteration = {w - right, 0, right, iteration_height};
  l.plots = {w - right, iteration_height, right, h - iteration_height};
  const float middle = w - left - right;
  const float debugger_height =
      show_debugger ? std::round(std::clamp(0.4f * h, 200.0f * scale, 480.0f * scale)) : 0.0f;
  l.debugger = {left, h - debugger_height, middle, debugger_height};
  l.view = {left, 0, middle, h - debugger_height};
  return l;
}

nlohmann::json ui_layout_json(float window_width, float window_height, const UiRect& view,
                              const std::vector<PanelReport>& panels) {
  auto rect = [](const UiRect& r) {
    return nlohmann::json{{"x", r.x}, {"y", r.y}, {"width", r.width}, {"height", r.height}};
  };
  nlohmann::json out{{"window", {{"width", window_width}, {"height", window_height}}}, {"view", rect(view)}};
  out["panels"] = nlohmann::json::array();
  for (const PanelReport& p : panels) {
    nlohmann::json j = rect(p.rect);
    j["name"] = p.name;
    j["overflow_x"] = p.overflow_x;
    out["panels"].push_back(j);
  }
  return out;
}

}  // namespace cudahull::viewer
