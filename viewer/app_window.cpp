// The window backend around the session: GLFW (OpenGL 4.5 core, loaded through glad) and Dear ImGui's GLFW
// and OpenGL3 backends from Debian's libimgui.
//
// Features:
//   - orbit (left drag), pan (right or middle drag, or Shift + left), zoom (wheel), fit and reset view,
//     Ctrl-C / Ctrl-V copy and paste the view as JSON through the clipboard;
//   - panels: data (open a path, drag and drop, generate, loading progress), stepping (Step, Run/Pause with a
//     speed, Run to end, Reset, the timeline slider that rewinds by replay), display (layers, sizes,
//     opacities, colour modes), the current IterationRecord, and plots over the iterations of the external
//     points and of host vs backend time (cf. Fig. 9);
//   - a help overlay (F1) listing the keyboard shortcuts;
//   - high-DPI: the UI and point sizes follow the monitor's content scale, drawing uses the framebuffer size
//     queried every frame, so resizing is clean;
//   - --script and --steps/--screenshot play one action per frame (run_plan.hpp); --frames N closes the
//     window N frames after that.
#include <glad/gl.h>
// glad first: GLFW must not pull in the system GL header.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <imgui_internal.h>  // the panels' content extents, for --ui-layout

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/mesh_io.hpp"
#include "export.hpp"
#include "legend.hpp"
#include "options.hpp"
#include "png.hpp"
#include "run_plan.hpp"
#include "session.hpp"
#include "text.hpp"
#include "ui_layout.hpp"

namespace cudahull::viewer {

namespace {

struct Shortcut {
  const char* keys;
  const char* what;
};
constexpr Shortcut kShortcuts[] = {
    {"S, Right", "one step (one iteration of Algorithm 1)"},
    {"Left", "back one step (replays from the start)"},
    {"Space", "run / pause"},
    {"E", "run to the end"},
    {"R", "reset to position 0 (the bare points)"},
    {"1 .. 5", "toggle hull, wireframe, internal, external, vertices"},
    {"C", "points coloured by state / by associated face"},
    {"A", "faces coloured by last step's state / by age"},
    {"F", "fit the view to the data"},
    {"Home", "reset the view"},
    {"Ctrl-C", "copy the view as JSON"},
    {"Ctrl-V", "paste a view (JSON)"},
    {"Left drag", "orbit"},
    {"Right / middle drag, Shift + left drag", "pan"},
    {"Wheel", "zoom"},
    {"Hover", "a point's or face's ids, state, face and signed distance"},
    {"Click", "on a point: its route through the step (Explain point); on a face: its cell (Fig. 2)"},
    {"N", "toggle the edge normals of all faces"},
    {"W", "toggle the last step's swaps (with their sequence numbers) and removals"},
    {"G", "toggle the last step's refinements (parent faces, apexes)"},
    {"J", "jump to the next step with a rejected swap"},
    {"D", "show / hide the debugger panel"},
    {"F1, ?", "this help"},
    {"Ctrl-Q", "quit"},
};

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

// Puts the next item (`width` wide) beside the last one when it fits, else on a new line: rows of buttons
// and checkboxes wrap in a narrow panel instead of running past its edge.
void same_line_if_fits(float width) {
  const float right = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width;
  if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
}

class AppWindow {
 public:
  AppWindow(const ViewerOptions& options, GLFWwindow* window) : o_(options), window_(window) {}
  int run();

 private:
  void start_load(const PointSource& source);
  void poll_load();
  void handle_input();
  void draw_ui();
  void panel_main();
  void panel_record();
  void panel_legend();
  void panel_plots();
  void panel_debugger();
  void help_overlay();
  // Panels are docked where compute_ui_layout() puts them (issue 17): Begin at that rectangle, and End
  // noting what was drawn, for --ui-layout.
  // The 3-d view's rectangle in framebuffer pixels: x and top from the top left (mouse), y from the bottom
  // left (GL).
  struct ViewPixels {
    int x = 0, y = 0, top = 0, width = 1, height = 1;
    double scale_x = 1, scale_y = 1;  // framebuffer pixels per window coordinate
  };
  ViewPixels view_pixels() const;
  bool begin_panel(const char* name, const UiRect& rect, bool* open = nullptr);
  void end_panel();
  void write_ui_layout() const;
  void write_window_png(int fb_w, int fb_h) const;
  void log(const std::string& line);
  void copy_view();
  void paste_view();

