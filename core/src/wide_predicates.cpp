// The wide-range exact predicates (wide_predicates.hpp): the fast predicates where the call's coordinates
// allow them, directly or scaled by a power of two, else a double filter with an underflow-aware error bound
// and, where it cannot decide, exact integer arithmetic in GMP.
#include "cudahull/wide_predicates.hpp"

#include <gmp.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace cudahull {
namespace {

// floor(log2 |x|) for a finite nonzero x, subnormals included (-1074 for the least one).
int binade(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased != 0) return biased - 1023;
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  return -1074 + (63 - __builtin_clzll(fraction));
}

// How one call is evaluated (see wide_predicates.hpp).
enum class Stage { kZero, kFast, kScaled, kGmp };

// Picks the stage for the call's coordinates v[0..n); for kScaled, `shift` is the power of two that moves
// every nonzero magnitude into [2^-250, 2^250) (the binades -250..249); for kGmp, the one that moves the
// largest magnitude into [2^299, 2^300) for the filter in front of GMP.  kZero: every coordinate is zero.
Stage choose_stage(const double* v, int n, int& shift) {
  bool fast = true;
  int lo = INT_MAX, hi = INT_MIN;
  for (int i = 0; i < n; ++i) {
    fast = fast && in_fast_exact_range(v[i]);
    if (v[i] == 0.0) continue;
    const int b = binade(v[i]);
    lo = std::min(lo, b);
    hi = std::max(hi, b);
  }
  if (lo == INT_MAX) return Stage::kZero;
  if (fast) return Stage::kFast;
  // Scaled by 2^k the binades are lo + k .. hi + k, which must lie in -250..249.
  const int k_min = -250 - lo, k_max = 249 - hi;
  if (k_min > k_max) {
    shift = 299 - hi;
    return Stage::kGmp;
  }
  shift = k_min + (k_max - k_min) / 2;  // centred
  return Stage::kScaled;
}

void scale(double* v, int n, int shift) {
  for (int i = 0; i < n; ++i)
    v[i] = std::ldexp(v[i], shift);  // exact: the result is a normal double (or zero)
}

