// The resident engine stepped one iteration at a time, with records (issue 15, deliverable 3): the
// SteppingEngine the viewer, `--trace` and `--table` drive, over the same operations the fast path runs
// (resident_driver.hpp), on the host or the GPU executor.
//
// design:
//   step 0        P (or section 3.1's tetrahedron) and the first distribution; the mesh read back
//   step k        ResidentHull::step(): refine, the swap and removal rounds stepped by the host with every
//                 candidate they turn down logged, route, compact; then read back what it did
//                 (RecordedIteration, O(faces) bytes) and the new mesh, and turn them into the
//                 IterationRecord the stepping Engine gives:
//                   refinements     the entries of kind refine: the killed face's corners and the apex
//                   swaps           the swap entries in round order, each round's rejections first; regular
//                                   when the swapped edge is an edge of a face refined this iteration
//                                   (Fig. 3b), complementary otherwise (Fig. 4)
//                   removals        the removal entries (Fig. 4); rejected ones where the new face would
//                                   not keep c strictly below, or the surface would not stay a 2-manifold
//                   decision array  the swap and removal entries as Fig. 7's entries: a swap's plane is the
//                                   plane through c and the new edge (the resident engine routes by cones
//                                   from c), a removal's has none
//   the end       the exact check on the executor (ResidentHull::end), as the fast path finishes
#pragma once

#include <algorithm>
#include <chrono>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_set>
#include <utility>
#include <vector>

#include "cudahull/engine.hpp"
#include "cudahull/resident/resident_driver.hpp"
#include "cudahull/resident/shared_phases.hpp"

namespace cudahull::resident {

template <class Point, class Exec>
class ResidentStepper : public SteppingEngine {
 public:
  // Borrows `points` (the host copy, for coordinates and exact checks); upload_points() says where the
  // executor reads them.  `exec_args` construct the executor (CudaExec's: a ResidentTuning).
  template <class... ExecArgs>
  ResidentStepper(const std::vector<Point>& points, std::string backend_name, bool device_point_states,
                  const ExecArgs&... exec_args)
      : exec_(exec_args...),
        points_(&points),
        name_(std::move(backend_name)),
        device_states_(device_point_states) {}
  // Its recorder points at its own last_: not copied.
  ResidentStepper(const ResidentStepper&) = delete;
  ResidentStepper& operator=(const ResidentStepper&) = delete;

  bool done() const override { return done_; }
  void restart() override {
    hull_.reset();
    mesh_ = Mesh{};
    iteration_ = 0;
    done_ = false;
    dimension_ = -2;
    c_ = {};
    stats_ = {};
    result_ = {};
    record_ = {};
    last_ = {};
    extremes_.clear();
    decisions_.clear();
    refinement_.clear();
    removed_.clear();
  }
  IterationRecord step() override {
    if (done_) throw std::logic_error("step() after done()");
    const auto t0 = std::chrono::steady_clock::now();
    const std::uint64_t to_before = exec_.bytes_to_device, from_before = exec_.bytes_from_device;
    IterationRecord r;
    r.iteration = iteration_++;
    host_ms_ = 0;
    if (!hull_) {
      first_step(r);
    } else {
      next_step(r);
    }
    // host_ms: the records and the mesh made of what came back; backend_ms: the rest, the executor's.
    r.host_ms = host_ms_;
    r.backend_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() - host_ms_;
    r.bytes_to_backend = exec_.bytes_to_device - to_before;
    r.bytes_from_backend = exec_.bytes_from_device - from_before;
    stats_.host_syncs = exec_.host_syncs;
    stats_.bytes_to_device = exec_.bytes_to_device;
    stats_.bytes_from_device = exec_.bytes_from_device;
    record_ = r;
    return r;
  }
  void run(const std::function<void(const IterationRecord&)>& on_step = {}) override {
    while (!done_) {
      const IterationRecord r = step();
      if (on_step) on_step(r);
    }
  }

