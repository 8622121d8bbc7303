// The resident engine's first mesh: P, the drop filter, and the first distribution (section 3.1).
//
// design:
//   P                  one pass over the points: the extremes along 14 directions (the axes and the
//                      diagonals, both ways); P is their exact hull (host, exact_hull)
//   drop filter        P's face planes in double with a proven error bound: a point proven strictly inside
//                      P is inside the hull, and dropped before any exact test (DropFilter, NotInsideP)
//   first mesh         P itself, with its centre as c, where the centre is exactly strictly below every
//                      face (its cones then tile space, and the star shape holds from the start); else
//                      section 3.1's tetrahedron, found by the executor's reductions and confirmed
//                      exactly (TetrahedronQueries, phases::find_initial_tetrahedron)
//   first distribution each listed point to the first face whose closed cone holds it, kept when above
//                      (AssignFirst); the first mesh written where the executor computes (FirstMesh)
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/resident/swaps.hpp"
#include "cudahull/types.hpp"

namespace cudahull::resident {

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

// The first mesh (P's faces or the tetrahedron's), written where the executor computes from the
// operation's own copy (a kernel parameter on the device: no upload and no wait), with the state zeroed.
inline constexpr int kMaxFirstFaces = kMaxDropPlanes;
struct FirstMesh {
  u32 faces;
  u32 fv[3 * kMaxFirstFaces], fn[3 * kMaxFirstFaces];
  u32 *fv_out, *fn_out, *replaced_by, *revisit;
  u64* extreme;
  RoundsState* st;
  CUDAHULL_HD void operator()(std::size_t i) const {
    fv_out[i] = fv[i];
    fn_out[i] = fn[i];
    if (i < faces) {  // live, unstamped, no furthest point yet (as ResetFaces leaves a compacted face)
      replaced_by[i] = kAlive;
      revisit[i] = 0;
      extreme[i] = 0;
    }
    if (i == 0) *st = RoundsState{};
  }
};

CUDAHULL_HD inline u64 ordered_bits(double v) {
#if defined(__CUDA_ARCH__)
  u64 bits = static_cast<u64>(__double_as_longlong(v));
#else
  u64 bits;
  std::memcpy(&bits, &v, sizeof bits);
#endif
  return (bits >> 63) ? ~bits : (bits | (u64{1} << 63));
}

// Section 3.1's rankings, one value per point (larger is better): -x, x, the squared distance from a
// line, the distance from a plane.
template <class Point>
struct TetrahedronValue {
  const Point* points;
  int what;  // 0: -x, 1: x, 2: from line (a, b), 3: from plane (a, b, d)
  Vec3d a, b, d;
  CUDAHULL_HD double operator()(std::size_t i) const {
    const Vec3d p = to_vec3d(points[i]);
    switch (what) {
      case 0:
        return -p.x;
      case 1:
        return p.x;
      case 2: {
        const Vec3d u{b.x - a.x, b.y - a.y, b.z - a.z}, w{p.x - a.x, p.y - a.y, p.z - a.z};
        const Vec3d n{u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x};
        return n.x * n.x + n.y * n.y + n.z * n.z;
      }
      default: {
        const double h = orient3d_fast(a, b, d, p);
        return h < 0 ? -h : h;
      }
    }
  }
};
template <class Point>
struct BestValueKey {
  TetrahedronValue<Point> value;
  CUDAHULL_HD u64 operator()(std::size_t i) const { return ordered_bits(value(i)); }
};
template <class Point>
struct RankedValue {
  TetrahedronValue<Point> value;
  CUDAHULL_HD u64 operator()(std::size_t i) const { return rank_key(value(i), static_cast<u32>(i)); }
};
template <class Point>
struct LowestIndexWith {
  TetrahedronValue<Point> value;
  u64 best;
  CUDAHULL_HD u64 operator()(std::size_t i) const {
    return ordered_bits(value(i)) == best ? static_cast<u64>(~static_cast<u32>(i)) : 0;
  }
};

// The Backend queries of section 3.1 on the executor, so that phases::find_initial_tetrahedron (which
// confirms every answer exactly) serves both engines.  Nothing else of the Backend is used.
template <class Point, class Exec>
class TetrahedronQueries final : public BasicBackend<Point> {
 public:
  TetrahedronQueries(Exec& exec, const std::vector<Point>& host_points, const Point* points)
      : exec_(exec), host_(host_points), points_(points), n_(host_points.size()) {}
  std::string name() const override { return "resident"; }
  void upload_points(const std::vector<Point>&) override {}
  void restart() override {}
  std::array<PointIndex, 2> extremes_x() override { return {best(0, {}, {}, {}), best(1, {}, {}, {})}; }
  PointIndex furthest_from_line(PointIndex a, PointIndex b) override { return best(2, at(a), at(b), {}); }
  PointIndex furthest_from_plane(PointIndex a, PointIndex b, PointIndex c) override {
    return best(3, at(a), at(b), at(c));
  }
  void distribute_points(const typename BasicBackend<Point>::Tables&) override { unused(); }
  std::size_t compact_index_array() override { unused(); }
  void get_extreme_points(std::vector<FaceExtreme>&) override { unused(); }
  void point_faces(std::vector<std::int32_t>&) override { unused(); }

