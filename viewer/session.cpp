#include "session.hpp"

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "cudahull/errors.hpp"
#include "export.hpp"
#include "legend.hpp"
#include "png.hpp"

namespace cudahull::viewer {

Session::Session() = default;

void Session::set_scene(std::unique_ptr<Scene> scene, bool fit_camera) {
  interop_.reset();  // registered for the old point count; the new scene reallocates the buffer
  scene_ = std::move(scene);
  selected_face_ = -1;
  if (scene_) {  // once per scene: bounds() reads every point
    float lo[3], hi[3];
    scene_->bounds(lo, hi);
    data_centre_ = 0.5f * (glm::vec3(lo[0], lo[1], lo[2]) + glm::vec3(hi[0], hi[1], hi[2]));
    data_radius_ = 0.5f * glm::length(glm::vec3(hi[0], hi[1], hi[2]) - glm::vec3(lo[0], lo[1], lo[2]));
    // The points' typical spacing were they spread over the box's surface (scans are surfaces; a solid
    // cloud seen from outside shows about as many).
    const glm::vec3 e = glm::vec3(hi[0], hi[1], hi[2]) - glm::vec3(lo[0], lo[1], lo[2]);
    const double area = 2.0 * (double{e.x} * e.y + double{e.y} * e.z + double{e.z} * e.x);
    data_spacing_ = static_cast<float>(std::sqrt(area / std::max<std::size_t>(scene_->points().size(), 1)));
  }
  choose_upload_path();
  if (scene_ && (fit_camera || !camera_fitted_)) fit_view();
}

void Session::fit_view() {
  if (!scene_) return;
  float lo[3], hi[3];
  scene_->bounds(lo, hi);
  camera_.fit({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]});
  camera_fitted_ = true;
}

void Session::choose_upload_path() {
  if (!scene_) {
    upload_path_ = "CPU upload (no scene)";
    return;
  }
  std::string why;
  if (!scene_->backend_has_device_point_states()) {
    why = "the CPU backend";
  } else if (!interop_allowed_) {
    why = "interop turned off";
  } else {
    why = cuda_gl_unavailable_reason();
  }
  scene_->set_device_point_states(why.empty());
  upload_path_ = why.empty() ? "CUDA-GL interop" : "CPU upload (" + why + ")";
}

void Session::write_device_states(RenderData& data) {
  data.dirty &= ~kDirtyDeviceState;
  bool written = false;
  if (!interop_) interop_ = std::make_unique<CudaGlBuffer>(renderer_.point_state_buffer());
  interop_->write(
      [&](void* device, std::size_t bytes) { written = scene_->write_device_point_states(device, bytes); });
  if (!written) {  // e.g. a degenerate input with no 3-d mesh: this scene uploads from the CPU instead
    scene_->set_device_point_states(false);
    upload_path_ = "CPU upload (the backend could not write this state)";
    renderer_.upload(scene_->render_data());
  }
}

void Session::update_overlay() {
  OverlayKey key;
  key.scene = scene_.get();
  key.position = scene_ ? scene_->position() : -1;
  key.selected = selected_face_;
  key.cells = settings_.shown(Layer::kCells);
  key.normals = settings_.shown(Layer::kNormals);
  key.refinement = settings_.shown(Layer::kRefinement);
  key.swaps = settings_.shown(Layer::kSwaps);
  key.sequence_limit = scene_ ? scene_->substep_sequence_limit() : 0;
  key.labels = settings_.shown(Layer::kLabels);
  if (key == overlay_key_) return;
  overlay_key_ = key;
  overlay_.triangles.clear();
  overlay_.lines.clear();
  if (scene_ && scene_->position() > 0)
    build_overlay(scene_->engine(), selected_face_,
                  {key.cells, key.normals, key.refinement, key.swaps, key.sequence_limit}, overlay_);
  renderer_.set_overlay(overlay_.triangles, overlay_.lines, overlay_.labels);
  renderer_.set_text_labels(key.labels ? id_labels() : std::vector<TextLabel>{});
}