  const ViewerOptions& o_;
  GLFWwindow* window_;
  std::unique_ptr<Session> session_;
  std::unique_ptr<BackgroundLoad> load_;
  bool first_load_ = true;
  Scene::BackendFactory backend_;
  std::string backend_note_;
  std::unique_ptr<RunPlan> plan_;
  bool running_ = false;
  float steps_per_second_ = 4.0f;
  double step_credit_ = 0.0;
  bool show_help_ = false;
  std::string status_;  // last message for the UI
  char path_field_[1024] = {};
  int gen_dist_ = 1;  // ball
  int gen_count_ = 20000;
  int gen_seed_ = 1;
  float ui_scale_ = 1.0f;
  float pixel_scale_ = 1.0f;
  std::vector<std::string> pending_drops_;
  bool show_debugger_ = true;
  bool substeps_on_ = false;
  int explain_index_ = 0;
  bool select_explain_tab_ = false;  // a click on a point opens its explanation
  Session::Pick hover_;
  int hover_position_ = -1;
  std::vector<std::string> explanation_;
  char export_path_[1024] = "cudahull_export";
  UiLayout layout_;
  std::vector<PanelReport> panels_drawn_;  // this frame's
  friend void drop_callback(GLFWwindow*, int, const char**);
};

void drop_callback(GLFWwindow* window, int count, const char** paths) {
  auto* app = static_cast<AppWindow*>(glfwGetWindowUserPointer(window));
  if (app != nullptr && count > 0) app->pending_drops_.push_back(paths[0]);
}

void AppWindow::log(const std::string& line) {
  log_line(o_, line);
  status_ = line;
}

void AppWindow::start_load(const PointSource& source) {
  running_ = false;
  load_ = std::make_unique<BackgroundLoad>(source, o_.precision);
  status_ = "loading " + source.label() + " ...";
}

void AppWindow::poll_load() {
  if (!load_ || !load_->ready()) return;
  const PointSource source = load_->source();
  try {
    auto points = load_->take();
    load_.reset();
    session_->set_scene(std::make_unique<Scene>(points, backend_, source.label()), true);
    log(source.label() + ": " + std::to_string(points.positions->size()) + " points; backend " +
        backend_note_ + "; precision " + precision_note(o_.precision, points.precision()) +
        "; per-point state: " + session_->upload_path());
  } catch (const std::exception& e) {
    load_.reset();
    // The input named on the command line fails the run (exit 3, like the CLI); one opened from the UI
    // only says why in the panel.
    if (first_load_) throw;
    log(std::string("cannot open: ") + e.what());
  }
  first_load_ = false;
}

void AppWindow::copy_view() {
  glfwSetClipboardString(window_, session_->camera().to_json().dump().c_str());
  log("view copied to the clipboard");
}

void AppWindow::paste_view() {
  const char* text = glfwGetClipboardString(window_);
  try {
    session_->camera().from_json(nlohmann::json::parse(text ? text : ""));
    log("view pasted");
  } catch (const std::exception& e) {
    log(std::string("paste view: not a camera JSON (") + e.what() + ")");
  }
}

void AppWindow::handle_input() {
  ImGuiIO& io = ImGui::GetIO();
  Scene* scene = session_->scene();
  Camera& camera = session_->camera();
  RenderSettings& s = session_->settings();
  int win_w = 1, win_h = 1;
  glfwGetWindowSize(window_, &win_w, &win_h);

  if (!io.WantCaptureMouse) {
    const float h = static_cast<float>(win_h);
    const bool pan = ImGui::IsMouseDown(ImGuiMouseButton_Right) ||
                     ImGui::IsMouseDown(ImGuiMouseButton_Middle) ||
                     (ImGui::IsMouseDown(ImGuiMouseButton_Left) && io.KeyShift);
    if (io.MouseDelta.x != 0 || io.MouseDelta.y != 0) {
      if (pan) {
        camera.pan(io.MouseDelta.x, io.MouseDelta.y, h);
      } else if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        camera.orbit(io.MouseDelta.x, io.MouseDelta.y, h);
      }
    }
    if (io.MouseWheel != 0) camera.zoom(io.MouseWheel);
    // Hover: a tooltip for the point or face under the mouse (looked up again only when the mouse moves).
    const ViewPixels v = view_pixels();
    const double mx = io.MousePos.x * v.scale_x - v.x, my = io.MousePos.y * v.scale_y - v.top;
    const bool over_view = mx >= 0 && my >= 0 && mx < v.width && my < v.height;
    if (over_view && !ImGui::IsAnyMouseDown() && scene && !load_) {
      if (io.MouseDelta.x != 0 || io.MouseDelta.y != 0 || hover_position_ != scene->position()) {
        hover_ = session_->pick(mx, my, v.width, v.height);
        hover_position_ = scene->position();
      }
      if (hover_.kind != Session::Pick::Kind::kNone) ImGui::SetTooltip("%s", hover_.text.c_str());
    } else if (!over_view) {
      hover_ = {};
    }
    // A click (released without dragging): a point's route in the debugger, or a face's cell.
    if (over_view && scene && !load_ && ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
        io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < 9.0f) {
      const Session::Pick p = session_->pick(mx, my, v.width, v.height);
      const std::vector<std::string> lines = session_->click(mx, my, v.width, v.height);
      if (p.kind == Session::Pick::Kind::kPoint) {
        explain_index_ = static_cast<int>(p.id);
        explanation_.assign(lines.begin() + 1, lines.end());
        show_debugger_ = true;
        select_explain_tab_ = true;
      } else if (!lines.empty()) {
        status_ = lines.front();
      }
    }
    if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
      session_->select_face(session_->face_at(io.MousePos.x * v.scale_x - v.x,
                                              io.MousePos.y * v.scale_y - v.top, v.width, v.height));
    }
  }
  if (io.WantCaptureKeyboard) return;
  auto pressed = [](int key) { return ImGui::IsKeyPressed(key, false); };
  auto pressed_repeat = [](int key) { return ImGui::IsKeyPressed(key, true); };
  if (io.KeyCtrl) {
    if (pressed(GLFW_KEY_C)) copy_view();
    if (pressed(GLFW_KEY_V)) paste_view();
    if (pressed(GLFW_KEY_Q)) glfwSetWindowShouldClose(window_, GLFW_TRUE);
    return;
  }
  if (pressed(GLFW_KEY_F1) || (pressed(GLFW_KEY_SLASH) && io.KeyShift)) show_help_ = !show_help_;
  if (pressed(GLFW_KEY_N)) s.show(Layer::kNormals, !s.shown(Layer::kNormals));
  if (pressed(GLFW_KEY_W)) s.show(Layer::kSwaps, !s.shown(Layer::kSwaps));
  if (pressed(GLFW_KEY_G)) s.show(Layer::kRefinement, !s.shown(Layer::kRefinement));
  if (pressed(GLFW_KEY_J) && !session_->next_rejected()) status_ = "no later step rejects a swap";
  if (pressed(GLFW_KEY_D)) show_debugger_ = !show_debugger_;
  if (pressed(GLFW_KEY_ESCAPE)) show_help_ = false;
  if (pressed(GLFW_KEY_F)) session_->fit_view();
  if (pressed(GLFW_KEY_HOME)) camera.reset();
  const int layer_keys[] = {GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4, GLFW_KEY_5};
  for (int i = 0; i < 5; ++i) {
    if (pressed(layer_keys[i])) s.show(static_cast<Layer>(i), !s.shown(static_cast<Layer>(i)));
  }
  if (pressed(GLFW_KEY_C))
    s.point_colors = s.point_colors == PointColors::kState ? PointColors::kFace : PointColors::kState;
  if (pressed(GLFW_KEY_A))
    s.face_colors = s.face_colors == FaceColors::kState ? FaceColors::kAge : FaceColors::kState;
  if (!scene || load_) return;
  if (pressed_repeat(GLFW_KEY_S) || pressed_repeat(GLFW_KEY_RIGHT)) scene->step();
  if (pressed_repeat(GLFW_KEY_LEFT)) scene->rewind(scene->position() - 1);
  if (pressed(GLFW_KEY_SPACE)) running_ = !running_;
  if (pressed(GLFW_KEY_E)) scene->run_to_end();
  if (pressed(GLFW_KEY_R)) {
    running_ = false;
    scene->reset();
  }
}

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
    int pc = static_cast<int>(s.point_colors);
    ImGui::Text("points:");
    ImGui::SameLine();
    ImGui::RadioButton("state##p", &pc, 0);
    ImGui::SameLine();
    ImGui::RadioButton("face##p", &pc, 1);
    s.point_colors = static_cast<PointColors>(pc);
    int pm = static_cast<int>(s.point_mode);
    ImGui::Text("draw:");
    ImGui::SameLine();
    ImGui::RadioButton("auto##m", &pm, 0);
    ImGui::SameLine();
    ImGui::RadioButton("GL points##m", &pm, 1);
    ImGui::SameLine();
    ImGui::RadioButton("splats##m", &pm, 2);
    s.point_mode = static_cast<PointMode>(pm);
    ImGui::TextDisabled("(now %s)", session_->renderer().uses_splats(s) ? "compute splats" : "GL points");
    int fc = static_cast<int>(s.face_colors);
    ImGui::Text("faces:");
    ImGui::SameLine();
    ImGui::RadioButton("last step##f", &fc, 0);
    ImGui::SameLine();
    ImGui::RadioButton("age##f", &fc, 1);
    s.face_colors = static_cast<FaceColors>(fc);
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
      // Columns as wide as their contents, scrolling sideways where the strip is narrower: nothing cut.
      if (ImGui::BeginTable("swaps", 5,
                            ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_SizingFixedFit,
                            ImVec2(0, 0))) {
        ImGui::TableSetupColumn("#");
        ImGui::TableSetupColumn("kind");
        ImGui::TableSetupColumn("old -> new edge");
        ImGui::TableSetupColumn("why / now");
        ImGui::TableSetupColumn("");
        ImGui::TableHeadersRow();
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
      if (ImGui::BeginTable("decisions", 5,
                            ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("index");
        ImGui::TableSetupColumn("separating plane");
        ImGui::TableSetupColumn("above");
        ImGui::TableSetupColumn("below");
        ImGui::TableSetupColumn("");
        ImGui::TableHeadersRow();
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

void AppWindow::help_overlay() {
  if (!show_help_) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.9f);
  ImGui::Begin(
      "Keyboard and mouse", &show_help_,
      ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
    for (const Shortcut& k : kShortcuts) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(k.keys);
      ImGui::TableSetColumnIndex(1);
      ImGui::TextUnformatted(k.what);
    }
    ImGui::EndTable();
  }
  ImGui::TextDisabled("Esc or F1 closes this");
  ImGui::End();
}

AppWindow::ViewPixels AppWindow::view_pixels() const {
  int fb_w = 1, fb_h = 1, win_w = 1, win_h = 1;
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  glfwGetWindowSize(window_, &win_w, &win_h);
  ViewPixels v;
  v.scale_x = static_cast<double>(fb_w) / std::max(win_w, 1);
  v.scale_y = static_cast<double>(fb_h) / std::max(win_h, 1);
  const UiRect& r = layout_.view;
  v.x = static_cast<int>(std::lround(r.x * v.scale_x));
  v.top = static_cast<int>(std::lround(r.y * v.scale_y));
  v.width = std::max(1, static_cast<int>(std::lround(r.width * v.scale_x)));
  v.height = std::max(1, static_cast<int>(std::lround(r.height * v.scale_y)));
  v.y = std::max(0, fb_h - v.top - v.height);
  return v;
}

bool AppWindow::begin_panel(const char* name, const UiRect& rect, bool* open) {
  ImGui::SetNextWindowPos(ImVec2(rect.x, rect.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(rect.width, rect.height), ImGuiCond_Always);
  return ImGui::Begin(name, open,
                      ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                          ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus);
}

void AppWindow::end_panel() {
  const ImGuiWindow* w = ImGui::GetCurrentWindow();
  PanelReport p;
  p.name = w->Name;
  p.rect = {w->Pos.x, w->Pos.y, w->Size.x, w->Size.y};
  // Content right of the visible area is cut unless the panel scrolls sideways.
  if (!w->ScrollbarX) p.overflow_x = std::max(0.0f, w->DC.CursorMaxPos.x - w->InnerClipRect.Max.x);
  panels_drawn_.push_back(p);
  ImGui::End();
}

void AppWindow::write_ui_layout() const {
  if (o_.ui_layout.empty()) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const std::string text = ui_layout_json(display.x, display.y, layout_.view, panels_drawn_).dump(2) + "\n";
  write_file_atomically(o_.ui_layout, [&](std::ostream& out) { out << text; });
}

void AppWindow::write_window_png(int fb_w, int fb_h) const {
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(fb_w) * fb_h * 4), flipped(pixels.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, fb_w, fb_h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  const std::size_t row = static_cast<std::size_t>(fb_w) * 4;
  for (int y = 0; y < fb_h; ++y)  // GL's first row is the bottom one
    std::copy_n(pixels.data() + (fb_h - 1 - y) * row, row, flipped.data() + y * row);
  write_png(o_.window_screenshot, flipped, fb_w, fb_h);
}

void AppWindow::draw_ui() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  layout_ = compute_ui_layout(display.x, display.y, ui_scale_, show_debugger_ && session_->scene());
  panels_drawn_.clear();
  panel_main();
  panel_record();
  panel_plots();
  panel_debugger();
  help_overlay();
}

int AppWindow::run() {
  glfwSetWindowUserPointer(window_, this);
  glfwSetDropCallback(window_, drop_callback);

  session_ = std::make_unique<Session>();
  session_->allow_interop(!o_.no_interop);
  backend_ = backend_factory(o_.backend, &backend_note_, o_.engine);
  log("window: " + gl_description() + "; text: " + session_->renderer().text_note());
  if (!o_.source.empty()) {
    start_load(o_.source);
  } else {
    first_load_ = false;
  }

  long long frames_after_plan = 0;
  auto last = std::chrono::steady_clock::now();

  while (!glfwWindowShouldClose(window_)) {
    glfwPollEvents();
    poll_load();
    for (const std::string& path : pending_drops_) {
      std::snprintf(path_field_, sizeof path_field_, "%s", path.c_str());
      if (!load_) start_load({path, "", 0, 1});
    }
    pending_drops_.clear();

    int fb_w = 0, fb_h = 0, win_w = 0, win_h = 0;
    glfwGetFramebufferSize(window_, &fb_w, &fb_h);
    glfwGetWindowSize(window_, &win_w, &win_h);
    float scale_x = 1, scale_y = 1;
    glfwGetWindowContentScale(window_, &scale_x, &scale_y);
    pixel_scale_ = std::max(scale_x, 1.0f);
    // ImGui works in window coordinates; where those are already scaled (macOS), it must not scale twice.
    ui_scale_ =
        std::max(1.0f, pixel_scale_ * (win_w > 0 ? static_cast<float>(win_w) / std::max(fb_w, 1) : 1.0f));

    // The command-line plan, one action per frame once the data is in; its screenshots have the size the
    // framebuffer has when it starts.
    const bool waiting = load_ != nullptr || first_load_;
    if (!plan_ && !waiting && fb_w > 0 && fb_h > 0) {
      plan_ = std::make_unique<RunPlan>(PlanOptions{o_.steps, o_.script, o_.screenshot, fb_w, fb_h});
      session_->record_fps = o_.record_fps;
      if (!o_.record.empty()) session_->start_recording(o_.record, fb_w, fb_h);
    }
    if (plan_ && !plan_->finished()) {
      std::string line;
      plan_->next(*session_, line);
      if (!line.empty()) log(line);
    } else if (plan_ && o_.frames && ++frames_after_plan > *o_.frames) {
      glfwSetWindowShouldClose(window_, GLFW_TRUE);
    }

    // Run: steps at the chosen rate, at most one replay-free step per frame.
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    Scene* scene = session_->scene();
    if (running_ && scene && !load_) {
      step_credit_ = std::min(step_credit_ + dt * steps_per_second_, 1.0);
      if (step_credit_ >= 1.0) {
        step_credit_ -= 1.0;
        scene->step();
      }
      if (scene->done()) running_ = false;
    }

    session_->record_if_changed();  // steps from the keyboard and the Run button too

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handle_input();
    draw_ui();
    ImGui::Render();

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (fb_w > 0 && fb_h > 0) {  // minimised: nothing to draw into
      // The scene in the view the panels leave free; the panels around it on the background.
      glDisable(GL_SCISSOR_TEST);
      const glm::vec3 b = session_->settings().background;
      glClearColor(b.r, b.g, b.b, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT);
      const ViewPixels v = view_pixels();
      session_->draw(v.width, v.height, pixel_scale_, v.x, v.y, true);
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      // The last frame, panels and all (--window-screenshot: the docs' pictures of the layout).
      if (glfwWindowShouldClose(window_) && !o_.window_screenshot.empty()) write_window_png(fb_w, fb_h);
    }
    glfwSwapBuffers(window_);
  }
  log(session_->stop_recording());
  write_ui_layout();  // the last frame's panels
  session_.reset();   // GL objects go while the context is alive
  return kExitOk;
}

void glfw_error(int code, const char* what) {
  std::fprintf(stderr, "cudahull-viewer: GLFW %d: %s\n", code, what);
}

}  // namespace