 private:
  [[noreturn]] static void unused() { throw std::logic_error("resident engine: backend call not used"); }
  Vec3d at(PointIndex i) const { return to_vec3d(host_[i]); }
  // The point of largest value, ties to the lowest index.  One reduction of rank_key() (the value rounded
  // to float, then ~index) where that rounding keeps the order exact or where the order need not be exact
  // (the distances: find_initial_tetrahedron confirms them); two exact ones for a double x.
  PointIndex best(int what, Vec3d a, Vec3d b, Vec3d d) {
    const TetrahedronValue<Point> value{points_, what, a, b, d};
    if (what >= 2 || std::is_same_v<Point, Point3>)
      return rank_key_index(exec_.reduce_max(n_, RankedValue<Point>{value}));
    const u64 top = exec_.reduce_max(n_, BestValueKey<Point>{value});
    return ~static_cast<u32>(exec_.reduce_max(n_, LowestIndexWith<Point>{value, top}));
  }
  Exec& exec_;
  const std::vector<Point>& host_;
  const Point* points_;
  std::size_t n_;
};

// The mean of P's vertices (rounded: every use of it is checked exactly or with a margin).
template <class Point>
Vec3d centre_of(const BasicHullMesh<Point>& polytope) {
  Vec3d centre{0, 0, 0};
  for (const Point& v : polytope.vertices) {
    const Vec3d p = to_vec3d(v);
    centre = {centre.x + p.x, centre.y + p.y, centre.z + p.z};
  }
  const double k = 1.0 / static_cast<double>(polytope.vertices.size());
  return {centre.x * k, centre.y * k, centre.z * k};
}

// P's face planes with the bounds that make DropFilter sound.  Rounding analysis (u = 2^-53, every
// operation rounded once, no fused operations): for a face (a, b, c) the edge vectors, the cross product
// n = (b - a) x (c - a) and d = -n.a are computed with |n - n*| <= 8u (|products|) per component and
// |d - d*| <= |n - n*|.|a| + 4u |n|.|a|; evaluating n.p + d costs 5u (|n|.|p| + |d|).  With every
// |coordinate| <= M the error is at most 2 |n - n*|_1 M + 4u |n|_1 M + 5u (|n|_1 M + |d|), taken
// with a margin, plus an absolute 2^-1000 for the rounding of results near underflow.
template <class Point>
DropFilter drop_filter(const BasicHullMesh<Point>& polytope, double max_coordinate) {
  DropFilter filter;
  if (polytope.dimension != 3 || polytope.triangles.size() > static_cast<std::size_t>(kMaxDropPlanes))
    return filter;
  constexpr double u = 0x1p-53;
  const double M = max_coordinate;
  const Vec3d centre = centre_of<Point>(polytope);
  for (const Triangle& t : polytope.triangles) {
    const Vec3d a = to_vec3d(polytope.vertices[t[0]]), b = to_vec3d(polytope.vertices[t[1]]),
                c = to_vec3d(polytope.vertices[t[2]]);
    const Vec3d e1{b.x - a.x, b.y - a.y, b.z - a.z}, e2{c.x - a.x, c.y - a.y, c.z - a.z};
    const double n[3] = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    const double err_n = 8 * u *
                         ((std::fabs(e1.y * e2.z) + std::fabs(e1.z * e2.y)) +
                          (std::fabs(e1.z * e2.x) + std::fabs(e1.x * e2.z)) +
                          (std::fabs(e1.x * e2.y) + std::fabs(e1.y * e2.x)));
    const double d = -((n[0] * a.x + n[1] * a.y) + n[2] * a.z);
    const double n1 = std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]);
    const double slack =
        (2 * err_n * M + 4 * u * n1 * M + 5 * u * (n1 * M + std::fabs(d))) * (1 + 0x1p-10) + 0x1p-1000;
    // Outward (exact_hull's triangles are), confirmed by P's centre lying below with room to spare;
    // otherwise no filter at all (it is only an acceleration).
    if (!(((n[0] * centre.x + n[1] * centre.y) + n[2] * centre.z) + d < -slack)) return DropFilter{};
    const u32 f = filter.planes++;
    for (int i = 0; i < 3; ++i)
      filter.n[f][i] = n[i];
    filter.d[f] = d;
    filter.slack[f] = slack;
  }
  return filter;
}

