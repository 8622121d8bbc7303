// The engine: Algorithm 1 of the paper, one iteration per step(), each phase a call into engine/src/phases/
// (docs/architecture.md draws them and the data between them).
#include "cudahull/engine.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <type_traits>

#include "cudahull/exact_hull.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "phases/cells.hpp"
#include "phases/decision_array.hpp"
#include "phases/final_check.hpp"
#include "phases/initial_tetrahedron.hpp"
#include "phases/local_edits.hpp"
#include "phases/refinement.hpp"
#include "phases/swap_scratch.hpp"
#include "phases/swaps.hpp"

namespace cudahull {

namespace {
constexpr int kStallLimit = 8;  // iterations without fewer external points before finishing
}  // namespace

const char* swap_kind_name(SwapKind kind) {
  switch (kind) {
    case SwapKind::kRegular:
      return "regular";
    case SwapKind::kComplementary:
      return "complementary";
    case SwapKind::kRejectedFoldover:
      return "rejected_foldover";
    case SwapKind::kRejectedEdgeExists:
      return "rejected_edge_exists";
    case SwapKind::kRejectedDegenerate:
      return "rejected_degenerate";
  }
  return "unknown";
}

std::vector<KeptEdit> kept_edits(const IterationRecord& record) {
  std::vector<KeptEdit> edits;
  for (const SwapRecord& w : record.swaps) {
    if (w.kind == SwapKind::kRegular || w.kind == SwapKind::kComplementary)
      edits.push_back({w.sequence, &w, nullptr});
  }
  for (const RemovalRecord& m : record.removals) {
    if (!m.rejected) edits.push_back({m.sequence, nullptr, &m});
  }
  std::sort(edits.begin(), edits.end(),
            [](const KeptEdit& a, const KeptEdit& b) { return a.sequence < b.sequence; });
  return edits;
}

std::optional<std::array<FaceId, 2>> redo_swap(Mesh& mesh, const SwapRecord& swap) {
  const PointIndex u = swap.old_edge[0], v = swap.old_edge[1];
  std::vector<PointIndex> ring;
  std::vector<FaceId> ring_faces;
  mesh.ring(u, ring, ring_faces);
  for (FaceId f : ring_faces) {
    const int i = mesh.edge_index(f, u, v);
    if (i >= 0) return mesh.swap(f, i);
  }
  return std::nullopt;
}

template <class Point>
BasicEngine<Point>::BasicEngine(const std::vector<Point>& points,
                                std::unique_ptr<BasicBackend<Point>> backend, EngineOptions options)
    : points_(&points), backend_(std::move(backend)), options_(options) {
  if (!backend_) throw std::invalid_argument("Engine needs a backend");
  if (points_->size() >= 0xffffffffu) throw std::invalid_argument("too many points (at most 2^32 - 2)");
}

template <class Point>
BasicEngine<Point>::~BasicEngine() = default;

template <class Point>
std::size_t BasicEngine<Point>::point_count() const {
  return points_->size();
}

template <class Point>
Vec3d BasicEngine<Point>::point(PointIndex i) const {
  return to_vec3d((*points_)[i]);
}

template <class Point>
Precision BasicEngine<Point>::precision() const {
  return precision_of<Point>();
}

template <class Point>
std::string BasicEngine<Point>::backend_name() const {
  return backend_->name();
}

template <class Point>
std::uint64_t BasicEngine<Point>::bytes_from_backend() const {
  return backend_->bytes_from_backend();
}

template <class Point>
bool BasicEngine<Point>::has_device_point_states() const {
  return backend_->has_device_point_states();
}

template <class Point>
const std::vector<PointIndex>& BasicEngine<Point>::result_vertex_ids() const {
  return result_.vertex_ids;
}

template <class Point>
const std::vector<Triangle>& BasicEngine<Point>::result_triangles() const {
  return result_.triangles;
}

template <class Point>
void BasicEngine<Point>::restart() {
  mesh_ = Mesh{};
  iteration_ = 0;
  started_ = done_ = false;
  dimension_ = -2;
  interior_ = {};
  external_ = 0;
  extremes_.clear();
  removed_vertices_.clear();
  removed_near_.clear();
  used_vertices_.clear();
  vertex_flags_.clear();
  stalled_ = 0;
  result_ = BasicHullMesh<Point>{};
  last_record_ = IterationRecord{};
  tables_.clear();
  // The swap rounds' hashed edge claims collide by the table's size, which grows with the rounds seen: a
  // table kept from the last run would delay other swaps than a fresh one and change the records.
  swap_scratch_.reset();
  if (uploaded_) backend_->restart();
}

template <class Point>
IterationRecord BasicEngine<Point>::step() {
  if (done_) throw std::logic_error("Engine::step() after done()");
  if (!started_) {
    started_ = true;
    last_record_ = initialize();
  } else {
    last_record_ = iterate();
  }
  return last_record_;
}

template <class Point>
void BasicEngine<Point>::run(const std::function<void(const IterationRecord&)>& on_step) {
  while (!done_) {
    IterationRecord r = step();
    if (on_step) on_step(r);
  }
}

template <class Point>
bool BasicEngine<Point>::write_point_states_on_device(std::int32_t* device_out, std::size_t count,
                                                      const std::vector<PointIndex>& vertices) {
  if (!started_ || dimension_ != 3 || count != points_->size()) return false;
  return backend_->write_point_states_on_device(device_out, count, vertices);
}

template <class Point>
std::vector<std::int32_t> BasicEngine<Point>::point_faces() const {
  std::vector<std::int32_t> out;
  if (started_ && dimension_ == 3) backend_->point_faces(out);
  for (auto& f : out) {
    if (f < 0) f = -1;
  }
  return out;
}

template <class Point>
FaceCell BasicEngine<Point>::face_cell(FaceId f) const {
  return phases::face_cell(mesh_, *points_, f);
}

template <class Point>
double BasicEngine<Point>::distribute() {
  const auto t0 = Clock::now();
  backend_->distribute_points(tables_);
  external_ = backend_->compact_index_array();
  backend_->get_extreme_points(extremes_);
  geometry_.swap(tables_.faces);  // the old geometry stays as the next iteration's buffer
  return ms_since(t0);
}

// The first step: section 3.1's tetrahedron, its four cells, and the first distribution.
template <class Point>
IterationRecord BasicEngine<Point>::initialize() {
  const auto t0 = Clock::now();
  IterationRecord record;
  record.iteration = iteration_++;
  const std::vector<Point>& points = *points_;
  auto finish_lower = [&](int dim, const std::string& why) {
    dimension_ = dim;
    result_ = exact_hull(points);
    record.note = why;
    record.host_ms = ms_since(t0);
    done_ = true;
    return record;
  };
  if (points.empty()) return finish_lower(-1, "no points");
  record.external_before = points.size();
  const std::uint64_t to_before = backend_->bytes_to_backend(), from_before = backend_->bytes_from_backend();

  if (!uploaded_) {
    const auto tu = Clock::now();
    backend_->upload_points(points);
    record.upload_ms = ms_since(tu);
    uploaded_ = true;
  }
  const phases::InitialTetrahedron tetrahedron = phases::find_initial_tetrahedron(points, *backend_);
  double backend_ms = record.upload_ms + tetrahedron.backend_ms;
  if (tetrahedron.dimension < 3) return finish_lower(tetrahedron.dimension, tetrahedron.note);
  dimension_ = 3;
  vertex_flags_.clear();
  used_vertices_.assign(tetrahedron.corners.begin(), tetrahedron.corners.end());
  if (!phases::make_initial_tetrahedron(points, tetrahedron.corners, mesh_, interior_)) {
    record.repairs = 1;
    return finish_lower(3, "tetrahedron too flat for an interior point: exact hull of all points");
  }

  auto& tables = tables_;
  tables.clear();
  tables.interior = interior_;
  for (FaceId f = 0; f < 4; ++f) {
    const FaceCell cell = face_cell(f);
    for (int i = 0; i < 3; ++i)
      tables.initial_cells.push_back(cell.edge_plane[i]);
  }
  phases::build_face_geometry(mesh_, points, interior_, geometry_, nullptr, tables.faces);
  tables.old_face_split.assign(1, -1);  // unused: the first distribution goes by the initial cells
  tables.old_face_route.assign(1, 0);
  record.host_ms = ms_since(t0) - backend_ms;
  record.backend_ms = backend_ms + distribute();
  record.faces_after = 4;
  record.external_after = external_;
  record.bytes_to_backend = backend_->bytes_to_backend() - to_before;
  record.bytes_from_backend = backend_->bytes_from_backend() - from_before;
  record.refined_apexes = used_vertices_;
  if (external_ == 0) finish(record);
  return record;
}

// One iteration of Algorithm 1: refine, regular swaps, complementary swaps and removals, build the tables,
// distribute.
template <class Point>
IterationRecord BasicEngine<Point>::iterate() {
  const auto t0 = Clock::now();
  const std::uint64_t to_before = backend_->bytes_to_backend(), from_before = backend_->bytes_from_backend();
  const std::vector<Point>& points = *points_;
  IterationRecord record;
  record.iteration = iteration_++;
  record.faces_before = mesh_.live_faces();
  record.external_before = external_;
  const auto old_faces = static_cast<FaceId>(mesh_.face_capacity());

  // 1. Refinement (Fig. 3a): every face with external points splits at its furthest point.
  phases::Refinement refinement = phases::refine(mesh_, extremes_, record);
  const std::size_t refined = refinement.refined.size();
  used_vertices_.insert(used_vertices_.end(), record.refined_apexes.begin(), record.refined_apexes.end());
  const double t_refine = ms_since(t0);

  // 2. Regular swaps of the refined faces' old edges (Figs. 3b, 5), touching the refined faces' corners.
  if (!swap_scratch_) swap_scratch_ = std::make_unique<phases::SwapScratch>();
  phases::DecisionArrayBuilder decisions;
  phases::LocalEdits edits{points,    interior_, options_.batched_swaps_from, mesh_,         vertex_flags_,
                           decisions, record,    removed_vertices_,           removed_near_, *swap_scratch_};
  // Room for every vertex the edits may flag (every point that was ever a vertex, the apexes included), so
  // touch() never rehashes.
  vertex_flags_.reserve(used_vertices_.size());
  if (refined >= options_.batched_swaps_from) {
    edits.touched.resize(3 * refined);
    parallel_chunks(
        refined, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k)
            std::copy_n(record.refined_faces[k].begin(), 3, edits.touched.begin() + 3 * k);
        },
        16384);
    edits.touched_unsorted = true;  // settle() sorts and dedupes them
  } else {
    for (const auto& corners : record.refined_faces) {
      for (PointIndex v : corners)
        edits.touch(v);
    }
  }
  std::vector<phases::SwapCandidate> regular;
  regular.reserve(3 * refined);
  for (const auto& kids : refinement.children) {
    for (FaceId child : kids)
      regular.push_back({{child, 0}, SwapKind::kRegular});
  }
  edits.reset_budget();
  phases::swap_edges(edits, std::move(regular));
  const double t_regular = ms_since(t0);

  // 3. Complementary swaps and removals until the mesh settles (Fig. 4).
  phases::settle(edits);
  const double t_settle = ms_since(t0);

  // 4. The tables (Fig. 7): the separating planes of the refinements and swaps (Fig. 2), the faces
  // renumbered, every work id turned into a route code, the new faces' geometry.
  phases::refinement_planes(mesh_, points, refinement.entries, refinement.children);
  decisions.resolve_swap_planes(mesh_, points);
  const double t_planes = ms_since(t0);
  const std::vector<FaceId>& remap = mesh_.compact();
  tables_.clear();
  tables_.interior = interior_;
  decisions.build_tables(tables_, std::move(refinement.entries), refinement.children, remap, old_faces,
                         record.refined_apexes);
  const double t_tables = ms_since(t0);
  phases::build_face_geometry(mesh_, points, interior_, geometry_, &remap, tables_.faces);
  record.decision_entries = tables_.decision.size();
  record.host_ms = ms_since(t0);
  if (phase_times_wanted())
    std::fprintf(stderr,
                 "iteration %d host ms: refine %.2f regular+batched %.2f settle %.2f planes %.2f tables %.2f "
                 "geometry %.2f\n",
                 record.iteration, t_refine, t_regular - t_refine, t_settle - t_regular, t_planes - t_settle,
                 t_tables - t_planes, record.host_ms - t_tables);

  // 5. Algorithm 2 on the backend: distribute, compact, extremes.
  record.backend_ms = distribute();
  record.faces_after = mesh_.live_faces();
  record.external_after = external_;
  record.bytes_to_backend = backend_->bytes_to_backend() - to_before;
  record.bytes_from_backend = backend_->bytes_from_backend() - from_before;
  if (options_.keep_decisions) record.decisions = tables_.decision;
  stalled_ = external_ < record.external_before ? 0 : stalled_ + 1;
  if (external_ == 0 || stalled_ >= kStallLimit) finish(record);
  return record;
}

// No external point is left (or progress stalled): the exact check, repair and result.
template <class Point>
void BasicEngine<Point>::finish(IterationRecord& record) {
  const auto t0 = Clock::now();
  phases::DecisionArrayBuilder decisions;  // the repairs' entries route no points
  if (!swap_scratch_) swap_scratch_ = std::make_unique<phases::SwapScratch>();
  phases::LocalEdits edits{*points_,  interior_, options_.batched_swaps_from, mesh_,         vertex_flags_,
                           decisions, record,    removed_vertices_,           removed_near_, *swap_scratch_};
  result_ =
      phases::final_check(edits, geometry_, used_vertices_, external_, [this] { return point_faces(); });
  record.host_ms += ms_since(t0);
  done_ = true;
}

template class BasicEngine<Point3>;
template class BasicEngine<Point3d>;

}  // namespace cudahull