int run_window(const ViewerOptions& o) {
  glfwSetErrorCallback(o.quiet ? nullptr : glfw_error);
  if (!glfwInit())
    throw DeviceError("no window system (no display?); use --headless for offscreen rendering");
  struct GlfwGuard {
    ~GlfwGuard() { glfwTerminate(); }
  } glfw_guard;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);  // high-DPI: the window grows with the content scale
  glfwWindowHint(GLFW_SAMPLES, 4);
  GLFWwindow* window = glfwCreateWindow(o.width, o.height, "cudahull-viewer", nullptr, nullptr);
  if (window == nullptr) throw DeviceError("cannot open a window with an OpenGL 4.5 core context");
  struct WindowGuard {
    GLFWwindow* w;
    ~WindowGuard() { glfwDestroyWindow(w); }
  } window_guard{window};
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  if (gladLoadGL(glfwGetProcAddress) == 0) throw DeviceError("cannot load the OpenGL 4.5 functions");

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  struct ImGuiGuard {
    ~ImGuiGuard() { ImGui::DestroyContext(); }
  } imgui_guard;
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini left in whatever folder the viewer ran from
  ImGui::StyleColorsDark();
  float scale_x = 1, scale_y = 1;
  glfwGetWindowContentScale(window, &scale_x, &scale_y);
  int win_w = 1, fb_w = 1, h = 1;
  glfwGetWindowSize(window, &win_w, &h);
  glfwGetFramebufferSize(window, &fb_w, &h);
  const float ui_scale = std::max(1.0f, scale_x * static_cast<float>(win_w) / std::max(fb_w, 1));
  ImGui::GetStyle().ScaleAllSizes(ui_scale);
  // The panels in the picture's font (DejaVu Sans) where it is installed, else Dear ImGui's own.
  const std::string font_path = viewer_font_path();
  if (std::FILE* f = std::fopen(font_path.c_str(), "rb"); f != nullptr) {
    std::fclose(f);
    io.Fonts->AddFontFromFileTTF(font_path.c_str(), 14.0f * ui_scale);
  } else {
    ImFontConfig font;
    font.SizePixels = 13.0f * ui_scale;
    io.Fonts->AddFontDefault(&font);
  }
  if (!ImGui_ImplGlfw_InitForOpenGL(window, true) || !ImGui_ImplOpenGL3_Init("#version 450 core"))
    throw DeviceError("Dear ImGui cannot initialise its GLFW or OpenGL backend");
  struct BackendGuard {
    ~BackendGuard() {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
    }
  } backend_guard;

  AppWindow app(o, window);
  return app.run();
}

}  // namespace cudahull::viewer
