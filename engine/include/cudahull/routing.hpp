// The O(faces) tables the host sends the backend each iteration (section 4, Fig. 7), and the per-point
// classification both backends run on them.  Plain structs and CUDAHULL_HD functions only: the CUDA backend
// compiles this same header, so the CPU and GPU route every point identically.
//
// Route codes: a code >= 0 is a face id of the new (compacted) mesh; a code < 0 names decision entry
// (-code - 1).  A point of old face f follows refinement[f] (three separating planes, if f was refined) and
// then decision entries (one separating plane each, for swaps; none for removals) until it reaches a face.
#pragma once

#include <cstdint>

#include "cudahull/host_device.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

// A separating plane n.x + d (section 3: through an edge, containing the average normal of its two faces).
// The positive side is "above".  Planes only route points among cells, so they need not be exact.
// Stored in double: an offset of float coordinates near 1e38 would overflow a float.
struct SeparatingPlane {
  double nx = 0, ny = 0, nz = 0, d = 0;
};

// Each face's cell (section 3): its plane and its three separating planes (through edge i, containing the
// average of the unit normals of the two faces of the edge), positive inside the cell.
struct FaceCell {
  SeparatingPlane face_plane;  // unit normal, positive outside
  SeparatingPlane edge_plane[3];
};

inline constexpr std::int32_t kRouteInternal = -0x7fffffff;  // point proven inside the hull

// One refined face (Fig. 3a): its apex and three children.  Only refined faces have an entry; every old
// face has a slot in `old_face_split` (the entry's index, or -1) and `old_face_route` (unrefined faces:
// where its points go), so the per-face traffic is 8 bytes plus 116 per refined face.
struct RefinementEntry {
  std::uint32_t face = 0;  // the old face
  PointIndex apex = 0xffffffffu;
  std::int32_t child[3] = {0, 0, 0};  // route codes of (a, b, p), (b, c, p), (c, a, p)
  // plane[i] passes through the apex and vertex i of the old face; its positive side is child i's side.
  SeparatingPlane plane[3];
};

enum DecisionKind : std::uint8_t { kDecisionSwap = 0, kDecisionRemoval = 1 };

struct DecisionEntry {
  SeparatingPlane plane;   // swap: the separating plane of the new edge; removal: unused
  std::int32_t above = 0;  // route code on the plane's positive side (or always, for removals)
  std::int32_t below = 0;  // route code on the other side
  std::uint8_t kind = kDecisionSwap;
};

// A face of the new mesh as the backend sees it: its corners (exact tests) and neighbours (stray walks).
// `Point` is Point3 (float) or Point3d (double): every function below is generic in it, and exact for the
// coordinates as given in either precision.
template <class Point>
struct BasicFaceGeometry {
  Point v[3];
  std::int32_t neighbor[3];  // across v[i] -> v[i+1]
  std::int8_t tet[4];        // see face_tetrahedron_signs()
};
using FaceGeometry = BasicFaceGeometry<Point3>;

// Evaluated in double with explicit rounding so host and device agree bit for bit.
template <class Point>
CUDAHULL_HD inline double plane_value(const SeparatingPlane& p, const Point& x) {
#if defined(__CUDA_ARCH__)
  return __dadd_rn(__dadd_rn(__dadd_rn(__dmul_rn(p.nx, x.x), __dmul_rn(p.ny, x.y)), __dmul_rn(p.nz, x.z)),
                   p.d);
#else
  return ((p.nx * x.x + p.ny * x.y) + p.nz * x.z) + p.d;  // -ffp-contract=off keeps this unfused
#endif
}

// Algorithm 2, lines "refinement" and "decision": the route code of the face that receives point x, which
// belonged to old face `old_face`.
template <class Point>
CUDAHULL_HD inline std::int32_t route_point(const Point& x, std::int32_t old_face,
                                            const std::int32_t* old_face_split,
                                            const std::int32_t* old_face_route,
                                            const RefinementEntry* refinement,
                                            const DecisionEntry* decision) {
  const std::int32_t split = old_face_split[old_face];
  std::int32_t code;
  if (split < 0) {
    code = old_face_route[old_face];
  } else {
    const RefinementEntry& r = refinement[split];
    // Child i lies on the positive side of plane[i] and the negative side of plane[i+1].  Exactly one child
    // matches unless the point is "behind" the apex (all signs equal); then child 0 is as good as any: such
    // points are far from this face, and the exact verdict that follows sends them where they belong.
    const bool s0 = plane_value(r.plane[0], x) >= 0, s1 = plane_value(r.plane[1], x) >= 0,
               s2 = plane_value(r.plane[2], x) >= 0;
    if (s0 && !s1) {
      code = r.child[0];
    } else if (s1 && !s2) {
      code = r.child[1];
    } else if (s2 && !s0) {
      code = r.child[2];
    } else {
      code = r.child[0];
    }
  }
  while (code < 0 && code != kRouteInternal) {
    const DecisionEntry& e = decision[-code - 1];
    if (e.kind == kDecisionRemoval) {
      code = e.above;
    } else {
      code = plane_value(e.plane, x) >= 0 ? e.above : e.below;
    }
  }
  return code;
}

