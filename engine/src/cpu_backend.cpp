#include "cudahull/cpu_backend.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "cudahull/parallel.hpp"
#include "cudahull/routing.hpp"

namespace cudahull {
namespace {

template <class Point>
class CpuBackend final : public BasicBackend<Point> {
 public:
  using Tables = BasicIterationTables<Point>;
  explicit CpuBackend(unsigned threads) : workers_(threads ? threads : hardware_workers()) {}

  std::string name() const override {
    return "cpu (" + std::to_string(workers_) + (workers_ == 1 ? " thread)" : " threads)");
  }

  void upload_points(const std::vector<Point>& points) override {
    points_ = &points;
    restart();
  }
  void restart() override {
    const std::size_t n = points_ ? points_->size() : 0;
    active_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      active_[i] = static_cast<PointIndex>(i);
    face_of_.assign(n, 0);
  }

  std::array<PointIndex, 2> extremes_x() override {
    const auto& p = *points_;
    PointIndex lo = 0, hi = 0;
    for (PointIndex i = 1; i < p.size(); ++i) {
      if (p[i].x < p[lo].x) lo = i;
      if (p[i].x > p[hi].x) hi = i;
    }
    return {lo, hi};
  }

  PointIndex furthest_from_line(PointIndex a, PointIndex b) override {
    const auto& p = *points_;
    const double ax = p[a].x, ay = p[a].y, az = p[a].z;
    const double dx = p[b].x - ax, dy = p[b].y - ay, dz = p[b].z - az;
    return argmax([&](const Point& q) {
      const double wx = q.x - ax, wy = q.y - ay, wz = q.z - az;
      const double cx = dy * wz - dz * wy, cy = dz * wx - dx * wz, cz = dx * wy - dy * wx;
      return cx * cx + cy * cy + cz * cz;
    });
  }

  PointIndex furthest_from_plane(PointIndex a, PointIndex b, PointIndex c) override {
    const auto& p = *points_;
    BasicFaceGeometry<Point> f{};
    f.v[0] = p[a];
    f.v[1] = p[b];
    f.v[2] = p[c];
    return argmax([&](const Point& q) { return std::fabs(face_height(f, q)); });
  }

  void distribute_points(const Tables& tables) override {
    BasicRoutingView<Point> view;
    view.old_face_split = tables.old_face_split.data();
    view.old_face_route = tables.old_face_route.data();
    view.refinement = tables.refinement.data();
    view.decision = tables.decision.data();
    view.faces = tables.faces.data();
    view.face_count = static_cast<std::int32_t>(tables.faces.size());
    view.initial_cells = tables.initial_cells.empty() ? nullptr : tables.initial_cells.data();
    view.interior = tables.interior;
    face_count_ = tables.faces.size();
    // Per-worker counts and packed maxima, reduced afterwards (getExtremePoints fused into the pass).
    per_worker_.assign(workers_, {});
    for (PointIndex i : tables.retired)
      face_of_[i] = kRouteInternal;
    // With more points than faces, each face's planes are prepared once (routing.hpp, FacePlanes), as the
    // CUDA backend does: the same verdicts, with fewer orient3d filters per point.
    const bool prepared = active_.size() >= face_count_;
    if (prepared) {
      planes_.resize(face_count_);
      parallel_chunks(face_count_, workers_, [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t f = begin; f < end; ++f)
          prepare_face_planes(tables.faces[f], view.interior, planes_[f]);
      });
    }
    const auto& p = *points_;
    parallel_chunks(active_.size(), workers_, [&](std::size_t begin, std::size_t end, unsigned w) {
      auto& local = per_worker_[w];
      local.count.assign(face_count_, 0);
      local.best.assign(face_count_, 0);
      for (std::size_t k = begin; k < end; ++k) {
        const PointIndex i = active_[k];
        if (face_of_[i] == kRouteInternal) continue;  // retired
        double height = 0;
        const std::int32_t face =
            prepared ? classify_point_prepared(p[i], face_of_[i], view, planes_.data(), &height)
                     : classify_point(p[i], face_of_[i], view);
        face_of_[i] = face;
        if (face == kRouteInternal) continue;
        ++local.count[face];
        if (!prepared) height = face_height(tables.faces[face], p[i]);
        const std::uint64_t packed = pack_extreme<Point>(height, i);
        if (packed > local.best[face]) local.best[face] = packed;
      }
    });
  }

  std::size_t compact_index_array() override {
    auto it = std::remove_if(active_.begin(), active_.end(),
                             [&](PointIndex i) { return face_of_[i] == kRouteInternal; });
    active_.erase(it, active_.end());
    return active_.size();
  }

  void get_extreme_points(std::vector<FaceExtreme>& out) override {
    out.assign(face_count_, {});
    for (std::size_t f = 0; f < face_count_; ++f) {
      std::uint64_t best = 0;
      std::uint32_t count = 0;
      for (const auto& local : per_worker_) {
        if (local.count.empty()) continue;
        count += local.count[f];
        best = std::max(best, local.best[f]);
      }
      out[f].count = count;
      if (count) out[f].furthest = unpack_extreme_index(best);
    }
  }

  void point_faces(std::vector<std::int32_t>& out) override {
    out.assign(points_->size(), -1);
    for (PointIndex i : active_)
      out[i] = face_of_[i];
  }

 private:
  template <class Score>
  PointIndex argmax(Score&& score) {
    const auto& p = *points_;
    std::vector<std::pair<double, PointIndex>> best(workers_, {-1.0, 0});
    parallel_chunks(p.size(), workers_, [&](std::size_t begin, std::size_t end, unsigned w) {
      std::pair<double, PointIndex> b{-1.0, 0};
      for (std::size_t i = begin; i < end; ++i) {
        const double s = score(p[i]);
        if (s > b.first) b = {s, static_cast<PointIndex>(i)};
      }
      best[w] = b;
    });
    std::pair<double, PointIndex> b{-1.0, 0};
    for (const auto& c : best) {
      if (c.first > b.first || (c.first == b.first && c.second < b.second)) b = c;
    }
    return b.second;
  }

  std::vector<FacePlanes> planes_;  // distribute_points(), when prepared

  struct WorkerState {
    std::vector<std::uint32_t> count;
    std::vector<std::uint64_t> best;
  };

  unsigned workers_;
  const std::vector<Point>* points_ = nullptr;
  std::vector<PointIndex> active_;
  std::vector<std::int32_t> face_of_;  // per point: face id, or kRouteInternal
  std::size_t face_count_ = 0;
  std::vector<WorkerState> per_worker_;
};

}  // namespace

template <class Point>
std::unique_ptr<BasicBackend<Point>> make_cpu_backend(unsigned threads) {
  return std::make_unique<CpuBackend<Point>>(threads);
}
template std::unique_ptr<BasicBackend<Point3>> make_cpu_backend<Point3>(unsigned);
template std::unique_ptr<BasicBackend<Point3d>> make_cpu_backend<Point3d>(unsigned);

}  // namespace cudahull
