// The resident engine's per-element operations: every step of an iteration of Algorithm 1 as a function of
// one face or one point, over flat arrays, compiled for the host (HostExec, loops) and the device
// (CudaExec, one thread each).  resident_driver.hpp runs them in order; the executor decides where.
//
// design:
//   The mesh is star-shaped from the interior point c: every face (a, b, d) has orient3d(c, a, b, d) > 0,
//   so the radial cones from c over the faces tile space.  Each external point belongs to the face whose
//   closed cone holds it; a point below (or on) its face is inside the tetrahedron (c, a, b, d), so inside
//   the hull, and is dropped.  Every edit keeps the cones a tiling, and appends a decision entry (Fig. 7)
//   that says, by one or two exact orient3d with c, which new face a point of a killed face belongs to:
//     refine (Fig. 3a)  face (a, b, d) at its furthest point p, strictly inside the cone: children
//                       (a, b, p), (b, d, p), (d, a, p), each written with its own links (gathers)
//     flip (Fig. 3b)    concave edge u - v of f = (u, v, x), g = (v, u, y) into x - y: n1 = (x, u, y),
//                       n2 = (y, v, x); only when both new faces keep c strictly below (the foldover test
//                       of Fig. 5, seen from c)
//     flop (Fig. 4)     a vertex v of degree 3 that is concave or flat: its three faces become (a, b, d)
//   Flips and flops run in conflict-free rounds: each candidate claims the faces it kills (two for a
//   flip, three for a flop) with a 64-bit atomicMax of (round, ~candidate id); the holders of all their
//   claims apply at once, numbered by a prefix sum, so the result is the same on any executor and thread
//   count.  A winner writes only its new faces and the killed faces' entries, and stamps the faces around it
//   for the next round (every winner that touches one writes the same stamp); those faces keep
//   links to killed faces until the next round's FixLinks gathers the new ones from the entries (as the
//   refinement's gathers do).  Disjoint flips cannot make the same edge: in the radial view each new edge
//   lies inside its own quadrilateral.
//   Face ids only grow within an iteration (killed faces keep their corners for the routing); compaction
//   renumbers between iterations.
#pragma once

#include <cstdint>
#include <cstring>

#include "cudahull/host_device.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull::resident {

using u32 = std::uint32_t;
using u64 = std::uint64_t;

inline constexpr u32 kAlive = 0xffffffffu;     // killer[] of a live face
inline constexpr u32 kDeadSlot = 0xfffffffeu;  // killer[] of a face slot a flop left unused
inline constexpr u32 kNone = 0xffffffffu;

enum EntryKind : u32 { kRefine = 0, kFlip = 1, kFlop = 2 };

// A decision entry (Fig. 7).  refine: p = apex, out = children; flip: p = x, q = y, out = n1, n2; flop:
// out[0] = the new face.
struct Entry {
  u32 kind, p, q;
  u32 out[3];
};

// ---------------------------------------------------------------------------------------------------------
// Atomics: the device's, or plain operations for the host's sequential loops (the same final values).

CUDAHULL_HD inline void atomic_max_u64(u64* at, u64 value) {
#if defined(__CUDA_ARCH__)
  atomicMax(reinterpret_cast<unsigned long long*>(at), static_cast<unsigned long long>(value));
#else
  if (value > *at) *at = value;
#endif
}

CUDAHULL_HD inline u32 atomic_add_u32(u32* at, u32 value) {
#if defined(__CUDA_ARCH__)
  return atomicAdd(at, value);
#else
  const u32 old = *at;
  *at += value;
  return old;
#endif
}

CUDAHULL_HD inline u32 float_bits(float f) {
#if defined(__CUDA_ARCH__)
  return __float_as_uint(f);
#else
  u32 u;
  std::memcpy(&u, &f, sizeof u);
  return u;
#endif
}

// A key whose unsigned order is the order of v (rounded to float), with ties to the lowest index: the upper
// half is v's float bits made monotone, the lower half ~index.  Ranking only; decisions are exact.
CUDAHULL_HD inline u64 rank_key(double v, u32 index) {
  u32 bits = float_bits(static_cast<float>(v));
  bits = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
  return (static_cast<u64>(bits) << 32) | static_cast<u64>(~index);
}
CUDAHULL_HD inline u32 rank_key_index(u64 key) {
  return ~static_cast<u32>(key);
}

// ---------------------------------------------------------------------------------------------------------
// The mesh as the operations see it.  Face f: corners fv[3f..3f+2] counter-clockwise from outside,
// fn[3f+i] the face across the directed edge fv[3f+i] -> fv[3f+(i+1)%3].

template <class Point>
struct MeshView {
  const Point* points;
  Vec3d c;  // the interior point
  u32* fv;
  u32* fn;
  u32* killer;  // kAlive, kDeadSlot, or the entry that killed the face this iteration
  Entry* entries;

