// The scene: the engine stepping one iteration at a time, and the render data derived from it (libigl's
// ViewerData: engine state -> CPU arrays with dirty bits; the renderer turns those into GL buffers).
//
// Positions on the timeline count engine steps: 0 is before the first step (the bare point set), 1 is after
// iteration 0 (the tetrahedron and the first distribution, section 3.1), k after iteration k - 1.  Rewinding
// replays deterministically from the start: the engine restarted (SteppingEngine::restart(): the same points
// and backend, nothing uploaded again) and stepped k times (the engine is deterministic, so the replay passes
// through the same meshes).  The debugger's replays (sub-steps, explain point, trace export) restart a
// second engine the scene keeps, so the main one stays where it is.  The history keeps one record per
// position reached, without the O(faces) vectors, for the plots (cf. Fig. 9).
//
// Precision: the engine computes on float (Engine) or double (BasicEngine<Point3d>) coordinates, seen through
// SteppingEngine either way.  The render positions are always float (GL).  In float precision there is one
// host copy of the points: the render positions, which the engine borrows.  In double precision the scene
// keeps two: the double points the engine borrows, and float positions (the same points rounded) to draw.
//
// render_data() is derived lazily, once per position shown, not once per step of a replay or a run.
// Per-point state comes from SteppingEngine::point_faces() (the "CPU upload" path, O(points) per refresh),
// or, with device point states on, the backend writes it into the GL buffer (CUDA-GL interop, no readback).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/engine.hpp"
#include "input_surface.hpp"
#include "render_data.hpp"

namespace cudahull::viewer {

// The points of a scene: `positions` (float, what the renderer draws) always, and in double precision
// `exact`, the points the engine computes on (`positions` are then those rounded to float).
struct ScenePoints {
  std::shared_ptr<const std::vector<Point3>> positions;
  std::shared_ptr<const std::vector<Point3d>> exact;  // null: float precision
  // The model's own faces (input_surface.hpp), indices into `positions`; null or empty for a bare cloud.
  std::shared_ptr<const std::vector<InputTriangle>> surface;
  Precision precision() const { return exact ? Precision::kDouble : Precision::kFloat; }
};

// Makes a backend (one per engine: the scene's and the replay one) in either precision; or, for the
// resident engine (--engine resident), the engine itself, which brings its own executor.
struct BackendFactory {
  std::function<std::unique_ptr<BasicBackend<Point3>>()> make_float;
  std::function<std::unique_ptr<BasicBackend<Point3d>>()> make_double;
  std::function<std::unique_ptr<SteppingEngine>(const std::vector<Point3>&)> resident_float;
  std::function<std::unique_ptr<SteppingEngine>(const std::vector<Point3d>&)> resident_double;
};

class Scene {
 public:
  using BackendFactory = viewer::BackendFactory;

  // `label` names the data in the UI and logs (a file name, or "ball 20000 seed 1").  The precision is the
  // points': double when `points.exact` is set, else float.
  Scene(ScenePoints points, BackendFactory make_backend, std::string label);
  // Float precision: the engine borrows the render positions.
  Scene(std::shared_ptr<const std::vector<Point3>> points, BackendFactory make_backend, std::string label)
      : Scene(ScenePoints{std::move(points), nullptr, nullptr}, std::move(make_backend), std::move(label)) {}

  const std::string& label() const { return label_; }
  // The render positions (float; in double precision the engine's points rounded).
  const std::vector<Point3>& points() const { return *points_; }
  Precision precision() const { return engine_->precision(); }
  std::string backend_name() const { return engine_->backend_name(); }

  int position() const { return position_; }
  // The last position known: the end of the timeline when final_known(), else the furthest reached.
  int known_end() const { return static_cast<int>(history_.size()); }
  bool final_known() const { return final_known_; }
  bool done() const { return engine_->done(); }

  void step(int count = 1);  // stops early once done
  void run_to_end();
  void rewind(int position);  // any position >= 0; forward positions are stepped to
  void reset() { rewind(0); }

  // One record per position 1..known_end() (index position - 1), without swaps, removals, apexes and
  // decisions.
  const std::vector<IterationRecord>& history() const { return history_; }
  // The full record of the step that led to the current position; nullptr at position 0.
  const IterationRecord* current_record() const { return position_ > 0 ? &engine_->last_record() : nullptr; }
  const SteppingEngine& engine() const { return *engine_; }