  std::size_t point_count() const override { return points_->size(); }
  Vec3d point(PointIndex i) const override { return to_vec3d((*points_)[i]); }
  Precision precision() const override { return precision_of<Point>(); }
  const Mesh& mesh() const override { return mesh_; }
  std::string backend_name() const override { return name_; }
  std::uint64_t bytes_from_backend() const override { return exec_.bytes_from_device; }
  bool has_device_point_states() const override { return device_states_; }
  int dimension() const override { return dimension_; }
  Vec3d interior_point() const override { return c_; }
  // Face f's cell: the cone from c over it (the resident engine's cells; section 3's separating planes
  // become the planes through c and each edge), its sides positive inside.
  FaceCell face_cell(FaceId f) const override {
    const MeshFace& face = mesh_.face(f);
    const Vec3d a = point(face.v[0]), b = point(face.v[1]), d = point(face.v[2]);
    const Vec3d centre{(a.x + b.x + d.x) / 3, (a.y + b.y + d.y) / 3, (a.z + b.z + d.z) / 3};
    FaceCell cell;
    cell.face_plane = plane_through(a, b, d, {2 * centre.x - c_.x, 2 * centre.y - c_.y, 2 * centre.z - c_.z});
    const Vec3d corners[3] = {a, b, d};
    for (int i = 0; i < 3; ++i)
      cell.edge_plane[i] = plane_through(c_, corners[i], corners[(i + 1) % 3], centre);
    return cell;
  }
  std::vector<std::int32_t> point_faces() const override {
    std::vector<std::int32_t> out;
    if (hull_ && dimension_ == 3) hull_->read_point_faces(out);
    return out;
  }
  bool write_point_states_on_device(std::int32_t* device_out, std::size_t count,
                                    const std::vector<PointIndex>& vertices) override {
    if (!device_states_ || !hull_ || dimension_ != 3 || count != points_->size()) return false;
    hull_->write_point_states(device_out, vertices);
    return true;
  }
  std::vector<std::string> explain_route(PointIndex point, std::int32_t old_face) const override;
  const std::vector<FaceExtreme>& face_extremes() const override { return extremes_; }
  const std::vector<DecisionEntry>& last_decisions() const override { return decisions_; }
  const std::vector<RefinementEntry>& last_refinement() const override { return refinement_; }
  const std::vector<PointIndex>& removed_vertices() const override { return removed_; }
  const IterationRecord& last_record() const override { return record_; }
  const std::vector<PointIndex>& result_vertex_ids() const override { return result_.vertex_ids; }
  const std::vector<Triangle>& result_triangles() const override { return result_.triangles; }

  const BasicHullMesh<Point>& result() const { return result_; }
  const ResidentStats* resident_stats() const override { return &stats_; }

 protected:
  // Where the executor reads the points; called once, on the first step (the host executor reads the
  // caller's vector and needs nothing; the GPU's stepper uploads them).
  virtual const Point* upload_points() { return points_->data(); }

  Exec exec_;
  const std::vector<Point>* points_;