  CUDAHULL_HD Vec3d P(u32 i) const { return to_vec3d(points[i]); }
  // The slot s of face f holding the directed edge a -> b, or -1.
  CUDAHULL_HD int edge_slot(u32 f, u32 a, u32 b) const {
    for (int s = 0; s < 3; ++s) {
      if (fv[3 * f + s] == a && fv[3 * f + (s + 1) % 3] == b) return s;
    }
    return -1;
  }
  CUDAHULL_HD int corner_slot(u32 f, u32 v) const {
    for (int s = 0; s < 3; ++s) {
      if (fv[3 * f + s] == v) return s;
    }
    return -1;
  }
  // Is q in the closed cone from c over face f?  Exact.
  CUDAHULL_HD bool in_cone(u32 f, const Vec3d& q) const {
    const Vec3d a = P(fv[3 * f]), b = P(fv[3 * f + 1]), d = P(fv[3 * f + 2]);
    return orient3d(c, a, b, q) >= 0 && orient3d(c, b, d, q) >= 0 && orient3d(c, d, a, q) >= 0;
  }
  CUDAHULL_HD int above(u32 f, const Vec3d& q) const {
    return orient3d(P(fv[3 * f]), P(fv[3 * f + 1]), P(fv[3 * f + 2]), q);
  }
  // The turn at edge i of face f (corners a, b, d): -1 strictly convex, 0 flat, 1 concave (the third
  // corner of the face across, against f's plane), or 1 when that face does not hold the edge the other
  // way.  Exact.
  CUDAHULL_HD int edge_turn(u32 f, int i, const Vec3d& a, const Vec3d& b, const Vec3d& d) const {
    const u32 g = fn[3 * f + i];
    const int j = edge_slot(g, fv[3 * f + (i + 1) % 3], fv[3 * f + i]);
    return j < 0 ? 1 : orient3d(a, b, d, P(fv[3 * g + (j + 2) % 3]));
  }
};

// ---------------------------------------------------------------------------------------------------------
// Points: the first distribution (section 3.1), the routing through the entries (Algorithm 2), and the
// furthest point per face.

// Section 3.1 looked at in more directions (the Akl-Toussaint throw-away): the points extreme along the
// three axes and the eight diagonals, both ways, span a polytope P of input points.  A point strictly
// inside P is inside the hull and never one of its vertices, so the first distribution drops it before
// any exact test; on a uniform cube that is nearly every point.  The ranking need not be exact (any input
// points span a P that is correct to use); the drop test is sound by its error bound (DropFilter).
inline constexpr int kDirections = 14;

// The value of p along direction k (larger is further): -x, x, -y, y, -z, z, then (+-1, +-1, +-1).
CUDAHULL_HD inline double direction_value(int k, const Vec3d& p) {
  if (k < 6) {
    const double v = k < 2 ? p.x : k < 4 ? p.y : p.z;
    return (k & 1) ? v : -v;
  }
  const int d = k - 6;
  const double x = (d & 1) ? p.x : -p.x, y = (d & 2) ? p.y : -p.y, z = (d & 4) ? p.z : -p.z;
  return (x + y) + z;
}

// The rank keys of point i along every direction (rank_key: ties to the lowest index).
template <class Point>
struct DirectionKeys {
  const Point* points;
  CUDAHULL_HD void operator()(std::size_t i, u64 (&keys)[kDirections]) const {
    const Vec3d p = to_vec3d(points[i]);
    for (int k = 0; k < kDirections; ++k)
      keys[k] = rank_key(direction_value(k, p), static_cast<u32>(i));
  }
};

// P's face planes, evaluated in double: e = n.p + d is within slack of the exact value of the plane
// through the face's corners (the host derives the bound from the rounding of n, d and this evaluation,
// over every point's coordinate range), so e < -slack on every plane proves p strictly inside P.  The
// evaluation order is fixed and unfused on both executors, so both drop the same points.
inline constexpr int kMaxDropPlanes = 2 * kDirections - 4;  // the faces of a polytope of 14 vertices
struct DropFilter {
  u32 planes = 0;  // 0: no polytope (lower-dimensional extremes), nothing is dropped
  double n[kMaxDropPlanes][3] = {}, d[kMaxDropPlanes] = {}, slack[kMaxDropPlanes] = {};
  // Unrolled, so that on the device a filter passed by value is read as kernel-parameter operands, not
  // loaded plane by plane.
  CUDAHULL_HD bool strictly_inside(const Vec3d& p) const {
    if (planes == 0) return false;
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
    for (u32 k = 0; k < static_cast<u32>(kMaxDropPlanes); ++k) {
      if (k == planes) break;
      const double e = ((n[k][0] * p.x + n[k][1] * p.y) + n[k][2] * p.z) + d[k];
      if (!(e < -slack[k])) return false;
    }
    return true;
  }
};

