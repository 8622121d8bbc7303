// The resident engine's local repair of the defects the rounds leave (the host's half: the plan).
//
// The rounds stop when no swap or removal is left.  What can remain (docs/architecture.md, "The resident
// engine's finish"):
//   - flat edges, where the input has four or more coplanar points on the hull (float coordinates on a
//     dense sphere do: the curvature between neighbours is below an ulp).  These are no defect: they
//     triangulate a coplanar facet, and the finish accepts them when every vertex is strictly extreme.
//   - defects: a concave edge (a swap rejected by Fig. 5's foldover test, seen from c, over a vertex of
//     degree above 3 that is not extreme), or a thin vertex, with fewer than three strictly convex edges
//     (inside a coplanar facet or on a polytope edge).  The stepping engine takes such vertices out with
//     complementary swaps (phases/vertex_removal.hpp); the resident engine repairs them here, where they
//     are, and the host hears only them.
//
// design:
//   patch D     the faces within `rings` of a defect, stamped on the executor ring by ring (FaultStamp,
//               SpreadStamp) and read back with one ring more (the faces that border D); one patch per
//               connected part of D
//   boundary L  the directed edges of D's faces whose other face is outside D
//   cap K       the exact hull of D's vertices (exact_hull), flooded from the hull faces that hold L's
//               edges in L's direction, never across L
//   accepted    when every edge of L is in K once and in its direction, no edge of K runs against L,
//               K has no more faces than D, and c is strictly below every face of K
//   written     K's faces in D's slots and the faces that border D linked to K; the last faces of the
//               mesh move into the slots left over (with their neighbours' links), so that the faces stay
//               0..F-1 with no compaction; then K's edges and vertices are checked where they are
//               (CheckRepaired), the rest of the mesh being as it was
//   why exact   D and K both project from c one-to-one onto the sphere (D: the mesh is star-shaped; K: a
//               convex polytope's faces that have c below), with the same boundary, so onto the same
//               region: the new mesh is star-shaped from c again.  Every vertex of D is below every
//               plane of K and on a ray from c that meets K, so inside the new mesh, and with it every
//               point that was inside D's cones.  The new mesh's vertices are input points, and the
//               finish accepts it only with no concave edge and no thin vertex: then it is the exact hull.
//   otherwise   a patch whose L is not on the hull of its vertices, or that is flat, waits for more rings;
//               after the last, the exact finish (the reference hull of every candidate) answers
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/resident/resident_ops.hpp"

