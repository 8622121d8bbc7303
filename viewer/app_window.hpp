// The viewer's window (app_window.cpp): the session behind GLFW and Dear ImGui, its input, its docked
// panels and its frame loop.  Each panel draws itself in a file of its own under panels/, as Polyscope
// builds its UI per structure; they share this class's state.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "options.hpp"
#include "run_plan.hpp"
#include "session.hpp"
#include "ui_layout.hpp"

struct GLFWwindow;

namespace cudahull::viewer {

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

}  // namespace cudahull::viewer