// Selects the points the first distribution looks at: those not proven strictly inside P.
template <class Point>
struct NotInsideP {
  const Point* points;
  DropFilter filter;
  CUDAHULL_HD bool operator()(u32 i) const { return !filter.strictly_inside(to_vec3d(points[i])); }
};

// Each point (of `list`, or every point) to the first of the first mesh's faces (P's, or the
// tetrahedron's) whose closed cone holds it, the last face by elimination; kept when above.
template <class Point>
struct AssignFirst {
  MeshView<Point> m;
  u32 faces;
  const u32* list;  // the points looked at (NotInsideP), or null for all
  u32* point_index;
  u32* point_face;
  u32* keep;
  CUDAHULL_HD void operator()(std::size_t j) const {
    const u32 i = list ? list[j] : static_cast<u32>(j);
    const Vec3d q = m.P(i);
    u32 face = faces - 1;
    for (u32 f = 0; f + 1 < faces; ++f) {
      if (m.in_cone(f, q)) {
        face = f;
        break;
      }
    }
    point_index[j] = i;
    point_face[j] = face;
    keep[j] = m.above(face, q) > 0 ? 1u : 0u;
  }
};

// Follows the entries from a point's face to the live face whose cone holds it; kept when above.
template <class Point>
struct RoutePoints {
  MeshView<Point> m;
  const u32* point_index;
  u32* point_face;
  u32* keep;
  CUDAHULL_HD void operator()(std::size_t j) const {
    const Vec3d q = m.P(point_index[j]);
    u32 f = point_face[j];
    for (u32 e = m.killer[f]; e != kAlive; e = m.killer[f]) {
      const Entry& entry = m.entries[e];
      if (entry.kind == kRefine) {
        // Child k = (v_k, v_k+1, p) holds q when q is left of p -> v_k+1 and right of p -> v_k.
        const Vec3d p = m.P(entry.p);
        int s[3];
        for (int k = 0; k < 3; ++k)
          s[k] = orient3d(m.c, m.P(m.fv[3 * f + k]), p, q);
        const int k = (s[1] >= 0 && s[0] <= 0) ? 0 : (s[2] >= 0 && s[1] <= 0) ? 1 : 2;
        f = entry.out[k];
      } else if (entry.kind == kFlip) {
        f = orient3d(m.c, m.P(entry.p), m.P(entry.q), q) >= 0 ? entry.out[1] : entry.out[0];
      } else {
        f = entry.out[0];
      }
    }
    point_face[j] = f;
    keep[j] = m.above(f, q) > 0 ? 1u : 0u;
  }
};

// Per face, the furthest external point (rank_key: largest height, ties to the lowest index).  `extreme`
// is zeroed first; a face with no external point keeps 0.
template <class Point>
struct FurthestPerFace {
  MeshView<Point> m;
  const u32* point_index;
  const u32* point_face;
  u64* extreme;
  const u32* keep = nullptr;  // optional: the points listed but not kept count for nothing (key 0)
  CUDAHULL_HD u32 segment(std::size_t j) const { return point_face[j]; }
  CUDAHULL_HD u64 key(std::size_t j) const {
    if (keep && !keep[j]) return 0;
    const u32 f = point_face[j], i = point_index[j];
    const double h = orient3d_fast(m.P(m.fv[3 * f]), m.P(m.fv[3 * f + 1]), m.P(m.fv[3 * f + 2]), m.P(i));
    return rank_key(h > 0 ? h : 0, i);
  }
  CUDAHULL_HD void operator()(std::size_t j) const { atomic_max_u64(&extreme[segment(j)], key(j)); }
};

// ---------------------------------------------------------------------------------------------------------
// Refinement (Fig. 3a).

// A face refines when its furthest point lies strictly inside its cone (on a side of the cone a child would
// be flat: the face waits, even if other points of it are strictly inside, and a stall ends in the exact
// finish).
template <class Point>
struct MarkRefined {
  MeshView<Point> m;
  const u64* extreme;
  u32* refine;
  CUDAHULL_HD void operator()(std::size_t fi) const {
    const u32 f = static_cast<u32>(fi);
    u32 flag = 0;
    if (extreme[f] != 0) {
      const Vec3d p = m.P(rank_key_index(extreme[f]));
      const Vec3d a = m.P(m.fv[3 * f]), b = m.P(m.fv[3 * f + 1]), d = m.P(m.fv[3 * f + 2]);
      flag = orient3d(m.c, a, b, p) > 0 && orient3d(m.c, b, d, p) > 0 && orient3d(m.c, d, a, p) > 0;
    }
    refine[f] = flag;
  }
};