std::vector<TextLabel> Session::id_labels() const {
  std::vector<TextLabel> out;
  if (!scene_ || scene_->position() == 0 || scene_->engine().dimension() != 3) return out;
  const Mesh& mesh = scene_->engine().mesh();
  const std::vector<Point3>& points = scene_->points();
  const std::uint32_t face_rgba = pack_rgba(kFaceIdColor.r, kFaceIdColor.g, kFaceIdColor.b, 1.0f);
  for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
    if (!mesh.alive(f)) continue;
    const MeshFace& face = mesh.face(f);
    glm::vec3 c[3];
    for (int i = 0; i < 3; ++i)
      c[i] = glm::vec3(points[face.v[i]].x, points[face.v[i]].y, points[face.v[i]].z);
    const glm::vec3 mid = (c[0] + c[1] + c[2]) / 3.0f, n = glm::cross(c[1] - c[0], c[2] - c[0]);
    out.push_back({mid.x, mid.y, mid.z, n.x, n.y, n.z, face_rgba, "f" + std::to_string(f)});
  }
  // Vertex ids up and to the right of their points, all of them, as the vertex points are all drawn (those
  // behind show through the translucent hull).
  const std::uint32_t vertex_rgba = pack_rgba(kVertexColor.r, kVertexColor.g, kVertexColor.b, 1.0f);
  const std::vector<PointIndex> vertices = mesh.vertices();
  for (PointIndex v : vertices)
    out.push_back({points[v].x, points[v].y, points[v].z, 0, 0, 0, vertex_rgba, std::to_string(v), 8, -8});
  // The points the step's swaps and removals name that are no hull vertex now (a vertex beneath a rejected
  // swap that a later removal took away, a removed vertex), in grey: the debugger's ids are all findable.
  if (const IterationRecord* r = scene_->current_record()) {
    std::vector<PointIndex> named;
    for (const SwapRecord& w : r->swaps) {
      named.insert(named.end(), {w.old_edge[0], w.old_edge[1], w.new_edge[0], w.new_edge[1]});
      if (w.beneath_vertex != kNoPoint)
        named.insert(named.end(),
                     {w.beneath_vertex, w.beneath_triangle[0], w.beneath_triangle[1], w.beneath_triangle[2]});
    }
    for (const RemovalRecord& m : r->removals)
      named.push_back(m.vertex);
    std::sort(named.begin(), named.end());
    named.erase(std::unique(named.begin(), named.end()), named.end());
    const std::uint32_t grey = pack_rgba(0.75f, 0.75f, 0.75f, 1.0f);
    for (PointIndex p : named) {
      if (p < points.size() && !std::binary_search(vertices.begin(), vertices.end(), p))
        out.push_back({points[p].x, points[p].y, points[p].z, 0, 0, 0, grey, std::to_string(p), 8, -8});
    }
  }
  return out;
}

bool Session::next_step_where(const std::function<bool(const IterationRecord&)>& wanted) {
  if (!scene_) return false;
  const int start = scene_->position();
  for (int p = start + 1;; ++p) {
    if (p > scene_->known_end()) {
      if (scene_->final_known()) break;
      scene_->rewind(p);  // forward: steps on
      if (scene_->known_end() < p) break;
    }
    if (wanted(scene_->history()[p - 1])) {
      if (scene_->position() != p) scene_->rewind(p);
      return true;
    }
  }
  if (scene_->position() != start) scene_->rewind(start);
  return false;
}

bool Session::next_rejected() {
  return next_step_where([](const IterationRecord& r) { return r.swaps_rejected > 0; });
}

bool Session::next_removal() {
  return next_step_where(
      [](const IterationRecord& r) { return r.vertices_removed > 0 && r.swaps_complementary > 0; });
}