enum PointVerdict : int { kVerdictInternal = 0, kVerdictExternal = 1, kVerdictStray = 2 };

// Signs the exact tetrahedron test needs per face, computed once per iteration on the host by
// face_tetrahedron_signs(): tet[0..2] = orientation of the opposite corner for the radial planes
// (c, a, b), (c, b, d), (c, d, a); tet[3] = orient3d(a, b, d, c), which is -1 when the interior point c is
// below the face, as it is wherever the mesh is convex.
template <class Point>
CUDAHULL_HD inline void face_tetrahedron_signs(const Vec3d& c, const Point v[3], std::int8_t tet[4]) {
  const Vec3d a = to_vec3d(v[0]), b = to_vec3d(v[1]), d = to_vec3d(v[2]);
  tet[0] = static_cast<std::int8_t>(orient3d(c, a, b, d));
  tet[1] = static_cast<std::int8_t>(orient3d(c, b, d, a));
  tet[2] = static_cast<std::int8_t>(orient3d(c, d, a, b));
  tet[3] = static_cast<std::int8_t>(orient3d(a, b, d, c));
}

// The exact verdict for point x in face f: external (strictly above f), internal (in the closed
// tetrahedron of f and the interior point c), or stray (neither).  Every such tetrahedron lies in the
// convex hull of the input (c is inside the first tetrahedron, the corners are input points), so discarding
// a point inside one is always safe, whatever shape the mesh has mid-iteration.  For a stray point,
// *exit_edge names the radial plane it is beyond (the neighbour to walk to), or -1.
template <class Point>
CUDAHULL_HD inline PointVerdict face_verdict(const BasicFaceGeometry<Point>& f, const Vec3d& c,
                                             const Point& x, int* exit_edge) {
  const Vec3d a = to_vec3d(f.v[0]), b = to_vec3d(f.v[1]), d = to_vec3d(f.v[2]), p = to_vec3d(x);
  *exit_edge = -1;
  const int above = orient3d(a, b, d, p);
  if (above > 0) return kVerdictExternal;
  if (f.tet[0] == 0 || f.tet[1] == 0 || f.tet[2] == 0 || f.tet[3] == 0) return kVerdictStray;  // flat
  if (above * f.tet[3] < 0) return kVerdictStray;  // c is above this (concave) face, x strictly below it
  if (orient3d(c, a, b, p) * f.tet[0] < 0) {
    *exit_edge = 0;
    return kVerdictStray;
  }
  if (orient3d(c, b, d, p) * f.tet[1] < 0) {
    *exit_edge = 1;
    return kVerdictStray;
  }
  if (orient3d(c, d, a, p) * f.tet[2] < 0) {
    *exit_edge = 2;
    return kVerdictStray;
  }
  return kVerdictInternal;
}

// Ranking distance for the extreme-point search (getExtremePoints): proportional to the distance above face
// f.  Not exact; only its order matters, and both backends compute it identically.
template <class Point>
CUDAHULL_HD inline double face_height(const BasicFaceGeometry<Point>& f, const Point& x) {
#if defined(__CUDA_ARCH__)
  const double ux = __dsub_rn(f.v[1].x, f.v[0].x), uy = __dsub_rn(f.v[1].y, f.v[0].y),
               uz = __dsub_rn(f.v[1].z, f.v[0].z);
  const double vx = __dsub_rn(f.v[2].x, f.v[0].x), vy = __dsub_rn(f.v[2].y, f.v[0].y),
               vz = __dsub_rn(f.v[2].z, f.v[0].z);
  const double wx = __dsub_rn(x.x, f.v[0].x), wy = __dsub_rn(x.y, f.v[0].y), wz = __dsub_rn(x.z, f.v[0].z);
  const double nx = __dsub_rn(__dmul_rn(uy, vz), __dmul_rn(uz, vy));
  const double ny = __dsub_rn(__dmul_rn(uz, vx), __dmul_rn(ux, vz));
  const double nz = __dsub_rn(__dmul_rn(ux, vy), __dmul_rn(uy, vx));
  return __dadd_rn(__dadd_rn(__dmul_rn(nx, wx), __dmul_rn(ny, wy)), __dmul_rn(nz, wz));
#else
  const double ux = double(f.v[1].x) - f.v[0].x, uy = double(f.v[1].y) - f.v[0].y,
               uz = double(f.v[1].z) - f.v[0].z;
  const double vx = double(f.v[2].x) - f.v[0].x, vy = double(f.v[2].y) - f.v[0].y,
               vz = double(f.v[2].z) - f.v[0].z;
  const double wx = double(x.x) - f.v[0].x, wy = double(x.y) - f.v[0].y, wz = double(x.z) - f.v[0].z;
  const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  return nx * wx + ny * wy + nz * wz;
#endif
}

