// The debugger panel: the last step's swaps (the rejected ones with their reasons, Fig. 5), its decision
// array (Fig. 7), a point's route explained, and the exports.
#include <glad/gl.h>
// glad first: GLFW must not pull in the system GL header.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <string>
#include <vector>

#include "app_window.hpp"
#include "export.hpp"
#include "ui_widgets.hpp"

namespace cudahull::viewer {

// Issue 6: the last step's swaps (with the rejected ones and their reasons, Fig. 5), its decision array
// (Fig. 7), and the exports.
void AppWindow::panel_debugger() {
  Scene* scene = session_->scene();
  if (!scene || !show_debugger_) return;
  if (!begin_panel("Debugger", layout_.debugger, &show_debugger_)) {
    end_panel();
    return;
  }
  if (ImGui::Button("Next step with a rejected swap")) {
    if (!session_->next_rejected()) status_ = "no later step rejects a swap";
  }
  const IterationRecord* r = scene->current_record();
  if (r == nullptr) {
    ImGui::TextDisabled("step once to see the swaps and the decision array");
    end_panel();
    return;
  }
  RenderSettings& s = session_->settings();
  if (ImGui::BeginTabBar("debugger")) {
    if (ImGui::BeginTabItem("Swaps")) {
      bool on = s.shown(Layer::kSwaps);
      if (ImGui::Checkbox("draw them (swaps layer)", &on)) s.show(Layer::kSwaps, on);
      ImGui::SameLine();
      on = s.shown(Layer::kRefinement);
      if (ImGui::Checkbox("refinement layer", &on)) s.show(Layer::kRefinement, on);
      static bool rejected_only = false;
      ImGui::Checkbox("rejected only", &rejected_only);
      if (begin_table_with_headers("swaps", {"#", "kind", "old -> new edge", "why / now", ""})) {
        const Mesh& mesh = scene->engine().mesh();
        for (const SwapRecord& w : r->swaps) {
          const bool done = w.kind == SwapKind::kRegular || w.kind == SwapKind::kComplementary;
          if (rejected_only && done) continue;
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          ImGui::Text("%d", w.sequence);
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(swap_kind_name(w.kind));
          ImGui::TableNextColumn();
          ImGui::Text("%u-%u -> %u-%u", w.old_edge[0], w.old_edge[1], w.new_edge[0], w.new_edge[1]);
          ImGui::TableNextColumn();
          if (done) {
            ImGui::Text("entry %d", w.decision_index);
          } else {
            // Resolved when a later swap or removal of the step took the old edge away.
            const bool gone = !mesh.has_vertex(w.old_edge[0]) || !mesh.adjacent(w.old_edge[0], w.old_edge[1]);
            if (w.beneath_vertex != kNoPoint) {
              ImGui::Text("%u beneath (%u,%u,%u); %s", w.beneath_vertex, w.beneath_triangle[0],
                          w.beneath_triangle[1], w.beneath_triangle[2],
                          gone ? "resolved later" : "edge still there");
              // The short form in the cell, the sentence on hover.
              if (ImGui::IsItemHovered())
                ImGui::SetTooltip(
                    "swapping %u-%u for %u-%u would put vertex %u beneath the new triangle (%u, %u, %u): the "
                    "surface would fold over.\n%s",
                    w.old_edge[0], w.old_edge[1], w.new_edge[0], w.new_edge[1], w.beneath_vertex,
                    w.beneath_triangle[0], w.beneath_triangle[1], w.beneath_triangle[2],
                    gone ? "A later swap or removal of this step took the edge away."
                         : "The edge is still there after the step.");
            } else {
              ImGui::Text("%s", gone ? "resolved later" : "edge still there");
              if (ImGui::IsItemHovered())
                ImGui::SetTooltip("%s",
                                  w.kind == SwapKind::kRejectedEdgeExists
                                      ? "rejected: the new edge is already an edge of the mesh"
                                      : "rejected: the four points are coplanar seen from the interior");
            }
          }
          ImGui::TableNextColumn();
          ImGui::PushID(w.sequence);
          if (ImGui::SmallButton("Frame")) {
            if (w.beneath_vertex != kNoPoint) {
              session_->frame_points(
                  {w.old_edge[0], w.old_edge[1], w.new_edge[0], w.new_edge[1], w.beneath_vertex});
            } else {
              session_->frame_points({w.old_edge[0], w.old_edge[1], w.new_edge[0], w.new_edge[1]});
            }
            s.show(Layer::kSwaps, true);
          }
          ImGui::PopID();
        }
        ImGui::EndTable();
      }
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Decision array")) {
      ImGui::TextDisabled(
          "Fig. 7: a point of a swapped face goes 'above' or 'below' the plane; codes >= 0 are faces");
      if (begin_table_with_headers("decisions", {"index", "separating plane", "above", "below", ""})) {
        auto code = [](std::int32_t c) {
          return c == kRouteInternal ? std::string("internal")
                 : c < 0             ? "entry " + std::to_string(-c - 1)
                                     : "face " + std::to_string(c);
        };
        ImGuiListClipper clipper;
        clipper.Begin(static_cast<int>(r->decisions.size()));
        while (clipper.Step()) {
          for (int k = clipper.DisplayStart; k < clipper.DisplayEnd; ++k) {
            const DecisionEntry& d = r->decisions[k];
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%d", k);
            ImGui::TableNextColumn();
            if (d.kind == kDecisionSwap) {
              ImGui::Text("(%.3f, %.3f, %.3f) . x + %.4g", d.plane.nx, d.plane.ny, d.plane.nz, d.plane.d);
              if (ImGui::IsItemHovered())  // the digits the cell rounds away
                ImGui::SetTooltip("(%.17g, %.17g, %.17g) . x + %.17g", d.plane.nx, d.plane.ny, d.plane.nz,
                                  d.plane.d);
            } else {
              ImGui::TextUnformatted("removal");
            }
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(code(d.above).c_str());
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(d.kind == kDecisionSwap ? code(d.below).c_str() : "");
            ImGui::TableNextColumn();
            ImGui::PushID(k);
            if (ImGui::SmallButton("Frame")) {
              for (const SwapRecord& w : r->swaps) {
                if (w.decision_index == k)
                  session_->frame_points({w.new_edge[0], w.new_edge[1], w.old_edge[0], w.old_edge[1]});
              }
              for (const RemovalRecord& m : r->removals) {
                if (m.decision_index == k)
                  session_->frame_points({m.vertex, m.ring[0], m.ring[1], m.ring[2]});
              }
            }
            ImGui::PopID();
          }
        }
        ImGui::EndTable();
      }
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Explain point", nullptr,
                            select_explain_tab_ ? ImGuiTabItemFlags_SetSelected : ImGuiTabItemFlags_None)) {
      select_explain_tab_ = false;
      // A point's path through this step's refinement[] and decision[] (Fig. 7) to its new face.
      ImGui::SetNextItemWidth(160);
      ImGui::InputInt("point index", &explain_index_);
      ImGui::SameLine();
      if (ImGui::Button("Explain") && explain_index_ >= 0)
        explanation_ = scene->explain_point(static_cast<PointIndex>(explain_index_));
      for (const std::string& line : explanation_)
        ImGui::TextWrapped("%s", line.c_str());
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Export")) {
      ImGui::InputText("base path", export_path_, sizeof export_path_);
      const std::string base = export_path_;
      auto attempt = [&](const char* what, const std::function<void()>& write) {
        try {
          write();
          status_ = std::string("wrote ") + what;
        } catch (const std::exception& e) {
          status_ = e.what();
        }
      };
      if (ImGui::Button("Mesh (.obj)")) attempt("the mesh", [&] { export_mesh(*scene, base + ".obj"); });
      ImGui::SameLine();
      if (ImGui::Button("Trace (.jsonl)"))
        attempt("the trace", [&] { export_trace(*scene, base + ".jsonl"); });
      ImGui::SameLine();
      if (ImGui::Button("Decisions (.csv)"))
        attempt("the decisions", [&] { export_decisions(*scene, base + ".csv"); });
      ImGui::SameLine();
      if (ImGui::Button("Screenshot (.png)")) {
        int fb_w = 1, fb_h = 1;
        glfwGetFramebufferSize(window_, &fb_w, &fb_h);
        attempt("the screenshot", [&] { session_->screenshot(base + ".png", fb_w, fb_h); });
      }
      // A clip of what happens from now on: one frame per step or sub-step (the view's size).
      if (!session_->recording()) {
        const char* extension = nullptr;
        if (ImGui::Button("Record (.mp4)")) extension = ".mp4";
        same_line_if_fits(button_width("Record (.gif)"));
        if (ImGui::Button("Record (.gif)")) extension = ".gif";
        if (extension != nullptr) {
          const ViewPixels v = view_pixels();
          attempt("nothing yet: recording",
                  [&] { session_->start_recording(base + extension, v.width, v.height); });
        }
      } else if (ImGui::Button("Stop recording")) {
        try {
          status_ = session_->stop_recording();
        } catch (const std::exception& e) {
          status_ = e.what();
        }
      }
      if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  end_panel();
}

}  // namespace cudahull::viewer