// Splits each marked face into three children at first + 3 rank[f] (rank: the prefix sum of the marks);
// every face writes only its own links, gathered from the neighbours' marks.
template <class Point>
struct SplitFaces {
  MeshView<Point> m;
  const u64* extreme;
  const u32* refine;
  const u32* rank;
  u32 first_face, first_entry;
  u32* look;  // an unrefined face next to a refined one is looked at in the first round
  u32 first_round;
  u32* refined_total;  // optional: the last face writes how many faces refine (no wait for the scan)
  // The face across edge (a -> b) of f after the split: nb itself, or nb's child on that edge.
  CUDAHULL_HD u32 across(u32 nb, u32 a, u32 b) const {
    if (!refine[nb]) return nb;
    return first_face + 3 * rank[nb] + static_cast<u32>(m.edge_slot(nb, b, a));
  }
  CUDAHULL_HD void operator()(std::size_t fi) const {
    const u32 f = static_cast<u32>(fi);
    if (refined_total && f + 1 == first_face) *refined_total = rank[f] + refine[f];
    if (!refine[f]) {
      bool touched = false;
      for (int k = 0; k < 3; ++k) {
        const u32 a = m.fv[3 * f + k], b = m.fv[3 * f + (k + 1) % 3], nb = m.fn[3 * f + k];
        touched = touched || refine[nb];
        m.fn[3 * f + k] = across(nb, a, b);
      }
      if (touched) look[f] = first_round;
      return;
    }
    const u32 p = rank_key_index(extreme[f]);
    const u32 kids = first_face + 3 * rank[f], e = first_entry + rank[f];
    for (int k = 0; k < 3; ++k) {
      const u32 child = kids + static_cast<u32>(k);
      const u32 a = m.fv[3 * f + k], b = m.fv[3 * f + (k + 1) % 3];
      m.fv[3 * child] = a;
      m.fv[3 * child + 1] = b;
      m.fv[3 * child + 2] = p;
      m.fn[3 * child] = across(m.fn[3 * f + k], a, b);
      m.fn[3 * child + 1] = kids + static_cast<u32>((k + 1) % 3);
      m.fn[3 * child + 2] = kids + static_cast<u32>((k + 2) % 3);
      m.killer[child] = kAlive;
      look[child] = 0;
    }
    m.entries[e] = Entry{kRefine, p, kNone, {kids, kids + 1, kids + 2}};
    m.killer[f] = e;
  }
};

// ---------------------------------------------------------------------------------------------------------
// Flip and flop rounds (Figs. 3b, 4, 5).

// A candidate edit: the faces it kills (claimed) and the faces around them (stamped for the next round).
struct Candidate {
  u32 kind = kNone;    // kFlip or kFlop, or kNone
  u32 id = 0;          // 6 f + slot: what it claims with
  u32 claims = 0;      // faces[0..claims): the faces it kills, claimed; the rest are the faces around
  u32 faces[6] = {};   // flip: f, g, A (across x->u), B (u->y), C (y->v), D (v->x); flop: f, h, t, the
                       // outer faces across a->b, b->d, d->a
  u32 vertex[4] = {};  // flip: u, v, x, y; flop: v, a, b, d
};

// What a candidate's id claims with in round `round`: later rounds win over stale claims, and within a
// round the lowest id.
CUDAHULL_HD inline u64 claim_key(u32 round, u32 candidate) {
  return (static_cast<u64>(round) << 32) | static_cast<u64>(~candidate);
}

// Face f and its three neighbours, read in three waves (f's corners and links, the neighbours' corners
// and links, the six points) so that a thread waits for three loads in a row rather than one per test.
template <class Point>
struct Around {
  u32 f;
  u32 v[3], n[3];          // f
  u32 gv[3][3], gn[3][3];  // neighbour i = n[i]: corners and links
  int j[3];                // the slot of edge v[i+1] -> v[i] in neighbour i, or -1
  Vec3d p[3], y[3];        // f's corners; neighbour i's corner opposite the shared edge (when j[i] >= 0)

  CUDAHULL_HD void gather(const MeshView<Point>& m, u32 face) {
    f = face;
    for (int k = 0; k < 3; ++k) {
      v[k] = m.fv[3 * f + k];
      n[k] = m.fn[3 * f + k];
    }
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        gv[i][k] = m.fv[3 * n[i] + k];
        gn[i][k] = m.fn[3 * n[i] + k];
      }
    }
    for (int i = 0; i < 3; ++i) {
      j[i] = -1;
      for (int s = 0; s < 3; ++s) {
        if (gv[i][s] == v[(i + 1) % 3] && gv[i][(s + 1) % 3] == v[i]) j[i] = s;
      }
    }
    for (int k = 0; k < 3; ++k)
      p[k] = m.P(v[k]);
    for (int i = 0; i < 3; ++i) {
      if (j[i] >= 0) y[i] = m.P(gv[i][(j[i] + 2) % 3]);
    }
  }
  CUDAHULL_HD u32 apex(int i) const { return gv[i][(j[i] + 2) % 3]; }
};

