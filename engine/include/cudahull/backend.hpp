// The backend: the paper's GPU module (section 4) as a small interface.  The engine edits the mesh on the
// host and hands the backend only O(faces) tables; the backend owns the O(points) work.
//
// Call order: upload_points() once, then the section 3.1 queries (extremes_x, furthest_from_line,
// furthest_from_plane), then per iteration distribute_points() -> compact_index_array() ->
// get_extreme_points().  Implementations: CpuBackend (engine/), CudaBackend (cuda/).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cudahull/parallel.hpp"
#include "cudahull/routing.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

// DefaultInitAllocator (parallel.hpp): the engine overwrites every face of its face arrays anyway, and
// zeroing two million faces (100 MB) on one core, first touch and all, cost more than the parallel pass that
// then fills them.
template <class Point>
using BasicFaceGeometryArray =
    std::vector<BasicFaceGeometry<Point>, DefaultInitAllocator<BasicFaceGeometry<Point>>>;
using FaceGeometryArray = BasicFaceGeometryArray<Point3>;

// The per-iteration tables (Fig. 7) and the new mesh's faces.
template <class Point>
struct BasicIterationTables {
  std::vector<std::int32_t> old_face_split;  // per face of the previous mesh: refinement index, or -1
  std::vector<std::int32_t> old_face_route;  // per face of the previous mesh: route code if not refined
  std::vector<RefinementEntry> refinement;   // one per refined face
  std::vector<DecisionEntry> decision;
  BasicFaceGeometryArray<Point> faces;         // the new mesh, compacted
  std::vector<SeparatingPlane> initial_cells;  // first distribution only (4 faces x 3 planes)
  // Points that became vertices this iteration (the apexes): they leave the point set without routing.  The
  // engine accounts for them exactly (they are hull candidates until its final check).
  std::vector<PointIndex> retired;
  Vec3d interior;

  // Empties every table but keeps the allocations.
  void clear() {
    old_face_split.clear();
    old_face_route.clear();
    refinement.clear();
    decision.clear();
    // `faces` is kept: phases::build_face_geometry() overwrites every face, and emptying it would make the
    // resize construct millions of faces again on one core every iteration.
    initial_cells.clear();
    retired.clear();
  }

  std::uint64_t bytes() const {
    return (old_face_split.size() + old_face_route.size()) * sizeof(std::int32_t) +
           refinement.size() * sizeof(RefinementEntry) + decision.size() * sizeof(DecisionEntry) +
           faces.size() * sizeof(BasicFaceGeometry<Point>) + initial_cells.size() * sizeof(SeparatingPlane) +
           retired.size() * sizeof(PointIndex) + sizeof(Vec3d);
  }
};
using IterationTables = BasicIterationTables<Point3>;

// What getExtremePoints returns per face: how many external points it holds and the furthest one.
struct FaceExtreme {
  std::uint32_t count = 0;
  PointIndex furthest = 0xffffffffu;
};

inline constexpr std::int32_t kPointStateInternal = -1;
inline constexpr std::int32_t kPointStateVertex = -2;

// `Point` is the coordinate type the backend computes on: Point3 (float) or Point3d (double).
template <class Point>
class BasicBackend {
 public:
  using Tables = BasicIterationTables<Point>;
  virtual ~BasicBackend() = default;
  virtual std::string name() const = 0;

  // Keeps (or uploads) the points; they stay resident for the whole run.
  virtual void upload_points(const std::vector<Point>& points) = 0;
  // Back to the state right after upload_points(), the points kept: every point active, no faces.  The
  // engine restarts this way (the viewer's rewind and replays) without sending the points again.
  virtual void restart() = 0;

  // Section 3.1.  Ties go to the lowest index.  furthest_* rank by an inexact distance; the engine checks
  // the answers with exact predicates.
  virtual std::array<PointIndex, 2> extremes_x() = 0;
  virtual PointIndex furthest_from_line(PointIndex a, PointIndex b) = 0;
  virtual PointIndex furthest_from_plane(PointIndex a, PointIndex b, PointIndex c) = 0;

  // Algorithm 2: routes every remaining point through the tables to its new face, or marks it internal.
  virtual void distribute_points(const Tables& tables) = 0;
  // Drops internal points from the index array; returns how many remain (all external).
  virtual std::size_t compact_index_array() = 0;
  // One entry per face of the new mesh.
  virtual void get_extreme_points(std::vector<FaceExtreme>& out) = 0;

  // Debugger support: each point's face in the current mesh, or -1 when it is internal (or a vertex).
  // For a GPU backend this copies O(points) data; the engine calls it only when asked.
  virtual void point_faces(std::vector<std::int32_t>& out) = 0;

  // CUDA-GL interop (issue 5): a backend whose points live in GPU memory writes each point's state straight
  // into `device_out` (`count` int32s in its device's memory, e.g. a mapped OpenGL buffer), so that no
  // per-point data comes to the host.  State: the point's face (>= 0) while external, kPointStateInternal
  // once discarded, kPointStateVertex for `vertices`.  Returns false when the backend cannot (the CPU).
  virtual bool has_device_point_states() const { return false; }
  virtual bool write_point_states_on_device(std::int32_t* /*device_out*/, std::size_t /*count*/,
                                            const std::vector<PointIndex>& /*vertices*/) {
    return false;
  }

  // Bytes moved between host and backend so far (0 for the CPU backend, which shares memory).
  virtual std::uint64_t bytes_to_backend() const { return 0; }
  virtual std::uint64_t bytes_from_backend() const { return 0; }
};
using Backend = BasicBackend<Point3>;

}  // namespace cudahull
