// Inline implementation of the exact predicates declared in cudahull/predicates.hpp.
//
// Structure of every predicate (Shewchuk 1997, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
// Geometric Predicates"):
//   1. a double-precision evaluation with his proven forward error bound (o3derrboundA, ccwerrboundA); if
//      |det| exceeds the bound its sign is certain;
//   2. otherwise the determinant is evaluated exactly in expansion arithmetic and the sign of its most
//      significant component is returned.
// Stage 2 starts from the coordinate differences as two-component expansions (two_diff), so it is exact for
// any finite double inputs as long as no product underflows or overflows.  For float32 inputs that can never
// happen: every float is a multiple of 2^-149 with magnitude < 2^128, so a difference is a multiple of 2^-149
// below 2^129 and every partial product of three differences (and every component of its expansion) is a
// multiple of 2^-447 below 2^387, far inside double's normal range [2^-1022, 2^1024).
//
// The error-free transformations need every operation rounded exactly once: no contraction of a*b+c into an
// fma.  On the device we use the explicitly rounded intrinsics (__dadd_rn, __dmul_rn, __fma_rn, which nvcc
// never fuses); on the host the library compiles with -ffp-contract=off, and when the target has hardware
// FMA (so that a TU built with contraction on could fuse) an empty asm barrier keeps every product rounded.
// The same rounding on both sides also makes orient3d_fast bit-identical on host and device.
//
// Device constraints: fixed-size stack arrays only, no exceptions, no statics, no std:: calls.
#pragma once

#if !defined(__CUDA_ARCH__)
#include <atomic>
#include <cmath>
#endif