void Session::frame_points(const std::vector<PointIndex>& points) {
  if (!scene_ || points.empty()) return;
  glm::vec3 lo(FLT_MAX), hi(-FLT_MAX);
  for (PointIndex i : points) {
    const Point3& p = scene_->points()[i];
    lo = glm::min(lo, glm::vec3(p.x, p.y, p.z));
    hi = glm::max(hi, glm::vec3(p.x, p.y, p.z));
  }
  camera_.frame(0.5f * (lo + hi), std::max(0.75f * glm::length(hi - lo), 1e-6f));
}

std::string Session::frame_case(const std::string& what, long long sequence) {
  const IterationRecord* r = scene_ ? scene_->current_record() : nullptr;
  if (r == nullptr) return "";
  const Mesh& mesh = scene_->engine().mesh();
  for (const SwapRecord& w : r->swaps) {
    const bool rejected = w.beneath_vertex != kNoPoint;
    if ((what == "rejected" && rejected) || (what == "swap" && w.sequence == sequence)) {
      std::vector<PointIndex> points{w.old_edge[0], w.old_edge[1], w.new_edge[0], w.new_edge[1]};
      if (rejected) points.push_back(w.beneath_vertex);
      frame_points(points);
      std::string line = "swap #" + std::to_string(w.sequence) + " (" + swap_kind_name(w.kind) +
                         "): " + std::to_string(w.old_edge[0]) + "-" + std::to_string(w.old_edge[1]) +
                         " -> " + std::to_string(w.new_edge[0]) + "-" + std::to_string(w.new_edge[1]);
      if (rejected) {
        const bool gone = !mesh.has_vertex(w.old_edge[0]) || !mesh.adjacent(w.old_edge[0], w.old_edge[1]);
        line += "; vertex " + std::to_string(w.beneath_vertex) + " lies beneath (" +
                std::to_string(w.beneath_triangle[0]) + ", " + std::to_string(w.beneath_triangle[1]) + ", " +
                std::to_string(w.beneath_triangle[2]) + "); " +
                (gone ? "resolved later in the step (the edge is gone)"
                      : "not resolved: the edge is still there");
      }
      return line;
    }
  }
  if (what == "removal") {
    for (const RemovalRecord& m : r->removals) {
      if (m.rejected) continue;
      frame_points({m.vertex, m.ring[0], m.ring[1], m.ring[2]});
      return "removal #" + std::to_string(m.sequence) + ": vertex " + std::to_string(m.vertex) +
             " -> face (" + std::to_string(m.ring[0]) + ", " + std::to_string(m.ring[1]) + ", " +
             std::to_string(m.ring[2]) + ")";
    }
  }
  return "";
}

namespace {

// The signed distance of p to the plane of triangle (a, b, c), positive on the side its normal points to
// (outside, for the hull's counter-clockwise faces).
double signed_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const glm::dvec3 ga(a.x, a.y, a.z),
      n = glm::cross(glm::dvec3(b.x, b.y, b.z) - ga, glm::dvec3(c.x, c.y, c.z) - ga);
  const double length = glm::length(n);
  return length > 0 ? glm::dot(n, glm::dvec3(p.x, p.y, p.z) - ga) / length : 0.0;
}

std::string format_distance(double d) {
  char s[64];
  std::snprintf(s, sizeof s, "%+.4g", d);
  return s;
}

}  // namespace