namespace cudahull::resident {

struct RepairPlan {
  std::vector<FaceRow> writes;   // the rows to write: the caps' faces, and the faces that border them
  std::vector<u32> repaired;     // the caps' faces
  std::vector<u32> holes;        // the patches' slots the caps left over, ascending
  std::size_t patches = 0;       // patches repaired
  std::size_t patches_left = 0;  // patches that wait for more rings (or the exact finish)
  std::size_t vertices = 0;      // the patches' vertices, whose coordinates the plan asked for
};

template <class Point>
using Coordinates = std::function<std::vector<Point>(const std::vector<PointIndex>&)>;

// The rows read back, by face id, and which of them are in D.
struct PatchRows {
  const std::vector<FaceRow>& rows;
  std::unordered_map<u32, std::size_t> slot;  // face id -> row
  u32 rings;
  const FaceRow* find(u32 face) const {
    const auto it = slot.find(face);
    return it == slot.end() ? nullptr : &rows[it->second];
  }
  bool in_patch(u32 face) const {
    const FaceRow* row = find(face);
    return row && row->ring <= rings;
  }
};

// One patch (`patch`: its rows, by face id): its cap written into the plan, and the faces outside it
// that border it relinked in `outside` (as they will be); false, with neither touched, when it cannot be
// repaired with this many rings.
template <class Point>
bool repair_patch(const PatchRows& read, const std::vector<std::size_t>& patch, const Vec3d& c,
                  const Coordinates<Point>& coordinates, RepairPlan& plan, std::map<u32, FaceRow>& outside) {
  const std::vector<FaceRow>& rows = read.rows;
  using Edge = std::pair<u32, u32>;
  // L: directed edge -> the face outside D across it.
  std::map<Edge, u32> boundary;
  std::vector<PointIndex> ids;
  for (const std::size_t r : patch) {
    for (int k = 0; k < 3; ++k) {
      ids.push_back(rows[r].v[k]);
      if (!read.in_patch(rows[r].n[k]))
        boundary.emplace(Edge{rows[r].v[k], rows[r].v[(k + 1) % 3]}, rows[r].n[k]);
    }
  }
  if (boundary.size() < 3) return false;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const std::vector<Point> at = coordinates(ids);
  plan.vertices += ids.size();
  const BasicHullMesh<Point> hull = exact_hull(at);
  if (hull.dimension != 3) return false;
  // K's faces as global corner ids, and each directed edge's face.
  const std::size_t hull_faces = hull.triangles.size();
  std::vector<std::array<u32, 3>> corners(hull_faces);
  std::map<Edge, u32> face_of_edge;
  for (std::size_t t = 0; t < hull_faces; ++t) {
    for (int k = 0; k < 3; ++k)
      corners[t][k] = ids[hull.vertex_ids[hull.triangles[t][k]]];
    for (int k = 0; k < 3; ++k)
      face_of_edge[{corners[t][k], corners[t][(k + 1) % 3]}] = static_cast<u32>(t);
  }
  // Flood from the faces that hold L's edges, never across L.
  std::vector<char> in_cap(hull_faces, 0);
  std::vector<u32> cap;
  for (const auto& [edge, face_outside] : boundary) {
    const auto it = face_of_edge.find(edge);
    if (it == face_of_edge.end()) return false;  // L is not on the hull of D's vertices
    if (!in_cap[it->second]) {
      in_cap[it->second] = 1;
      cap.push_back(it->second);
    }
  }
  auto P = [&](u32 id) { return to_vec3d(at[std::lower_bound(ids.begin(), ids.end(), id) - ids.begin()]); };
  for (std::size_t k = 0; k < cap.size(); ++k) {
    const auto& t = corners[cap[k]];
    if (orient3d(c, P(t[0]), P(t[1]), P(t[2])) <= 0) return false;  // c not strictly below
    for (int s = 0; s < 3; ++s) {
      const Edge e{t[s], t[(s + 1) % 3]}, twin{e.second, e.first};
      if (boundary.count(e)) continue;
      if (boundary.count(twin)) return false;  // K runs against L: it is not D's side
      const u32 other = face_of_edge.at(twin);
      if (!in_cap[other]) {
        in_cap[other] = 1;
        cap.push_back(other);
      }
    }
  }
  if (cap.size() > patch.size()) return false;
  // K in D's slots (the lowest ids), the rest left over (plan.holes); links within K, to the faces outside
  // across L, and those faces' links back.
  std::map<u32, u32> slot_of;  // hull face -> mesh face id
  for (std::size_t k = 0; k < cap.size(); ++k)
    slot_of[cap[k]] = rows[patch[k]].id;
  std::vector<FaceRow> mine;
  std::map<u32, FaceRow> relinked;  // the bordering faces this patch relinks, from `outside` or as read
  for (std::size_t k = 0; k < cap.size(); ++k) {
    const auto& t = corners[cap[k]];
    FaceRow row{rows[patch[k]].id, {t[0], t[1], t[2]}, {}, 1};
    for (int s = 0; s < 3; ++s) {
      const Edge e{t[s], t[(s + 1) % 3]};
      const auto b = boundary.find(e);
      if (b == boundary.end()) {
        row.n[s] = slot_of.at(face_of_edge.at({e.second, e.first}));
        continue;
      }
      row.n[s] = b->second;
      auto it = relinked.find(b->second);
      if (it == relinked.end()) {
        const auto before = outside.find(b->second);
        const FaceRow* as_read = read.find(b->second);
        if (before == outside.end() && !as_read) return false;
        it = relinked.emplace(b->second, before != outside.end() ? before->second : *as_read).first;
      }
      bool linked = false;
      for (int q = 0; q < 3; ++q) {
        if (it->second.v[q] == e.second && it->second.v[(q + 1) % 3] == e.first) {
          it->second.n[q] = row.id;
          linked = true;
        }
      }
      if (!linked) return false;
    }
    mine.push_back(row);
  }
  for (const FaceRow& row : mine) {
    plan.writes.push_back(row);
    plan.repaired.push_back(row.id);
  }
  for (std::size_t k = cap.size(); k < patch.size(); ++k)
    plan.holes.push_back(rows[patch[k]].id);
  for (const auto& [id, row] : relinked)
    outside[id] = row;
  return true;
}

// The plan for the faces read back (`rows`: rings 1 .. rings + 1), given the interior point `c` and the
// coordinates of listed points (`coordinates(ids)`, ids ascending).
template <class Point>
RepairPlan plan_repair(const std::vector<FaceRow>& rows, u32 rings, const Vec3d& c,
                       const Coordinates<Point>& coordinates) {
  RepairPlan plan;
  PatchRows read{rows, {}, rings};
  for (std::size_t r = 0; r < rows.size(); ++r)
    read.slot.emplace(rows[r].id, r);
  std::map<u32, FaceRow> outside;
  std::vector<char> seen(rows.size(), 0);
  for (std::size_t start = 0; start < rows.size(); ++start) {
    if (seen[start] || rows[start].ring > rings) continue;
    // One connected part of D.
    std::vector<std::size_t> patch{start};
    seen[start] = 1;
    for (std::size_t k = 0; k < patch.size(); ++k) {
      for (const u32 nb : rows[patch[k]].n) {
        if (!read.in_patch(nb)) continue;
        const std::size_t r = read.slot.at(nb);
        if (!seen[r]) {
          seen[r] = 1;
          patch.push_back(r);
        }
      }
    }
    std::sort(patch.begin(), patch.end(),
              [&](std::size_t a, std::size_t b) { return rows[a].id < rows[b].id; });
    if (repair_patch<Point>(read, patch, c, coordinates, plan, outside)) {
      ++plan.patches;
    } else {
      ++plan.patches_left;
    }
  }
  for (const auto& [id, row] : outside)
    plan.writes.push_back(row);
  std::sort(plan.holes.begin(), plan.holes.end());
  return plan;
}

}  // namespace cudahull::resident