// Records (the viewer, --trace): the candidates a round turned down, as FindCandidate meets them.  Only
// the recording driver's rounds log them (FindCandidate<Point, RejectionLog>); the fast paths' NoLog
// compiles the logging away.
enum RejectionKind : u32 {
  kRejectFoldover = 0,     // a flip whose new faces would not keep c strictly below (Fig. 5, seen from c)
  kRejectNotManifold = 1,  // a flip whose new edge is already an edge of the mesh
  kRejectRemoval = 2,      // a degree-3 concave vertex whose removal would fold over or not be a 2-manifold
};
struct Rejection {
  u32 kind, round, id;  // id: 6 f + slot, as Candidate::id
  u32 vertex[4];        // flip: u, v, x, y; removal: v, a, b, d
};
struct NoLog {
  CUDAHULL_HD void add(u32, u32, u32, u32, u32, u32) const {}
};
struct RejectionLog {
  Rejection* at = nullptr;
  u32* count = nullptr;
  u32 capacity = 0, round = 0;
  CUDAHULL_HD void add(u32 kind, u32 id, u32 a, u32 b, u32 c, u32 d) const {
    if (!at) return;
    const u32 k = atomic_add_u32(count, 1);
    if (k < capacity) at[k] = Rejection{kind, round, id, {a, b, c, d}};
  }
};

template <class Point, class Log = NoLog>
struct FindCandidate {
  MeshView<Point> m;
  Log log;

  // Edge i of f, owned by f when f is the lower of its two faces: a concave edge whose flip keeps both new
  // faces' cones proper.
  CUDAHULL_HD bool flip(const Around<Point>& a, int i, Candidate& out) const {
    const u32 f = a.f, g = a.n[i];
    const int j = a.j[i];
    if (g < f || j < 0) return false;
    const int iv = (i + 1) % 3, ix = (i + 2) % 3;
    const Vec3d &pu = a.p[i], &pv = a.p[iv], &px = a.p[ix], &py = a.y[i];
    if (orient3d(pu, pv, px, py) <= 0) return false;  // convex or flat
    if (orient3d(m.c, px, pu, py) <= 0 || orient3d(m.c, py, pv, px) <= 0) {
      log.add(kRejectFoldover, 6 * f + static_cast<u32>(i), a.v[i], a.v[iv], a.v[ix], a.apex(i));
      return false;
    }
    const u32 A = a.n[ix], D = a.n[iv], B = a.gn[i][(j + 1) % 3], C = a.gn[i][(j + 2) % 3];
    if (A == B || C == D || A == g || B == f || C == f || D == g) {  // not a 2-manifold
      log.add(kRejectNotManifold, 6 * f + static_cast<u32>(i), a.v[i], a.v[iv], a.v[ix], a.apex(i));
      return false;
    }
    out = Candidate{kFlip, 0, 2, {f, g, A, B, C, D}, {a.v[i], a.v[iv], a.v[ix], a.apex(i)}};
    return true;
  }

  // Corner k of f: a vertex v of degree 3 (faces f = (v, a, b), h = (v, d, a), t = (v, b, d)), owned by
  // the lowest of its faces, concave or flat, whose removal keeps the new face's cone proper.  h is
  // neighbour k and t neighbour k + 2; d is h's apex over the edge a -> v.
  CUDAHULL_HD bool flop(const Around<Point>& r, int k, Candidate& out) const {
    const int ka = (k + 1) % 3, kb = (k + 2) % 3;
    const u32 f = r.f, v = r.v[k], a = r.v[ka], b = r.v[kb], h = r.n[k], t = r.n[kb];
    if (h < f || t < f || r.j[k] < 0) return false;
    int hv = -1, tv = -1;
    for (int s = 0; s < 3; ++s) {
      if (r.gv[k][s] == v) hv = s;
      if (r.gv[kb][s] == v) tv = s;
    }
    if (hv < 0 || tv < 0) return false;
    const u32 d = r.gv[k][(hv + 1) % 3];
    if (r.gv[k][(hv + 2) % 3] != a || r.gv[kb][(tv + 1) % 3] != b || r.gv[kb][(tv + 2) % 3] != d)
      return false;
    if (r.gn[k][hv] != t || r.gn[kb][tv] != f) return false;  // degree above 3
    const Vec3d &pv = r.p[k], &pa = r.p[ka], &pb = r.p[kb], &pd = r.y[k];
    if (orient3d(pa, pb, pd, pv) > 0) return false;  // v is strictly extreme here
    const u32 ab = r.n[ka], da = r.gn[k][(hv + 1) % 3], bd = r.gn[kb][(tv + 1) % 3];
    if (orient3d(m.c, pa, pb, pd) <= 0 || ab == da || ab == bd || da == bd || ab == h || ab == t || da == f ||
        da == t || bd == f || bd == h) {
      log.add(kRejectRemoval, 6 * f + 3 + static_cast<u32>(k), v, a, b, d);
      return false;
    }
    out = Candidate{kFlop, 0, 3, {f, h, t, ab, bd, da}, {v, a, b, d}};
    return true;
  }