// A face's four planes prepared once for all the points of an iteration (the CUDA backend's distribution
// pass; docs/benchmarks.md): the normal of the face as face_height() computes it, and the normals of its
// three radial planes through the interior point c, each with per-axis permanents that bound the rounding
// error of normal . (x - base).  face_verdict_prepared() then needs no orient3d unless a point lies within
// that bound of a plane, and gives exactly face_verdict()'s answer.
struct FacePlanes {
  double normal[3], normal_perm[3];        // (v1 - v0) x (v2 - v0), base v0
  double radial[3][3], radial_perm[3][3];  // radial plane k: (v[k] - c) x (v[k+1] - c), base c
};

namespace detail {
// (a - base) x (b - base), rounded as face_height() rounds it, and its permanents |.y||.z| + |.z||.y|, ...
CUDAHULL_HD inline void prepared_cross(double ax, double ay, double az, double bx, double by, double bz,
                                       double out[3], double perm[3]) {
  out[0] = sub_rn(mul_rn(ay, bz), mul_rn(az, by));
  out[1] = sub_rn(mul_rn(az, bx), mul_rn(ax, bz));
  out[2] = sub_rn(mul_rn(ax, by), mul_rn(ay, bx));
  perm[0] = add_rn(mul_rn(abs_d(ay), abs_d(bz)), mul_rn(abs_d(az), abs_d(by)));
  perm[1] = add_rn(mul_rn(abs_d(az), abs_d(bx)), mul_rn(abs_d(ax), abs_d(bz)));
  perm[2] = add_rn(mul_rn(abs_d(ax), abs_d(by)), mul_rn(abs_d(ay), abs_d(bx)));
}
// n . w, rounded as face_height() rounds it.
CUDAHULL_HD inline double prepared_dot(const double n[3], double wx, double wy, double wz) {
  return add_rn(add_rn(mul_rn(n[0], wx), mul_rn(n[1], wy)), mul_rn(n[2], wz));
}
// The sign of the exact n . w when the rounded `value` is certain of it, else 0.  Each of the six terms of
// the exact determinant passes through at most 8 roundings (two differences, a product and a difference
// for n, the difference w, a product and two sums), so |value - exact| <= gamma_8 * sum|terms|, and
// perm . |w| bounds sum|terms| up to a few more roundings: 16 u (2^-49) covers it all with room to spare.
// No underflow or overflow is possible for float32 coordinates (predicates_impl.hpp).
CUDAHULL_HD inline int certain_sign(double value, const double perm[3], double wx, double wy, double wz) {
  const double bound = mul_rn(0x1p-49, prepared_dot(perm, abs_d(wx), abs_d(wy), abs_d(wz)));
  return value > bound ? 1 : (value < -bound ? -1 : 0);
}
}  // namespace detail

template <class Point>
CUDAHULL_HD inline void prepare_face_planes(const BasicFaceGeometry<Point>& f, const Vec3d& c,
                                            FacePlanes& out) {
  using namespace detail;
  const Point* v = f.v;
  detail::prepared_cross(sub_rn(v[1].x, v[0].x), sub_rn(v[1].y, v[0].y), sub_rn(v[1].z, v[0].z),
                         sub_rn(v[2].x, v[0].x), sub_rn(v[2].y, v[0].y), sub_rn(v[2].z, v[0].z), out.normal,
                         out.normal_perm);
  for (int k = 0; k < 3; ++k) {
    const Point& a = v[k];
    const Point& b = v[(k + 1) % 3];
    detail::prepared_cross(sub_rn(a.x, c.x), sub_rn(a.y, c.y), sub_rn(a.z, c.z), sub_rn(b.x, c.x),
                           sub_rn(b.y, c.y), sub_rn(b.z, c.z), out.radial[k], out.radial_perm[k]);
  }
}

