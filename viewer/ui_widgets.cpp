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

int radio_row(const char* label, int value, std::initializer_list<const char*> choices) {
  ImGui::Text("%s", label);
  int i = 0;
  for (const char* choice : choices) {
    ImGui::SameLine();
    ImGui::RadioButton(choice, &value, i++);
  }
  return value;
}

bool begin_table_with_headers(const char* id, std::initializer_list<const char*> columns) {
  // Columns as wide as their contents, scrolling sideways where the strip is narrower: nothing cut.
  if (!ImGui::BeginTable(id, static_cast<int>(columns.size()),
                         ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_RowBg |
                             ImGuiTableFlags_SizingFixedFit))
    return false;
  for (const char* column : columns)
    ImGui::TableSetupColumn(column);
  ImGui::TableHeadersRow();
  return true;
}

}  // namespace cudahull::viewer