  // The first candidate of face f: its three edges, then its three corners.  slot receives 0..5.  (Two
  // loops of three, which unroll: one loop over the six slots, tried on the H100, made the rounds slower.)
  CUDAHULL_HD bool operator()(u32 f, Candidate& out, int& slot) const {
    Around<Point> around;
    around.gather(m, f);
    for (int i = 0; i < 3; ++i) {
      if (flip(around, i, out)) {
        slot = i;
        return true;
      }
    }
    for (int k = 0; k < 3; ++k) {
      if (flop(around, k, out)) {
        slot = 3 + k;
        return true;
      }
    }
    return false;
  }
};

// The faces round `round` looks at: live ones made in the previous round (id >= fresh_from), and those
// stamped for it (look[f] == round): the faces next to the previous round's new ones (the lower face of an
// edge owns it, and a flop belongs to the lowest of three faces), and those whose candidate lost a claim.
template <class Point>
struct MarkWork {
  MeshView<Point> m;
  const u32* look;
  u32 fresh_from, round;
  u32* work;
  CUDAHULL_HD bool is_work(u32 f) const {
    return m.killer[f] == kAlive && (f >= fresh_from || look[f] == round);
  }
  CUDAHULL_HD void operator()(std::size_t f) const { work[f] = is_work(static_cast<u32>(f)) ? 1u : 0u; }
};

// A work face's links to faces the previous round killed, pointed at the new faces that hold the edges
// (the entry of the edit that killed them names those).  Every face writes only its own links.
template <class Point>
struct FixLinks {
  MeshView<Point> m;
  const u32* work_list;
  CUDAHULL_HD void fix(u32 f) const {
    for (int k = 0; k < 3; ++k) {
      const u32 nb = m.fn[3 * f + k], e = m.killer[nb];
      if (e == kAlive) continue;
      const Entry& entry = m.entries[e];
      const u32 a = m.fv[3 * f + k], b = m.fv[3 * f + (k + 1) % 3];
      for (int o = 0; o < (entry.kind == kFlip ? 2 : 1); ++o) {
        if (m.edge_slot(entry.out[o], b, a) >= 0) m.fn[3 * f + k] = entry.out[o];
      }
    }
  }
  CUDAHULL_HD void operator()(std::size_t w) const { fix(work_list[w]); }
};

// Each work face finds its first candidate, keeps it, and claims the candidate's faces.
template <class Point, class Find = FindCandidate<Point>>
struct Claim {
  Find find;
  const u32* work_list;
  u32 round;
  u64* claim;
  u32* look;
  Candidate* cands;  // per work item
  CUDAHULL_HD void claim_for(u32 f, Candidate& cand) const {
    int slot = 0;
    if (!find(f, cand, slot)) {
      cand.kind = kNone;
      return;
    }
    take(f, cand, slot);
  }
  // Face f's first candidate, found at `slot`: kept, and its faces claimed.
  CUDAHULL_HD void take(u32 f, Candidate& cand, int slot) const {
    look[f] = round + 1;  // won (then killed) or lost (then tried again)
    cand.id = 6 * f + static_cast<u32>(slot);
    const u64 key = claim_key(round, cand.id);
    for (u32 k = 0; k < cand.claims; ++k)
      atomic_max_u64(&claim[cand.faces[k]], key);
  }
  CUDAHULL_HD void operator()(std::size_t w) const { claim_for(work_list[w], cands[w]); }
};

// Did the work item's candidate hold all its claims?
struct Won {
  u32 round;
  const u64* claim;
  const Candidate* cands;
  u32* won;
  CUDAHULL_HD bool holds(const Candidate& cand) const {
    if (cand.kind == kNone) return false;
    const u64 key = claim_key(round, cand.id);
    for (u32 k = 0; k < cand.claims; ++k) {
      if (claim[cand.faces[k]] != key) return false;
    }
    return true;
  }
  CUDAHULL_HD void operator()(std::size_t w) const { won[w] = holds(cands[w]) ? 1u : 0u; }
};

// The winners apply: two new face slots and one entry each, by the prefix sum of the wins; each rewrites
// only the faces it claimed and its new ones (and stamps the faces around).
template <class Point>
struct Apply {
  MeshView<Point> m;
  const Candidate* cands;
  const u32* won;
  const u32* rank;
  u32 first_face, first_entry;
  u32* look;
  u32 round;

