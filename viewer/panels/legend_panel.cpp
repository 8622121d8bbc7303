// The legend panel: what each colour means.
#include <imgui.h>

#include <string>
#include <vector>

#include "app_window.hpp"
#include "legend.hpp"

namespace cudahull::viewer {

// The colour key of the layers shown (legend.hpp; the same list `set legend on` draws into pictures).
void AppWindow::panel_legend() {
  RenderSettings& s = session_->settings();
  ImGui::Checkbox("draw it into screenshots and recordings", &s.legend);
  std::string group;
  for (const LegendEntry& e : legend_entries(s, session_->selected_face() >= 0)) {
    if (e.group != group) {
      group = e.group;
      ImGui::TextDisabled("%s", group.c_str());
    }
    ImGui::ColorButton(e.name.c_str(), ImVec4(e.color.r, e.color.g, e.color.b, 1),
                       ImGuiColorEditFlags_NoTooltip, ImVec2(12 * ui_scale_, 12 * ui_scale_));
    ImGui::SameLine();
    ImGui::TextWrapped("%s", e.name.c_str());
  }
}

}  // namespace cudahull::viewer