 private:
  void first_step(IterationRecord& r) {
    if (!exec_points_) {
      // The points go to the executor on the first step (and stay for restarts), counted in its record.
      const auto t0 = std::chrono::steady_clock::now();
      exec_points_ = upload_points();
      r.upload_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    hull_.emplace(exec_, exec_points_, points_->size(), points_);
    r.external_before = points_->size();
    BasicHullMesh<Point> answer;
    if (!hull_->begin(stats_, answer)) {
      // The answer already (no points, lower-dimensional input, or a tetrahedron too flat for an interior
      // point: then the exact hull of all the points, a repair); no mesh to query.
      hull_.reset();
      dimension_ = points_->empty() ? -1 : answer.dimension;
      if (dimension_ == 3) r.repairs = 1;
      result_ = std::move(answer);
      r.note = points_->empty() ? "no points" : stats_.note;
      done_ = true;
      return;
    }
    dimension_ = 3;
    c_ = hull_->interior();
    read_mesh();
    r.faces_after = mesh_.live_faces();
    r.external_after = hull_->active_points();
    r.refined_apexes = mesh_.vertices();  // the first mesh's corners (P's, or the tetrahedron's)
    r.note = stats_.polytope_first ? "first mesh: P, the hull of the extremes along 14 directions"
                                   : "first mesh: section 3.1's tetrahedron";
    if (r.external_after == 0) finish(r, false);
  }

  void next_step(IterationRecord& r) {
    r.faces_before = mesh_.live_faces();
    r.external_before = hull_->active_points();
    refinement_.clear();
    decisions_.clear();
    if (!hull_->step(stats_, recorder_)) {
      // A stall: no face could refine, the mesh is as it was; the exact finish answers.
      r.faces_after = r.faces_before;
      r.external_after = r.external_before;
      finish(r, true);
      return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    describe(last_, r);
    host_ms_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    read_mesh();
    r.faces_after = mesh_.live_faces();
    r.external_after = hull_->active_points();
    if (r.external_after == 0) finish(r, false);
  }

  void finish(IterationRecord& r, bool stalled) {
    result_ = hull_->end(stats_, stalled);
    if (stats_.exact_finish) {
      r.repairs = std::max<std::uint64_t>(1, stats_.faults);
      r.note = (r.note.empty() ? "" : r.note + "; ") + "exact finish: " + stats_.note;
    } else if (stats_.faults != 0) {
      r.repairs = stats_.faults;
      r.note = (r.note.empty() ? "" : r.note + "; ") + "repaired " + std::to_string(stats_.faults) +
               " defects (concave edges, vertices not strictly extreme) in " +
               std::to_string(stats_.repaired_patches) + " patches";
    }
    done_ = true;
  }

  // The mesh read back into buffers kept between steps: fresh ones of a few MB each step cost their
  // pages' first touch again.
  void read_mesh() {
    hull_->read_mesh(read_fv_, read_fn_);
    const auto t0 = std::chrono::steady_clock::now();
    read_faces_.resize(read_fv_.size() / 3);
    for (std::size_t f = 0; f < read_faces_.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        read_faces_[f].v[k] = read_fv_[3 * f + k];
        read_faces_[f].n[k] = read_fn_[3 * f + k];
      }
    }
    mesh_.assign(read_faces_);
    host_ms_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    hull_->read_face_extremes(extremes_);
  }

  // Where a point of face id `o` of the iteration goes (Fig. 7's route codes): its id in the new mesh,
  // or the decision entry that killed it later in the iteration.
  static std::int32_t route_code(const RecordedIteration& it, u32 o) {
    const u32 e = it.replaced_by[o];
    if (e == kAlive) return static_cast<std::int32_t>(it.new_id[o]);
    return -static_cast<std::int32_t>(e - it.refined) - 1;
  }

  void describe(const RecordedIteration& it, IterationRecord& r) {
    const std::size_t entries = it.entries.size();
    // The faces each entry killed (a refinement one, a swap two, a removal three).
    std::vector<std::array<u32, 3>> killed(entries, {kNone, kNone, kNone});
    for (u32 f = 0; f < it.replaced_by.size(); ++f) {
      const u32 e = it.replaced_by[f];
      if (e >= entries) continue;
      for (u32& slot : killed[e]) {
        if (slot == kNone) {
          slot = f;
          break;
        }
      }
    }
    auto corner = [&](u32 f, int k) { return it.fv[3 * f + k]; };
    auto edge_key = [](u32 a, u32 b) { return (u64{std::min(a, b)} << 32) | std::max(a, b); };
    // Regular swaps are of the refined faces' edges (Fig. 3b); complementary ones of edges made this
    // iteration or of other faces around (Fig. 4).
    std::unordered_set<u64> refined_edges;
    refined_edges.reserve(3 * it.refined);
    for (u32 e = 0; e < it.refined; ++e) {
      for (int k = 0; k < 3; ++k)
        refined_edges.insert(edge_key(corner(killed[e][0], k), corner(killed[e][0], (k + 1) % 3)));
    }

    // Refinements (Fig. 3a): the old face, its apex, and the planes through c, the apex and each corner.
    refinement_.clear();
    for (u32 e = 0; e < it.refined; ++e) {
      const Entry& entry = it.entries[e];
      const u32 f = killed[e][0];
      RefinementEntry out;
      out.face = f;
      out.apex = entry.p;
      std::array<PointIndex, 3> corners{};
      const Vec3d p = point(entry.p);
      for (int k = 0; k < 3; ++k) {
        corners[k] = corner(f, k);
        out.child[k] = route_code(it, entry.out[k]);
      }
      for (int k = 0; k < 3; ++k) {
        const Vec3d a = point(corners[k]), b = point(corners[(k + 1) % 3]);
        out.plane[k] =
            plane_through(c_, a, p, {(a.x + b.x + p.x) / 3, (a.y + b.y + p.y) / 3, (a.z + b.z + p.z) / 3});
      }
      refinement_.push_back(out);
      r.refined_apexes.push_back(entry.p);
      r.refined_faces.push_back(corners);
    }
    r.faces_refined = it.refined;

    // The decision array (Fig. 7) and the edits in the order they were made: round by round, each round's
    // rejections (the first time they were met) and then its winners.
    decisions_.clear();
    for (std::size_t e = it.refined; e < entries; ++e) {
      const Entry& entry = it.entries[e];
      DecisionEntry d;
      if (entry.kind == kSwap) {
        const u32 n2 = entry.out[1];
        const Vec3d x = point(entry.p), y = point(entry.q), v = point(corner(n2, 1));
        d.plane =
            plane_through(c_, x, y, {(x.x + y.x + v.x) / 3, (x.y + y.y + v.y) / 3, (x.z + y.z + v.z) / 3});
        d.above = route_code(it, n2);
        d.below = route_code(it, entry.out[0]);
        d.kind = kDecisionSwap;
      } else {
        d.above = d.below = route_code(it, entry.out[0]);
        d.kind = kDecisionRemoval;
      }
      decisions_.push_back(d);
    }
    r.decisions = decisions_;
    r.decision_entries = decisions_.size();

    std::set<std::array<u32, 5>> seen;  // rejections already recorded this iteration
    int sequence = 0;
    std::size_t next_rejection = 0;
    const std::size_t rounds = it.round_first_entry.size();
    for (std::size_t k = 0; k < rounds; ++k) {
      const u32 round = it.first_round + static_cast<u32>(k);
      for (; next_rejection < it.rejections.size() && it.rejections[next_rejection].round <= round;
           ++next_rejection) {
        const Rejection& rej = it.rejections[next_rejection];
        if (!seen.insert({rej.kind, rej.vertex[0], rej.vertex[1], rej.vertex[2], rej.vertex[3]}).second)
          continue;
        record_rejection(rej, sequence++, r);
      }
      const std::size_t begin = it.round_first_entry[k];
      const std::size_t end = k + 1 < rounds ? it.round_first_entry[k + 1] : entries;
      for (std::size_t e = begin; e < end; ++e) {
        const Entry& entry = it.entries[e];
        const auto index = static_cast<std::int32_t>(e - it.refined);
        if (entry.kind == kSwap) {
          SwapRecord s;
          const u32 u = corner(entry.out[0], 1), v = corner(entry.out[1], 1);
          s.kind = refined_edges.count(edge_key(u, v)) ? SwapKind::kRegular : SwapKind::kComplementary;
          s.sequence = sequence++;
          s.old_edge[0] = u;
          s.old_edge[1] = v;
          s.new_edge[0] = entry.p;
          s.new_edge[1] = entry.q;
          s.decision_index = index;
          (s.kind == SwapKind::kRegular ? r.swaps_regular : r.swaps_complementary) += 1;
          r.swaps.push_back(s);
        } else {
          // The removed vertex: the corner its three faces share.
          auto holds = [&](u32 face, u32 v) {
            return v == corner(face, 0) || v == corner(face, 1) || v == corner(face, 2);
          };
          u32 vertex = kNone;
          for (int a = 0; a < 3 && vertex == kNone; ++a) {
            const u32 v = corner(killed[e][0], a);
            if (holds(killed[e][1], v) && holds(killed[e][2], v)) vertex = v;
          }
          RemovalRecord rm;
          rm.sequence = sequence++;
          rm.vertex = vertex;
          for (int k2 = 0; k2 < 3; ++k2)
            rm.ring[k2] = corner(entry.out[0], k2);
          rm.decision_index = index;
          r.removals.push_back(rm);
          removed_.push_back(vertex);
          ++r.vertices_removed;
        }
      }
    }
  }

  void record_rejection(const Rejection& rej, int sequence, IterationRecord& r) const {
    if (rej.kind == kRejectRemoval) {
      RemovalRecord rm;
      rm.sequence = sequence;
      rm.vertex = rej.vertex[0];
      rm.ring[0] = rej.vertex[1];
      rm.ring[1] = rej.vertex[2];
      rm.ring[2] = rej.vertex[3];
      rm.rejected = true;
      r.removals.push_back(rm);
      ++r.removals_rejected;
      return;
    }
    // Swap u - v into x - y: n1 = (x, u, y), n2 = (y, v, x).  A foldover (Fig. 5): seen from c, the vertex
    // of the old edge whose new face would turn over lies beneath the other new face.
    const u32 u = rej.vertex[0], v = rej.vertex[1], x = rej.vertex[2], y = rej.vertex[3];
    SwapRecord s;
    s.sequence = sequence;
    s.old_edge[0] = u;
    s.old_edge[1] = v;
    s.new_edge[0] = x;
    s.new_edge[1] = y;
    if (rej.kind == kRejectFoldover) {
      s.kind = SwapKind::kRejectedFoldover;
      // One new face turned over: its old-edge vertex lies beneath the other.  Both (the four points
      // coplanar with c, seen edge on): no single vertex is beneath, and none is named.
      const bool u_turns = orient3d(c_, point(x), point(u), point(y)) <= 0,
                 v_turns = orient3d(c_, point(y), point(v), point(x)) <= 0;
      if (u_turns != v_turns) {
        s.beneath_vertex = u_turns ? u : v;
        const std::array<PointIndex, 3> other =
            u_turns ? std::array<PointIndex, 3>{y, v, x} : std::array<PointIndex, 3>{x, u, y};
        std::copy(other.begin(), other.end(), s.beneath_triangle);
      }
    } else {
      s.kind = SwapKind::kRejectedEdgeExists;
    }
    ++r.swaps_rejected;
    r.swaps.push_back(s);
  }

  const Point* exec_points_ = nullptr;  // upload_points()'s answer, kept across restarts
  double host_ms_ = 0;                  // this step's host work on what came back
  std::string name_;
  bool device_states_;
  mutable std::optional<ResidentHull<Point, Exec>> hull_;  // reads back on const queries
  Mesh mesh_;
  int iteration_ = 0;
  bool done_ = false;
  int dimension_ = -2;
  Vec3d c_{};
  ResidentStats stats_;
  BasicHullMesh<Point> result_;
  IterationRecord record_;
  RecordedIteration last_;
  IterationRecorder<Point, Exec> recorder_{last_};  // step()'s log and read-back, into last_
  std::vector<FaceExtreme> extremes_;
  std::vector<DecisionEntry> decisions_;
  std::vector<RefinementEntry> refinement_;
  std::vector<u32> read_fv_, read_fn_;  // read_mesh()'s
  std::vector<MeshFace> read_faces_;
  std::vector<PointIndex> removed_;
};

// The debugger's "explain point": the point's route through the last step's entries, as RoutePoints
// takes it, hop by hop, ending in "face F", "internal" or "vertex".
template <class Point, class Exec>
std::vector<std::string> ResidentStepper<Point, Exec>::explain_route(PointIndex point_id,
                                                                     std::int32_t old_face) const {
  if (!hull_ || dimension_ != 3 || point_id >= points_->size()) return {"no 3-d step to explain"};
  const Vec3d q = point(point_id);
  std::vector<std::string> lines;
  auto verdict = [&](u32 face_now, std::vector<std::string>& out) {
    const MeshFace& face = mesh_.face(face_now);
    if (orient3d(point(face.v[0]), point(face.v[1]), point(face.v[2]), q) > 0) {
      out.push_back("strictly above it (exact orient3d): kept");
      out.push_back("face " + std::to_string(face_now));
    } else if (mesh_.has_vertex(point_id)) {
      out.push_back("on it: a vertex of the mesh");
      out.push_back("vertex");
    } else {
      out.push_back("on or below it, so inside the tetrahedron of c and the face (exact orient3d): dropped");
      out.push_back("internal");
    }
    return out;
  };
  if (iteration_ == 1) {
    // The first distribution: the first face (P's or the tetrahedron's) whose closed cone from c holds it.
    const std::size_t faces = mesh_.live_faces();
    u32 f = static_cast<u32>(faces - 1);
    for (u32 g = 0; g + 1 < faces; ++g) {
      const MeshFace& face = mesh_.face(g);
      const Vec3d a = point(face.v[0]), b = point(face.v[1]), d = point(face.v[2]);
      if (orient3d(c_, a, b, q) >= 0 && orient3d(c_, b, d, q) >= 0 && orient3d(c_, d, a, q) >= 0) {
        f = g;
        break;
      }
    }
    lines.push_back("first distribution: in the cone from c over first-mesh face " + std::to_string(f));
    return verdict(f, lines);
  }
  const RecordedIteration& it = last_;
  if (it.replaced_by.empty())
    return {"the last step refined no face (a stall): the exact finish answered, no point was routed"};
  if (old_face < 0 || static_cast<std::size_t>(old_face) >= it.faces_before)
    return {"point " + std::to_string(point_id) + " had no face before this step (inside, or a vertex)"};
  u32 f = static_cast<u32>(old_face);
  lines.push_back("from face " + std::to_string(f) + " of the mesh before the step");
  for (u32 e = it.replaced_by[f]; e != kAlive; e = it.replaced_by[f]) {
    const Entry& entry = it.entries[e];
    if (entry.kind == kRefine) {
      const Vec3d p = point(entry.p);
      int s[3];
      for (int k = 0; k < 3; ++k)
        s[k] = orient3d(c_, point(it.fv[3 * f + k]), p, q);
      const int k = (s[1] >= 0 && s[0] <= 0) ? 0 : (s[2] >= 0 && s[1] <= 0) ? 1 : 2;
      lines.push_back("refinement at apex " + std::to_string(entry.p) + " (Fig. 3a): child " +
                      std::to_string(k) + " by the planes through c, the apex and the corners");
      f = entry.out[k];
    } else if (entry.kind == kSwap) {
      const bool above = orient3d(c_, point(entry.p), point(entry.q), q) >= 0;
      lines.push_back("decision[" + std::to_string(e - it.refined) + "]: swap to edge " +
                      std::to_string(entry.p) + "-" + std::to_string(entry.q) + ", " + (above ? "+" : "-") +
                      " side of the plane through c and the new edge");
      f = entry.out[above ? 1 : 0];
    } else {
      lines.push_back("decision[" + std::to_string(e - it.refined) + "]: vertex removal (Fig. 4), one face");
      f = entry.out[0];
    }
  }
  const u32 now = it.new_id[f];
  lines.push_back("the cone of face " + std::to_string(now) + " of the new mesh holds it");
  return verdict(now, lines);
}

}  // namespace cudahull::resident