  // An outer face: it links to a face killed here until FixLinks, in the next round, points it at the new
  // one (another winner may be killing it this round).  Every winner that touches it writes the same stamp.
  CUDAHULL_HD void touch(u32 face) const { look[face] = round + 1; }
  CUDAHULL_HD void set_face(u32 f, u32 a, u32 b, u32 d, u32 na, u32 nb, u32 nd) const {
    u32* fv = m.fv + 3 * f;
    u32* fn = m.fn + 3 * f;
    fv[0] = a, fv[1] = b, fv[2] = d;
    fn[0] = na, fn[1] = nb, fn[2] = nd;
    m.killer[f] = kAlive;
    look[f] = 0;
  }
  CUDAHULL_HD void operator()(std::size_t w) const {
    if (won[w]) apply(cands[w], rank[w]);
  }
  // A winning candidate, the r-th winner of its round.
  CUDAHULL_HD void apply(const Candidate& cand, u32 r) const {
    const u32 n1 = first_face + 2 * r, n2 = n1 + 1, e = first_entry + r;
    if (cand.kind == kFlip) {
      const u32 u = cand.vertex[0], v = cand.vertex[1], x = cand.vertex[2], y = cand.vertex[3];
      const u32 A = cand.faces[2], B = cand.faces[3], C = cand.faces[4], D = cand.faces[5];
      set_face(n1, x, u, y, A, B, n2);
      set_face(n2, y, v, x, C, D, n1);
      touch(A);
      touch(B);
      touch(C);
      touch(D);
      m.entries[e] = Entry{kFlip, x, y, {n1, n2, kNone}};
      m.killer[cand.faces[0]] = e;
      m.killer[cand.faces[1]] = e;
    } else {
      const u32 a = cand.vertex[1], b = cand.vertex[2], d = cand.vertex[3];
      const u32 ab = cand.faces[3], bd = cand.faces[4], da = cand.faces[5];
      set_face(n1, a, b, d, ab, bd, da);
      touch(ab);
      touch(bd);
      touch(da);
      m.killer[n2] = kDeadSlot;
      for (int k = 0; k < 3; ++k)
        m.fv[3 * n2 + k] = m.fn[3 * n2 + k] = kNone;
      look[n2] = 0;
      m.entries[e] = Entry{kFlop, kNone, kNone, {n1, kNone, kNone}};
      for (int k = 0; k < 3; ++k)
        m.killer[cand.faces[k]] = e;
    }
  }
};

// The state of a fused run of rounds (an executor that loops the rounds itself, CudaExec): what the host
// sets before and reads after.  The rounds stop when no candidate is left, or when a round's winners would
// not fit the capacities, before they apply (overflow: the round's work stamped back, the host grows the
// buffers and the round runs again, with the same claims and winners).
//   The state stays where the executor computes for the whole run, and the host reads it once an
//   iteration, after the compaction: the iteration's kernels take their counts from it (refined, faces,
//   entries), not from the host.  The counters (rounds, edits, work_items, phase_ns) add up over the run.
struct RoundsState {
  u32 faces, fresh_from, entries, round;    // faces and entries in use; faces from fresh_from are new
  u32 face_capacity, entry_capacity;        // set at each launch
  u32 rounds, edits, work_items, overflow;  // out
  u32 needed_faces, needed_entries;         // out, on overflow: what the next round needs
  u32 round_work, round_winners;            // scratch, zero
  u32 refined;                              // faces refined this iteration (SplitFaces)
  u32 live_faces, kept_points;              // the compaction's totals (MoveLive, MovePoints)
  // A device loop of whole iterations (CudaExec's small-mesh kernel): how many it finished, the faces they
  // refined, and why it stopped (LoopExit).
  u32 loop_iterations, loop_refined, loop_exit;
  u32 faults, vertices;  // the finish's counts: edges not strictly convex (CountFaults), hull vertices
  u32 defects;           // concave edges and thin vertices (CountConcave, CountThin)
  u64 phase_ns[4];       // out, device only: claim, judge, number, apply (profiling)
};

// Why a device loop of iterations stopped: every point is inside (done), an iteration refined no face
// (stall: the mesh is as it was), the next iteration might not fit (room: nothing of it done), or a round
// did not fit (overflow: mid-iteration, after the split; the host goes on with the rounds).
enum LoopExit : u32 { kLoopDone = 0, kLoopStall = 1, kLoopRoom = 2, kLoopOverflow = 3 };

// The buffers of a device loop of iterations: the current ones and the spares the compaction writes.
template <class Point>
struct LoopBuffers {
  MeshView<Point> m;  // fv, fn: the current faces
  u32 *fv_spare, *fn_spare;
  u32 *index, *face, *index_spare, *face_spare;  // the kept points and their faces
  u32 *keep, *point_rank, *flags, *face_rank, *look, *list;
  u32 *win_mask, *block_offset;  // the executor's
  u64 *extreme, *claim;
  Candidate* cands;
  RoundsState* st;
  u32 first;              // begin with the first distribution (AssignFirst) of ...
  const u32* first_list;  // ... these points (null: all), into the spares, then compacted into index, face
};

// What the host gives a fused run of rounds: `begin` (the iteration's first: faces = fresh_from + 3 refined,
// entries = refined, from the state) or not (it goes on after an overflow), and the room there is.
struct RoundsLaunch {
  u32 begin, fresh_from, face_capacity, entry_capacity;
};

