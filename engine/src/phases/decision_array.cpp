#include "phases/decision_array.hpp"

#include "cudahull/parallel.hpp"
#include "phases/cells.hpp"

namespace cudahull::phases {

void DecisionArrayBuilder::note_killed(FaceId f, std::int32_t entry) {
  if (killed_by_.size() <= f) killed_by_.resize(f + 1, -1);
  killed_by_[f] = entry;
}

std::int32_t DecisionArrayBuilder::add_removal(FaceId n, const std::vector<FaceId>& old_faces) {
  DecisionEntry entry;
  entry.kind = kDecisionRemoval;
  entries_.push_back(entry);
  targets_.push_back({n, n});
  pending_.push_back({kNoFace, kNoFace, kNoPoint});
  const auto index = static_cast<std::int32_t>(entries_.size() - 1);
  for (FaceId f : old_faces)
    note_killed(f, index);
  return index;
}

std::int32_t DecisionArrayBuilder::add_swap_slots(std::size_t count, std::size_t face_capacity) {
  const std::size_t first = entries_.size();
  entries_.resize(first + count);
  targets_.resize(first + count);
  pending_.resize(first + count);
  if (killed_by_.size() < face_capacity) killed_by_.resize(face_capacity, -1);
  return static_cast<std::int32_t>(first);
}

void DecisionArrayBuilder::write_swap(std::int32_t index, FaceId f, FaceId g, FaceId n1, FaceId n2,
                                      PointIndex u) {
  entries_[index] = DecisionEntry{};
  entries_[index].kind = kDecisionSwap;
  targets_[index] = {n1, n2};
  pending_[index] = {n1, n2, u};
  killed_by_[f] = index;
  killed_by_[g] = index;
}

template <class Point>
void DecisionArrayBuilder::resolve_swap_planes(const Mesh& mesh, const std::vector<Point>& points) {
  parallel_chunks(
      entries_.size(), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          const PendingPlane& p = pending_[k];
          if (entries_[k].kind == kDecisionSwap)
            entries_[k].plane = swap_plane(mesh, points, p.n1, p.n2, p.u);
        }
      },
      512);
}

std::int32_t DecisionArrayBuilder::route_code(FaceId work, const std::vector<FaceId>& remap) const {
  if (remap[work] != kNoFace) return static_cast<std::int32_t>(remap[work]);
  return -(killed_by_.at(work) + 1);
}

template <class Point>
void DecisionArrayBuilder::build_tables(BasicIterationTables<Point>& tables,
                                        std::vector<RefinementEntry> refinement,
                                        const std::vector<std::array<FaceId, 3>>& children,
                                        const std::vector<FaceId>& remap, FaceId old_faces,
                                        const std::vector<PointIndex>& apexes) const {
  tables.refinement = std::move(refinement);
  tables.old_face_split.assign(old_faces, -1);
  tables.old_face_route.resize(old_faces);
  const unsigned workers = hardware_workers();
  parallel_chunks(
      tables.refinement.size(), workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          RefinementEntry& r = tables.refinement[k];
          tables.old_face_split[r.face] = static_cast<std::int32_t>(k);
          for (int i = 0; i < 3; ++i)
            r.child[i] = route_code(children[k][i], remap);
        }
      },
      16384);
  parallel_chunks(
      old_faces, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t f = begin; f < end; ++f)
          tables.old_face_route[f] =
              tables.old_face_split[f] < 0 ? route_code(static_cast<FaceId>(f), remap) : 0;
      },
      16384);
  tables.retired = apexes;
  tables.decision = entries_;
  parallel_chunks(
      tables.decision.size(), workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          tables.decision[k].above = route_code(targets_[k][0], remap);
          tables.decision[k].below = route_code(targets_[k][1], remap);
        }
      },
      16384);
}

template <class Point>
void build_face_geometry(const Mesh& mesh, const std::vector<Point>& points, const Vec3d& interior,
                         const BasicFaceGeometryArray<Point>& previous, const std::vector<FaceId>* remap,
                         BasicFaceGeometryArray<Point>& faces) {
  const std::size_t count = mesh.live_faces();
  // Reuses the spare buffer: a fresh 100 MB array costs page faults every iteration.  When it must grow, a
  // new one with room to spare, its old contents not copied (every face is written below), and its pages
  // first touched by the parallel passes below rather than by one core (growing them was over a third of
  // a dense sphere's host time (docs/benchmarks.md, "Measurements behind the code")).  The spare room is only
  // address space until written, so it is generous.
  if (count > faces.capacity()) {
    BasicFaceGeometryArray<Point> grown;
    grown.reserve(2 * count);
    faces.swap(grown);
  }
  faces.resize(count);
  // Faces that survived the iteration keep their corners and tetrahedron signs (4 exact orient3d each);
  // compaction keeps the order, so this is one forward pass.  Only new faces are computed.
  std::vector<std::uint8_t> known(count, 0);
  if (remap != nullptr) {
    const std::size_t old_count = std::min(previous.size(), remap->size());
    parallel_chunks(
        old_count, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t o = begin; o < end; ++o) {
            const FaceId f = (*remap)[o];
            if (f == kNoFace) continue;
            faces[f] = previous[o];
            known[f] = 1;
          }
        },
        16384);
  }
  parallel_chunks(
      count, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t f = begin; f < end; ++f) {
          const MeshFace& face = mesh.face(static_cast<FaceId>(f));
          for (int k = 0; k < 3; ++k)
            faces[f].neighbor[k] = static_cast<std::int32_t>(face.n[k]);
        }
      },
      16384);
  // The new faces sit together at the end (compaction keeps the id order), so they are listed first and
  // shared out evenly: split by position, one core would get them all.
  std::vector<FaceId> fresh;
  for (std::size_t f = 0; f < count; ++f) {
    if (!known[f]) fresh.push_back(static_cast<FaceId>(f));
  }
  parallel_chunks(
      fresh.size(), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          const MeshFace& face = mesh.face(fresh[k]);
          auto& g = faces[fresh[k]];
          for (int i = 0; i < 3; ++i)
            g.v[i] = points[face.v[i]];
          face_tetrahedron_signs(interior, g.v, g.tet);
        }
      },
      2048);
}

// The two coordinate types (README, "Precision").
template void DecisionArrayBuilder::resolve_swap_planes(const Mesh&, const std::vector<Point3>&);
template void DecisionArrayBuilder::build_tables(BasicIterationTables<Point3>&, std::vector<RefinementEntry>,
                                                 const std::vector<std::array<FaceId, 3>>&,
                                                 const std::vector<FaceId>&, FaceId,
                                                 const std::vector<PointIndex>&) const;
template void build_face_geometry(const Mesh&, const std::vector<Point3>&, const Vec3d&,
                                  const BasicFaceGeometryArray<Point3>&, const std::vector<FaceId>*,
                                  BasicFaceGeometryArray<Point3>&);
template void DecisionArrayBuilder::resolve_swap_planes(const Mesh&, const std::vector<Point3d>&);
template void DecisionArrayBuilder::build_tables(BasicIterationTables<Point3d>&, std::vector<RefinementEntry>,
                                                 const std::vector<std::array<FaceId, 3>>&,
                                                 const std::vector<FaceId>&, FaceId,
                                                 const std::vector<PointIndex>&) const;
template void build_face_geometry(const Mesh&, const std::vector<Point3d>&, const Vec3d&,
                                  const BasicFaceGeometryArray<Point3d>&, const std::vector<FaceId>*,
                                  BasicFaceGeometryArray<Point3d>&);

}  // namespace cudahull::phases