namespace cudahull {
namespace detail {

// ---------------------------------------------------------------------------------------------------------
// Host-only statistics.  One counter block per thread (a plain load/store of a thread-local slot, no locked
// instruction, no sharing of cache lines); predicates.cpp registers each block so predicate_stats() can sum
// them over all threads.
#if !defined(__CUDA_ARCH__)
struct PredicateCounterBlock {
  std::atomic<unsigned long long> orient3d_calls{0};
  std::atomic<unsigned long long> orient3d_exact{0};
};
#if defined(__GNUC__)
extern __thread PredicateCounterBlock* predicate_counters_tls;  // no TLS wrapper call, unlike thread_local
#else
extern thread_local PredicateCounterBlock* predicate_counters_tls;
#endif
PredicateCounterBlock* register_predicate_counters();  // predicates.cpp; first use on each thread

inline PredicateCounterBlock& predicate_counters() {
  PredicateCounterBlock* block = predicate_counters_tls;
  if (block == nullptr) block = register_predicate_counters();
  return *block;
}
inline void bump(std::atomic<unsigned long long>& counter) {
  // Only the owning thread writes, so load + store (no lock prefix) is enough.
  counter.store(counter.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}
#endif

// ---------------------------------------------------------------------------------------------------------
// Correctly rounded operations that the compiler may not fuse or reassociate.
CUDAHULL_HD inline double add_rn(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dadd_rn(a, b);
#else
  return a + b;
#endif
}
CUDAHULL_HD inline double sub_rn(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dsub_rn(a, b);
#else
  return a - b;
#endif
}
CUDAHULL_HD inline double mul_rn(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dmul_rn(a, b);
#else
  double p = a * b;
#if (defined(__FMA__) || defined(__ARM_FEATURE_FMA)) && defined(__GNUC__)
  // Opaque to the optimiser: the rounded product cannot be fused into a following add.
#if defined(__x86_64__) || defined(__i386__)
  __asm__("" : "+x"(p));
#elif defined(__aarch64__)
  __asm__("" : "+w"(p));
#endif
#endif
  return p;
#endif
}
CUDAHULL_HD inline double div_rn(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __ddiv_rn(a, b);
#else
  return a / b;
#endif
}
CUDAHULL_HD inline double sqrt_rn(double a) {
#if defined(__CUDA_ARCH__)
  return __dsqrt_rn(a);
#else
  return std::sqrt(a);
#endif
}
CUDAHULL_HD inline double fma_rn(double a, double b, double c) {
#if defined(__CUDA_ARCH__)
  return __fma_rn(a, b, c);
#else
  return std::fma(a, b, c);
#endif
}
// Branch-free |a| (a branch on random signs mispredicts half the time and dominates the filter's cost).
CUDAHULL_HD inline double abs_d(double a) {
#if defined(__CUDA_ARCH__)
  return fabs(a);
#else
  return std::fabs(a);
#endif
}
CUDAHULL_HD inline int sign_of(double a) {
  return (a > 0.0) - (a < 0.0);
}

// ---------------------------------------------------------------------------------------------------------
// Error-free transformations (Shewchuk 1997, section 2).  x is the rounded result, y the exact error.
CUDAHULL_HD inline void two_sum(double a, double b, double& x, double& y) {
  x = add_rn(a, b);
  double bv = sub_rn(x, a);
  double av = sub_rn(x, bv);
  y = add_rn(sub_rn(a, av), sub_rn(b, bv));
}
// Requires |a| >= |b| (or a == 0).
CUDAHULL_HD inline void fast_two_sum(double a, double b, double& x, double& y) {
  x = add_rn(a, b);
  y = sub_rn(b, sub_rn(x, a));
}
CUDAHULL_HD inline void two_diff(double a, double b, double& x, double& y) {
  x = sub_rn(a, b);
  double bv = sub_rn(a, x);
  double av = add_rn(x, bv);
  y = add_rn(sub_rn(a, av), sub_rn(bv, b));
}
CUDAHULL_HD inline void two_product(double a, double b, double& x, double& y) {
  x = mul_rn(a, b);
  y = fma_rn(a, b, -x);
}
// (a1 + a0) - (b1 + b0) as a four-component expansion x[0..3] (increasing magnitude, may hold zeros).
CUDAHULL_HD inline void two_two_diff(double a1, double a0, double b1, double b0, double* x) {
  double i, j, k;
  two_diff(a0, b0, i, x[0]);
  two_sum(a1, i, j, k);
  double m;
  two_diff(k, b1, m, x[1]);
  two_sum(j, m, x[3], x[2]);
}

// ---------------------------------------------------------------------------------------------------------
// Expansion arithmetic on nonoverlapping expansions stored in increasing magnitude (Shewchuk 1997, figs. 8
// and 11).  Zero components are dropped, so the last component carries the sign; lengths are >= 1.

// The components of e + f in increasing magnitude (figure 8): each nonzero one but the last goes to
// emit(double), the last (Q, possibly zero) is returned.  expansion_sum stores them; expansion_sum_sign keeps
// the sign.
template <class Emit>
CUDAHULL_HD inline double expansion_sum_components(int elen, const double* e, int flen, const double* f,
                                                   const Emit& emit) {
  int ei = 0, fi = 0;
  double enow = e[0], fnow = f[0];
  // Gives op the next component of e or f, the smaller in magnitude, and moves past it.
  auto take = [&](const auto& op) {
    if ((fnow > enow) == (fnow > -enow)) {
      op(enow);
      ++ei;
      enow = ei < elen ? e[ei] : 0.0;
    } else {
      op(fnow);
      ++fi;
      fnow = fi < flen ? f[fi] : 0.0;
    }
  };
  double q, qnew, hh;
  take([&](double x) { q = x; });
  auto add = [&](double x) {
    two_sum(q, x, qnew, hh);
    q = qnew;
    if (hh != 0.0) emit(hh);
  };
  if (ei < elen && fi < flen) {
    take([&](double x) { fast_two_sum(x, q, qnew, hh); });
    q = qnew;
    if (hh != 0.0) emit(hh);
    while (ei < elen && fi < flen)
      take(add);
  }
  // One of them is used up: the other's components follow.
  while (ei < elen)
    add(e[ei++]);
  while (fi < flen)
    add(f[fi++]);
  return q;
}

// h = e + f.  h must hold elen + flen components and must not alias e or f.
CUDAHULL_HD inline int expansion_sum(int elen, const double* e, int flen, const double* f, double* h) {
  int hi = 0;
  const double q = expansion_sum_components(elen, e, flen, f, [&](double c) { h[hi++] = c; });
  if (q != 0.0 || hi == 0) h[hi++] = q;
  return hi;
}

// Sign of e + f, without storing the sum: the last nonzero component (Q when it is nonzero) carries it.
CUDAHULL_HD inline int expansion_sum_sign(int elen, const double* e, int flen, const double* f) {
  double last = 0.0;
  const double q = expansion_sum_components(elen, e, flen, f, [&](double c) { last = c; });
  if (q != 0.0) last = q;
  return sign_of(last);
}

// h = e * b.  h must hold 2 * elen components and must not alias e.
CUDAHULL_HD inline int scale_expansion(int elen, const double* e, double b, double* h) {
  double q, hh, p1, p0, sum;
  two_product(e[0], b, q, hh);
  int hi = 0;
  if (hh != 0.0) h[hi++] = hh;
  for (int i = 1; i < elen; ++i) {
    two_product(e[i], b, p1, p0);
    two_sum(q, p0, sum, hh);
    if (hh != 0.0) h[hi++] = hh;
    fast_two_sum(p1, sum, q, hh);
    if (hh != 0.0) h[hi++] = hh;
  }
  if (q != 0.0 || hi == 0) h[hi++] = q;
  return hi;
}

// h = e * f for a one- or two-component f.  h must hold 4 * elen components.
CUDAHULL_HD inline int multiply_by_pair(int elen, const double* e, int flen, const double* f, double* h) {
  if (flen == 1) return scale_expansion(elen, e, f[0], h);
  double lo[32], hi[32];  // callers keep elen <= 16
  int lolen = scale_expansion(elen, e, f[0], lo);
  int hilen = scale_expansion(elen, e, f[1], hi);
  return expansion_sum(lolen, lo, hilen, hi, h);
}

CUDAHULL_HD inline void negate_expansion(int len, double* e) {
  for (int i = 0; i < len; ++i)
    e[i] = -e[i];
}

// a - b as an exact expansion of one or two components (increasing magnitude).
struct Pair {
  double v[2];
  int len;
};
CUDAHULL_HD inline Pair exact_diff(double a, double b) {
  Pair p;
  double x, y;
  two_diff(a, b, x, y);
  if (y == 0.0) {
    p.v[0] = x;
    p.len = 1;
  } else {
    p.v[0] = y;
    p.v[1] = x;
    p.len = 2;
  }
  return p;
}

// u * v - w * z exactly, for pairs; h must hold 16 components.
CUDAHULL_HD inline int pair_cross(const Pair& u, const Pair& v, const Pair& w, const Pair& z, double* h) {
  double uv[8], wz[8];
  int uvlen = multiply_by_pair(u.len, u.v, v.len, v.v, uv);
  int wzlen = multiply_by_pair(w.len, w.v, z.len, z.v, wz);
  negate_expansion(wzlen, wz);
  return expansion_sum(uvlen, uv, wzlen, wz, h);
}

// Shewchuk's error bound constants, epsilon = 2^-53 (half an ulp of 1).
constexpr double kEpsilon = 1.1102230246251565404236316680908203125e-16;
constexpr double kCcwErrBoundA = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kO3dErrBoundA = (7.0 + 56.0 * kEpsilon) * kEpsilon;

// Shewchuk's orient3d determinant det[a-d, b-d, c-d] (positive when d is BELOW the counter-clockwise
// triangle abc; our orient3d negates it) evaluated exactly as two expansions whose sum it is; `last` is told
// them (length, components; twice) and gives the result: their sum's sign, or its value.
template <class Last>
CUDAHULL_HD inline auto orient3d_exact_parts(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d,
                                             const Last& last) {
  double adx, adx0, bdx, bdx0, cdx, cdx0, ady, ady0, bdy, bdy0, cdy, cdy0, adz, adz0, bdz, bdz0, cdz, cdz0;
  two_diff(a.x, d.x, adx, adx0);
  two_diff(b.x, d.x, bdx, bdx0);
  two_diff(c.x, d.x, cdx, cdx0);
  two_diff(a.y, d.y, ady, ady0);
  two_diff(b.y, d.y, bdy, bdy0);
  two_diff(c.y, d.y, cdy, cdy0);
  two_diff(a.z, d.z, adz, adz0);
  two_diff(b.z, d.z, bdz, bdz0);
  two_diff(c.z, d.z, cdz, cdz0);
  if (adx0 == 0.0 && bdx0 == 0.0 && cdx0 == 0.0 && ady0 == 0.0 && bdy0 == 0.0 && cdy0 == 0.0 && adz0 == 0.0 &&
      bdz0 == 0.0 && cdz0 == 0.0) {
    // Common case (always for float inputs within 2^28 of each other in exponent): exact differences.
    // This is Shewchuk's stage B, which is exact when all difference tails vanish: <= 24 components.
    double p1, p0, q1, q0;
    double bc[4], ca[4], ab[4];
    two_product(bdx, cdy, p1, p0);
    two_product(cdx, bdy, q1, q0);
    two_two_diff(p1, p0, q1, q0, bc);
    two_product(cdx, ady, p1, p0);
    two_product(adx, cdy, q1, q0);
    two_two_diff(p1, p0, q1, q0, ca);
    two_product(adx, bdy, p1, p0);
    two_product(bdx, ady, q1, q0);
    two_two_diff(p1, p0, q1, q0, ab);
    double adet[8], bdet[8], cdet[8], abdet[16];
    int alen = scale_expansion(4, bc, adz, adet);
    int blen = scale_expansion(4, ca, bdz, bdet);
    int clen = scale_expansion(4, ab, cdz, cdet);
    int ablen = expansion_sum(alen, adet, blen, bdet, abdet);
    return last(ablen, abdet, clen, cdet);
  }
  // General case: every difference is a one- or two-component expansion; up to 192 components in all.
  // Buffers are reused to keep the (GPU local-memory) stack frame small.
  Pair ax = exact_diff(a.x, d.x), bx = exact_diff(b.x, d.x), cx = exact_diff(c.x, d.x);
  Pair ay = exact_diff(a.y, d.y), by = exact_diff(b.y, d.y), cy = exact_diff(c.y, d.y);
  Pair az = exact_diff(a.z, d.z), bz = exact_diff(b.z, d.z), cz = exact_diff(c.z, d.z);
  double minor[16], adet[64], bdet[64], abdet[128];
  int mlen = pair_cross(bx, cy, cx, by, minor);
  int alen = multiply_by_pair(mlen, minor, az.len, az.v, adet);
  mlen = pair_cross(cx, ay, ax, cy, minor);
  int blen = multiply_by_pair(mlen, minor, bz.len, bz.v, bdet);
  int ablen = expansion_sum(alen, adet, blen, bdet, abdet);
  mlen = pair_cross(ax, by, bx, ay, minor);
  double* cdet = adet;
  int clen = multiply_by_pair(mlen, minor, cz.len, cz.v, cdet);
  return last(ablen, abdet, clen, cdet);
}

// The exact sign of Shewchuk's orient3d determinant.
CUDAHULL_HD CUDAHULL_COLD inline int orient3d_exact_shewchuk(const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                                             const Vec3d& d) {
  return orient3d_exact_parts(a, b, c, d, [](int elen, const double* e, int flen, const double* f) {
    return expansion_sum_sign(elen, e, flen, f);
  });
}

// Shewchuk's orient3d determinant's value, from its exact expansion: the components added in increasing
// magnitude (his `estimate`), within a few ulps of the exact value since they do not overlap.  For the
// measures of a solid (plane_impl.hpp), where the double evaluation's error bound is too wide.
CUDAHULL_HD CUDAHULL_COLD inline double orient3d_exact_value(const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                                             const Vec3d& d) {
  return orient3d_exact_parts(a, b, c, d, [](int elen, const double* e, int flen, const double* f) {
    double sum[192];  // the general case's 128 + 64 components at most
    const int len = expansion_sum(elen, e, flen, f, sum);
    double value = sum[0];
    for (int i = 1; i < len; ++i)
      value = add_rn(value, sum[i]);
    return value;
  });
}

// Exact sign of det[a-c, b-c] (Shewchuk's orient2d, same sign as ours).
CUDAHULL_HD CUDAHULL_COLD inline int orient2d_exact(double ax, double ay, double bx, double by, double cx,
                                                    double cy) {
  Pair acx = exact_diff(ax, cx), bcx = exact_diff(bx, cx);
  Pair acy = exact_diff(ay, cy), bcy = exact_diff(by, cy);
  double uv[8], wz[8];
  int uvlen = multiply_by_pair(acx.len, acx.v, bcy.len, bcy.v, uv);
  int wzlen = multiply_by_pair(acy.len, acy.v, bcx.len, bcx.v, wz);
  negate_expansion(wzlen, wz);
  return expansion_sum_sign(uvlen, uv, wzlen, wz);
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------------------

CUDAHULL_HD inline double orient3d_fast(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  using namespace detail;
  double adx = sub_rn(a.x, d.x), bdx = sub_rn(b.x, d.x), cdx = sub_rn(c.x, d.x);
  double ady = sub_rn(a.y, d.y), bdy = sub_rn(b.y, d.y), cdy = sub_rn(c.y, d.y);
  double adz = sub_rn(a.z, d.z), bdz = sub_rn(b.z, d.z), cdz = sub_rn(c.z, d.z);
  double bc = sub_rn(mul_rn(bdx, cdy), mul_rn(cdx, bdy));
  double ca = sub_rn(mul_rn(cdx, ady), mul_rn(adx, cdy));
  double ab = sub_rn(mul_rn(adx, bdy), mul_rn(bdx, ady));
  double det = add_rn(add_rn(mul_rn(adz, bc), mul_rn(bdz, ca)), mul_rn(cdz, ab));
  return -det;  // Shewchuk's determinant is positive when d is below; ours when above
}

CUDAHULL_HD inline int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  using namespace detail;
#if !defined(__CUDA_ARCH__) && !defined(CUDAHULL_NO_PREDICATE_STATS)
  PredicateCounterBlock& counters = predicate_counters();
  bump(counters.orient3d_calls);
#endif
  // Shewchuk's orient3d filter, differences relative to d as in the derivation of o3derrboundA.
  double adx = sub_rn(a.x, d.x), bdx = sub_rn(b.x, d.x), cdx = sub_rn(c.x, d.x);
  double ady = sub_rn(a.y, d.y), bdy = sub_rn(b.y, d.y), cdy = sub_rn(c.y, d.y);
  double adz = sub_rn(a.z, d.z), bdz = sub_rn(b.z, d.z), cdz = sub_rn(c.z, d.z);
  double bdxcdy = mul_rn(bdx, cdy), cdxbdy = mul_rn(cdx, bdy);
  double cdxady = mul_rn(cdx, ady), adxcdy = mul_rn(adx, cdy);
  double adxbdy = mul_rn(adx, bdy), bdxady = mul_rn(bdx, ady);
  double det = add_rn(add_rn(mul_rn(adz, sub_rn(bdxcdy, cdxbdy)), mul_rn(bdz, sub_rn(cdxady, adxcdy))),
                      mul_rn(cdz, sub_rn(adxbdy, bdxady)));
  double permanent = add_rn(add_rn(mul_rn(add_rn(abs_d(bdxcdy), abs_d(cdxbdy)), abs_d(adz)),
                                   mul_rn(add_rn(abs_d(cdxady), abs_d(adxcdy)), abs_d(bdz))),
                            mul_rn(add_rn(abs_d(adxbdy), abs_d(bdxady)), abs_d(cdz)));
  double errbound = mul_rn(kO3dErrBoundA, permanent);
  if (abs_d(det) > errbound) return -sign_of(det);
  // A zero permanent means every term of the determinant is exactly zero (no underflow, see above), as for
  // four points in an axis-parallel plane: no exact stage needed.
  if (permanent == 0.0) return 0;
#if !defined(__CUDA_ARCH__) && !defined(CUDAHULL_NO_PREDICATE_STATS)
  bump(counters.orient3d_exact);
#endif
  return -orient3d_exact_shewchuk(a, b, c, d);
}

CUDAHULL_HD inline int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  using namespace detail;
  // Shewchuk's orient2d filter (ccwerrboundA), differences relative to c.  His bound holds for the
  // permanent |detleft| + |detright|; we skip his sign-case shortcuts to stay branch-free.
  double detleft = mul_rn(sub_rn(ax, cx), sub_rn(by, cy));
  double detright = mul_rn(sub_rn(ay, cy), sub_rn(bx, cx));
  double det = sub_rn(detleft, detright);
  double permanent = add_rn(abs_d(detleft), abs_d(detright));
  double errbound = mul_rn(kCcwErrBoundA, permanent);
  if (abs_d(det) > errbound) return sign_of(det);
  if (permanent == 0.0) return 0;  // both products exactly zero
  return orient2d_exact(ax, ay, bx, by, cx, cy);
}

CUDAHULL_HD inline bool collinear3d(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  // (b-a) x (c-a) == 0 componentwise; its components are the three projected orient2d determinants.
  return orient2d(a.x, a.y, b.x, b.y, c.x, c.y) == 0 && orient2d(a.y, a.z, b.y, b.z, c.y, c.z) == 0 &&
         orient2d(a.z, a.x, b.z, b.x, c.z, c.x) == 0;
}

}  // namespace cudahull
