// The record panel: the current step's IterationRecord.
#include <imgui.h>

#include <cstdio>
#include <string>
#include <vector>

#include "app_window.hpp"
#include "ui_widgets.hpp"

namespace cudahull::viewer {

void AppWindow::panel_record() {
  Scene* scene = session_->scene();
  begin_panel("Iteration", layout_.iteration);
  const IterationRecord* r = scene && !load_ ? scene->current_record() : nullptr;
  if (r == nullptr) {
    ImGui::TextDisabled("no step taken yet");
  } else if (ImGui::BeginTable("record", 2, ImGuiTableFlags_RowBg)) {
    // The names' column as wide as the longest name, the values wrapped in the rest: nothing is cut.
    ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthFixed,
                            ImGui::CalcTextSize("swaps complementary").x);
    ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch);
    auto row = [](const char* name, const std::string& value) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(name);
      ImGui::TableSetColumnIndex(1);
      ImGui::TextWrapped("%s", value.c_str());
    };
    auto num = [](double x) {
      char s[32];
      std::snprintf(s, sizeof s, "%.3f", x);
      return std::string(s);
    };
    row("iteration", std::to_string(r->iteration));
    row("faces", std::to_string(r->faces_before) + " -> " + std::to_string(r->faces_after));
    row("refined", std::to_string(r->faces_refined));
    row("swaps regular", std::to_string(r->swaps_regular));
    row("swaps complementary", std::to_string(r->swaps_complementary));
    row("swaps rejected", std::to_string(r->swaps_rejected));
    row("vertices removed", std::to_string(r->vertices_removed));
    row("removals rejected", std::to_string(r->removals_rejected));
    row("decision entries", std::to_string(r->decision_entries));
    row("external", std::to_string(r->external_before) + " -> " + std::to_string(r->external_after));
    row("repairs", std::to_string(r->repairs));
    row("host ms", num(r->host_ms));
    row("backend ms", num(r->backend_ms));
    row("to backend", format_bytes(r->bytes_to_backend));
    row("from backend", format_bytes(r->bytes_from_backend));
    row("per-point upload",
        format_bytes(session_->renderer().last_point_upload_bytes()) + " (" + session_->upload_path() + ")");
    if (session_->selected_face() >= 0) row("selected face", std::to_string(session_->selected_face()));
    ImGui::EndTable();
    if (!r->note.empty()) ImGui::TextWrapped("%s", r->note.c_str());
  }
  end_panel();
}

}  // namespace cudahull::viewer
