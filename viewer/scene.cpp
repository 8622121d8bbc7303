#include "scene.hpp"

#include <algorithm>
#include <stdexcept>
#include <unordered_set>
#include <utility>

namespace cudahull::viewer {

namespace {

// A face as a key that survives renumbering: its vertices rotated so the smallest comes first (the
// orientation is kept, so a face and its flipped twin differ).
std::array<PointIndex, 3> rotated(PointIndex a, PointIndex b, PointIndex c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

std::uint64_t edge_key(PointIndex a, PointIndex b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t{a} << 32) | b;
}

std::array<PointIndex, 3> sorted(std::array<PointIndex, 3> k) {
  std::sort(k.begin(), k.end());
  return k;
}

}  // namespace

Scene::Scene(ScenePoints points, BackendFactory make_backend, std::string label)
    : points_(std::move(points.positions)),
      exact_(std::move(points.exact)),
      surface_(std::move(points.surface)),
      make_backend_(std::move(make_backend)),
      label_(std::move(label)) {
  if (exact_ && exact_->size() != points_->size())
    throw std::invalid_argument("Scene: the double points and the render positions differ in number");
  restart();
  render_.positions = points_;
  render_.surface = surface_;
  render_.dirty = kDirtyAll;
}

std::unique_ptr<SteppingEngine> Scene::make_engine() const {
  if (make_backend_.resident_float)
    return exact_ ? make_backend_.resident_double(*exact_) : make_backend_.resident_float(*points_);
  if (exact_) return std::make_unique<BasicEngine<Point3d>>(*exact_, make_backend_.make_double());
  return std::make_unique<Engine>(*points_, make_backend_.make_float());
}

SteppingEngine& Scene::restarted_replay() const {
  if (replay_) {
    replay_->restart();
  } else {
    replay_ = make_engine();
  }
  return *replay_;
}

std::vector<IterationRecord> Scene::replay_records() const {
  std::vector<IterationRecord> records;
  SteppingEngine& replay = restarted_replay();
  for (int k = 0; k < position_ && !replay.done(); ++k)
    records.push_back(replay.step());
  return records;
}

std::vector<std::string> Scene::explain_point(PointIndex point) const {
  if (point >= points_->size())
    return {"no point " + std::to_string(point) + " (there are " + std::to_string(points_->size()) + ")"};
  if (position_ == 0) return {"position 0: no step yet"};
  SteppingEngine& replay = restarted_replay();
  const std::uint64_t bytes_before = replay.bytes_from_backend();  // cumulative per backend
  for (int k = 0; k + 1 < position_ && !replay.done(); ++k)
    replay.step();
  std::int32_t before = 0;
  if (position_ >= 2) {
    const std::vector<std::int32_t> faces = replay.point_faces();
    before = point < faces.size() ? faces[point] : -1;
  }
  replay.step();
  std::vector<std::string> lines = replay.explain_route(point, before);
  const std::vector<std::int32_t> after = replay.point_faces();
  point_readback_bytes_ += replay.bytes_from_backend() - bytes_before;  // the replay's
  const bool verdict = !lines.empty() && (lines.back() == "internal" || lines.back() == "vertex" ||
                                          lines.back().rfind("face ", 0) == 0);
  if (verdict && point < after.size()) {
    const std::string backend = after[point] >= 0 ? "face " + std::to_string(after[point]) : "internal";
    const std::string& ours = lines.back();
    const bool same = ours == backend || (ours == "vertex" && after[point] < 0);
    lines.push_back(same ? "the backend agrees (" + backend + ")"
                         : "the backend says " + backend + " instead");
  }
  return lines;
}

void Scene::restart() {
  if (engine_) {
    engine_->restart();  // the backend keeps its points
  } else {
    engine_ = make_engine();
  }
  position_ = 0;
  born_.clear();
  substep_ = -1;
  substeps_position_ = -1;
  render_stale_ = true;
}

void Scene::step_once() {
  substep_ = -1;
  IterationRecord record = engine_->step();
  ++position_;
  record.swaps.clear();
  record.removals.clear();
  record.refined_apexes.clear();
  record.refined_faces.clear();
  record.decisions.clear();
  record.swaps.shrink_to_fit();
  record.decisions.shrink_to_fit();
  if (static_cast<std::size_t>(position_) > history_.size()) {
    history_.push_back(std::move(record));
  } else {
    history_[position_ - 1] = std::move(record);  // the same iteration again, timed anew
  }
  if (engine_->done()) {
    final_known_ = true;
    history_.resize(position_);  // nothing lies beyond the end
  }

  // The birth iteration of every face now shown, for the colour-by-age mode.
  const int iteration = engine_->last_record().iteration;
  std::vector<FaceKey> faces;
  current_faces(faces);
  BirthMap born;
  born.reserve(faces.size());
  for (const FaceKey& f : faces) {
    const auto it = born_.find(f);
    born.emplace(f, it == born_.end() ? iteration : it->second);
  }
  born_ = std::move(born);
  render_stale_ = true;
}

void Scene::step(int count) {
  for (int i = 0; i < count && !engine_->done(); ++i)
    step_once();
}

void Scene::run_to_end() {
  while (!engine_->done())
    step_once();
}

void Scene::rewind(int position) {
  position = std::max(position, 0);
  if (position < position_) restart();
  step(position - position_);
}

void Scene::build_substeps() {
  if (substeps_position_ == position_) return;
  substeps_position_ = position_;
  substeps_.clear();
  substep_point_state_.clear();
  if (position_ < 2 || engine_->dimension() != 3) return;
  // The mesh and the points as they were before the step.
  SteppingEngine& before = restarted_replay();
  const std::uint64_t bytes_before = before.bytes_from_backend();  // cumulative per backend
  for (int k = 0; k + 1 < position_ && !before.done(); ++k)
    before.step();
  if (before.done()) return;
  substep_point_state_ = before.point_faces();
  point_readback_bytes_ += before.bytes_from_backend() - bytes_before;  // the replay's
  substep_point_state_.resize(points_->size(), kPointInternal);
  for (PointIndex v : before.mesh().vertices())
    substep_point_state_[v] = kPointVertex;

  Mesh mesh = before.mesh();
  std::vector<FaceState> state(mesh.face_capacity(), FaceState::kUnchanged);
  auto snapshot = [&](std::string label, int limit) {
    SubStep phase;
    phase.label = std::move(label);
    phase.sequence_limit = limit;
    for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
      if (!mesh.alive(f)) continue;
      const auto& v = mesh.face(f).v;
      phase.faces.push_back(rotated(v[0], v[1], v[2]));
      phase.states.push_back(f < state.size() ? state[f] : FaceState::kUnchanged);
    }
    substeps_.push_back(std::move(phase));
  };
  auto mark_new = [&](FaceState s) { state.resize(mesh.face_capacity(), s); };
  snapshot("before the step", -1);
  const IterationRecord& record = engine_->last_record();
  for (const RefinementEntry& r : engine_->last_refinement()) {
    mesh.split(r.face, r.apex);
    mark_new(FaceState::kRefined);
  }
  snapshot("refinement: " + std::to_string(engine_->last_refinement().size()) + " faces split (Fig. 3a)", -1);

