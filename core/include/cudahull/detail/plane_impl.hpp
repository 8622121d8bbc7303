// Inline implementation of the facet planes (cudahull/plane.hpp) and of a hull's measures, for the host and
// the device alike (CUDAHULL_HD): the batch kernel describes its hulls on the device with the same code as
// convex_hull() on the host, so the planes, volumes and areas are the same bits on every backend.
//
// design:
//   facet_plane_in_range  the plane of a face whose corners are in the fast exact range: the cross product in
//                         double where it cannot cancel (within 32 times the normal's length of its
//                         permanents), else the exact one rounded (plane_through); see api/src/describe.cpp
//   plane_through         plane.cpp's exact plane: the cross product's components as exact expansions, each
//                         rounded once (Compress's guess, corrected by exact comparisons)
//   SolidMeasures         six times the volume and twice the area, summed face by face in the order given;
//                         the volume's tetrahedra from one of the solid's vertices (no term negative), each
//                         in double with its error bound, or exactly where their bounds add up to more than
//                         2^-40 of the volume (slivers)
// Every operation is explicitly rounded (the predicates' add_rn, mul_rn, div_rn, sqrt_rn), so neither
// the host's contraction nor the device's fused multiply-add changes a bit.
#pragma once

#include "cudahull/host_device.hpp"
#include "cudahull/predicates.hpp"

#if !defined(__CUDA_ARCH__)
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#endif

