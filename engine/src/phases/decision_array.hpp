// The decision array and the per-iteration tables (Fig. 7).
//
// design:
//   While the mesh is edited, faces have work ids (ids before compaction) and the edits append entries:
//     a swap of faces f, g into n1, n2:   entry {plane of the new edge, above -> n1, below -> n2};
//                                          f and g are killed by it
//     a removal of three faces into n:     entry {above = below = n}; the three are killed by it
//   A killed face's points follow the entry that killed it, and an entry's target may itself be killed by a
//   later entry, so a point walks a chain of entries to a live face (Algorithm 2, routing.hpp).
//   After compaction each target becomes a route code: a new face id (>= 0) or -(entry + 1).
//   The tables the backend reads are then: per old face its refinement index or route code,
//   refinement[] (the three children's codes and planes), decision[], and the new faces' geometry.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/mesh.hpp"
#include "cudahull/routing.hpp"

namespace cudahull::phases {

class DecisionArrayBuilder {
 public:
  // A removal: the faces `old_faces` became face n.  Returns the entry's index.
  std::int32_t add_removal(FaceId n, const std::vector<FaceId>& old_faces);

  // Room for `count` swap entries at the end; returns the first one's index.  Each slot is then filled by
  // write_swap(), on any thread (a slot is written by its swap alone).
  std::int32_t add_swap_slots(std::size_t count, std::size_t face_capacity);
  // Swap entry `index`: faces f and g became n1 = (x, u, y) and n2 = (y, v, x).  Its plane is computed by
  // resolve_swap_planes() once the edits are done.
  void write_swap(std::int32_t index, FaceId f, FaceId g, FaceId n1, FaceId n2, PointIndex u);

  // Every swap entry's separating plane (cells.hpp), on all cores.
  template <class Point>
  void resolve_swap_planes(const Mesh& mesh, const std::vector<Point>& points);

  std::size_t size() const { return entries_.size(); }

  // The iteration's tables (Fig. 7) for the compacted mesh (`remap`: work id -> new id): the old faces'
  // routes, refinement[] with its children as route codes, decision[] and the retired apexes.
  template <class Point>
  void build_tables(BasicIterationTables<Point>& tables, std::vector<RefinementEntry> refinement,
                    const std::vector<std::array<FaceId, 3>>& children, const std::vector<FaceId>& remap,
                    FaceId old_faces, const std::vector<PointIndex>& apexes) const;

 private:
  std::int32_t route_code(FaceId work, const std::vector<FaceId>& remap) const;
  void note_killed(FaceId f, std::int32_t entry);

  std::vector<DecisionEntry> entries_;
  std::vector<std::array<FaceId, 2>> targets_;  // per entry, work ids: above, below
  std::vector<std::int32_t> killed_by_;         // per work id: the entry that killed it, or -1
  // Per swap entry: its new faces and u, for the plane.
  struct PendingPlane {
    FaceId n1, n2;
    PointIndex u;
  };
  std::vector<PendingPlane> pending_;  // per entry (unused for removals)
};

// The faces of the compacted mesh as the backend reads them (corners, exact signs of the tetrahedra with
// the interior point, neighbours).  With `remap` (old id -> new id from the last compaction) surviving faces
// copy their signs from `previous`.
template <class Point>
void build_face_geometry(const Mesh& mesh, const std::vector<Point>& points, const Vec3d& interior,
                         const BasicFaceGeometryArray<Point>& previous, const std::vector<FaceId>* remap,
                         BasicFaceGeometryArray<Point>& out);

}  // namespace cudahull::phases