Session::Pick Session::pick(double x, double y, int width, int height) {
  Pick out;
  if (!scene_ || width <= 0 || height <= 0) return out;
  const std::vector<Point3>& points = scene_->points();
  RenderData& data = scene_->render_data();
  // Per-point state as drawn: the CPU copy, or (interop) the engine's.
  std::vector<std::int32_t> engine_states;
  const std::vector<std::int32_t>* states = &data.point_state;
  const bool search_points = points.size() <= kPickPointLimit;  // beyond, no per-point pass nor readback
  if (search_points && states->size() != points.size() && scene_->position() > 0) {
    engine_states = scene_->engine().point_faces();
    for (PointIndex v : data.hull_vertex_ids)
      if (v < engine_states.size()) engine_states[v] = kPointVertex;
    states = &engine_states;
  }
  auto state_of = [&](std::size_t i) { return i < states->size() ? (*states)[i] : 0; };
  auto drawn = [&](std::int32_t s) {
    return s == kPointVertex ? settings_.shown(Layer::kVertices)
           : s < 0
               ? settings_.shown(Layer::kInternal)
               : settings_.shown(Layer::kExternal) || (settings_.shown(Layer::kCells) && s == selected_face_);
  };
  const glm::mat4 view_proj =
      camera_.projection(static_cast<float>(width) / static_cast<float>(height)) * camera_.view();
  ViewParams view;
  view.width = width;
  view.height = height;
  const float radius = std::max(6.0f, 0.5f * point_pixels(view, settings_) + 2.0f);
  double best = radius * radius, best_depth = 2.0;
  long long best_point = -1;
  if (search_points) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      const glm::vec4 clip = view_proj * glm::vec4(points[i].x, points[i].y, points[i].z, 1.0f);
      if (clip.w <= 0) continue;
      const double px = (clip.x / clip.w * 0.5 + 0.5) * width, py = (0.5 - clip.y / clip.w * 0.5) * height;
      const double d2 = (px - x) * (px - x) + (py - y) * (py - y), depth = clip.z / clip.w;
      // The nearest on the screen; among points a pixel apart, the one in front.
      if (d2 > best + 1.0 || (d2 > best - 1.0 && depth >= best_depth) || !drawn(state_of(i))) continue;
      best = d2;
      best_depth = depth;
      best_point = static_cast<long long>(i);
    }
  }
  const SteppingEngine& engine = scene_->engine();
  if (best_point >= 0) {
    const auto i = static_cast<PointIndex>(best_point);
    const std::int32_t s = state_of(i);
    out.kind = Pick::Kind::kPoint;
    out.id = best_point;
    out.text = "point " + std::to_string(i);
    if (scene_->position() == 0) {
      out.text += ": no step yet";
    } else if (s == kPointVertex) {
      out.text += ": a hull vertex";
    } else if (s < 0) {
      out.text += ": internal (proven inside the polyhedron)";
    } else {
      const MeshFace& f = engine.mesh().face(static_cast<FaceId>(s));
      out.text += ": external, face " + std::to_string(s) + ", signed distance " +
                  format_distance(signed_distance(engine.point(i), engine.point(f.v[0]), engine.point(f.v[1]),
                                                  engine.point(f.v[2]))) +
                  " to its plane";
    }
    return out;
  }
  const long long face = face_at(x, y, width, height);
  if (face < 0 || !settings_.shown(Layer::kHull)) return out;
  const auto f = static_cast<FaceId>(face);
  const MeshFace& mf = engine.mesh().face(f);
  out.kind = Pick::Kind::kFace;
  out.id = face;
  out.text = "face " + std::to_string(face) + ": vertices " + std::to_string(mf.v[0]) + " " +
             std::to_string(mf.v[1]) + " " + std::to_string(mf.v[2]);
  const std::vector<FaceExtreme>& extremes = engine.face_extremes();
  if (f < extremes.size() && extremes[f].count > 0) {
    out.text += "; " + std::to_string(extremes[f].count) + " external points, the furthest " +
                std::to_string(extremes[f].furthest) + " at signed distance " +
                format_distance(signed_distance(engine.point(extremes[f].furthest), engine.point(mf.v[0]),
                                                engine.point(mf.v[1]), engine.point(mf.v[2])));
  } else {
    out.text += "; no external points (final)";
  }
  return out;
}