// P as the first mesh (corners and links as the driver keeps them) with its centre as c, when the
// centre is exactly strictly below every face (then the centre into `centre_out`, as c); false otherwise
// (or when P is flat).
template <class Point>
bool polytope_mesh(const BasicHullMesh<Point>& polytope, std::vector<u32>& fv, std::vector<u32>& fn,
                   Vec3d& centre_out) {
  // FirstMesh holds 2 * 14 - 4 faces, all a hull of 14 points can have.
  if (polytope.dimension != 3 || polytope.triangles.size() < 4 ||
      polytope.triangles.size() > static_cast<std::size_t>(kMaxFirstFaces))
    return false;
  const Vec3d centre = centre_of<Point>(polytope);
  const std::size_t faces = polytope.triangles.size();
  fv.assign(3 * faces, 0);
  fn.assign(3 * faces, kNone);
  for (std::size_t f = 0; f < faces; ++f) {
    const Triangle& t = polytope.triangles[f];
    if (orient3d(to_vec3d(polytope.vertices[t[0]]), to_vec3d(polytope.vertices[t[1]]),
                 to_vec3d(polytope.vertices[t[2]]), centre) >= 0)
      return false;
    for (int i = 0; i < 3; ++i)
      fv[3 * f + i] = polytope.vertex_ids[t[i]];
  }
  // Links: the face across directed edge a -> b holds b -> a (a closed 2-manifold: every edge twice).
  for (std::size_t f = 0; f < faces; ++f) {
    for (int i = 0; i < 3; ++i) {
      const u32 a = fv[3 * f + i], b = fv[3 * f + (i + 1) % 3];
      for (std::size_t g = 0; g < faces && fn[3 * f + i] == kNone; ++g) {
        for (int j = 0; j < 3; ++j) {
          if (fv[3 * g + j] == b && fv[3 * g + (j + 1) % 3] == a) fn[3 * f + i] = static_cast<u32>(g);
        }
      }
      if (fn[3 * f + i] == kNone) return false;
    }
  }
  centre_out = centre;
  return true;
}

}  // namespace cudahull::resident
