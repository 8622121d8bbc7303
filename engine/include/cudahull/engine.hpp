// The CudaHull engine: Algorithm 1 of Stein, Geva and El-Sana (2012), one iteration per step().
//
//   Engine engine(points, make_cpu_backend());
//   while (!engine.done()) IterationRecord r = engine.step();
//   HullMesh hull = engine.result();
//
// Exactness (README, "Exactness"): every decision that changes the result uses exact orient3d; points are
// discarded only when proven inside the hull; when no external point remains, the mesh is checked exactly
// and, where the paper's local procedure could not reach the exact hull (degenerate input), finished by an
// exact hull of the vertices it used.  IterationRecord::repairs counts those fixes (0 in general position).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/mesh.hpp"
#include "cudahull/point_map.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/records.hpp"
#include "cudahull/routing.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

namespace phases {
struct SwapScratch;
}
struct ResidentStats;

struct EngineOptions {
  bool keep_decisions = true;  // copy the decision array into each IterationRecord
  // Swap candidates from this many on are tried in batched rounds on all cores (phases/swaps.cpp,
  // swap_edges()); fewer go one at a time.  Either way the hull is the same; the order of the edits, and so
  // the intermediate meshes, can differ.  SIZE_MAX: never batch.  The command line sets it from
  // CUDAHULL_BATCHED_SWAPS_FROM for A/B runs (docs/cli.md); the library reads no environment for it.
  std::size_t batched_swaps_from = 4096;
};

// The coordinate-free part of BasicEngine<Point>: what a caller that steps and inspects the engine needs
// without knowing the coordinate type (the viewer runs either precision through it).  BasicEngine documents
// each member.
class SteppingEngine {
 public:
  virtual ~SteppingEngine() = default;

  virtual bool done() const = 0;
  virtual void restart() = 0;
  virtual IterationRecord step() = 0;
  virtual void run(const std::function<void(const IterationRecord&)>& on_step = {}) = 0;

  virtual std::size_t point_count() const = 0;
  virtual Vec3d point(PointIndex i) const = 0;  // point i's coordinates, widened to double (exactly)
  virtual Precision precision() const = 0;      // kFloat or kDouble: the coordinates computed on
  virtual const Mesh& mesh() const = 0;
  // The backend's name(), bytes_from_backend() and has_device_point_states().
  virtual std::string backend_name() const = 0;
  virtual std::uint64_t bytes_from_backend() const = 0;
  virtual bool has_device_point_states() const = 0;
  virtual int dimension() const = 0;
  virtual Vec3d interior_point() const = 0;
  virtual FaceCell face_cell(FaceId f) const = 0;
  virtual std::vector<std::int32_t> point_faces() const = 0;
  virtual bool write_point_states_on_device(std::int32_t* device_out, std::size_t count,
                                            const std::vector<PointIndex>& vertices) = 0;
  virtual std::vector<std::string> explain_route(PointIndex point, std::int32_t old_face) const = 0;
  virtual const std::vector<FaceExtreme>& face_extremes() const = 0;
  virtual const std::vector<DecisionEntry>& last_decisions() const = 0;
  virtual const std::vector<RefinementEntry>& last_refinement() const = 0;
  virtual const std::vector<PointIndex>& removed_vertices() const = 0;
  virtual const IterationRecord& last_record() const = 0;
  // The resident engine's counters (resident.hpp) when this steps it; null for the stepping Engine.
  virtual const ResidentStats* resident_stats() const { return nullptr; }
  // result()'s vertex_ids and triangles (its coordinates are point(vertex_ids[k])); valid once done().
  virtual const std::vector<PointIndex>& result_vertex_ids() const = 0;
  virtual const std::vector<Triangle>& result_triangles() const = 0;
};

// `Point` is Point3 (float) or Point3d (double) coordinates: one generic implementation, exact for the
// coordinates as given in either precision (README, "Precision").
template <class Point>
class BasicEngine final : public SteppingEngine {
 public:
  // The engine borrows `points` (as std::span would): they must stay alive and unchanged while it lives.
  // The backend keeps what it needs of them (a GPU backend uploads them once, on the first step).
  BasicEngine(const std::vector<Point>& points, std::unique_ptr<BasicBackend<Point>> backend,
              EngineOptions options = {});
  BasicEngine(std::vector<Point>&& points, std::unique_ptr<BasicBackend<Point>> backend,
              EngineOptions options = {}) = delete;
  ~BasicEngine() override;
  BasicEngine(const BasicEngine&) = delete;
  BasicEngine& operator=(const BasicEngine&) = delete;