// face_verdict() through the prepared planes: the same verdict and exit edge (exact orient3d decides
// whenever the rounded value is not certain), plus *height = face_height(f, x), bit for bit.
template <class Point>
CUDAHULL_HD inline PointVerdict face_verdict_prepared(const BasicFaceGeometry<Point>& f,
                                                      const FacePlanes& planes, const Vec3d& c,
                                                      const Point& x, int* exit_edge, double* height) {
  using namespace detail;
  *exit_edge = -1;
  const double wx = sub_rn(x.x, f.v[0].x), wy = sub_rn(x.y, f.v[0].y), wz = sub_rn(x.z, f.v[0].z);
  *height = prepared_dot(planes.normal, wx, wy, wz);
  int above = certain_sign(*height, planes.normal_perm, wx, wy, wz);
  if (above == 0) above = orient3d(to_vec3d(f.v[0]), to_vec3d(f.v[1]), to_vec3d(f.v[2]), to_vec3d(x));
  if (above > 0) return kVerdictExternal;
  if (f.tet[0] == 0 || f.tet[1] == 0 || f.tet[2] == 0 || f.tet[3] == 0) return kVerdictStray;  // flat
  if (above * f.tet[3] < 0) return kVerdictStray;
  const double cx = sub_rn(x.x, c.x), cy = sub_rn(x.y, c.y), cz = sub_rn(x.z, c.z);
  for (int k = 0; k < 3; ++k) {
    int side = certain_sign(prepared_dot(planes.radial[k], cx, cy, cz), planes.radial_perm[k], cx, cy, cz);
    if (side == 0) side = orient3d(c, to_vec3d(f.v[k]), to_vec3d(f.v[(k + 1) % 3]), to_vec3d(x));
    if (side * f.tet[k] < 0) {
      *exit_edge = k;
      return kVerdictStray;
    }
  }
  return kVerdictInternal;
}