std::vector<std::string> Session::click(double x, double y, int width, int height) {
  const Pick p = pick(x, y, width, height);
  if (p.kind == Pick::Kind::kPoint) {
    std::vector<std::string> lines{"explain point " + std::to_string(p.id) + ":"};
    for (const std::string& line : scene_->explain_point(static_cast<PointIndex>(p.id)))
      lines.push_back("  " + line);
    return lines;
  }
  if (p.kind == Pick::Kind::kFace) {
    select_face(p.id);
    settings_.show(Layer::kCells, true);
    return {"selected face " + std::to_string(p.id) + " (its cell: the cells layer)"};
  }
  return {"nothing there"};
}

long long Session::face_at(double x, double y, int width, int height) const {
  if (!scene_ || scene_->position() == 0 || width <= 0 || height <= 0) return -1;
  const glm::mat4 inverse = glm::inverse(
      camera_.projection(static_cast<float>(width) / static_cast<float>(height)) * camera_.view());
  const double nx = 2.0 * x / width - 1.0, ny = 1.0 - 2.0 * y / height;
  const glm::vec4 near = inverse * glm::vec4(nx, ny, -1.0, 1.0), far = inverse * glm::vec4(nx, ny, 1.0, 1.0);
  const glm::dvec3 a = glm::dvec3(near) / static_cast<double>(near.w);
  const glm::dvec3 b = glm::dvec3(far) / static_cast<double>(far.w);
  return pick_face(scene_->engine(), a, b - a);
}

void Session::draw(int width, int height, float pixel_scale, int origin_x, int origin_y, bool window_view) {
  update_overlay();
  if (scene_) {
    RenderData& data = scene_->render_data();
    if (data.dirty & kDirtyPositions) interop_.reset();  // upload() reallocates the state buffer
    renderer_.upload(data);
    if (data.dirty & kDirtyDeviceState) write_device_states(data);
  }
  ViewParams view;
  view.width = std::max(width, 1);
  view.height = std::max(height, 1);
  view.pixel_scale = pixel_scale;
  view.origin_x = origin_x;
  view.origin_y = origin_y;
  view.view = camera_.view();
  view.projection = camera_.projection(static_cast<float>(view.width) / static_cast<float>(view.height));
  view.selected_face = selected_face_;
  // The depth cue spans the data's bounding sphere as seen from the eye.
  const float distance = glm::length(camera_.eye() - data_centre_);
  view.cue_near = distance - data_radius_;
  view.cue_far = distance + data_radius_;
  // Pixels per unit at the data's centre: projection[1][1] is 1 / tan(fov / 2).
  const float pixels_per_unit = 0.5f * static_cast<float>(view.height) * view.projection[1][1] /
                                std::max(distance, 1e-20f) / std::max(pixel_scale, 1.0f);
  view.auto_point_size = std::clamp(1.5f * data_spacing_ * pixels_per_unit, 2.0f, 6.0f);
  std::vector<Renderer::LegendRow> legend;
  if (settings_.legend && !window_view) {
    std::string group;
    for (const LegendEntry& e : legend_entries(settings_, selected_face_ >= 0)) {
      if (e.group != group) legend.push_back({group = e.group, glm::vec3(1.0f), true});
      legend.push_back({e.name, e.color, false});
    }
  }
  renderer_.set_legend(std::move(legend));
  renderer_.draw(view, settings_);
}

std::vector<std::uint8_t> Session::render_rgba(int width, int height) {
  if (!offscreen_ || offscreen_->width() != width || offscreen_->height() != height)
    offscreen_ = std::make_unique<OffscreenTarget>(width, height);
  offscreen_->bind();
  // Screenshots use logical pixels = framebuffer pixels, whatever the screen's scale.
  draw(width, height, 1.0f);
  return offscreen_->read_rgba();
}

void Session::start_recording(const std::string& path, int width, int height) {
  if (recorder_) stop_recording();
  recorder_ = std::make_unique<Recorder>(path, width, height, record_fps);
  recorded_at_ = now_at();
}

