// The renderer: plain OpenGL 4.5 core on whatever context is current (README, "Layout"); it knows
// nothing of GLFW, EGL or the engine.
//
// Draws (cf. the paper's Figs. 1 and 10):
//   - the point cloud, coloured by state (internal red, external brown) or by associated face;
//   - the hull vertices, highlighted;
//   - the current polyhedron, shaded faces coloured by what the last iteration did to them (refined,
//     swapped, made by a vertex removal, unchanged) or by age, plus a wireframe;
//   - layers toggled by name: hull, wireframe, internal, external, vertices (cells and swaps are reserved
//     for the debugger views of issue 6 and draw nothing yet).
//
// Contract: construct, use and destroy it with the same context current and glad loaded.  upload() copies
// what RenderData's dirty bits name into GL buffers and clears those bits; draw() renders into the bound
// framebuffer.  The per-point state lives in one GL buffer, point_state_buffer(): an int32 per point, laid
// out as render_data.hpp says; the CUDA backend can register it with cudaGraphicsGLRegisterBuffer and write
// it after each step (then leave kDirtyPointState clear: upload() would overwrite it).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "render_data.hpp"

namespace cudahull::viewer {

class TextRenderer;
// Compiles and links a vertex + fragment program of the embedded shaders (colors.glsl prepended); throws
// DeviceError with the driver's log.
unsigned link_program(const char* vertex, const char* fragment, const char* name);

// kCells: the selected face's separating planes, cell points and extreme point (Fig. 2); kSwaps: the last
// step's swaps, rejected swaps and removals (Figs. 3b, 4, 5); kNormals: every edge's normal (the average of
// its faces' normals, which the separating plane contains) as an arrow; kRefinement: the last step's
// refined faces, their apexes and the edges to them (Fig. 3a).
enum class Layer {
  kHull,
  kWireframe,
  kInternal,
  kExternal,
  kVertices,
  kCells,
  kSwaps,
  kNormals,
  kRefinement,
  kLabels,  // the hull's vertex ids and face ids, in the font (text.hpp)
  kInput,   // the input model's own surface (input_surface.hpp), lit, grey, half transparent
};
inline constexpr int kLayerCount = 11;
const char* layer_name(Layer layer);
std::optional<Layer> layer_from_name(std::string_view name);
std::string layer_names();  // "hull, wireframe, ..." for messages

enum class PointColors { kState, kFace };
enum class FaceColors { kState, kAge };
// How the cloud is drawn: GL points (round, blended with the point opacity), or compute splats (square,
// opaque; shaders/points_splat.comp.glsl), which keep 20M points interactive.  kAuto splats from
// kSplatAutoPoints points on when the points are opaque.
enum class PointMode { kAuto, kPoints, kSplats };
inline constexpr std::size_t kSplatAutoPoints = 2000000;

struct RenderSettings {
  std::array<bool, kLayerCount> layers{true, true, true, true, true, true, false, false, false, false, false};
  float point_size = 3.0f;      // logical pixels (times pixel_scale), unless point_size_auto
  bool point_size_auto = true;  // the size at which neighbouring points touch (ViewParams::auto_point_size)
  float point_opacity = 1.0f;   // 0..1
  float hull_opacity = 0.6f;    // 0..1; below 1 the points inside show through
  float wire_width = 1.2f;      // logical pixels
  PointColors point_colors = PointColors::kState;
  PointMode point_mode = PointMode::kAuto;
  FaceColors face_colors = FaceColors::kState;
  float age_span = 5.0f;  // iterations over which "by age" fades from new to old
  glm::vec3 background{0.11f, 0.115f, 0.13f};
  bool legend = false;  // the colour key drawn into the picture (legend.hpp)

