// The resident engine's mesh as its per-element operations see it: flat arrays of corners and links, the
// decision entries (Fig. 7), the atomics both executors share, and the exact tests on a face.  The operations
// of each phase are in their own file (refinement.hpp, swaps.hpp, distribution.hpp, compaction.hpp,
// finish.hpp; the first mesh in first_mesh.hpp), compiled for the host (HostExec, loops) and the device
// (CudaExec, one thread each); resident_driver.hpp runs them in order, and the executor decides where.
//
// design:
//   The mesh is star-shaped from the interior point c: every face (a, b, d) has orient3d(c, a, b, d) > 0,
//   so the radial cones from c over the faces tile space.  Each external point belongs to the face whose
//   closed cone holds it; a point below (or on) its face is inside the tetrahedron (c, a, b, d), so inside
//   the hull, and is dropped.  Every edit keeps the cones a tiling, and appends a decision entry (Fig. 7)
//   that says, by one or two exact orient3d with c, which new face a point of a killed face belongs to:
//     refine (Fig. 3a)  face (a, b, d) at its furthest point p, strictly inside the cone: children
//                       (a, b, p), (b, d, p), (d, a, p), each written with its own links (gathers)
//     swap (Fig. 3b)    concave edge u - v of f = (u, v, x), g = (v, u, y) into x - y: n1 = (x, u, y),
//                       n2 = (y, v, x); only when both new faces keep c strictly below (the foldover test
//                       of Fig. 5, seen from c)
//     removal (Fig. 4)  a vertex v of degree 3 that is concave or flat: its three faces become (a, b, d)
//   Swaps and removals run in conflict-free rounds: each candidate claims the faces it kills (two for a
//   swap, three for a removal) with a 64-bit atomicMax of (round, ~candidate id); the holders of all their
//   claims apply at once, numbered by a prefix sum, so the result is the same on any executor and thread
//   count.  A winner writes only its new faces and the killed faces' entries, and stamps the faces around it
//   for the next round (every winner that touches one writes the same stamp); those faces keep
//   links to killed faces until the next round's FixLinks gathers the new ones from the entries (as the
//   refinement's gathers do).  Disjoint swaps cannot make the same edge: in the radial view each new edge
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

inline constexpr u32 kAlive = 0xffffffffu;     // replaced_by[] of a live face
inline constexpr u32 kDeadSlot = 0xfffffffeu;  // replaced_by[] of a face slot a removal left unused
inline constexpr u32 kNone = 0xffffffffu;

enum EntryKind : u32 { kRefine = 0, kSwap = 1, kRemoval = 2 };

// A decision entry (Fig. 7).  refine: p = apex, out = children; swap: p = x, q = y, out = n1, n2;
// removal: out[0] = the new face.
struct Entry {
  u32 kind, p, q;
  u32 out[3];
};

// ---------------------------------------------------------------------------------------------------------
// Atomics: the device's, or plain operations for the host's sequential loops (the same final values).

template <class T>
CUDAHULL_HD inline void swap_pointers(T*& a, T*& b) {
  T* t = a;
  a = b;
  b = t;
}

CUDAHULL_HD inline void atomic_max_u64(u64* at, u64 value) {
#if defined(__CUDA_ARCH__)
  atomicMax(reinterpret_cast<unsigned long long*>(at), static_cast<unsigned long long>(value));
#else
  if (value > *at) *at = value;
#endif
}

CUDAHULL_HD inline void atomic_min_u32(u32* at, u32 value) {
#if defined(__CUDA_ARCH__)
  atomicMin(at, value);
#else
  if (value < *at) *at = value;
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

CUDAHULL_HD inline void atomic_or_u32(u32* at, u32 bits) {
#if defined(__CUDA_ARCH__)
  atomicOr(at, bits);
#else
  *at |= bits;
#endif
}

CUDAHULL_HD inline u32 popcount_u32(u32 bits) {
#if defined(__CUDA_ARCH__)
  return static_cast<u32>(__popc(bits));
#else
  return static_cast<u32>(__builtin_popcount(bits));
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
  u32* replaced_by;  // kAlive, kDeadSlot, or the entry that killed the face this iteration
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

}  // namespace cudahull::resident
