#include "phases/vertex_removal.hpp"

#include <algorithm>
#include <array>

#include "phases/swaps.hpp"
#include "phases/vector_math.hpp"

namespace cudahull::phases {

template <class Point>
bool try_remove(LocalEdits<Point>& edits, PointIndex v, bool doomed_vertex) {
  Mesh& mesh = edits.mesh;
  IterationRecord& record = edits.record;
  std::vector<PointIndex>& ring = edits.ring;
  std::vector<FaceId>& ring_faces = edits.ring_faces;
  if (!mesh.has_vertex(v)) return false;
  mesh.ring(v, ring, ring_faces);
  if (ring.size() != 3) return false;
  const PointIndex a = ring[0], b = ring[1], d = ring[2];
  const int height = orient3d(edits.P(a), edits.P(b), edits.P(d), edits.P(v));
  if (!doomed_vertex && height > 0) return false;  // convex: stays
  if (!doomed_vertex && (edits.vertex_flags.get(v) & kRemovedOnce)) return false;

  RemovalRecord removal;
  removal.vertex = v;
  removal.ring[0] = a, removal.ring[1] = b, removal.ring[2] = d;
  // Seen from far below the new triangle (its normal's parallel projection, as for swaps).
  const Vec3d pa = edits.P(a), pb = edits.P(b), pd = edits.P(d);
  const Vec3d centroid{(pa.x + pb.x + pd.x) / 3, (pa.y + pb.y + pd.y) / 3, (pa.z + pb.z + pd.z) / 3};
  const Vec3d view = far_below(centroid, normalized(cross(sub(pb, pa), sub(pd, pa))), extent({pa, pb, pd}));
  bool valid = height < 0 || in_cone_from(view, pa, pb, pd, edits.P(v));
  std::array<FaceId, 3> outer{};
  for (int k = 0; k < 3 && valid; ++k) {
    const PointIndex from = ring[k], to = ring[(k + 1) % 3], other = ring[(k + 2) % 3];
    outer[k] = mesh.face(ring_faces[k]).n[mesh.edge_index(ring_faces[k], from, to)];
    const MeshFace& out = mesh.face(outer[k]);
    if (out.v[0] == other || out.v[1] == other || out.v[2] == other) valid = false;
  }
  if (valid && (outer[0] == outer[1] || outer[1] == outer[2] || outer[0] == outer[2])) valid = false;
  if (!valid) {
    removal.rejected = true;
    removal.sequence = edits.sequence++;
    record.removals.push_back(removal);
    ++record.removals_rejected;
    return false;
  }
  const std::vector<FaceId> old_faces = ring_faces;
  const FaceId n = mesh.remove_degree3(v);
  removal.decision_index = edits.decisions.add_removal(n, old_faces);
  removal.sequence = edits.sequence++;
  record.removals.push_back(removal);
  ++record.vertices_removed;
  edits.vertex_flags[v] |= kRemovedOnce;
  edits.dropped.push_back(v);
  edits.dropped_near.push_back(a);
  for (int k = 0; k < 3; ++k)
    edits.queue.push_back({n, k});
  for (PointIndex p : {a, b, d})
    edits.touch(p);
  return true;
}

template <class Point>
bool take_out(LocalEdits<Point>& edits, PointIndex w) {
  Mesh& mesh = edits.mesh;
  std::vector<PointIndex>& ring = edits.ring;
  std::vector<FaceId>& ring_faces = edits.ring_faces;
  std::size_t last_degree = SIZE_MAX;
  for (;;) {
    if (!mesh.has_vertex(w)) return true;
    mesh.ring(w, ring, ring_faces);
    if (ring.size() == 3) return try_remove(edits, w, true);
    // Every swap here takes an edge out of w's star, so the degree must fall each round.  On degenerate
    // input (the property test's 1e6-offset cluster) a swap can leave it as it was; stop rather than cycle
    // (the exact finish deals with what remains).
    if (ring.size() >= last_degree || edits.budget == 0) return false;
    last_degree = ring.size();
    --edits.budget;
    // One viewpoint for the whole star: far below w along the mean normal of its faces.
    const Vec3d pw = edits.P(w);
    Vec3d mean{0, 0, 0};
    double size = 0;
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const Vec3d a = edits.P(ring[k]), b = edits.P(ring[(k + 1) % ring.size()]);
      mean = add(mean, normalized(cross(sub(a, pw), sub(b, pw))));
      size = std::max(size, extent({pw, a}));
    }
    const Vec3d view = far_below(pw, normalized(mean), size);
    bool swapped = false;
    for (int pass = 0; pass < 2 && !swapped; ++pass) {
      for (std::size_t k = 0; k < ring.size() && !swapped; ++k) {
        const std::size_t prev = (k + ring.size() - 1) % ring.size(), next = (k + 1) % ring.size();
        // Edge w -> ring[k] lies in face (w, ring[k], ring[k+1]); swapping it gives ring[k+1] - ring[k-1].
        const bool concave = orient3d(pw, edits.P(ring[k]), edits.P(ring[next]), edits.P(ring[prev])) > 0;
        if (pass == 0 && !concave) continue;
        const FaceId f = ring_faces[k];
        const int i = mesh.edge_index(f, w, ring[k]);
        if (i < 0) continue;  // a ring that does not close cleanly (degenerate input): not this edge
        SwapRecord probe;
        if (swap_validity(edits, w, ring[k], ring[next], ring[prev], probe, &view) != SwapKind::kRegular)
          continue;
        swapped = try_swap(edits, f, i, SwapKind::kComplementary, &view);
      }
    }
    if (!swapped) return false;
  }
}

// The two coordinate types (README, "Precision").
template bool try_remove(LocalEdits<Point3>&, PointIndex, bool);
template bool take_out(LocalEdits<Point3>&, PointIndex);
template bool try_remove(LocalEdits<Point3d>&, PointIndex, bool);
template bool take_out(LocalEdits<Point3d>&, PointIndex);

}  // namespace cudahull::phases