namespace cudahull {
namespace detail {

CUDAHULL_HD inline double max3(double a, double b, double c) {
  const double ab = a < b ? b : a;
  return ab < c ? c : ab;
}

constexpr int kPlaneComponents = 16;  // pair_cross's output
constexpr int kPlaneSteps = 4;        // rounding corrections; Compress's guess needs at most two

// Shewchuk 1997, fig. 15 and Theorem 23: `e` (nonoverlapping, increasing magnitude, length >= 1) rewritten
// as a nonadjacent expansion whose largest component, returned, differs from the sum by less than one of
// its ulps.  Only used as a first guess, so its accuracy affects the number of correction steps, not the
// result.
CUDAHULL_HD inline double compress_largest(int len, const double* e) {
  double h[kPlaneComponents];
  int bottom = len - 1;
  double q = e[bottom];
  for (int i = len - 2; i >= 0; --i) {
    double qnew, tail;
    fast_two_sum(q, e[i], qnew, tail);
    if (tail != 0.0) {
      h[bottom--] = qnew;
      q = tail;
    } else {
      q = qnew;
    }
  }
  for (int i = bottom + 1; i < len; ++i) {
    double qnew, tail;
    fast_two_sum(h[i], q, qnew, tail);
    q = qnew;
  }
  return q;
}

// The next double from r towards +infinity (up) or -infinity.
CUDAHULL_HD inline double next_double(double r, bool up) {
#if defined(__CUDA_ARCH__)
  return nextafter(
      r, up ? __longlong_as_double(0x7ff0000000000000LL) : -__longlong_as_double(0x7ff0000000000000LL));
#else
  return std::nextafter(
      r, up ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity());
#endif
}
CUDAHULL_HD inline bool is_even_double(double r) {
#if defined(__CUDA_ARCH__)
  return (__double_as_longlong(r) & 1) == 0;
#else
  std::uint64_t bits;
  std::memcpy(&bits, &r, sizeof bits);
  return (bits & 1) == 0;
#endif
}
CUDAHULL_HD inline bool is_finite_double(double r) {
  return r - r == 0.0;  // false for infinities and NaN
}

// The double nearest to the exact sum of `e` (as produced by expansion_sum: nonoverlapping, increasing
// magnitude, no zero components except a lone zero), ties to even.
CUDAHULL_HD inline double round_expansion(int len, const double* e) {
  double r = compress_largest(len, e);
  // The remainder e - r, exactly.  Each correction step appends at most one component.
  double rem[kPlaneComponents + kPlaneSteps + 1], next_rem[kPlaneComponents + kPlaneSteps + 1];
  double twice[kPlaneComponents + kPlaneSteps + 1];
  double minus_r = -r;
  int rlen = expansion_sum(len, e, 1, &minus_r, rem);
  for (int step = 0; step < kPlaneSteps; ++step) {
    const double top = rem[rlen - 1];  // carries the remainder's sign
    if (top == 0.0) return r;          // r is the exact value
    const double neighbour = next_double(r, top > 0);
    if (!is_finite_double(neighbour)) return r;  // beyond the largest double: out of contract
    // Adjacent doubles: the gap is a power of two and the subtraction exact.  Compare 2 * rem with it
    // rather than rem with half of it, which could underflow.
    double minus_gap = sub_rn(r, neighbour);
    for (int i = 0; i < rlen; ++i)
      twice[i] = mul_rn(2.0, rem[i]);
    const int side = expansion_sum_sign(rlen, twice, 1, &minus_gap);  // sign of 2 rem - gap
    const int direction = top > 0 ? 1 : -1;
    if (side == -direction) return r;                         // less than half way to the neighbour
    if (side == 0) return is_even_double(r) ? r : neighbour;  // exactly half way: the even one
    // Past half way: the neighbour is nearer; the remainder from it is rem - gap.
    rlen = expansion_sum(rlen, rem, 1, &minus_gap, next_rem);
    for (int i = 0; i < rlen; ++i)
      rem[i] = next_rem[i];
    r = neighbour;
  }
  return r;  // not reached: Compress's guess is within one ulp, so two steps suffice
}

// u_j v_k - u_k v_j, rounded to nearest, from its exact expansion.
CUDAHULL_HD inline double rounded_minor_exact(const Pair& uj, const Pair& vk, const Pair& uk,
                                              const Pair& vj) {
  double h[kPlaneComponents];
  const int len = pair_cross(uj, vk, uk, vj, h);
  return add_rn(round_expansion(len, h), 0.0);  // + 0.0: a zero component is +0, never -0
}

#if !defined(__CUDA_ARCH__)
// The next double above the positive normal double a, and the one below it.
inline double next_up_positive(double a) {
  std::uint64_t bits;
  std::memcpy(&bits, &a, sizeof bits);
  ++bits;
  std::memcpy(&a, &bits, sizeof bits);
  return a;
}
inline double next_down_positive(double a) {
  std::uint64_t bits;
  std::memcpy(&bits, &a, sizeof bits);
  --bits;
  std::memcpy(&a, &bits, sizeof bits);
  return a;
}

// The minor rounded to nearest, where about double-double arithmetic proves it: true with it in *rounded.
// With each pair h + l, u_j v_k = P + e (h h's product, exact) + the three products with an l, each within
// u of u_j v_k's scale times u; so the minor is S + s (P - Q, exact) plus a tail of nine terms whose computed
// sum T is within E = 16u of their magnitudes (8 roundings of the sum, one of each rounded product).  S + T
// = r + r' exactly (two_sum), so the minor is r + r' + (tail - T): r is its rounding where |r'| + E stays
// under half the gap to r's neighbour on that side (on either side where E could change the side).  False
// otherwise (a tie, or the cancellation of a sliver): rounded_minor_exact() then.  Host only: the device
// keeps the exact path, which is not measured there.
inline bool rounded_minor_fast(const Pair& uj, const Pair& vk, const Pair& uk, const Pair& vj,
                               double* rounded) {
  const auto hi = [](const Pair& x) { return x.len == 1 ? x.v[0] : x.v[1]; };
  const auto lo = [](const Pair& x) { return x.len == 1 ? 0.0 : x.v[0]; };
  double p, p_err, q, q_err;
  two_product(hi(uj), hi(vk), p, p_err);
  two_product(hi(uk), hi(vj), q, q_err);
  double big, big_err;
  two_diff(p, q, big, big_err);
  const double tail[9] = {big_err,
                          p_err,
                          -q_err,
                          mul_rn(hi(uj), lo(vk)),
                          mul_rn(lo(uj), hi(vk)),
                          mul_rn(lo(uj), lo(vk)),
                          -mul_rn(hi(uk), lo(vj)),
                          -mul_rn(lo(uk), hi(vj)),
                          -mul_rn(lo(uk), lo(vj))};
  double sum = 0.0, spread = 0.0;
  for (const double t : tail) {
    sum = add_rn(sum, t);
    spread = add_rn(spread, abs_d(t));
  }
  const double error = mul_rn(mul_rn(16.0 * kEpsilon, spread), 1.0 + 0x1p-40);  // 16u (kEpsilon is u)
  double r, r_err;
  two_sum(big, sum, r, r_err);
  const double a = abs_d(r);
  if (!(a >= 0x1p-900 && a <= 0x1p+900)) return false;  // zero, tiny or huge: the exact path
  const double up = sub_rn(next_up_positive(a), a), down = sub_rn(a, next_down_positive(a));
  const double drift = abs_d(r_err);
  // The side r's remainder lies on, away from zero or towards it; both where the error could cross zero.
  const double gap = error < drift ? ((r_err > 0) == (r > 0) ? up : down) : (up < down ? up : down);
  if (!(mul_rn(add_rn(drift, error), 1.0 + 0x1p-40) < mul_rn(0.5, gap))) return false;
  *rounded = r;
  return true;
}
#endif

// u_j v_k - u_k v_j, rounded to nearest.
CUDAHULL_HD inline double rounded_minor(const Pair& uj, const Pair& vk, const Pair& uk, const Pair& vj) {
  if (uj.len == 1 && vk.len == 1 && uk.len == 1 && vj.len == 1) {
    // Shortcut, common for float32 input: when both products are exact in double, their rounded difference
    // is the exact minor rounded to nearest.
    double p, p_err, q, q_err;
    two_product(uj.v[0], vk.v[0], p, p_err);
    two_product(uk.v[0], vj.v[0], q, q_err);
    if (p_err == 0.0 && q_err == 0.0) return add_rn(sub_rn(p, q), 0.0);
  }
#if !defined(__CUDA_ARCH__)
  double fast;
  if (rounded_minor_fast(uj, vk, uk, vj, &fast)) return add_rn(fast, 0.0);
#endif
  return rounded_minor_exact(uj, vk, uk, vj);
}

// (b - a) x (c - a), each component the exact value rounded to nearest (plane.hpp's cross_rounded).
CUDAHULL_HD inline void cross_rounded(const Vec3d& a, const Vec3d& b, const Vec3d& c, double* n) {
  const Pair ux = exact_diff(b.x, a.x), uy = exact_diff(b.y, a.y), uz = exact_diff(b.z, a.z);
  const Pair vx = exact_diff(c.x, a.x), vy = exact_diff(c.y, a.y), vz = exact_diff(c.z, a.z);
  n[0] = rounded_minor(uy, vz, uz, vy);
  n[1] = rounded_minor(uz, vx, ux, vz);
  n[2] = rounded_minor(ux, vy, uy, vx);
}

// The unit normal `n` (its length `length`, any positive scale) and offset d = -max(n . corners) into
// `plane`.
CUDAHULL_HD inline void unit_plane(double x, double y, double z, double length, const Vec3d& a,
                                   const Vec3d& b, const Vec3d& c, double* plane) {
  const double nx = div_rn(x, length), ny = div_rn(y, length), nz = div_rn(z, length);
  const auto height = [&](const Vec3d& p) {
    return add_rn(add_rn(mul_rn(nx, p.x), mul_rn(ny, p.y)), mul_rn(nz, p.z));
  };
  plane[0] = nx;
  plane[1] = ny;
  plane[2] = nz;
  plane[3] = -max3(height(a), height(b), height(c));
}

// n scaled by a power of two (exact) so that its largest component lies in [1, 2), into `scaled` with the
// exponent: the squares can neither overflow nor underflow whatever the input's magnitude.  False for n = 0.
CUDAHULL_HD inline bool scaled_to_unit_range(const double* n, double* scaled, int* exponent) {
  const double largest = max3(abs_d(n[0]), abs_d(n[1]), abs_d(n[2]));
  if (largest == 0.0) return false;
  *exponent = ilogb(largest);
  for (int k = 0; k < 3; ++k)
    scaled[k] = ldexp(n[k], -*exponent);
  return true;
}

CUDAHULL_HD inline double length_of(const double* n) {
  return sqrt_rn(add_rn(add_rn(mul_rn(n[0], n[0]), mul_rn(n[1], n[1])), mul_rn(n[2], n[2])));
}

// plane.hpp's plane_through into plane[0..3].
CUDAHULL_HD inline void plane_through(const Vec3d& a, const Vec3d& b, const Vec3d& c, double* plane) {
  double n[3], scaled[3];
  int exponent = 0;
  cross_rounded(a, b, c, n);
  if (!scaled_to_unit_range(n, scaled, &exponent)) {  // collinear or coincident: no plane
    plane[0] = plane[1] = plane[2] = plane[3] = 0.0;
    return;
  }
  unit_plane(scaled[0], scaled[1], scaled[2], length_of(scaled), a, b, c, plane);
}

// (b - a) x (c - a) in double, each component n[k] beside its permanent p[k] (its two products' magnitudes
// summed): where the permanents are much longer than n, the products cancelled.
struct DoubleCross {
  double n[3], p[3];
};
CUDAHULL_HD inline DoubleCross double_cross(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double ux = sub_rn(b.x, a.x), uy = sub_rn(b.y, a.y), uz = sub_rn(b.z, a.z);
  const double vx = sub_rn(c.x, a.x), vy = sub_rn(c.y, a.y), vz = sub_rn(c.z, a.z);
  const double uyvz = mul_rn(uy, vz), uzvy = mul_rn(uz, vy), uzvx = mul_rn(uz, vx), uxvz = mul_rn(ux, vz),
               uxvy = mul_rn(ux, vy), uyvx = mul_rn(uy, vx);
  return DoubleCross{
      {sub_rn(uyvz, uzvy), sub_rn(uzvx, uxvz), sub_rn(uxvy, uyvx)},
      {add_rn(abs_d(uyvz), abs_d(uzvy)), add_rn(abs_d(uzvx), abs_d(uxvz)), add_rn(abs_d(uxvy), abs_d(uyvx))}};
}

// A hull face's plane (its corners in the fast exact range), accurate on slivers too.  The cross product in
// double first: each component is within 3u of its permanent (|products| summed; Shewchuk's orient2d
// bound), so where the permanents are within 32 times the normal's length its direction is within about
// 100u of the exact one, and every point lies within ~5e-14 x scale of the plane.  Otherwise (a sliver,
// where the products cancel) plane_through() evaluates the normal exactly and rounds it.
CUDAHULL_HD inline void facet_plane_in_range(const Vec3d& a, const Vec3d& b, const Vec3d& c, double* plane) {
  const DoubleCross cross = double_cross(a, b, c);
  const double* n = cross.n;
  const double length2 = add_rn(add_rn(mul_rn(n[0], n[0]), mul_rn(n[1], n[1])), mul_rn(n[2], n[2]));
  const double* p = cross.p;
  const double permanent2 = add_rn(add_rn(mul_rn(p[0], p[0]), mul_rn(p[1], p[1])), mul_rn(p[2], p[2]));
  if (length2 > 0 && permanent2 <= mul_rn(1024.0, length2)) {
    unit_plane(n[0], n[1], n[2], sqrt_rn(length2), a, b, c, plane);
    return;
  }
  plane_through(a, b, c, plane);
}

// Twice the area of triangle abc, |(b - a) x (c - a)|, from its double cross product where that does not
// cancel and its squares stay normal (facet_plane_in_range()'s test), else from the exactly rounded
// components (cross_rounded(): a needle's area to a few ulps, not 1e-15 off 3e-15).
CUDAHULL_HD inline double twice_triangle_area(const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                              const DoubleCross& cross) {
  const double* n = cross.n;
  const double length2 = add_rn(add_rn(mul_rn(n[0], n[0]), mul_rn(n[1], n[1])), mul_rn(n[2], n[2]));
  const double* p = cross.p;
  const double permanent2 = add_rn(add_rn(mul_rn(p[0], p[0]), mul_rn(p[1], p[1])), mul_rn(p[2], p[2]));
  if (length2 >= 0x1p-1000 && permanent2 <= mul_rn(1024.0, length2) && permanent2 <= 0x1p+1000)
    return sqrt_rn(length2);
  double exact[3], scaled[3];
  int exponent = 0;
  cross_rounded(a, b, c, exact);
  return scaled_to_unit_range(exact, scaled, &exponent) ? ldexp(length_of(scaled), exponent) : 0.0;
}

// A closed outward mesh's six times volume and twice area, face by face in the order given (the order is
// part of the result: the same order gives the same bits).  The volume's tetrahedra share an apex at one of
// the solid's vertices (`apex`), so that no term is negative: each is Shewchuk's orient3d determinant of the
// face and the apex, exactly zero or positive.  A first pass adds the terms in double with their error
// bounds; where the bounds' sum exceeds 2^-40 of the volume (a sliver, where the terms cancel inside each
// determinant), a second pass adds the exact determinants' values instead (exact_volume_pass()).
struct SolidMeasures {
  static constexpr double kVolumeTolerance = 0x1p-40;
  double six_volume = 0, twice_area = 0, six_volume_error = 0;
  // A face's own terms (twice its area, six times its tetrahedron's volume from the apex and the bound on
  // that term's error): independent of the other faces, so a warp may compute them at once and add them in
  // order (add_terms()).
  struct FaceTerms {
    double twice_area, six_volume, six_volume_error;
  };
  CUDAHULL_HD static bool is_corner(const Vec3d& p, const Vec3d& apex) {
    return p.x == apex.x && p.y == apex.y && p.z == apex.z;
  }
  CUDAHULL_HD static FaceTerms face_terms(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& apex) {
    // n = (b - a) x (c - a), twice the face's area; the term n . (a - apex), the determinant expanded
    // along its row a - apex, whose error Shewchuk's orient3d bound holds (each of its three products a
    // rounded difference times a rounded minor of rounded differences).  From the face's own short edges
    // the far faces' terms do not cancel, as three long vectors to a small face do.
    const DoubleCross cross = double_cross(a, b, c);
    const double *n = cross.n, *p = cross.p;
    const double twice_area = twice_triangle_area(a, b, c, cross);
    // A face at the apex has no volume (and its determinant, exactly zero, would take the second pass).
    if (is_corner(a, apex) || is_corner(b, apex) || is_corner(c, apex)) return FaceTerms{twice_area, 0, 0};
    const double wx = sub_rn(a.x, apex.x), wy = sub_rn(a.y, apex.y), wz = sub_rn(a.z, apex.z);
    const double det = add_rn(add_rn(mul_rn(wx, n[0]), mul_rn(wy, n[1])), mul_rn(wz, n[2]));
    const double permanent =
        add_rn(add_rn(mul_rn(p[0], abs_d(wx)), mul_rn(p[1], abs_d(wy))), mul_rn(p[2], abs_d(wz)));
    return FaceTerms{twice_area, det, mul_rn(kO3dErrBoundA, permanent)};
  }
  // The second pass's term: the face's exact determinant with the apex, to a few ulps.
  CUDAHULL_HD static double exact_six_volume(const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                             const Vec3d& apex) {
    if (is_corner(a, apex) || is_corner(b, apex) || is_corner(c, apex)) return 0;
    return orient3d_exact_value(a, b, c, apex);
  }
  // The area's and the volume's terms, in the mesh's order.
  CUDAHULL_HD void add_terms(const FaceTerms& t) {
    twice_area = add_rn(twice_area, t.twice_area);
    six_volume = add_rn(six_volume, t.six_volume);
  }
  // The error bounds go into kErrorSums strided partial sums (face f's into sum f mod 32), and those into
  // six_volume_error in order: the order a warp adds them in, a lane a sum, with 32 shuffles a mesh and
  // not one a face.
  static constexpr int kErrorSums = 32;
  // After the first pass: whether the volume needs the second (its error bound above 2^-40 of it).
  CUDAHULL_HD bool volume_uncertain() const {
    return !(six_volume_error <= mul_rn(kVolumeTolerance, six_volume));
  }
  // The second pass: exact_six_volume() of every face, added in the same order after this call.
  CUDAHULL_HD void exact_volume_pass() { six_volume = 0; }
  CUDAHULL_HD void add_exact(double term) { six_volume = add_rn(six_volume, term); }
  CUDAHULL_HD double volume() const { return div_rn(six_volume, 6.0); }
  CUDAHULL_HD double area() const { return div_rn(twice_area, 2.0); }
};

// The first pass over faces [begin, end) (`corner(f, k)` the k-th corner of face f, `apex` one of the mesh's
// vertices): their terms into `measures`, their error bounds into `error_sums` (face f's into f mod 32).
template <class Corner>
CUDAHULL_HD void add_face_terms(unsigned long long begin, unsigned long long end, const Corner& corner,
                                const Vec3d& apex, SolidMeasures& measures, double* error_sums) {
  for (unsigned long long f = begin; f < end; ++f) {
    const SolidMeasures::FaceTerms terms =
        SolidMeasures::face_terms(corner(f, 0), corner(f, 1), corner(f, 2), apex);
    measures.add_terms(terms);
    double& sum = error_sums[f % SolidMeasures::kErrorSums];
    sum = add_rn(sum, terms.six_volume_error);
  }
}

// The second pass over faces [begin, end): their exact volume terms into `measures`.
template <class Corner>
CUDAHULL_HD void add_exact_terms(unsigned long long begin, unsigned long long end, const Corner& corner,
                                 const Vec3d& apex, SolidMeasures& measures) {
  for (unsigned long long f = begin; f < end; ++f)
    measures.add_exact(SolidMeasures::exact_six_volume(corner(f, 0), corner(f, 1), corner(f, 2), apex));
}

// A closed outward mesh's measures, both passes on one thread (the batch's describe spreads them over a
// warp; convex_hull() a mesh of more than 2^20 faces over the cores, a fixed chunk a task).
template <class Corner>
CUDAHULL_HD SolidMeasures measure_mesh(unsigned long long faces, const Corner& corner, const Vec3d& apex) {
  SolidMeasures measures;
  double error_sums[SolidMeasures::kErrorSums] = {};
  add_face_terms(0, faces, corner, apex, measures, error_sums);
  for (const double sum : error_sums)
    measures.six_volume_error = add_rn(measures.six_volume_error, sum);
  if (measures.volume_uncertain()) {
    measures.exact_volume_pass();
    add_exact_terms(0, faces, corner, apex, measures);
  }
  return measures;
}

}  // namespace detail
}  // namespace cudahull
