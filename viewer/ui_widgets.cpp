#include "ui_widgets.hpp"

#include <imgui.h>

#include <cstdio>

namespace cudahull::viewer {

std::string format_bytes(std::uint64_t b) {
  char s[32];
  if (b >= (1u << 20)) {
    std::snprintf(s, sizeof s, "%.1f MiB", b / 1048576.0);
  } else if (b >= 1024) {
    std::snprintf(s, sizeof s, "%.1f KiB", b / 1024.0);
  } else {
    std::snprintf(s, sizeof s, "%llu B", static_cast<unsigned long long>(b));
  }
  return s;
}

float button_width(const char* label) {
  return ImGui::CalcTextSize(label, nullptr, true).x + 2 * ImGui::GetStyle().FramePadding.x;
}

float checkbox_width(const char* label) {
  return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
         ImGui::CalcTextSize(label, nullptr, true).x;
}

void same_line_if_fits(float width) {
  const float right = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width;
  if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
}

}  // namespace cudahull::viewer