  bool shown(Layer layer) const { return layers[static_cast<int>(layer)]; }
  void show(Layer layer, bool on) { layers[static_cast<int>(layer)] = on; }
};

// The palette, shared with tests that recognise colours in screenshots.
inline constexpr glm::vec3 kInternalColor{0.85f, 0.16f, 0.12f};
inline constexpr glm::vec3 kExternalColor{0.62f, 0.40f, 0.20f};
inline constexpr glm::vec3 kVertexColor{1.0f, 0.92f, 0.35f};
inline constexpr glm::vec3 kSelectedColor{0.20f, 0.90f, 0.95f};  // the selected face's cell points
inline constexpr glm::vec3 kFaceIdColor{0.62f, 0.85f, 1.0f};     // face ids (the labels layer)
inline constexpr std::array<glm::vec3, kFaceStateCount> kFaceStateColors{
    glm::vec3{0.33f, 0.55f, 0.88f},  // unchanged
    glm::vec3{0.96f, 0.62f, 0.16f},  // refined this step
    glm::vec3{0.30f, 0.80f, 0.42f},  // swapped this step
    glm::vec3{0.80f, 0.35f, 0.85f},  // made by a vertex removal this step
};

struct ViewParams {
  glm::mat4 view{1.0f}, projection{1.0f};
  int width = 1, height = 1;       // framebuffer pixels
  int origin_x = 0, origin_y = 0;  // the view's bottom left corner in the framebuffer (the window's panels)
  float pixel_scale = 1.0f;        // framebuffer pixels per logical pixel (high-DPI)
  long long selected_face = -1;    // its cell's points are highlighted while the cells layer is shown
  float cue_near = 0.0f, cue_far = 1.0f;  // view depths of the data's near and far side (the depth cue)
  // Logical pixels: the data's typical spacing on the screen, so that a regular scan (the bunny) draws as a
  // closed surface rather than a grid of dots beating against the pixels' (moire).
  float auto_point_size = 3.0f;
};

class Renderer {
 public:
  Renderer();  // compiles the embedded shaders; throws DeviceError on a GL failure
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void upload(RenderData& data);
  // The debugger's overlay, drawn after the hull: translucent triangles, then lines.
  // Labels are numbers drawn in screen space beside their points (seven-segment digits, so they show in
  // headless screenshots too).
  void set_overlay(const std::vector<OverlayVertex>& triangles, const std::vector<OverlayVertex>& lines,
                   const std::vector<OverlayLabel>& labels = {});
  void draw(const ViewParams& view, const RenderSettings& settings) const;
  // Ids drawn in the font beside their points (the labels layer), and the legend's rows (drawn while not
  // empty).  Both need the font: text_note() says which one, or why there is none.
  void set_text_labels(std::vector<TextLabel> labels) { text_labels_ = std::move(labels); }
  struct LegendRow {
    std::string text;
    glm::vec3 color{1.0f};
    bool heading = false;
  };
  void set_legend(std::vector<LegendRow> rows) { legend_ = std::move(rows); }
  const std::string& text_note() const;

  unsigned point_state_buffer() const { return state_buffer_; }
  // Whether draw() splats the cloud with these settings (the rest of the time it draws GL points).
  bool uses_splats(const RenderSettings& settings) const;
  // Bytes of per-point data copied from host memory into GL buffers by the last upload() and in total.
  std::uint64_t last_point_upload_bytes() const { return last_point_bytes_; }
  std::uint64_t total_point_upload_bytes() const { return total_point_bytes_; }

 private:
  static constexpr float kTextPixels = 15.0f;  // the labels' and the legend's font size, logical pixels

  void draw_splats(const ViewParams& view, const glm::mat4& view_proj, const RenderSettings& s) const;

  unsigned points_program_ = 0, hull_program_ = 0, splat_program_ = 0, resolve_program_ = 0;
  unsigned resolve_vao_ = 0;
  unsigned overlay_program_ = 0, overlay_vao_ = 0, overlay_buffer_ = 0;
  std::size_t overlay_capacity_ = 0, overlay_triangle_vertices_ = 0, overlay_line_vertices_ = 0;
  std::vector<OverlayLabel> labels_;
  void draw_labels(const ViewParams& view, const glm::mat4& view_proj) const;
  void draw_text(const ViewParams& view, const glm::mat4& view_proj) const;
  // Baked for the last pixel scale drawn at (high-DPI: the text keeps its logical size); draw() is const.
  mutable std::unique_ptr<TextRenderer> text_;
  std::vector<TextLabel> text_labels_;
  std::vector<LegendRow> legend_;
  unsigned label_buffer_ = 0, label_vao_ = 0;
  mutable std::size_t label_capacity_ = 0;
  // The splats' per-pixel depth and colour, grown to the largest framebuffer drawn (draw() is const).
  mutable unsigned splat_depth_buffer_ = 0, splat_color_buffer_ = 0;
  mutable std::size_t splat_capacity_ = 0;
  unsigned points_vao_ = 0, vertices_vao_ = 0, hull_vao_ = 0;
  unsigned input_program_ = 0, input_vao_ = 0, input_index_buffer_ = 0;
  std::size_t input_index_count_ = 0;
  unsigned position_buffer_ = 0, state_buffer_ = 0, vertex_id_buffer_ = 0, hull_buffer_ = 0;
  std::size_t point_count_ = 0, hull_corner_count_ = 0, hull_vertex_count_ = 0;
  std::size_t hull_buffer_capacity_ = 0, vertex_id_capacity_ = 0;
  std::uint64_t last_point_bytes_ = 0, total_point_bytes_ = 0;
};

// A multisampled offscreen framebuffer for screenshots and headless rendering, resolved on readback.
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height, int samples = 4);  // throws DeviceError when incomplete
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  void bind() const;  // as the draw framebuffer, with the viewport set
  // RGBA8, top row first (as PNG wants).  Leaves the default framebuffer bound.
  std::vector<std::uint8_t> read_rgba() const;

 private:
  int width_, height_;
  unsigned fbo_ = 0, color_ = 0, depth_ = 0;      // multisampled
  unsigned resolve_fbo_ = 0, resolve_color_ = 0;  // single-sampled
};

// The points' diameter in framebuffer pixels for these settings.
float point_pixels(const ViewParams& view, const RenderSettings& settings);

// GL_RENDERER and GL_VERSION of the current context, for logs.
std::string gl_description();
// glFinish: for timings.
void finish_gl();

}  // namespace cudahull::viewer
