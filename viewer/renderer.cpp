// The Renderer (design: renderer.hpp): its GL objects, the upload of RenderData, and the draw of points,
// splats, hull and overlay; the text is in renderer_text.cpp, the GL helpers in gl_helpers.cpp.
#include "renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cstddef>
#include <glm/gtc/type_ptr.hpp>
#include <initializer_list>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "embedded_shaders.hpp"
#include "gl_helpers.hpp"
#include "text.hpp"

namespace cudahull::viewer {

namespace {

unsigned link(const char* vertex, const char* fragment, const char* name) {
  return link_program(vertex, fragment, name);
}

// The points' colouring, which the GL points and the compute splats share: by state or face, the layers
// shown.
void set_point_color_uniforms(GLuint program, const RenderSettings& s) {
  glUniform1i(loc(program, "u_color_mode"), s.point_colors == PointColors::kFace ? 1 : 0);
  glUniform1i(loc(program, "u_show_internal"), s.shown(Layer::kInternal));
  glUniform1i(loc(program, "u_show_external"), s.shown(Layer::kExternal));
  glUniform3fv(loc(program, "u_internal_color"), 1, glm::value_ptr(kInternalColor));
  glUniform3fv(loc(program, "u_external_color"), 1, glm::value_ptr(kExternalColor));
}

}  // namespace

Renderer::Renderer() {
  points_program_ = link(shaders::points_vert, shaders::points_frag, "points");
  hull_program_ = link(shaders::hull_vert, shaders::hull_frag, "hull");
  splat_program_ = link_compute(shaders::points_splat_comp, "points_splat");
  resolve_program_ = link(shaders::splat_resolve_vert, shaders::splat_resolve_frag, "splat_resolve");
  glCreateVertexArrays(1, &resolve_vao_);
  overlay_program_ = link(shaders::overlay_vert, shaders::overlay_frag, "overlay");
  glCreateVertexArrays(1, &overlay_vao_);
  glCreateBuffers(1, &overlay_buffer_);
  bind_overlay_layout(overlay_vao_, overlay_buffer_);
  glCreateVertexArrays(1, &label_vao_);
  glCreateBuffers(1, &label_buffer_);
  bind_overlay_layout(label_vao_, label_buffer_);
  text_ = std::make_unique<TextRenderer>(kTextPixels);

  create_objects(glCreateBuffers, {&splat_depth_buffer_, &splat_color_buffer_});

  create_objects(glCreateBuffers, {&position_buffer_, &state_buffer_, &vertex_id_buffer_, &hull_buffer_});
  create_objects(glCreateVertexArrays, {&points_vao_, &vertices_vao_, &hull_vao_});

  // The cloud and the vertex highlight read the same two point buffers; the latter through vertex ids.
  for (GLuint vao : {points_vao_, vertices_vao_}) {
    glVertexArrayVertexBuffer(vao, 0, position_buffer_, 0, sizeof(Point3));
    float_attribute(vao, 0, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayVertexBuffer(vao, 1, state_buffer_, 0, sizeof(std::int32_t));
    int_attribute(vao, 1, 1, 1, GL_INT, 0);
  }
  glVertexArrayElementBuffer(vertices_vao_, vertex_id_buffer_);

  // The input layer: the model's triangles index the same positions.
  input_program_ = link(shaders::input_vert, shaders::input_frag, "input");
  glCreateVertexArrays(1, &input_vao_);
  glCreateBuffers(1, &input_index_buffer_);
  glVertexArrayVertexBuffer(input_vao_, 0, position_buffer_, 0, sizeof(Point3));
  float_attribute(input_vao_, 0, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayElementBuffer(input_vao_, input_index_buffer_);

  glVertexArrayVertexBuffer(hull_vao_, 0, hull_buffer_, 0, sizeof(HullCorner));
  float_attribute(hull_vao_, 0, 0, 3, GL_FLOAT, GL_FALSE, offsetof(HullCorner, x));
  int_attribute(hull_vao_, 1, 0, 1, GL_UNSIGNED_INT, offsetof(HullCorner, info));

  // Empty but valid stores, so a draw before the first upload is harmless.
  glNamedBufferData(position_buffer_, 16, nullptr, GL_STATIC_DRAW);
  glNamedBufferData(state_buffer_, 16, nullptr, GL_DYNAMIC_DRAW);
  if (const GLenum e = glGetError(); e != GL_NO_ERROR)
    throw DeviceError("OpenGL: error " + std::to_string(e) + " while creating the renderer's buffers");
}

const std::string& Renderer::text_note() const {
  return text_->font_note();
}

Renderer::~Renderer() {
  const GLuint buffers[6] = {position_buffer_, state_buffer_,       vertex_id_buffer_,
                             hull_buffer_,     splat_depth_buffer_, splat_color_buffer_};
  glDeleteBuffers(6, buffers);
  glDeleteVertexArrays(1, &resolve_vao_);
  glDeleteVertexArrays(1, &overlay_vao_);
  glDeleteBuffers(1, &overlay_buffer_);
  glDeleteVertexArrays(1, &label_vao_);
  glDeleteBuffers(1, &label_buffer_);
  glDeleteProgram(overlay_program_);
  glDeleteProgram(splat_program_);
  glDeleteProgram(resolve_program_);
  const GLuint vaos[3] = {points_vao_, vertices_vao_, hull_vao_};
  glDeleteVertexArrays(3, vaos);
  glDeleteProgram(points_program_);
  glDeleteProgram(hull_program_);
  glDeleteVertexArrays(1, &input_vao_);
  glDeleteBuffers(1, &input_index_buffer_);
  glDeleteProgram(input_program_);
}

void Renderer::upload(RenderData& data) {
  // kDirtyDeviceState is the session's (CUDA-GL interop), not an upload: it stays set.
  if ((data.dirty & ~kDirtyDeviceState) == 0) return;  // last_point_upload_bytes() keeps the last real one
  last_point_bytes_ = 0;
  if (data.dirty & kDirtyPositions) {
    point_count_ = data.positions ? data.positions->size() : 0;
    const std::size_t bytes = std::max<std::size_t>(point_count_ * sizeof(Point3), 16);
    glNamedBufferData(position_buffer_, static_cast<GLsizeiptr>(bytes),
                      point_count_ ? data.positions->data() : nullptr, GL_STATIC_DRAW);
    // Reallocated to the new size here; its contents come with kDirtyPointState (or from CUDA).
    glNamedBufferData(state_buffer_, static_cast<GLsizeiptr>(std::max<std::size_t>(point_count_ * 4, 16)),
                      nullptr, GL_DYNAMIC_DRAW);
    last_point_bytes_ += point_count_ * sizeof(Point3);
    data.dirty |= kDirtyPointState;
    input_index_count_ = data.surface ? data.surface->size() * 3 : 0;
    glNamedBufferData(input_index_buffer_,
                      static_cast<GLsizeiptr>(std::max<std::size_t>(input_index_count_ * 4, 16)),
                      input_index_count_ ? data.surface->data() : nullptr, GL_STATIC_DRAW);
  }
  if (data.dirty & kDirtyPointState) {
    const std::size_t n = std::min(point_count_, data.point_state.size());
    if (n > 0)
      glNamedBufferSubData(state_buffer_, 0, static_cast<GLsizeiptr>(n * 4), data.point_state.data());
    last_point_bytes_ += n * 4;
  }
  if (data.dirty & kDirtyHull) {
    hull_corner_count_ = data.hull.size();
    hull_vertex_count_ = data.hull_vertex_ids.size();
    ensure_capacity(hull_buffer_, hull_buffer_capacity_, hull_corner_count_ * sizeof(HullCorner));
    ensure_capacity(vertex_id_buffer_, vertex_id_capacity_, hull_vertex_count_ * 4);
    if (hull_corner_count_)
      glNamedBufferSubData(hull_buffer_, 0, static_cast<GLsizeiptr>(hull_corner_count_ * sizeof(HullCorner)),
                           data.hull.data());
    if (hull_vertex_count_)
      glNamedBufferSubData(vertex_id_buffer_, 0, static_cast<GLsizeiptr>(hull_vertex_count_ * 4),
                           data.hull_vertex_ids.data());
  }
  total_point_bytes_ += last_point_bytes_;
  data.dirty &= kDirtyDeviceState;
}

void Renderer::set_overlay(const std::vector<OverlayVertex>& triangles,
                           const std::vector<OverlayVertex>& lines, const std::vector<OverlayLabel>& labels) {
  labels_ = labels;
  overlay_triangle_vertices_ = triangles.size();
  overlay_line_vertices_ = lines.size();
  const std::size_t bytes = (triangles.size() + lines.size()) * sizeof(OverlayVertex);
  if (bytes == 0) return;
  ensure_capacity(overlay_buffer_, overlay_capacity_, bytes);
  if (!triangles.empty())
    glNamedBufferSubData(overlay_buffer_, 0,
                         static_cast<GLsizeiptr>(triangles.size() * sizeof(OverlayVertex)), triangles.data());
  if (!lines.empty())
    glNamedBufferSubData(overlay_buffer_, static_cast<GLintptr>(triangles.size() * sizeof(OverlayVertex)),
                         static_cast<GLsizeiptr>(lines.size() * sizeof(OverlayVertex)), lines.data());
}

float point_pixels(const ViewParams& view, const RenderSettings& s) {
  return std::max(1.0f, (s.point_size_auto ? view.auto_point_size : s.point_size) * view.pixel_scale);
}

bool Renderer::uses_splats(const RenderSettings& s) const {
  if (s.point_mode == PointMode::kSplats) return true;
  return s.point_mode == PointMode::kAuto && point_count_ >= kSplatAutoPoints && s.point_opacity >= 1.0f;
}

void Renderer::draw_splats(const ViewParams& view, const glm::mat4& view_proj,
                           const RenderSettings& s) const {
  const std::size_t pixels = static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height);
  if (pixels > splat_capacity_) {
    for (GLuint buffer : {splat_depth_buffer_, splat_color_buffer_})
      glNamedBufferData(buffer, static_cast<GLsizeiptr>(pixels * 4), nullptr, GL_DYNAMIC_COPY);
    splat_capacity_ = pixels;
  }
  const GLuint far = 0xffffffffu;
  glClearNamedBufferSubData(splat_depth_buffer_, GL_R32UI, 0, static_cast<GLsizeiptr>(pixels * 4),
                            GL_RED_INTEGER, GL_UNSIGNED_INT, &far);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, position_buffer_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, state_buffer_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, splat_depth_buffer_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, splat_color_buffer_);

  glUseProgram(splat_program_);
  glUniformMatrix4fv(loc(splat_program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  glUniform1ui(loc(splat_program_, "u_count"), static_cast<GLuint>(point_count_));
  glUniform2i(loc(splat_program_, "u_size"), view.width, view.height);
  glUniform1f(loc(splat_program_, "u_point_size"), point_pixels(view, s));
  set_point_color_uniforms(splat_program_, s);
  glUniform1i(loc(splat_program_, "u_selected_face"),
              s.shown(Layer::kCells) ? static_cast<int>(view.selected_face) : -1);
  glUniform3fv(loc(splat_program_, "u_selected_color"), 1, glm::value_ptr(kSelectedColor));
  const std::size_t groups = (point_count_ + 255) / 256;
  const GLuint row = 65535;  // the least GL_MAX_COMPUTE_WORK_GROUP_COUNT any GL 4.3 driver allows
  const GLuint groups_x = static_cast<GLuint>(std::min<std::size_t>(groups, row));
  const GLuint groups_y = static_cast<GLuint>((groups + row - 1) / row);
  for (int pass = 0; pass < 2; ++pass) {
    glUniform1i(loc(splat_program_, "u_pass"), pass);
    glDispatchCompute(groups_x, groups_y, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  glUseProgram(resolve_program_);
  glUniform2i(loc(resolve_program_, "u_size"), view.width, view.height);
  glUniform2i(loc(resolve_program_, "u_origin"), view.origin_x, view.origin_y);
  glDepthMask(GL_TRUE);
  glBindVertexArray(resolve_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void Renderer::draw(const ViewParams& view, const RenderSettings& s) const {
  glViewport(view.origin_x, view.origin_y, view.width, view.height);
  // The clear only within the view (the window's panels are around it).
  glScissor(view.origin_x, view.origin_y, view.width, view.height);
  glEnable(GL_SCISSOR_TEST);
  glClearColor(s.background.r, s.background.g, s.background.b, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_BLEND);
  // Destination alpha stays 1, so screenshots and composited windows are opaque.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_MULTISAMPLE);
  glDisable(GL_STENCIL_TEST);

  const glm::mat4 view_proj = view.projection * view.view;

  // The model's own surface first, without depth writes: the points then draw over it, the hull around it.
  if (s.shown(Layer::kInput) && input_index_count_ > 0) {
    glUseProgram(input_program_);
    glUniformMatrix4fv(loc(input_program_, "u_view"), 1, GL_FALSE, glm::value_ptr(view.view));
    glUniformMatrix4fv(loc(input_program_, "u_proj"), 1, GL_FALSE, glm::value_ptr(view.projection));
    glUniform1f(loc(input_program_, "u_opacity"), 0.5f);
    glDepthMask(GL_FALSE);
    glBindVertexArray(input_vao_);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(input_index_count_), GL_UNSIGNED_INT, nullptr);
    glDepthMask(GL_TRUE);
  }

  // Points first: the translucent hull then blends over the ones inside it.
  const bool any_points = s.shown(Layer::kInternal) || s.shown(Layer::kExternal);
  const bool vertices = s.shown(Layer::kVertices) && hull_vertex_count_ > 0;
  const bool splats = any_points && point_count_ > 0 && uses_splats(s);
  if (splats) draw_splats(view, view_proj, s);
  if ((any_points && point_count_ > 0 && !splats) || vertices) {
    glUseProgram(points_program_);
    glUniformMatrix4fv(loc(points_program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glUniform1f(loc(points_program_, "u_point_size"), point_pixels(view, s));
    set_point_color_uniforms(points_program_, s);
    glUniform3fv(loc(points_program_, "u_vertex_color"), 1, glm::value_ptr(kVertexColor));
    glUniform1i(loc(points_program_, "u_selected_face"),
                s.shown(Layer::kCells) ? static_cast<int>(view.selected_face) : -1);
    glUniform3fv(loc(points_program_, "u_selected_color"), 1, glm::value_ptr(kSelectedColor));
    glUniform1f(loc(points_program_, "u_opacity"), s.point_opacity);
    glUniform2f(loc(points_program_, "u_cue_range"), view.cue_near, view.cue_far);
    glDepthMask(s.point_opacity >= 1.0f ? GL_TRUE : GL_FALSE);
    // Opaque points: their discs' soft edges as MSAA coverage, not blending (order independent).
    if (s.point_opacity >= 1.0f) glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    if (any_points && point_count_ > 0 && !splats) {
      glUniform1i(loc(points_program_, "u_pass"), 0);
      glBindVertexArray(points_vao_);
      glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(point_count_));
    }
    if (vertices) {
      glUniform1i(loc(points_program_, "u_pass"), 1);
      glUniform1f(loc(points_program_, "u_opacity"), 1.0f);
      glDepthMask(GL_TRUE);
      glBindVertexArray(vertices_vao_);
      glDrawElements(GL_POINTS, static_cast<GLsizei>(hull_vertex_count_), GL_UNSIGNED_INT, nullptr);
    }
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  }

  const bool faces = s.shown(Layer::kHull), wire = s.shown(Layer::kWireframe);
  if ((faces || wire) && hull_corner_count_ > 0) {
    glUseProgram(hull_program_);
    glUniformMatrix4fv(loc(hull_program_, "u_view"), 1, GL_FALSE, glm::value_ptr(view.view));
    glUniformMatrix4fv(loc(hull_program_, "u_proj"), 1, GL_FALSE, glm::value_ptr(view.projection));
    glUniform3fv(loc(hull_program_, "u_state_colors"), kFaceStateCount, glm::value_ptr(kFaceStateColors[0]));
    glUniform1i(loc(hull_program_, "u_color_mode"), s.face_colors == FaceColors::kAge ? 1 : 0);
    glUniform1f(loc(hull_program_, "u_age_span"), s.age_span);
    glUniform1i(loc(hull_program_, "u_show_faces"), faces);
    glUniform1i(loc(hull_program_, "u_show_wire"), wire);
    glUniform1f(loc(hull_program_, "u_opacity"), s.hull_opacity);
    glUniform1f(loc(hull_program_, "u_wire_width"), s.wire_width * view.pixel_scale);
    // Faces are counter-clockwise seen from outside (mesh.hpp): with faces shown only the front ones are
    // drawn, so a translucent hull blends once; a bare wireframe shows the back edges too.
    if (faces) {
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      glFrontFace(GL_CCW);
    } else {
      glDisable(GL_CULL_FACE);
    }
    glDepthMask(faces && s.hull_opacity >= 1.0f ? GL_TRUE : GL_FALSE);
    glBindVertexArray(hull_vao_);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(hull_corner_count_));
    glDisable(GL_CULL_FACE);
  }
  if (overlay_triangle_vertices_ + overlay_line_vertices_ > 0) {
    // Translucent quads without depth writes, so that what is behind them still shows; lines on top of
    // them.
    glUseProgram(overlay_program_);
    glUniformMatrix4fv(loc(overlay_program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glBindVertexArray(overlay_vao_);
    glDepthMask(GL_FALSE);
    if (overlay_triangle_vertices_ > 0)
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(overlay_triangle_vertices_));
    if (overlay_line_vertices_ > 0)
      glDrawArrays(GL_LINES, static_cast<GLint>(overlay_triangle_vertices_),
                   static_cast<GLsizei>(overlay_line_vertices_));
  }
  if (text_->available()) {
    draw_text(view, view_proj);
  } else if (!labels_.empty()) {  // no font: the sequence numbers as line digits
    glUseProgram(overlay_program_);
    draw_labels(view, view_proj);
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_SCISSOR_TEST);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace cudahull::viewer
