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

#include "app_window.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/mesh_io.hpp"
#include "options.hpp"
#include "png.hpp"
#include "run_plan.hpp"
#include "session.hpp"
#include "text.hpp"
#include "ui_layout.hpp"
#include "ui_widgets.hpp"

namespace cudahull::viewer {

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

namespace {

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