  // The accepted swaps and removals in the order the engine made them.
  for (const KeptEdit& e : kept_edits(record)) {
    if (e.swap) {
      if (!redo_swap(mesh, *e.swap)) break;  // the record does not replay: stop at what is known to be right
      mark_new(FaceState::kSwapped);
      const PointIndex u = e.swap->old_edge[0], v = e.swap->old_edge[1];
      snapshot("swap #" + std::to_string(e.sequence) + " (" + swap_kind_name(e.swap->kind) +
                   "): " + std::to_string(u) + "-" + std::to_string(v) + " -> " +
                   std::to_string(e.swap->new_edge[0]) + "-" + std::to_string(e.swap->new_edge[1]),
               e.sequence);
    } else {
      if (!mesh.has_vertex(e.removal->vertex) || mesh.degree(e.removal->vertex, 4) != 3) break;
      mesh.remove_degree3(e.removal->vertex);
      mark_new(FaceState::kRemoval);
      snapshot("removal #" + std::to_string(e.sequence) + ": vertex " + std::to_string(e.removal->vertex) +
                   " (Fig. 4)",
               e.sequence);
    }
  }
  SubStep last;
  last.label = "redistribution: the points go to their new faces (Algorithm 2)";
  last.sequence_limit = -1;
  substeps_.push_back(std::move(last));
}

int Scene::substep_count() {
  build_substeps();
  return static_cast<int>(substeps_.size());
}

void Scene::set_substep(int phase) {
  const int count = substep_count();
  substep_ = (count == 0 || phase < 0 || phase >= count - 1) ? -1 : phase;
  render_stale_ = true;
}

std::string Scene::substep_label(int phase) {
  const int count = substep_count();
  if (phase < 0 || phase >= count) return "";
  return substeps_[phase].label;
}

int Scene::substep_sequence_limit() const {
  if (substep_ < 0 || substeps_position_ != position_) return 1 << 30;
  return substeps_[substep_].sequence_limit;
}

std::vector<std::array<PointIndex, 3>> Scene::displayed_faces() const {
  std::vector<FaceKey> faces;
  current_faces(faces);
  return faces;
}

void Scene::current_faces(std::vector<FaceKey>& faces) const {
  faces.clear();
  if (position_ == 0) return;
  if (substep_ >= 0 && substeps_position_ == position_) {
    faces = substeps_[substep_].faces;
    return;
  }
  if (engine_->done()) {
    const std::vector<PointIndex>& ids = engine_->result_vertex_ids();
    for (const Triangle& t : engine_->result_triangles())
      faces.push_back(rotated(ids[t[0]], ids[t[1]], ids[t[2]]));
    return;
  }
  const Mesh& mesh = engine_->mesh();
  for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
    if (!mesh.alive(f)) continue;
    const auto& v = mesh.face(f).v;
    faces.push_back(rotated(v[0], v[1], v[2]));
  }
}