// Packs (height, point index) so that a 64-bit max picks the highest point and, among equal heights, the
// lowest index: duplicates then always elect their lowest-index copy.  Heights are > 0 here.  The key is
// the height as a float for float points, and the upper half of the double for double points (positive
// doubles order as their bits; a float would overflow above 3e38, and double coordinates reach 2^250, so
// heights reach 2^750).  Any external point is a correct apex; the key only picks a good one.
template <class Point>
CUDAHULL_HD inline std::uint64_t pack_extreme(double height, PointIndex index) {
  std::uint32_t bits;
  if constexpr (sizeof(Point::x) == sizeof(float)) {
    const float h = height > 0 ? static_cast<float>(height) : 0.0f;  // keep the sign bit clear
#if defined(__CUDA_ARCH__)
    bits = __float_as_uint(h);
#else
    __builtin_memcpy(&bits, &h, sizeof bits);
#endif
  } else {
    const double h = height > 0 ? height : 0.0;
    std::uint64_t all;
#if defined(__CUDA_ARCH__)
    all = static_cast<std::uint64_t>(__double_as_longlong(h));
#else
    __builtin_memcpy(&all, &h, sizeof all);
#endif
    bits = static_cast<std::uint32_t>(all >> 32);
  }
  return (static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint64_t>(0xffffffffu - index);
}
CUDAHULL_HD inline PointIndex unpack_extreme_index(std::uint64_t packed) {
  return 0xffffffffu - static_cast<PointIndex>(packed & 0xffffffffu);
}

// Views of the per-iteration tables, as both backends hold them (host vectors or device buffers).
template <class Point>
struct BasicRoutingView {
  const std::int32_t* old_face_split = nullptr;  // per old face: refinement index or -1
  const std::int32_t* old_face_route = nullptr;  // per old face: route code when not refined
  const RefinementEntry* refinement = nullptr;
  const DecisionEntry* decision = nullptr;
  const BasicFaceGeometry<Point>* faces = nullptr;  // the new mesh
  std::int32_t face_count = 0;
  const SeparatingPlane* initial_cells = nullptr;  // first distribution only: 3 planes per tetrahedron face
  Vec3d interior;                                  // the interior reference point c
};
using RoutingView = BasicRoutingView<Point3>;

inline constexpr int kMaxStrayWalk = 64;

// From face `start`, the face x is strictly above, or kRouteInternal when x is proven inside the hull.  A
// point below a face but outside that face's tetrahedron with c crossed a radial plane: walk to the
// neighbour across it, at most `max_walk` steps, then fall back to an exhaustive exact scan.
// `verdict(g, &exit_edge)` is face_verdict() for face g, or an equivalent (face_verdict_prepared()).
template <class Point, class Verdict>
CUDAHULL_HD inline std::int32_t walk_to_face(const Point& x, std::int32_t start,
                                             const BasicFaceGeometry<Point>* faces, std::int32_t face_count,
                                             int max_walk, Verdict&& verdict) {
  std::int32_t g = start;
  for (int step = 0; step < max_walk; ++step) {
    int exit_edge;
    const PointVerdict v = verdict(g, &exit_edge);
    if (v == kVerdictExternal) return g;
    if (v == kVerdictInternal) return kRouteInternal;
    if (exit_edge < 0) break;
    g = faces[g].neighbor[exit_edge];
  }
  // Exhaustive: above some face, or below every face plane of the closed mesh and hence inside it (and so
  // inside the hull of the input).
  for (std::int32_t f = 0; f < face_count; ++f) {
    const BasicFaceGeometry<Point>& face = faces[f];
    if (orient3d(to_vec3d(face.v[0]), to_vec3d(face.v[1]), to_vec3d(face.v[2]), to_vec3d(x)) > 0) return f;
  }
  return kRouteInternal;
}

template <class Point>
CUDAHULL_HD inline std::int32_t locate_point(const Point& x, std::int32_t start,
                                             const BasicFaceGeometry<Point>* faces, std::int32_t face_count,
                                             const Vec3d& interior, int max_walk) {
  return walk_to_face(x, start, faces, face_count, max_walk, [&](std::int32_t g, int* exit_edge) {
    return face_verdict(faces[g], interior, x, exit_edge);
  });
}

// Algorithm 2's routing of x from old face `old_face` by the separating planes (no exact test yet): the
// face of the new mesh to start the exact verdicts from, or kRouteInternal.
template <class Point>
CUDAHULL_HD inline std::int32_t routed_face(const Point& x, std::int32_t old_face,
                                            const BasicRoutingView<Point>& t) {
  if (t.initial_cells == nullptr)
    return route_point(x, old_face, t.old_face_split, t.old_face_route, t.refinement, t.decision);
  for (std::int32_t f = 0; f < 4; ++f) {  // section 3.1: the first tetrahedron face whose cell holds x
    const SeparatingPlane* cell = t.initial_cells + 3 * f;
    if (plane_value(cell[0], x) >= 0 && plane_value(cell[1], x) >= 0 && plane_value(cell[2], x) >= 0)
      return f;
  }
  return 0;
}

// Algorithm 2 for one point: the new face id that x belongs to (x strictly above it), or kRouteInternal when
// x is proven inside the hull.  Deterministic and exact in its verdict; only the choice of face among those
// x is above depends on the (inexact) separating planes.
template <class Point>
CUDAHULL_HD inline std::int32_t classify_point(const Point& x, std::int32_t old_face,
                                               const BasicRoutingView<Point>& t) {
  const std::int32_t g = routed_face(x, old_face, t);
  if (g == kRouteInternal) return kRouteInternal;
  return locate_point(x, g, t.faces, t.face_count, t.interior, kMaxStrayWalk);
}

// classify_point() with each face's planes prepared (`planes[f]` for t.faces[f]): the same face, and
// *height = face_height() of x above it (for the extreme-point key) when x is external.
template <class Point>
CUDAHULL_HD inline std::int32_t classify_point_prepared(const Point& x, std::int32_t old_face,
                                                        const BasicRoutingView<Point>& t,
                                                        const FacePlanes* planes, double* height) {
  const std::int32_t g = routed_face(x, old_face, t);
  if (g == kRouteInternal) return kRouteInternal;
  std::int32_t last = kRouteInternal;  // the face of the last verdict, whose height *height holds
  const std::int32_t found =
      walk_to_face(x, g, t.faces, t.face_count, kMaxStrayWalk, [&](std::int32_t f, int* exit_edge) {
        last = f;
        return face_verdict_prepared(t.faces[f], planes[f], t.interior, x, exit_edge, height);
      });
  if (found != kRouteInternal && found != last)
    *height = face_height(t.faces[found], x);  // found by the scan
  return found;
}

}  // namespace cudahull
