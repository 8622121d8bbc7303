// The main panel: data (open, drop, generate, loading), stepping, display and export.
#include <imgui.h>

#include <algorithm>
#include <string>
#include <vector>

#include "app_window.hpp"
#include "cudahull/generators.hpp"
#include "ui_widgets.hpp"

namespace cudahull::viewer {

void AppWindow::panel_main() {
  begin_panel("cudahull", layout_.controls);
  // Sliders and fields take the panel's width less their labels, so no label runs past the edge.
  ImGui::PushItemWidth(-ImGui::CalcTextSize("point opacity").x - ImGui::GetStyle().ItemInnerSpacing.x * 2);
  Scene* scene = session_->scene();
  RenderSettings& s = session_->settings();

  // The path that per-point state takes to the GL buffer (issue 5, item 3), said in the UI and the log.
  ImGui::TextWrapped("Per-point state: %s", session_->upload_path().c_str());
  if (session_->scene())
    ImGui::TextWrapped("Per-point bytes read back: %s",
                       format_bytes(session_->scene()->point_readback_bytes()).c_str());
  ImGui::TextWrapped("Backend: %s", backend_note_.c_str());
  ImGui::TextWrapped("Precision: %s", scene ? precision_note(o_.precision, scene->precision()).c_str()
                                            : precision_name(o_.precision));
  ImGui::Text("%.0f fps", static_cast<double>(ImGui::GetIO().Framerate));

  if (ImGui::CollapsingHeader("Data", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::InputText("##path", path_field_, sizeof path_field_);
    ImGui::SameLine();
    if (ImGui::Button("Open") && path_field_[0] != '\0' && !load_) start_load({path_field_, "", 0, 1});
    ImGui::TextDisabled("or drop a file on the window");
    const std::vector<std::string> names = distribution_names();
    std::vector<const char*> items;
    for (const auto& n : names)
      items.push_back(n.c_str());
    ImGui::Combo("distribution", &gen_dist_, items.data(), static_cast<int>(items.size()));
    ImGui::InputInt("N", &gen_count_, 1000, 100000);
    gen_count_ = std::clamp(gen_count_, 4, 200000000);
    ImGui::InputInt("seed", &gen_seed_);
    if (ImGui::Button("Generate") && !load_)
      start_load({"", names[gen_dist_], static_cast<std::uint64_t>(gen_count_),
                  static_cast<std::uint64_t>(gen_seed_)});
    if (load_) {
      const double p = load_->progress();
      if (p >= 0) {
        ImGui::ProgressBar(static_cast<float>(p), ImVec2(-1, 0),
                           ("loading " + load_->source().label()).c_str());
      } else {
        ImGui::Text("loading %s ...", load_->source().label().c_str());
      }
    } else if (scene) {
      ImGui::TextWrapped("%s: %zu points", scene->label().c_str(), scene->points().size());
    }
  }

  if (ImGui::CollapsingHeader("Steps", ImGuiTreeNodeFlags_DefaultOpen) && scene && !load_) {
    if (ImGui::Button("Step")) scene->step();
    same_line_if_fits(button_width("Pause"));
    if (ImGui::Button(running_ ? "Pause" : "Run")) running_ = !running_;
    same_line_if_fits(button_width("Run to end"));
    if (ImGui::Button("Run to end")) scene->run_to_end();
    same_line_if_fits(button_width("Reset"));
    if (ImGui::Button("Reset")) {
      running_ = false;
      scene->reset();
    }
    ImGui::SliderFloat("steps/s", &steps_per_second_, 0.25f, 60.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    int position = scene->position();
    const int end = std::max(scene->known_end(), position);
    // Rewinding replays from the start (scene.hpp); forward positions already seen step on.
    if (ImGui::SliderInt("timeline", &position, 0, std::max(end, 1),
                         scene->final_known() ? "%d (end known)" : "%d"))
      scene->rewind(position);
    ImGui::TextWrapped("position %d%s", scene->position(), scene->done() ? ": done, the exact hull" : "");
    // Sub-steps (teaching): the step's phases one by one, built by replay when first asked for.
    if (ImGui::Checkbox("sub-steps", &substeps_on_)) scene->set_substep(substeps_on_ ? 0 : -1);
    if (substeps_on_) {
      const int count = scene->substep_count();
      if (count == 0) {
        ImGui::TextDisabled("no sub-steps at position 0 or 1");
      } else {
        int phase = scene->substep() < 0 ? count - 1 : scene->substep();
        if (ImGui::SliderInt("phase", &phase, 0, count - 1)) scene->set_substep(phase);
        ImGui::TextWrapped("%s", scene->substep_label(phase).c_str());
      }
    }
  }

  if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (int i = 0; i < kLayerCount; ++i) {
      const Layer layer = static_cast<Layer>(i);
      bool on = s.shown(layer);
      if (i > 0) same_line_if_fits(checkbox_width(layer_name(layer)));
      if (ImGui::Checkbox(layer_name(layer), &on)) s.show(layer, on);
    }
    ImGui::Checkbox("auto##size", &s.point_size_auto);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("points as large as their spacing on the screen (no moire)");
    ImGui::SameLine();
    if (ImGui::SliderFloat("point size", &s.point_size, 1.0f, 16.0f, s.point_size_auto ? "auto" : "%.1f"))
      s.point_size_auto = false;
    ImGui::SliderFloat("point opacity", &s.point_opacity, 0.05f, 1.0f, "%.2f");
    ImGui::SliderFloat("hull opacity", &s.hull_opacity, 0.0f, 1.0f, "%.2f");
    ImGui::SliderFloat("wire width", &s.wire_width, 0.5f, 4.0f, "%.1f");
    s.point_colors = static_cast<PointColors>(
        radio_row("points:", static_cast<int>(s.point_colors), {"state##p", "face##p"}));
    s.point_mode = static_cast<PointMode>(
        radio_row("draw:", static_cast<int>(s.point_mode), {"auto##m", "GL points##m", "splats##m"}));
    ImGui::TextDisabled("(now %s)", session_->renderer().uses_splats(s) ? "compute splats" : "GL points");
    s.face_colors = static_cast<FaceColors>(
        radio_row("faces:", static_cast<int>(s.face_colors), {"last step##f", "age##f"}));
    // Fig. 2: a face's cell.  Double-click a face, or type its id.
    int face = static_cast<int>(session_->selected_face());
    ImGui::SetNextItemWidth(120);
    if (ImGui::InputInt("selected face", &face)) session_->select_face(std::max(face, -1));
    ImGui::SameLine();
    if (ImGui::Button("Clear")) session_->select_face(-1);
    if (scene && session_->selected_face() >= 0 && scene->position() > 0 &&
        session_->selected_face() < static_cast<long long>(scene->engine().face_extremes().size())) {
      const auto f = static_cast<FaceId>(session_->selected_face());
      const FaceExtreme& x = scene->engine().face_extremes()[f];
      const MeshFace& mf = scene->engine().mesh().face(f);
      ImGui::TextWrapped("vertices %u %u %u; %u external points", mf.v[0], mf.v[1], mf.v[2], x.count);
      if (x.count > 0) ImGui::TextWrapped("extreme point %u (the next apex)", x.furthest);
      const FaceCell cell = scene->engine().face_cell(f);
      for (int i = 0; i < 3; ++i) {
        const SeparatingPlane& p = cell.edge_plane[i];
        ImGui::TextWrapped("plane %d: (%.3f, %.3f, %.3f) . x + %.4g", i, p.nx, p.ny, p.nz, p.d);
      }
    }
    if (ImGui::Button("Fit view")) session_->fit_view();
    same_line_if_fits(button_width("Reset view"));
    if (ImGui::Button("Reset view")) session_->camera().reset();
    same_line_if_fits(button_width("Copy view"));
    if (ImGui::Button("Copy view")) copy_view();
    same_line_if_fits(button_width("Paste view"));
    if (ImGui::Button("Paste view")) paste_view();
  }
  if (ImGui::CollapsingHeader("Legend", ImGuiTreeNodeFlags_DefaultOpen)) panel_legend();
  if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
  ImGui::TextDisabled("F1: keyboard shortcuts");
  ImGui::PopItemWidth();
  end_panel();
}

}  // namespace cudahull::viewer