std::string Session::stop_recording() {
  if (!recorder_) return "";
  std::unique_ptr<Recorder> recorder = std::move(recorder_);
  const int frames = recorder->close();
  return "wrote " + recorder->path() + " (" + std::to_string(frames) + " frames)";
}

Session::RecordedAt Session::now_at() const {
  return {scene_.get(), scene_ ? scene_->position() : -1, scene_ ? scene_->substep() : -2};
}

void Session::record_if_changed() {
  if (!recorder_ || now_at() == recorded_at_) return;
  recorded_at_ = now_at();
  recorder_->add(render_rgba(recorder_->width(), recorder_->height()));
}

void Session::step(int count) {
  for (int i = 0; i < count && scene_ && !scene_->done(); ++i) {
    scene_->step();
    record_if_changed();
  }
}

void Session::run_to_end() {
  if (!recorder_) {
    if (scene_) scene_->run_to_end();
    return;
  }
  step(1 << 30);
}

std::string Session::screenshot(const std::string& path, int width, int height) {
  const std::vector<std::uint8_t> rgba = render_rgba(width, height);
  const std::string out = format_numbered_path(path, scene_ ? scene_->position() : 0);
  write_png(out, rgba, width, height);
  return out;
}

double Session::time_frames(int frames, int width, int height) {
  if (!offscreen_ || offscreen_->width() != width || offscreen_->height() != height)
    offscreen_ = std::make_unique<OffscreenTarget>(width, height);
  offscreen_->bind();
  draw(width, height, 1.0f);  // warm-up: uploads and first-use costs stay out of the timing
  finish_gl();
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i)
    draw(width, height, 1.0f);
  finish_gl();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  offscreen_->read_rgba();  // leaves the default framebuffer bound, as screenshot() does
  return frames > 0 ? ms / frames : 0.0;
}

