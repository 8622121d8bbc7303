// What one viewer holds, windowed or headless: the scene (engine -> render data), the camera, the render
// settings and the selection; it runs script commands and takes screenshots.  The window (app_window.cpp)
// and the headless run (main.cpp) are thin backends around it, as the renderer is around GL.
//
// Contract: construct and use it with the GL context current (it owns the Renderer).  set_scene() fits
// the camera the first time only (so a view pasted or scripted before a reload survives it) unless asked.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "camera.hpp"
#include "cuda_gl_buffer.hpp"
#include "overlay.hpp"
#include "recorder.hpp"
#include "renderer.hpp"
#include "scene.hpp"
#include "script.hpp"

namespace cudahull::viewer {

class Session {
 public:
  Session();
  Scene* scene() { return scene_.get(); }
  void set_scene(std::unique_ptr<Scene> scene, bool fit_camera);

  Camera& camera() { return camera_; }
  void fit_view();  // to the scene's points
  RenderSettings& settings() { return settings_; }
  const Renderer& renderer() const { return renderer_; }
  long long selected_face() const { return selected_face_; }
  void select_face(long long face) { selected_face_ = face; }
  // The face of the current polyhedron under framebuffer pixel (x, y) (origin top left) of a width x height
  // view, or -1: a ray cast from the camera (issue 6, picking a face to inspect its cell).
  long long face_at(double x, double y, int width, int height) const;
  // What is under framebuffer pixel (x, y) of a width x height view (issue 17's hover and click): the
  // nearest drawn point within a few pixels (a hull vertex, an external or an internal point), else the
  // face the ray hits.  `text` is the tooltip: ids, state, the point's face and its signed distance to that
  // face's plane.  Points are searched up to kPickPointLimit of them (a pass over all of them per call).
  struct Pick {
    enum class Kind { kNone, kPoint, kFace } kind = Kind::kNone;
    long long id = -1;
    std::string text;
  };
  static constexpr std::size_t kPickPointLimit = 2000000;
  Pick pick(double x, double y, int width, int height);
  // A click: on a point, its route through the step (explain_point, one line each); on a face, selects it
  // and shows its cell (the cells layer).
  std::vector<std::string> click(double x, double y, int width, int height);

  // Steps or replays to the next position after the current one whose step rejected a swap (Fig. 5);
  // false, staying put, when the run ends without one.
  bool next_rejected();
  // The same for the next step that removed a vertex after complementary swaps (Fig. 4).
  bool next_removal();
  // Points the camera at these input points (a debugger case).
  void frame_points(const std::vector<PointIndex>& points);
  // Frames a case of the current step: "rejected" (its first rejected foldover: the edge and the vertex
  // beneath), "removal" (its first degree-3 removal), or "swap" with `sequence`.  Returns a line that
  // describes the case (for a rejected swap: the vertex beneath, the triangle, and whether a later edit of
  // the step took the edge away), or "" if there is none.
  std::string frame_case(const std::string& what, long long sequence = -1);

  // How per-point state reaches the GL buffer: "CUDA-GL interop" (the CUDA backend writes it on the
  // device, no readback) or "CPU upload (why)".  Decided by set_scene(); allow_interop(false) forces the
  // upload (for comparisons).
  const std::string& upload_path() const { return upload_path_; }
  bool interop_active() const { return scene_ && scene_->device_point_states(); }
  void allow_interop(bool allowed) { interop_allowed_ = allowed; }

  // Uploads what changed and draws into the bound framebuffer, in the width x height rectangle whose
  // bottom left corner is (origin_x, origin_y).  The legend (`set legend on`) is drawn into pictures
  // (screenshots, recordings, headless), not into the window's view, whose panel has it already.
  void draw(int width, int height, float pixel_scale, int origin_x = 0, int origin_y = 0,
            bool window_view = false);
  // Renders the scene offscreen at width x height and writes a PNG atomically; %d in `path` becomes the
  // timeline position.  Returns the path written.  Throws OutputError or DeviceError.
  std::string screenshot(const std::string& path, int width, int height);

  // Recordings (recorder.hpp, issue 17): while one is on, each step, sub-step or jump on the timeline adds
  // one frame (the scene at width x height, as screenshot() renders it); `record start` itself adds none.
  // Throw OutputError.
  void start_recording(const std::string& path, int width, int height);
  std::string stop_recording();  // "wrote PATH (N frames)", or "" when not recording
  bool recording() const { return recorder_ != nullptr; }
  double record_fps = 2.0;  // frames a second in the file
  // A frame if the scene, its position or its sub-step changed since the last one: the window calls it every
  // frame, so that stepping from the keyboard records too.
  void record_if_changed();
  // Steps `count` times or to the end, one frame each while recording.
  void step(int count);
  void run_to_end();

  // Draws `frames` frames offscreen at width x height, waiting for the GPU after the last; returns the
  // milliseconds per frame (upload included where something changed).
  double time_frames(int frames, int width, int height);

  // Runs one script command; screenshots are width x height.  Failures name c.where: ScriptError for a
  // value the parser could not check (a camera value), OutputError for a screenshot that cannot be written.
  // Returns a line for the log, or "".
  std::string execute(const ScriptCommand& c, int width, int height);

 private:
  Renderer renderer_;
  std::unique_ptr<Scene> scene_;
  Camera camera_;
  bool camera_fitted_ = false;
  RenderSettings settings_;
  long long selected_face_ = -1;
  glm::vec3 data_centre_{0.0f};  // the scene's bounding sphere (the depth cue)
  float data_radius_ = 1.0f;
  float data_spacing_ = 0.0f;  // the points' typical spacing (the automatic point size)
  std::unique_ptr<OffscreenTarget> offscreen_;
  bool interop_allowed_ = true;
  std::string upload_path_ = "CPU upload (no scene)";
  std::unique_ptr<CudaGlBuffer> interop_;  // the registered state buffer, while interop is active
  // The overlay as last built, and what it was built for (rebuilt when any of these change).
  struct OverlayKey {
    const Scene* scene = nullptr;
    int position = -1;
    long long selected = -1;
    bool cells = false, normals = false, refinement = false, swaps = false, labels = false;
    int sequence_limit = 0;
    bool operator==(const OverlayKey&) const = default;
  } overlay_key_;
  Overlay overlay_;
  std::unique_ptr<Recorder> recorder_;
  struct RecordedAt {
    const Scene* scene = nullptr;
    int position = -1, substep = -2;
    bool operator==(const RecordedAt&) const = default;
  } recorded_at_;
  RecordedAt now_at() const;
  std::vector<std::uint8_t> render_rgba(int width, int height);
  void update_overlay();
  std::vector<TextLabel> id_labels() const;  // the labels layer: vertex and face ids
  bool next_step_where(const std::function<bool(const IterationRecord&)>& wanted);
  void choose_upload_path();
  void write_device_states(RenderData& data);
};

}  // namespace cudahull::viewer
