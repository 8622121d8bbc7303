// The plots panel: external points and host vs backend time over the iterations (cf. Fig. 9).
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <string>
#include <vector>

#include "app_window.hpp"

namespace cudahull::viewer {

void AppWindow::panel_plots() {
  Scene* scene = session_->scene();
  begin_panel("Over the iterations", layout_.plots);
  if (scene && !load_ && !scene->history().empty()) {
    // Cf. Fig. 9: the points still outside the hull, and where the time goes.
    const auto& h = scene->history();
    std::vector<float> external, host, backend;
    for (const IterationRecord& r : h) {
      external.push_back(static_cast<float>(r.external_after));
      host.push_back(static_cast<float>(r.host_ms));
      backend.push_back(static_cast<float>(r.backend_ms));
    }
    const float height = 70 * ui_scale_;
    const int n = static_cast<int>(h.size());
    ImGui::Text("external points (after each iteration)");
    // Dear ImGui 1.86's plots take their width from the item width, not from a negative size.
    ImGui::PushItemWidth(-FLT_MIN);
    ImGui::PlotLines("##external", external.data(), n, 0, nullptr, 0.0f, FLT_MAX, ImVec2(0, height));
    const float max_ms = std::max(*std::max_element(host.begin(), host.end()),
                                  *std::max_element(backend.begin(), backend.end()));
    // Host and backend time on one scale, overlaid: the host's share should stay small (section 4).
    const ImVec4 host_color(1.0f, 0.75f, 0.3f, 1.0f), backend_color(0.4f, 0.8f, 1.0f, 1.0f);
    ImGui::TextColored(host_color, "host ms");
    ImGui::SameLine();
    ImGui::Text("vs");
    ImGui::SameLine();
    ImGui::TextColored(backend_color, "backend ms");
    const ImVec2 at = ImGui::GetCursorPos();
    ImGui::PushStyleColor(ImGuiCol_PlotLines, backend_color);
    ImGui::PlotLines("##backend", backend.data(), n, 0, nullptr, 0.0f, max_ms, ImVec2(0, 2 * height));
    ImGui::SetCursorPos(at);
    ImGui::PushStyleColor(ImGuiCol_FrameBg, ImVec4(0, 0, 0, 0));
    ImGui::PushStyleColor(ImGuiCol_PlotLines, host_color);
    ImGui::PlotLines("##host", host.data(), n, 0, nullptr, 0.0f, max_ms, ImVec2(0, 2 * height));
    ImGui::PopStyleColor(3);
    ImGui::PopItemWidth();
    ImGui::TextDisabled("at position %d of %d%s", scene->position(), n,
                        scene->final_known() ? "" : " so far");
  } else {
    ImGui::TextDisabled("step to see the plots");
  }
  end_panel();
}

}  // namespace cudahull::viewer