  // CUDA-GL interop (issue 5): when on, render_data() leaves point_state empty and sets kDirtyDeviceState,
  // and the session maps the GL buffer and calls write_device_point_states().  Only for a backend with
  // device point states (the CUDA backend).
  bool backend_has_device_point_states() const { return engine_->has_device_point_states(); }
  void set_device_point_states(bool on) {
    device_point_states_ = on;
    render_stale_ = true;
  }
  bool device_point_states() const { return device_point_states_; }
  // Writes every point's state into `device` (the mapped GL buffer, `bytes` long); false if it cannot
  // (then the caller falls back to uploading).
  bool write_device_point_states(void* device, std::size_t bytes);
  // Per-point bytes read back from backends so far: the upload path's, and the replays of the sub-steps and
  // of explain_point (0 on the interop path while just stepping).
  std::uint64_t point_readback_bytes() const { return point_readback_bytes_; }

  // The full records (swaps, decisions, ...) of every step from the start to the current position, by a
  // deterministic replay on the replay engine (the history keeps only the counters): for the trace export.
  std::vector<IterationRecord> replay_records() const;
  // The debugger's "explain point" for the step that led here: the point's face before the step, its path
  // through refinement[] and decision[] to a face or "internal" (SteppingEngine::explain_route), and whether
  // that matches where the backend put it.  By replay, like rewinding.
  std::vector<std::string> explain_point(PointIndex point) const;

  // Sub-steps (issue 6, teaching): the step that led here, played phase by phase on a copy of the mesh
  // before it: 0 the mesh before, 1 after refinement (Fig. 3a), then one phase per swap or removal in the
  // order the engine made them (Figs. 3b, 4), and last the redistribution (the step's result, where the
  // points change).  substep_count() is 0 where there is nothing to split (position 0 or 1).  Replays
  // from the start, like rewinding.
  int substep_count();
  int substep() const { return substep_; }  // -1: off (the step's result)
  void set_substep(int phase);              // clamped; the last phase is the same as off
  std::string substep_label(int phase);
  // The swaps and removals with sequence numbers up to this have been played (for the overlay); all of
  // them when sub-steps are off.
  int substep_sequence_limit() const;
  // The polyhedron shown (the sub-step's or the step's), as outward triangles of input indices.
  std::vector<std::array<PointIndex, 3>> displayed_faces() const;

  RenderData& render_data();
  // Bounds of the point set (all zero when empty).
  void bounds(float lo[3], float hi[3]) const;

 private:
  struct FaceKeyHash {
    std::size_t operator()(const std::array<PointIndex, 3>& k) const {
      return (std::size_t{k[0]} * 73856093u) ^ (std::size_t{k[1]} * 19349663u) ^
             (std::size_t{k[2]} * 83492791u);
    }
  };
  using FaceKey = std::array<PointIndex, 3>;
  using BirthMap = std::unordered_map<FaceKey, int, FaceKeyHash>;

  void restart();
  // The replay engine, made on first use (with a backend of its own) or restarted: before its first step.
  SteppingEngine& restarted_replay() const;
  std::unique_ptr<SteppingEngine> make_engine() const;  // in the points' precision, with a new backend
  void step_once();
  void current_faces(std::vector<FaceKey>& faces) const;  // the polyhedron shown now, input indices
  void refresh_render_data();

  std::shared_ptr<const std::vector<Point3>> points_;  // render positions (the engine's in float precision)
  std::shared_ptr<const std::vector<Point3d>> exact_;  // the engine's in double precision, else null
  std::shared_ptr<const std::vector<InputTriangle>> surface_;
  BackendFactory make_backend_;
  std::string label_;
  std::unique_ptr<SteppingEngine> engine_;
  // The debugger's replays (sub-steps, explain_point, replay_records): kept between them so that its
  // backend keeps its points, and restarted before each.
  mutable std::unique_ptr<SteppingEngine> replay_;
  int position_ = 0;
  bool final_known_ = false;
  std::vector<IterationRecord> history_;
  BirthMap born_;  // the iteration each face of the current polyhedron was made in (for "by age")
  struct SubStep {
    std::string label;
    std::vector<FaceKey> faces;
    std::vector<FaceState> states;  // per face
    int sequence_limit = -1;
  };
  void build_substeps();
  std::vector<SubStep> substeps_;  // for position substeps_position_
  int substeps_position_ = -1;
  std::vector<std::int32_t> substep_point_state_;  // the points before the step
  int substep_ = -1;

  RenderData render_;
  bool render_stale_ = true;
  bool device_point_states_ = false;
  mutable std::uint64_t point_readback_bytes_ = 0;  // also the debugger's replays (explain_point is const)
};

}  // namespace cudahull::viewer