// Scratch integers, one set per thread (no allocation per call once they have grown).
struct Scratch {
  static constexpr int kCount = 24;
  mpz_t z[kCount];
  Scratch() {
    for (mpz_t& x : z)
      mpz_init(x);
  }
  ~Scratch() {
    for (mpz_t& x : z)
      mpz_clear(x);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// A finite double as m * 2^e: m a signed integer below 2^53 in magnitude, with its trailing zero bits moved
// into e (so e is as large as possible); e >= -1074.
struct Dyadic {
  std::int64_t m = 0;
  int e = 0;
};
Dyadic decompose(double x) {
  Dyadic d;
  if (x == 0.0) return d;
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  std::uint64_t m = bits & ((std::uint64_t{1} << 52) - 1);
  int e = -1074;
  if (biased != 0) {
    m |= std::uint64_t{1} << 52;
    e = biased - 1075;
  }
  const int tz = __builtin_ctzll(m);
  m >>= tz;
  e += tz;
  d.m = (bits >> 63) ? -static_cast<std::int64_t>(m) : static_cast<std::int64_t>(m);
  d.e = e;
  return d;
}

// out[i] = v[i] * 2^-E exactly, for E the least exponent among the nonzero v[i]: integers.
void to_integers(const double* v, int n, mpz_t* out) {
  Dyadic d[12];
  int e_min = INT_MAX;
  for (int i = 0; i < n; ++i) {
    d[i] = decompose(v[i]);
    if (d[i].m != 0) e_min = std::min(e_min, d[i].e);
  }
  for (int i = 0; i < n; ++i) {
    mpz_set_si(out[i], static_cast<long>(d[i].m));
    if (d[i].m != 0) mpz_mul_2exp(out[i], out[i], static_cast<mp_bitcnt_t>(d[i].e - e_min));
  }
}

// Sign of det[b-a, c-a, d-a] = ((b-a) x (c-a)) . (d-a) on the integers v = (a, b, c, d).
int orient3d_integers(double (&v)[12]) {
  Scratch& s = scratch();
  mpz_t* c = s.z;       // coordinates a, b, c, d: c[0..12)
  mpz_t* u = s.z + 12;  // b - a: u[0..3), c - a: u[3..6), d - a: u[6..9)
  mpz_t& t = s.z[21];
  mpz_t& det = s.z[22];
  to_integers(v, 12, c);
  for (int k = 0; k < 3; ++k) {
    mpz_sub(u[k], c[3 + k], c[k]);
    mpz_sub(u[3 + k], c[6 + k], c[k]);
    mpz_sub(u[6 + k], c[9 + k], c[k]);
  }
  mpz_t *p = u, *q = u + 3, *w = u + 6;  // (p x q) . w
  mpz_mul(t, p[1], q[2]);
  mpz_submul(t, p[2], q[1]);
  mpz_mul(det, t, w[0]);
  mpz_mul(t, p[2], q[0]);
  mpz_submul(t, p[0], q[2]);
  mpz_addmul(det, t, w[1]);
  mpz_mul(t, p[0], q[1]);
  mpz_submul(t, p[1], q[0]);
  mpz_addmul(det, t, w[2]);
  return mpz_sgn(det);
}

// Sign of (bx-ax)(cy-ay) - (by-ay)(cx-ax) on the integers v = (ax, ay, bx, by, cx, cy).
int orient2d_integers(double (&v)[6]) {
  Scratch& s = scratch();
  mpz_t* c = s.z;
  mpz_t* u = s.z + 6;
  mpz_t& det = s.z[10];
  to_integers(v, 6, c);
  mpz_sub(u[0], c[2], c[0]);  // bx - ax
  mpz_sub(u[1], c[3], c[1]);  // by - ay
  mpz_sub(u[2], c[4], c[0]);  // cx - ax
  mpz_sub(u[3], c[5], c[1]);  // cy - ay
  mpz_mul(det, u[0], u[3]);
  mpz_submul(det, u[1], u[2]);
  return mpz_sgn(det);
}

// (b-a) x (c-a) == 0 on the integers v = (a, b, c).
bool collinear3d_integers(double (&v)[9]) {
  Scratch& s = scratch();
  mpz_t* c = s.z;
  mpz_t* u = s.z + 9;  // b - a: u[0..3), c - a: u[3..6)
  mpz_t& t = s.z[15];
  to_integers(v, 9, c);
  for (int k = 0; k < 3; ++k) {
    mpz_sub(u[k], c[3 + k], c[k]);
    mpz_sub(u[3 + k], c[6 + k], c[k]);
  }
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    mpz_mul(t, u[i], u[3 + j]);
    mpz_submul(t, u[j], u[3 + i]);
    if (mpz_sgn(t) != 0) return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------------------
// A double filter for stage 3, in front of GMP: the fast predicates' filter on the call's coordinates scaled
// by 2^shift (the largest magnitude into [2^299, 2^300): no product or sum of the filter can overflow), its
// bound widened for underflow and for the scaling.  The sign of the determinant of the exactly scaled
// coordinates is the sign sought.
//  - Rounding.  Shewchuk's bounds assume every operation rounds with a relative error of at most
//    eps = 2^-53.  With gradual underflow a sum or difference still does (a subnormal result is exact), and
//    a product fl(x * y) = x * y * (1 + delta) + eta with |delta| <= eps, |eta| <= 2^-1075.  Each eta
//    travels linearly to the determinant: for orient3d the six 2x2 products through one subtraction and one
//    product by a z difference, and the three products by the z differences through two additions: at most
//    2^-1075 (2 (|adz| + |bdz| + |cdz|) + 3) (1 + 4 eps); the permanent falls short by about as much, which
//    Shewchuk's bound scales by 7 eps.  For orient2d: two products, one subtraction: 2^-1075 * 2 (1 + eps).
//  - Scaling down (shift < 0) rounds a coordinate that becomes subnormal, by at most 2^-1075, so each
//    difference by at most 2^-1074, with every difference below L = 2^301.  orient3d is a sum of six
//    products of three differences: it moves by at most 6 * 3 * 2^-1074 L^2 (1 + 2^-200) < 2^-467;
//    orient2d, two products of two: by at most 2 * 2 * 2^-1074 L (1 + 2^-200) < 2^-770.
// The bounds used are far above these: 2^-50 (8 eps, against Shewchuk's 7 eps + 56 eps^2) times the
// permanent, plus 2^-1070 (|adz| + |bdz| + |cdz| + 1) for orient3d or 2^-1072 for orient2d (32 and 8 times
// the rounding terms' unit), plus 2^-460 or 2^-760 when scaled down; the slack covers the rounding (and
// any underflow) of the bound itself.  A permanent that is not finite (which cannot happen after the
// scaling, but costs nothing to check) leaves the call to GMP.
// The result: the sign, or kUndecided.
constexpr int kUndecided = 2;

int orient3d_filter(const double (&in)[12], int shift) {
  using namespace detail;
  double v[12];
  for (int i = 0; i < 12; ++i)
    v[i] = std::ldexp(in[i], shift);
  const double adx = sub_rn(v[0], v[9]), bdx = sub_rn(v[3], v[9]), cdx = sub_rn(v[6], v[9]);
  const double ady = sub_rn(v[1], v[10]), bdy = sub_rn(v[4], v[10]), cdy = sub_rn(v[7], v[10]);
  const double adz = sub_rn(v[2], v[11]), bdz = sub_rn(v[5], v[11]), cdz = sub_rn(v[8], v[11]);
  const double bdxcdy = mul_rn(bdx, cdy), cdxbdy = mul_rn(cdx, bdy);
  const double cdxady = mul_rn(cdx, ady), adxcdy = mul_rn(adx, cdy);
  const double adxbdy = mul_rn(adx, bdy), bdxady = mul_rn(bdx, ady);
  const double det = add_rn(add_rn(mul_rn(adz, sub_rn(bdxcdy, cdxbdy)), mul_rn(bdz, sub_rn(cdxady, adxcdy))),
                            mul_rn(cdz, sub_rn(adxbdy, bdxady)));
  const double permanent = add_rn(add_rn(mul_rn(add_rn(abs_d(bdxcdy), abs_d(cdxbdy)), abs_d(adz)),
                                         mul_rn(add_rn(abs_d(cdxady), abs_d(adxcdy)), abs_d(bdz))),
                                  mul_rn(add_rn(abs_d(adxbdy), abs_d(bdxady)), abs_d(cdz)));
  if (!(permanent <= std::numeric_limits<double>::max())) return kUndecided;
  const double rounding = mul_rn(add_rn(add_rn(add_rn(abs_d(adz), abs_d(bdz)), abs_d(cdz)), 1.0), 0x1p-1070);
  const double bound = add_rn(add_rn(mul_rn(0x1p-50, permanent), rounding), shift < 0 ? 0x1p-460 : 0.0);
  if (abs_d(det) > bound) return -sign_of(det);  // Shewchuk's determinant is positive when d is below
  return kUndecided;
}

int orient2d_filter(const double (&in)[6], int shift) {
  using namespace detail;
  double v[6];
  for (int i = 0; i < 6; ++i)
    v[i] = std::ldexp(in[i], shift);
  const double detleft = mul_rn(sub_rn(v[0], v[4]), sub_rn(v[3], v[5]));
  const double detright = mul_rn(sub_rn(v[1], v[5]), sub_rn(v[2], v[4]));
  const double det = sub_rn(detleft, detright);
  const double permanent = add_rn(abs_d(detleft), abs_d(detright));
  if (!(permanent <= std::numeric_limits<double>::max())) return kUndecided;
  // 4 eps against Shewchuk's 3 eps + 16 eps^2.
  const double bound = add_rn(add_rn(mul_rn(0x1p-51, permanent), 0x1p-1072), shift < 0 ? 0x1p-760 : 0.0);
  if (abs_d(det) > bound) return sign_of(det);
  return kUndecided;
}

void pack(const Vec3d& p, double* v) {
  v[0] = p.x, v[1] = p.y, v[2] = p.z;
}
Vec3d unpack(const double* v) {
  return {v[0], v[1], v[2]};
}

}  // namespace

int orient3d_wide(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  double v[12];
  pack(a, v), pack(b, v + 3), pack(c, v + 6), pack(d, v + 9);
  int shift = 0;
  switch (choose_stage(v, 12, shift)) {
    case Stage::kZero:
      return 0;
    case Stage::kFast:
      return orient3d(a, b, c, d);
    case Stage::kScaled:
      scale(v, 12, shift);
      return orient3d(unpack(v), unpack(v + 3), unpack(v + 6), unpack(v + 9));
    case Stage::kGmp:
      break;
  }
  const int s = orient3d_filter(v, shift);
  return s != kUndecided ? s : orient3d_integers(v);
}

int orient2d_wide(double ax, double ay, double bx, double by, double cx, double cy) {
  double v[6] = {ax, ay, bx, by, cx, cy};
  int shift = 0;
  switch (choose_stage(v, 6, shift)) {
    case Stage::kZero:
      return 0;
    case Stage::kFast:
      return orient2d(ax, ay, bx, by, cx, cy);
    case Stage::kScaled:
      scale(v, 6, shift);
      return orient2d(v[0], v[1], v[2], v[3], v[4], v[5]);
    case Stage::kGmp:
      break;
  }
  const int s = orient2d_filter(v, shift);
  return s != kUndecided ? s : orient2d_integers(v);
}

bool collinear3d_wide(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  double v[9];
  pack(a, v), pack(b, v + 3), pack(c, v + 6);
  int shift = 0;
  switch (choose_stage(v, 9, shift)) {
    case Stage::kZero:
      return true;
    case Stage::kFast:
      return collinear3d(a, b, c);
    case Stage::kScaled:
      scale(v, 9, shift);
      return collinear3d(unpack(v), unpack(v + 3), unpack(v + 6));
    case Stage::kGmp:
      break;
  }
  // Collinear iff the three projections of the cross product (orient2d on (x,y), (y,z), (z,x)) vanish: one
  // that the filter proves nonzero settles it.
  for (int k = 0; k < 3; ++k) {
    const int u = k, w = (k + 1) % 3;
    const double p[6] = {v[u], v[w], v[3 + u], v[3 + w], v[6 + u], v[6 + w]};
    const int s = orient2d_filter(p, shift);  // the call's shift: every magnitude of p is below 2^300
    if (s != kUndecided && s != 0) return false;
  }
  return collinear3d_integers(v);
}

namespace detail {

int orient3d_gmp(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  double v[12];
  pack(a, v), pack(b, v + 3), pack(c, v + 6), pack(d, v + 9);
  return orient3d_integers(v);
}

int orient2d_gmp(double ax, double ay, double bx, double by, double cx, double cy) {
  double v[6] = {ax, ay, bx, by, cx, cy};
  return orient2d_integers(v);
}

bool collinear3d_gmp(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  double v[9];
  pack(a, v), pack(b, v + 3), pack(c, v + 6);
  return collinear3d_integers(v);
}

}  // namespace detail
}  // namespace cudahull