void Scene::bounds(float lo[3], float hi[3]) const {
  for (int k = 0; k < 3; ++k)
    lo[k] = hi[k] = 0;
  if (points_->empty()) return;
  const Point3& p0 = points_->front();
  lo[0] = hi[0] = p0.x;
  lo[1] = hi[1] = p0.y;
  lo[2] = hi[2] = p0.z;
  for (const Point3& p : *points_) {
    const float c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], c[k]);
      hi[k] = std::max(hi[k], c[k]);
    }
  }
}

RenderData& Scene::render_data() {
  if (render_stale_) refresh_render_data();
  return render_;
}

void Scene::refresh_render_data() {
  render_stale_ = false;
  const std::size_t n = points_->size();

  std::vector<FaceKey> faces;
  current_faces(faces);
  render_.hull_vertex_ids.clear();
  const bool in_substep = substep_ >= 0 && substeps_position_ == position_;
  if (in_substep) {
    for (const FaceKey& f : faces)
      render_.hull_vertex_ids.insert(render_.hull_vertex_ids.end(), f.begin(), f.end());
    std::sort(render_.hull_vertex_ids.begin(), render_.hull_vertex_ids.end());
    render_.hull_vertex_ids.erase(std::unique(render_.hull_vertex_ids.begin(), render_.hull_vertex_ids.end()),
                                  render_.hull_vertex_ids.end());
  } else if (engine_->done()) {
    render_.hull_vertex_ids = engine_->result_vertex_ids();
  } else if (position_ > 0) {
    render_.hull_vertex_ids = engine_->mesh().vertices();
  }

  // Per-point state: written on the device by the backend (CUDA-GL interop: write_device_point_states()),
  // or read back and uploaded.  Before the first step no point has a face yet: all are shown as external.
  std::uint32_t state_bit = kDirtyPointState;
  if (position_ == 0) {
    render_.point_state.assign(n, 0);
  } else if (in_substep) {
    render_.point_state = substep_point_state_;  // before the redistribution, the points are as they were
  } else if (device_point_states_ && engine_->dimension() == 3) {
    render_.point_state.clear();
    state_bit = kDirtyDeviceState;
  } else {
    const std::uint64_t before = engine_->bytes_from_backend();
    render_.point_state = engine_->point_faces();
    point_readback_bytes_ += engine_->bytes_from_backend() - before;
    if (render_.point_state.size() != n) render_.point_state.assign(n, kPointInternal);
    for (PointIndex v : render_.hull_vertex_ids)
      render_.point_state[v] = kPointVertex;
  }

  // What the last iteration did to each face (Algorithm 1): made by a swap, by a removal, or otherwise new
  // (a refinement, Fig. 3a; at iteration 0 the tetrahedron).
  render_.hull.clear();
  if (position_ > 0) {
    const IterationRecord& record = engine_->last_record();
    std::unordered_set<std::uint64_t> swapped_edges;
    for (const SwapRecord& s : record.swaps) {
      if (s.kind == SwapKind::kRegular || s.kind == SwapKind::kComplementary)
        swapped_edges.insert(edge_key(s.new_edge[0], s.new_edge[1]));
    }
    std::unordered_set<FaceKey, FaceKeyHash> removal_faces;
    for (const RemovalRecord& r : record.removals) {
      if (!r.rejected) removal_faces.insert(sorted({r.ring[0], r.ring[1], r.ring[2]}));
    }
    render_.hull.reserve(faces.size() * 3);
    if (in_substep) {
      const SubStep& phase = substeps_[substep_];
      for (std::size_t k = 0; k < faces.size(); ++k) {
        const std::uint32_t info = pack_face_info(phase.states[k], 0);
        for (PointIndex v : faces[k]) {
          const Point3& p = (*points_)[v];
          render_.hull.push_back({p.x, p.y, p.z, info});
        }
      }
      faces.clear();  // drawn
    }
    for (const FaceKey& f : faces) {
      const auto it = born_.find(f);
      const int born = it == born_.end() ? record.iteration : it->second;
      FaceState state = FaceState::kUnchanged;
      if (born == record.iteration) {
        state = FaceState::kRefined;
        if (swapped_edges.count(edge_key(f[0], f[1])) || swapped_edges.count(edge_key(f[1], f[2])) ||
            swapped_edges.count(edge_key(f[2], f[0])))
          state = FaceState::kSwapped;
        if (removal_faces.count(sorted(f))) state = FaceState::kRemoval;
      }
      const std::uint32_t info = pack_face_info(state, static_cast<std::uint32_t>(record.iteration - born));
      for (PointIndex v : f) {
        const Point3& p = (*points_)[v];
        render_.hull.push_back({p.x, p.y, p.z, info});
      }
    }
  }
  render_.dirty |= state_bit | kDirtyHull;
}

bool Scene::write_device_point_states(void* device, std::size_t bytes) {
  const std::size_t n = points_->size();
  if (bytes < n * sizeof(std::int32_t)) return false;
  return engine_->write_point_states_on_device(static_cast<std::int32_t*>(device), n,
                                               render_.hull_vertex_ids);
}

}  // namespace cudahull::viewer