std::string Session::execute(const ScriptCommand& c, int width, int height) {
  using Kind = ScriptCommand::Kind;
  switch (c.kind) {
    case Kind::kStep:
      step(static_cast<int>(c.number));
      return "";
    case Kind::kRun:
      run_to_end();
      return "";
    case Kind::kRewind:
      if (scene_) scene_->rewind(static_cast<int>(c.number));
      record_if_changed();
      return "";
    case Kind::kRecordStart:
      try {
        start_recording(c.text, width, height);
      } catch (const OutputError& e) {
        throw OutputError(c.where + ": " + e.what());
      }
      return "recording " + c.text;
    case Kind::kRecordStop:
      try {
        const std::string line = stop_recording();
        return line.empty() ? c.where + ": note: not recording" : line;
      } catch (const OutputError& e) {
        throw OutputError(c.where + ": " + e.what());
      }
    case Kind::kSelectFace:
      selected_face_ = c.number;
      return "";
    case Kind::kShow:
    case Kind::kHide: {
      const Layer layer = *layer_from_name(c.text);
      settings_.show(layer, c.kind == Kind::kShow);
      if (layer == Layer::kCells && c.kind == Kind::kShow && selected_face_ < 0)
        return c.where + ": note: the cells layer shows the selected face's cell: select-face ID first";
      return "";
    }
    case Kind::kCamera:
      try {
        camera_.from_json(c.json);
      } catch (const std::exception& e) {
        throw ScriptError(c.where + ": " + e.what());
      }
      return "";
    case Kind::kScreenshot:
      try {
        return "wrote " + screenshot(c.text, width, height);
      } catch (const OutputError& e) {
        throw OutputError(c.where + ": " + e.what());
      }
    case Kind::kNextRejected: {
      const bool found = next_rejected();
      record_if_changed();
      return found ? "" : c.where + ": note: no later step rejects a swap";
    }
    case Kind::kNextRemoval: {
      const bool found = next_removal();
      record_if_changed();
      return found ? "" : c.where + ": note: no later step removes a vertex after complementary swaps";
    }
    case Kind::kSubstep: {
      if (!scene_) return "";
      const int count = scene_->substep_count();
      if (count == 0 && c.number != -1)
        return c.where + ": note: this step has no sub-steps (position 0 or 1)";
      if (c.number == kAllSubsteps) {  // each phase in turn: a frame each while recording
        for (int phase = 0; phase < count; ++phase) {
          scene_->set_substep(phase);
          record_if_changed();
        }
        return "played sub-steps 0 to " + std::to_string(count - 1);
      }
      scene_->set_substep(static_cast<int>(c.number));
      record_if_changed();
      if (c.number < 0) return "";
      const int phase = std::min<int>(static_cast<int>(c.number), count - 1);
      return "sub-step " + std::to_string(phase) + " of " + std::to_string(count - 1) + ": " +
             scene_->substep_label(phase);
    }
    case Kind::kHover:
    case Kind::kClick: {
      std::string text = std::string(c.kind == Kind::kHover ? "hover " : "click ") +
                         std::to_string(c.number) + " " + c.value + ": ";
      const double x = static_cast<double>(c.number), y = std::strtod(c.value.c_str(), nullptr);
      if (c.kind == Kind::kHover) {
        const Pick p = pick(x, y, width, height);
        return text + (p.kind == Pick::Kind::kNone ? "nothing there" : p.text);
      }
      const std::vector<std::string> lines = click(x, y, width, height);
      for (std::size_t k = 0; k < lines.size(); ++k)
        text += (k ? "\n" : "") + lines[k];
      return text;
    }
    case Kind::kExplainPoint: {
      if (!scene_) return "";
      std::string text = "explain point " + std::to_string(c.number) + ":";
      for (const std::string& line : scene_->explain_point(static_cast<PointIndex>(c.number)))
        text += "\n  " + line;
      return text;
    }
    case Kind::kFrame: {
      const std::string line = frame_case(c.text, c.number);
      return line.empty() ? c.where + ": note: this step has no such case to frame" : "framed " + line;
    }
    case Kind::kExportMesh:
    case Kind::kExportTrace:
    case Kind::kExportDecisions:
      if (!scene_) return "";
      try {
        if (c.kind == Kind::kExportMesh) export_mesh(*scene_, c.text);
        if (c.kind == Kind::kExportTrace) export_trace(*scene_, c.text);
        if (c.kind == Kind::kExportDecisions) export_decisions(*scene_, c.text);
      } catch (const std::exception& e) {
        throw OutputError(c.where + ": " + e.what());
      }
      return "wrote " + c.text;
    case Kind::kSet: {
      const double x = std::strtod(c.value.c_str(), nullptr);
      if (c.text == "point-size") {
        settings_.point_size_auto = c.value == "auto";
        if (!settings_.point_size_auto) settings_.point_size = static_cast<float>(x);
      }
      if (c.text == "point-opacity") settings_.point_opacity = static_cast<float>(x);
      if (c.text == "hull-opacity") settings_.hull_opacity = static_cast<float>(x);
      if (c.text == "wire-width") settings_.wire_width = static_cast<float>(x);
      if (c.text == "point-colors")
        settings_.point_colors = c.value == "face" ? PointColors::kFace : PointColors::kState;
      if (c.text == "point-mode")
        settings_.point_mode = c.value == "points"   ? PointMode::kPoints
                               : c.value == "splats" ? PointMode::kSplats
                                                     : PointMode::kAuto;
      if (c.text == "legend") settings_.legend = c.value == "on";
      if (c.text == "record-fps") record_fps = x;
      if (c.text == "face-colors")
        settings_.face_colors = c.value == "age" ? FaceColors::kAge : FaceColors::kState;
      return "";
    }
  }
  return "";
}

}  // namespace cudahull::viewer