  bool done() const override { return done_; }
  // Back to before the first step, on the same points and backend: the backend keeps its points (nothing
  // is uploaded again), so stepping again repeats the same steps.
  void restart() override;
  // One iteration of Algorithm 1 (the first call builds the tetrahedron and distributes the points).
  IterationRecord step() override;
  // Steps until no external point remains; `on_step` sees every record.
  void run(const std::function<void(const IterationRecord&)>& on_step = {}) override;

  const std::vector<Point>& points() const { return *points_; }
  const Mesh& mesh() const override { return mesh_; }
  const BasicBackend<Point>& backend() const { return *backend_; }
  // SteppingEngine's coordinate-free view (engine.cpp).
  std::size_t point_count() const override;
  Vec3d point(PointIndex i) const override;
  Precision precision() const override;
  std::string backend_name() const override;
  std::uint64_t bytes_from_backend() const override;
  bool has_device_point_states() const override;
  const std::vector<PointIndex>& result_vertex_ids() const override;
  const std::vector<Triangle>& result_triangles() const override;
  int dimension() const override { return dimension_; }  // affine dimension of the input, known after step 0
  Vec3d interior_point() const override { return interior_; }
  FaceCell face_cell(FaceId f) const override;
  // Per point: its face in the current mesh, or -1 (internal or a vertex).  O(points); for the debugger.
  std::vector<std::int32_t> point_faces() const override;
  // The same, written by the backend into its own device memory (Backend::write_point_states_on_device),
  // with `vertices` marked; false when the backend cannot or there is no 3-d mesh yet.
  bool write_point_states_on_device(std::int32_t* device_out, std::size_t count,
                                    const std::vector<PointIndex>& vertices) override;
  // The debugger's "explain point" (issue 6): how the last step's tables (Fig. 7: refinement[], decision[])
  // routed input point `point`, which belonged to face `old_face` of the mesh before that step (any value
  // for the first step, whose distribution goes by the tetrahedron's cells), one line per hop, and the
  // exact verdict that ended it.  The last line is then "face F", "internal" or "vertex"; a point that had
  // no face before the step gets one line saying so.
  std::vector<std::string> explain_route(PointIndex point, std::int32_t old_face) const override;
  const std::vector<FaceExtreme>& face_extremes() const override { return extremes_; }
  // The last step's tables (Fig. 7), as sent to the backend; they stay until the next step.
  const std::vector<DecisionEntry>& last_decisions() const override { return tables_.decision; }
  const std::vector<RefinementEntry>& last_refinement() const override { return tables_.refinement; }
  const std::vector<PointIndex>& removed_vertices() const override { return removed_vertices_; }
  // The record of the last step(): its swaps with their kinds (rejected ones with the vertex beneath),
  // removals, refined apexes and decision array.
  const IterationRecord& last_record() const override { return last_record_; }

  // The exact hull; valid once done().
  const BasicHullMesh<Point>& result() const { return result_; }

 private:
  // Algorithm 1 (engine.cpp): the first step (section 3.1), then one iteration per step, then the exact
  // finish.  The phases themselves live in engine/src/phases/ (docs/architecture.md).
  IterationRecord initialize();
  IterationRecord iterate();
  void finish(IterationRecord& record);
  // Algorithm 2 on the backend: distribute, compact, extremes; returns the backend's milliseconds.
  double distribute();

  const std::vector<Point>* points_;
  std::unique_ptr<BasicBackend<Point>> backend_;
  EngineOptions options_;
  bool uploaded_ = false;  // the backend holds the points
  Mesh mesh_;
  int iteration_ = 0;
  bool started_ = false, done_ = false;
  int dimension_ = -2;
  Vec3d interior_;
  std::size_t external_ = 0;
  std::vector<FaceExtreme> extremes_;
  std::vector<PointIndex> removed_vertices_;
  std::vector<PointIndex> removed_near_;   // per removed vertex: one of its ring, where finish() looks for it
  std::vector<PointIndex> used_vertices_;  // every point that was ever a mesh vertex
  PointMap<std::uint8_t> vertex_flags_;    // per vertex: the local edits' flags (phases/local_edits.hpp)
  int stalled_ = 0;                        // iterations without progress
  BasicHullMesh<Point> result_;
  IterationRecord last_record_;
  BasicFaceGeometryArray<Point> geometry_;  // the current mesh's faces as last sent to the backend
  BasicIterationTables<Point> tables_;      // reused every iteration (its buffers keep their capacity)
  std::unique_ptr<phases::SwapScratch> swap_scratch_;  // the swap rounds' buffers, also reused
};
using Engine = BasicEngine<Point3>;

}  // namespace cudahull
