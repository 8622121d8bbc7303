// The resident engine's finish, once no point is outside: the defects counted (CountFaults, then
// CountConcave and CountThin: flat edges inside coplanar facets are no defect), the result renumbered where
// it is, the device side of the local repair (fault_repair.hpp plans it), and what the records read back.
//
// design:
//   check    CountFaults: the edges that are not strictly convex; none, and the mesh is the exact hull
//            with every vertex strictly extreme (section 3's convexity, checked exactly)
//   defects  with some: CountConcave (concave edges) and CountThin (a vertex with fewer than three creases
//            lies inside a facet or an edge); none, and the flat edges only triangulate coplanar facets
//   repair   the defects' faces stamped with rings around them (FaultRing, SpreadStamp), read back
//            (GatherRows), re-hulled on the host and written (WriteRows), then checked (CheckRepaired)
//   result   the vertices in index order (FlagCorners and a prefix sum, or the corners sorted) and each
//            corner renumbered to its vertex's rank (RenumberCorners, FindCorners)
#pragma once

#include <cstddef>
#include <cstdint>

#include "cudahull/resident/star_mesh.hpp"

namespace cudahull::resident {

// The finish of a mesh of at most this many faces runs in one launch (the GPU's finish_small_kernel, one
// block) and one read; DevicePathHostExec mirrors it for the CPU tests.
inline constexpr std::size_t kSmallFinishFaces = 2048;

// The result, renumbered where it is: each vertex flagged (every corner writes 1), then corners to ranks.
struct FlagCorners {
  const u32* fv;
  u32* used;
  CUDAHULL_HD void operator()(std::size_t k) const { used[fv[k]] = 1; }
};
// Corner k to its vertex's rank in the sorted vertex list (bisection).
struct FindCorners {
  const u32* fv;
  const u32* vertices;
  const u32* count;  // where the executor computes
  u32* out;
  CUDAHULL_HD void operator()(std::size_t k) const {
    u32 lo = 0, hi = *count;  // vertices[lo..hi) holds fv[k]
    while (hi - lo > 1) {
      const u32 mid = lo + (hi - lo) / 2;
      if (vertices[mid] <= fv[k]) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    out[k] = lo;
  }
};
// Records: how many kept points each face holds (with FurthestPerFace, the debugger's face extremes).
struct CountPerFace {
  const u32* point_face;
  u32* count;
  CUDAHULL_HD void operator()(std::size_t j) const { atomic_add_u32(&count[point_face[j]], 1); }
};

// The debugger's point states (Backend::write_point_states_on_device): every point internal, then each
// kept point its face, then the vertices marked.
struct ScatterPointStates {
  const u32* point_index;
  const u32* point_face;
  std::int32_t* out;
  CUDAHULL_HD void operator()(std::size_t j) const {
    out[point_index[j]] = static_cast<std::int32_t>(point_face[j]);
  }
};
struct MarkPoints {
  const u32* ids;
  std::int32_t value;
  std::int32_t* out;
  CUDAHULL_HD void operator()(std::size_t k) const { out[ids[k]] = value; }
};

// The coordinates of listed points, for a caller whose points are only where the executor computes.
template <class Point>
struct GatherPoints {
  const Point* points;
  const u32* ids;
  Point* out;
  CUDAHULL_HD void operator()(std::size_t k) const { out[k] = points[ids[k]]; }
};
struct RenumberCorners {
  const u32* fv;
  const u32* rank;
  u32* out;
  CUDAHULL_HD void operator()(std::size_t k) const { out[k] = rank[fv[k]]; }
};

// Counts the edges that are not strictly convex (each once, from its lower face): zero means the mesh is
// the exact hull of its vertices, with every vertex strictly extreme.
template <class Point>
struct CountFaults {
  MeshView<Point> m;
  u32* faults;
  CUDAHULL_HD void operator()(std::size_t fi) const {
    const u32 f = static_cast<u32>(fi);
    const Vec3d a = m.P(m.fv[3 * f]), b = m.P(m.fv[3 * f + 1]), d = m.P(m.fv[3 * f + 2]);
    for (int i = 0; i < 3; ++i) {
      if (m.fn[3 * f + i] >= f && m.edge_turn(f, i, a, b, d) >= 0) atomic_add_u32(faults, 1);
    }
  }
};

// The local repair of the faults the rounds leave (fault_repair.hpp plans it on the host).

// A face as read back for the repair, or as written by it: id, corners, links, and its ring (1: it holds
// a fault; r: r - 1 faces from one).
struct FaceRow {
  u32 id;
  u32 v[3];
  u32 n[3];
  u32 ring;
};

// Counts the defects of a mesh with edges that are not strictly convex (CountFaults): concave edges, and
// vertices with fewer than three strictly convex edges (creases), which lie inside a facet or an edge of
// the polytope and are not strictly extreme.  With none, the flat edges only triangulate coplanar facets
// and the mesh is the exact hull.  Per face, its edges owned as CountFaults owns them: `creases` and
// `used` (zero before, one per point) count each vertex's creases and flag the mesh's vertices.
template <class Point>
struct CountConcave {
  MeshView<Point> m;
  u32* creases;
  u32* used;
  u32* defects;
  u32* ring;  // zero before: 1 on both faces of a concave edge (the repair's first ring, FaultRing)
  CUDAHULL_HD void operator()(std::size_t fi) const {
    const u32 f = static_cast<u32>(fi);
    const Vec3d a = m.P(m.fv[3 * f]), b = m.P(m.fv[3 * f + 1]), d = m.P(m.fv[3 * f + 2]);
    for (int i = 0; i < 3; ++i) {
      used[m.fv[3 * f + i]] = 1;
      const u32 g = m.fn[3 * f + i];
      if (g < f) continue;
      const int turn = m.edge_turn(f, i, a, b, d);
      if (turn > 0) {
        atomic_add_u32(defects, 1);
        ring[f] = 1;
        ring[g] = 1;
      } else if (turn < 0) {
        atomic_add_u32(&creases[m.fv[3 * f + i]], 1);
        atomic_add_u32(&creases[m.fv[3 * f + (i + 1) % 3]], 1);
      }
    }
  }
};
// Per point: a vertex of the mesh with fewer than three creases.
struct CountThin {
  const u32* creases;
  const u32* used;
  u32* defects;
  CUDAHULL_HD bool thin(u32 v) const { return used[v] && creases[v] < 3; }
  CUDAHULL_HD void operator()(std::size_t i) const {
    if (thin(static_cast<u32>(i))) atomic_add_u32(defects, 1);
  }
};

// The repair's first ring: 1 also on the faces with a thin corner (CountConcave stamped the concave edges).
struct FaultRing {
  CountThin thin;
  const u32* fv;
  u32* ring;
  CUDAHULL_HD void operator()(std::size_t f) const {
    if (thin.thin(fv[3 * f]) || thin.thin(fv[3 * f + 1]) || thin.thin(fv[3 * f + 2])) ring[f] = 1;
  }
};

// Ring `ring_now + 1` on the unstamped faces next to ring `ring_now` (a face written in this pass holds
// ring_now + 1, which no reader takes for ring_now: the same stamps in any order).
struct SpreadStamp {
  const u32* fn;
  u32* ring;
  u32 ring_now;
  CUDAHULL_HD void operator()(std::size_t f) const {
    if (ring[f] != 0) return;
    if (ring[fn[3 * f]] == ring_now || ring[fn[3 * f + 1]] == ring_now || ring[fn[3 * f + 2]] == ring_now)
      ring[f] = ring_now + 1;
  }
};

// 1 on a stamped face, else 0 (select() counts flags of 0 and 1).
struct Stamped {
  const u32* ring;
  u32* flag;
  CUDAHULL_HD void operator()(std::size_t f) const { flag[f] = ring[f] != 0 ? 1u : 0u; }
};

// The stamped faces' rows, for the host's plan.
struct GatherRows {
  const u32* ids;
  const u32* fv;
  const u32* fn;
  const u32* ring;
  FaceRow* out;
  CUDAHULL_HD void operator()(std::size_t k) const {
    const u32 f = ids[k];
    FaceRow row{
        f, {fv[3 * f], fv[3 * f + 1], fv[3 * f + 2]}, {fn[3 * f], fn[3 * f + 1], fn[3 * f + 2]}, ring[f]};
    out[k] = row;
  }
};

// The repaired faces checked where they are (the rest of the mesh is as it was): no concave edge, and each
// corner a vertex with three creases or more, counted by a walk around it.  A walk longer than kMaxWalk
// (or one that does not close) counts as a defect.
template <class Point>
struct CheckRepaired {
  static constexpr u32 kMaxWalk = 1u << 16;
  MeshView<Point> m;
  const u32* faces;
  u32* defects;
  CUDAHULL_HD bool thin(u32 start, int slot) const {
    const u32 v = m.fv[3 * start + slot];
    u32 f = start, creases = 0;
    int s = slot;
    for (u32 step = 0; step < kMaxWalk; ++step) {
      if (m.edge_turn(f, s, m.P(m.fv[3 * f]), m.P(m.fv[3 * f + 1]), m.P(m.fv[3 * f + 2])) < 0) ++creases;
      f = m.fn[3 * f + s];
      s = m.corner_slot(f, v);
      if (s < 0) return true;
      if (f == start) return creases < 3;
    }
    return true;
  }
  CUDAHULL_HD void operator()(std::size_t k) const {
    const u32 f = faces[k];
    const Vec3d a = m.P(m.fv[3 * f]), b = m.P(m.fv[3 * f + 1]), d = m.P(m.fv[3 * f + 2]);
    for (int i = 0; i < 3; ++i) {
      if (m.edge_turn(f, i, a, b, d) > 0 || thin(f, i)) atomic_add_u32(defects, 1);
    }
  }
};

// The plan's rows written into the mesh, live faces (the slots a repair leaves over are filled by the
// mesh's last faces, resident_finish.hpp's fill_holes, not written dead).
struct WriteRows {
  const FaceRow* rows;
  u32* fv;
  u32* fn;
  u32* replaced_by;
  CUDAHULL_HD void operator()(std::size_t k) const {
    const FaceRow& row = rows[k];
    for (int i = 0; i < 3; ++i) {
      fv[3 * row.id + i] = row.v[i];
      fn[3 * row.id + i] = row.n[i];
    }
    replaced_by[row.id] = kAlive;
  }
};

}  // namespace cudahull::resident
