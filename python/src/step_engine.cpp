// The stepping engine for notebooks (cudahull.Engine): one iteration per step(), its record, the mesh and
// the result as dicts of NumPy arrays.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "bindings.hpp"
#include "cudahull/convex_hull.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/hull_runner.hpp"
#include "hull_conversions.hpp"
#include "numpy_arrays.hpp"

namespace cudahull::python {

namespace {

// The stepping engine for notebooks: one iteration per step(), its record as a dict of NumPy arrays.
class StepEngine {
 public:
  template <class Scalar>
  StepEngine(PointArray<Scalar> points, const std::string& backend, const std::string& precision) {
    ConvexHullOptions request;
    request.precision = precision_from_name_strict(precision);
    request.backend = backend_from_name(backend);
    request.engine = EngineChoice::kStepping;  // what this class steps
    HullInput input;
    input.precision = precision_of<Scalar>();
    input.count = points.shape(0);
    const HullPlan plan = plan_hull(request, input);
    // The engine borrows its points: they live on the heap, owned here, for as long as it does.  The
    // points are checked before the plan's DeviceError, where it has one; the backend is the plan's
    // (hull_runner.hpp).
    if (plan.precision == Precision::kDouble) {
      double_points_ =
          std::make_unique<std::vector<Point3d>>(checked_points<Point3d>(points.data(), points.shape(0)));
      if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
      double_engine_ =
          std::make_unique<BasicEngine<Point3d>>(*double_points_, planned_backend<Point3d>(plan));
      engine_ = double_engine_.get();
    } else {
      float_points_ =
          std::make_unique<std::vector<Point3>>(checked_points<Point3>(points.data(), points.shape(0)));
      if (!plan.unavailable.empty()) throw DeviceError(plan.unavailable);
      float_engine_ = std::make_unique<BasicEngine<Point3>>(*float_points_, planned_backend<Point3>(plan));
      engine_ = float_engine_.get();
    }
  }

  bool done() const { return engine_->done(); }
  int dimension() const { return engine_->dimension(); }
  std::string precision() const { return precision_name(engine_->precision()); }
  std::string backend() const { return engine_->backend_name(); }
  std::size_t point_count() const { return engine_->point_count(); }
  void restart() { engine_->restart(); }

  nb::dict step() {
    if (engine_->done()) throw std::logic_error("the engine is done: restart() it to step again");
    IterationRecord record;
    {
      nb::gil_scoped_release unlocked;
      record = engine_->step();
    }
    return record_to_dict(record);
  }

  // The current mesh: live faces as input indices (counter-clockwise from outside), and each face's
  // neighbours in scipy's convention (the k-th across the edge opposite corner k).
  nb::dict mesh() const {
    const Mesh& mesh = engine_->mesh();
    std::vector<FaceId> live;
    std::vector<FaceId> new_id(mesh.face_capacity(), kNoFace);
    for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
      if (!mesh.alive(f)) continue;
      new_id[f] = static_cast<FaceId>(live.size());
      live.push_back(f);
    }
    nb::dict d;
    d["faces"] =
        rows_to_numpy<std::uint32_t, 3>(live, [&](FaceId f, std::size_t k) { return mesh.face(f).v[k]; });
    // Mesh::n[i] lies across the edge v[i] -> v[i+1], which is opposite corner i + 2.
    d["neighbors"] = rows_to_numpy<std::int32_t, 3>(live, [&](FaceId f, std::size_t k) {
      const FaceId across = mesh.face(f).n[(k + 1) % 3];
      return across == kNoFace ? -1 : static_cast<std::int32_t>(new_id[across]);
    });
    d["vertices"] = to_numpy(mesh.vertices());
    return d;
  }

  // The exact hull, as cudahull.convex_hull returns it; once done.
  nb::dict result() const {
    if (!engine_->done()) throw std::logic_error("the engine is not done: step() until done");
    if (float_engine_) return hull_to_dict(hull_from_mesh(float_engine_->result(), engine_->backend_name()));
    return hull_to_dict(hull_from_mesh(double_engine_->result(), engine_->backend_name()));
  }