// A fused run of rounds starts (one thread): the iteration's counts from the refinement's, or those the last
// run stopped at; the room there is; no overflow, and no work listed yet (a run that overflowed left its
// count).
CUDAHULL_HD inline void start_rounds(RoundsState* st, const RoundsLaunch& launch) {
  if (launch.begin) {
    st->fresh_from = launch.fresh_from;
    st->faces = launch.fresh_from + 3 * st->refined;
    st->entries = st->refined;
  }
  st->face_capacity = launch.face_capacity;
  st->entry_capacity = launch.entry_capacity;
  st->overflow = 0;
  st->round_work = 0;
}

// The first mesh (P's faces or the tetrahedron's), written where the executor computes from the
// operation's own copy (a kernel parameter on the device: no upload and no wait), with the state zeroed.
inline constexpr int kMaxFirstFaces = kMaxDropPlanes;

// The finish of a mesh of at most this many faces runs in one launch (the GPU's finish_small_kernel, one
// block) and one read; FusedHostExec mirrors it for the CPU tests.
inline constexpr std::size_t kSmallFinishFaces = 2048;
struct FirstMesh {
  u32 faces;
  u32 fv[3 * kMaxFirstFaces], fn[3 * kMaxFirstFaces];
  u32 *fv_out, *fn_out, *killer, *look;
  u64* extreme;
  RoundsState* st;
  CUDAHULL_HD void operator()(std::size_t i) const {
    fv_out[i] = fv[i];
    fn_out[i] = fn[i];
    if (i < faces) {  // live, unstamped, no furthest point yet (as ResetFaces leaves a compacted face)
      killer[i] = kAlive;
      look[i] = 0;
      extreme[i] = 0;
    }
    if (i == 0) *st = RoundsState{};
  }
};

// ---------------------------------------------------------------------------------------------------------
// Compaction between iterations, and the final exact check.

// Run over a bound of the face ids in use; `count` (optional, where the executor computes) is the number.
template <class Point>
struct MarkLive {
  MeshView<Point> m;
  u32* live;
  const u32* count;
  CUDAHULL_HD void operator()(std::size_t f) const {
    live[f] = (!count || f < *count) && m.killer[f] == kAlive ? 1u : 0u;
  }
};

// Live face f moves to rank[f] in (fv_out, fn_out), its links renumbered.
template <class Point>
struct MoveLive {
  MeshView<Point> m;
  const u32* live;
  const u32* rank;
  u32* fv_out;
  u32* fn_out;
  std::size_t last;  // the last face id it runs over: that thread writes the number of live faces
  u32* total;
  CUDAHULL_HD void operator()(std::size_t fi) const {
    if (fi == last) *total = rank[fi] + live[fi];
    if (!live[fi]) return;
    const u32 to = rank[fi];
    for (int k = 0; k < 3; ++k) {
      fv_out[3 * to + k] = m.fv[3 * fi + k];
      fn_out[3 * to + k] = rank[m.fn[3 * fi + k]];
    }
  }
};

// The mark of a mark_scan_move whose flags are already written (the kept points: RoutePoints, AssignFirst).
struct AlreadyMarked {
  CUDAHULL_HD void operator()(std::size_t) const {}
};

// Kept point j moves to rank[j], its face renumbered.
struct MovePoints {
  const u32* keep;
  const u32* rank;
  const u32* face_rank;
  const u32* index_in;
  const u32* face_in;
  u32* index_out;
  u32* face_out;
  std::size_t last;  // the last point it runs over: that thread writes the number of kept points
  u32* total;
  CUDAHULL_HD void operator()(std::size_t j) const {
    if (j == last) *total = rank[j] + keep[j];
    if (!keep[j]) return;
    index_out[rank[j]] = index_in[j];
    face_out[rank[j]] = face_rank[face_in[j]];
  }
};

// Between iterations: the compacted faces live, unstamped, with no furthest point yet.
struct ResetFaces {
  u32* killer;
  u32* look;
  u64* extreme;
  CUDAHULL_HD void operator()(std::size_t f) const {
    killer[f] = kAlive;
    look[f] = 0;
    extreme[f] = 0;
  }
};

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

// ---------------------------------------------------------------------------------------------------------
// The local repair of the faults the rounds leave (fault_repair.hpp plans it on the host).

// A face as read back for the repair, or as written by it: id, corners, links, and its ring (1: it holds
// a fault; r: r - 1 faces from one).  A written face with corners kNone is a dead slot.
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

// The plan's rows written into the mesh: a live face, or a dead slot.
struct WriteRows {
  const FaceRow* rows;
  u32* fv;
  u32* fn;
  u32* killer;
  CUDAHULL_HD void operator()(std::size_t k) const {
    const FaceRow& row = rows[k];
    for (int i = 0; i < 3; ++i) {
      fv[3 * row.id + i] = row.v[i];
      fn[3 * row.id + i] = row.n[i];
    }
    killer[row.id] = row.v[0] == kNone ? kDeadSlot : kAlive;
  }
};

}  // namespace cudahull::resident