 private:
  static nb::dict record_to_dict(const IterationRecord& r) {
    nb::dict d;
    for_each_count(r, [&](const char* name, const auto& value) { d[name] = value; });
    d["note"] = r.note;
    // Fig. 3a: each refined face's corners and the apex it split at.
    d["refined_apexes"] = to_numpy(std::vector<PointIndex>(r.refined_apexes));
    d["refined_faces"] =
        rows_to_numpy<std::uint32_t, 3>(r.refined_faces, [](const auto& f, std::size_t k) { return f[k]; });
    // Figs. 3b, 4, 5: every swap tried, in order; swap_kind indexes cudahull.SWAP_KINDS.
    const auto& s = r.swaps;
    d["swap_kind"] = column_to_numpy<std::uint8_t>(s, [](const SwapRecord& w) { return w.kind; });
    d["swap_sequence"] = column_to_numpy<std::int32_t>(s, [](const SwapRecord& w) { return w.sequence; });
    d["swap_old_edge"] =
        rows_to_numpy<std::uint32_t, 2>(s, [](const SwapRecord& w, std::size_t k) { return w.old_edge[k]; });
    d["swap_new_edge"] =
        rows_to_numpy<std::uint32_t, 2>(s, [](const SwapRecord& w, std::size_t k) { return w.new_edge[k]; });
    d["swap_beneath_vertex"] =
        column_to_numpy<std::uint32_t>(s, [](const SwapRecord& w) { return w.beneath_vertex; });
    d["swap_beneath_triangle"] = rows_to_numpy<std::uint32_t, 3>(
        s, [](const SwapRecord& w, std::size_t k) { return w.beneath_triangle[k]; });
    d["swap_decision_index"] =
        column_to_numpy<std::int32_t>(s, [](const SwapRecord& w) { return w.decision_index; });
    // Fig. 4: degree-3 vertices removed (or, rejected, left), with the face that replaced them.
    const auto& m = r.removals;
    d["removal_sequence"] =
        column_to_numpy<std::int32_t>(m, [](const RemovalRecord& v) { return v.sequence; });
    d["removal_vertex"] = column_to_numpy<std::uint32_t>(m, [](const RemovalRecord& v) { return v.vertex; });
    d["removal_ring"] =
        rows_to_numpy<std::uint32_t, 3>(m, [](const RemovalRecord& v, std::size_t k) { return v.ring[k]; });
    d["removal_decision_index"] =
        column_to_numpy<std::int32_t>(m, [](const RemovalRecord& v) { return v.decision_index; });
    std::vector<std::uint8_t> rejected;
    for (const RemovalRecord& v : m)
      rejected.push_back(v.rejected ? 1 : 0);
    d["removal_rejected"] = to_numpy(std::move(rejected), true);
    // Fig. 7: the decision array sent to the backend (plane: nx, ny, nz, d; above/below: route codes).
    const auto& e = r.decisions;
    d["decision_kind"] = column_to_numpy<std::uint8_t>(e, [](const DecisionEntry& x) { return x.kind; });
    d["decision_plane"] = rows_to_numpy<double, 4>(e, [](const DecisionEntry& x, std::size_t k) {
      const double plane[4] = {x.plane.nx, x.plane.ny, x.plane.nz, x.plane.d};
      return plane[k];
    });
    d["decision_above"] = column_to_numpy<std::int32_t>(e, [](const DecisionEntry& x) { return x.above; });
    d["decision_below"] = column_to_numpy<std::int32_t>(e, [](const DecisionEntry& x) { return x.below; });
    return d;
  }

  std::unique_ptr<std::vector<Point3>> float_points_;
  std::unique_ptr<std::vector<Point3d>> double_points_;
  std::unique_ptr<BasicEngine<Point3>> float_engine_;
  std::unique_ptr<BasicEngine<Point3d>> double_engine_;
  SteppingEngine* engine_ = nullptr;
};

}  // namespace

void bind_step_engine(nb::module_& m) {
  nb::list kinds;
  for (SwapKind kind : {SwapKind::kRegular, SwapKind::kComplementary, SwapKind::kRejectedFoldover,
                        SwapKind::kRejectedEdgeExists, SwapKind::kRejectedDegenerate})
    kinds.append(swap_kind_name(kind));
  m.attr("SWAP_KINDS") = nb::tuple(kinds);

  nb::class_<StepEngine>(m, "Engine")
      .def(nb::init<PointArray<float>, const std::string&, const std::string&>(), nb::arg("points"),
           nb::arg("backend"), nb::arg("precision"))
      .def(nb::init<PointArray<double>, const std::string&, const std::string&>(), nb::arg("points"),
           nb::arg("backend"), nb::arg("precision"))
      .def_prop_ro("done", &StepEngine::done)
      .def_prop_ro("dimension", &StepEngine::dimension)
      .def_prop_ro("precision", &StepEngine::precision)
      .def_prop_ro("backend", &StepEngine::backend)
      .def_prop_ro("npoints", &StepEngine::point_count)
      .def("restart", &StepEngine::restart)
      .def("step", &StepEngine::step)
      .def("mesh", &StepEngine::mesh)
      .def("result", &StepEngine::result);
}

}  // namespace cudahull::python
