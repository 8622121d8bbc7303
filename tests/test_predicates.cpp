// Exact predicates (cudahull/predicates.hpp) against an independent exact reference, plus the Qhull
// reference wrapper (reference/qhull/qhull_reference.hpp).
#include "cudahull/predicates.hpp"

#include <cstring>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "cudahull/routing.hpp"
#include "qhull_reference.hpp"

namespace cudahull {
namespace {

// ---------------------------------------------------------------------------------------------------------
// Independent reference: every double is m * 2^e with an integer m of at most 53 bits.  Scaling all
// coordinates of a query by 2^-emin turns them into integers; the determinant is then evaluated in a small
// sign-magnitude big integer.  Shares nothing with the expansion arithmetic under test.
class BigInt {
 public:
  static constexpr int kLimbs = 80;  // 2560 bits: three products of ~ (2^128 / 2^-1074)-range differences

  BigInt() = default;
  // x * 2^-emin, which must be an integer.
  static BigInt from_scaled(double x, int emin) {
    BigInt r;
    if (x == 0) return r;
    int e = 0;
    double m = std::frexp(x, &e);
    auto mant = static_cast<std::int64_t>(std::ldexp(m, 53));
    int shift = e - 53 - emin;
    EXPECT_GE(shift, 0);
    r.neg_ = mant < 0;
    std::uint64_t mag = static_cast<std::uint64_t>(mant < 0 ? -mant : mant);
    int limb = shift / 32, bit = shift % 32;
    EXPECT_LT(limb + 3, kLimbs);
    unsigned __int128 v = static_cast<unsigned __int128>(mag) << bit;
    for (int i = 0; i < 3 && v != 0; ++i) {
      r.limb_[limb + i] = static_cast<std::uint32_t>(v);
      v >>= 32;
    }
    r.trim(kLimbs);
    return r;
  }
  // Exponent of the lowest set bit of x's 53-bit integer mantissa representation (for the common scale).
  static int low_exponent(double x) {
    int e = 0;
    std::frexp(x, &e);
    return e - 53;
  }

  int sign() const { return len_ == 0 ? 0 : (neg_ ? -1 : 1); }
  BigInt operator-() const {
    BigInt r = *this;
    if (r.len_ != 0) r.neg_ = !r.neg_;
    return r;
  }
  friend BigInt operator+(const BigInt& a, const BigInt& b) {
    if (a.neg_ == b.neg_) {
      BigInt r = add_mag(a, b);
      r.neg_ = a.len_ != 0 ? a.neg_ : b.neg_;
      if (r.len_ == 0) r.neg_ = false;
      return r;
    }
    int c = cmp_mag(a, b);
    if (c == 0) return BigInt();
    BigInt r = c > 0 ? sub_mag(a, b) : sub_mag(b, a);
    r.neg_ = c > 0 ? a.neg_ : b.neg_;
    return r;
  }
  friend BigInt operator-(const BigInt& a, const BigInt& b) { return a + (-b); }
  friend BigInt operator*(const BigInt& a, const BigInt& b) {
    BigInt r;
    if (a.len_ == 0 || b.len_ == 0) return r;
    EXPECT_LE(a.len_ + b.len_, kLimbs) << "reference big integer too small";
    for (int i = 0; i < a.len_; ++i) {
      std::uint64_t carry = 0;
      for (int j = 0; j < b.len_ && i + j < kLimbs; ++j) {
        std::uint64_t t = static_cast<std::uint64_t>(a.limb_[i]) * b.limb_[j] + r.limb_[i + j] + carry;
        r.limb_[i + j] = static_cast<std::uint32_t>(t);
        carry = t >> 32;
      }
      if (i + b.len_ < kLimbs) r.limb_[i + b.len_] = static_cast<std::uint32_t>(carry);
    }
    r.neg_ = a.neg_ != b.neg_;
    r.trim(std::min(kLimbs, a.len_ + b.len_));
    return r;
  }

 private:
  void trim(int n) {
    len_ = n;
    while (len_ > 0 && limb_[len_ - 1] == 0)
      --len_;
  }
  static int cmp_mag(const BigInt& a, const BigInt& b) {
    if (a.len_ != b.len_) return a.len_ < b.len_ ? -1 : 1;
    for (int i = a.len_ - 1; i >= 0; --i) {
      if (a.limb_[i] != b.limb_[i]) return a.limb_[i] < b.limb_[i] ? -1 : 1;
    }
    return 0;
  }
  static BigInt add_mag(const BigInt& a, const BigInt& b) {
    BigInt r;
    int n = std::max(a.len_, b.len_);
    std::uint64_t carry = 0;
    for (int i = 0; i < n; ++i) {
      std::uint64_t t = static_cast<std::uint64_t>(a.limb_[i]) + b.limb_[i] + carry;
      r.limb_[i] = static_cast<std::uint32_t>(t);
      carry = t >> 32;
    }
    EXPECT_TRUE(n < kLimbs || carry == 0);
    if (n < kLimbs) r.limb_[n] = static_cast<std::uint32_t>(carry);
    r.trim(std::min(n + 1, kLimbs));
    return r;
  }
  static BigInt sub_mag(const BigInt& a, const BigInt& b) {  // |a| > |b|
    BigInt r;
    std::int64_t borrow = 0;
    for (int i = 0; i < a.len_; ++i) {
      std::int64_t t = static_cast<std::int64_t>(a.limb_[i]) - b.limb_[i] - borrow;
      borrow = t < 0;
      r.limb_[i] = static_cast<std::uint32_t>(t + (borrow << 32));
    }
    r.trim(a.len_);
    return r;
  }

  std::array<std::uint32_t, kLimbs> limb_{};
  int len_ = 0;
  bool neg_ = false;
};

int common_low_exponent(std::initializer_list<double> values) {
  int emin = std::numeric_limits<int>::max();
  for (double v : values) {
    if (v != 0) emin = std::min(emin, BigInt::low_exponent(v));
  }
  return emin == std::numeric_limits<int>::max() ? 0 : emin;
}

int ref_orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  int e = common_low_exponent({a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z});
  auto big = [e](double v) { return BigInt::from_scaled(v, e); };
  BigInt ax = big(a.x), ay = big(a.y), az = big(a.z);
  BigInt ux = big(b.x) - ax, uy = big(b.y) - ay, uz = big(b.z) - az;
  BigInt vx = big(c.x) - ax, vy = big(c.y) - ay, vz = big(c.z) - az;
  BigInt wx = big(d.x) - ax, wy = big(d.y) - ay, wz = big(d.z) - az;
  // ((b - a) x (c - a)) . (d - a)
  BigInt det = (uy * vz - uz * vy) * wx + (uz * vx - ux * vz) * wy + (ux * vy - uy * vx) * wz;
  return det.sign();
}

int ref_orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  int e = common_low_exponent({ax, ay, bx, by, cx, cy});
  auto big = [e](double v) { return BigInt::from_scaled(v, e); };
  BigInt det = (big(bx) - big(ax)) * (big(cy) - big(ay)) - (big(by) - big(ay)) * (big(cx) - big(ax));
  return det.sign();
}

bool ref_collinear3d(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return ref_orient2d(a.x, a.y, b.x, b.y, c.x, c.y) == 0 && ref_orient2d(a.y, a.z, b.y, b.z, c.y, c.z) == 0 &&
         ref_orient2d(a.z, a.x, b.z, b.x, c.z, c.x) == 0;
}

// The determinant in plain double arithmetic, the way a naive implementation would do it.
int naive_orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  double wx = d.x - a.x, wy = d.y - a.y, wz = d.z - a.z;
  double det = (uy * vz - uz * vy) * wx + (uz * vx - ux * vz) * wy + (ux * vy - uy * vx) * wz;
  return (det > 0) - (det < 0);
}

Vec3d vf(float x, float y, float z) {
  return {x, y, z};
}

// Every property orient3d must have on one query; returns the reference sign.
int check_orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  int s = ref_orient3d(a, b, c, d);
  EXPECT_EQ(orient3d(a, b, c, d), s) << "a=(" << a.x << "," << a.y << "," << a.z << ") b=(" << b.x << ","
                                     << b.y << "," << b.z << ") c=(" << c.x << "," << c.y << "," << c.z
                                     << ") d=(" << d.x << "," << d.y << "," << d.z << ")";
  // Even permutations keep the sign, odd ones flip it.
  EXPECT_EQ(orient3d(b, c, a, d), s);
  EXPECT_EQ(orient3d(d, c, b, a), s);
  EXPECT_EQ(orient3d(b, a, c, d), -s);
  EXPECT_EQ(orient3d(a, b, d, c), -s);
  EXPECT_EQ(orient3d(d, b, c, a), -s);
  return s;
}

float ulp_step(float x, int steps) {
  float inf = std::numeric_limits<float>::infinity();
  for (int i = 0; i < std::abs(steps); ++i)
    x = std::nextafter(x, steps > 0 ? inf : -inf);
  return x;
}

// ---------------------------------------------------------------------------------------------------------
// orient3d

TEST(Orient3d, SignConvention) {
  Vec3d a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_EQ(orient3d(a, b, c, Vec3d{0, 0, 1}), 1);
  EXPECT_EQ(orient3d(a, b, c, Vec3d{0, 0, -1}), -1);
  EXPECT_EQ(orient3d(a, c, b, Vec3d{0, 0, 1}), -1);
  EXPECT_EQ(orient3d(a, b, c, Vec3d{5, -7, 0}), 0);
  EXPECT_GT(orient3d_fast(a, b, c, Vec3d{0, 0, 1}), 0.0);
  EXPECT_EQ(orient3d_fast(a, b, c, Vec3d{0, 0, 2}), 2.0);  // det[b-a, c-a, d-a] exactly
  EXPECT_LT(orient3d_fast(a, b, c, Vec3d{0, 0, -1}), 0.0);
  EXPECT_EQ(ref_orient3d(a, b, c, Vec3d{0, 0, 1}), 1);  // the reference agrees on the convention
}

TEST(Orient3d, DegenerateInputsGiveZero) {
  Vec3d a{1.5, -2, 3}, b{4, 0.25, -1}, c{-3, 2, 7};
  EXPECT_EQ(orient3d(a, a, a, a), 0);
  EXPECT_EQ(orient3d(a, b, c, a), 0);
  EXPECT_EQ(orient3d(a, b, c, b), 0);
  EXPECT_EQ(orient3d(a, a, b, c), 0);
  EXPECT_EQ(orient3d(a, b, Vec3d{a.x + 2 * (b.x - a.x), a.y + 2 * (b.y - a.y), a.z + 2 * (b.z - a.z)}, c), 0);
}

// Exactly coplanar float points (parallelogram d = b + c - a on an integer lattice, scaled by a power of
// two and translated) where the naive double determinant is often nonzero.
TEST(Orient3d, ExactlyCoplanarWhereNaiveDoubleFails) {
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<int> coord(-(1 << 21), (1 << 21));
  std::uniform_int_distribution<int> scale(-60, 60);
  int naive_wrong = 0;
  const int kCases = 20000;
  for (int i = 0; i < kCases; ++i) {
    int k = scale(rng);
    auto p = [&] { return std::array<int, 3>{coord(rng), coord(rng), coord(rng)}; };
    auto a = p(), b = p(), c = p();
    auto mk = [&](int x, int y, int z) {
      return vf(std::ldexp(float(x), k), std::ldexp(float(y), k), std::ldexp(float(z), k));
    };
    Vec3d va = mk(a[0], a[1], a[2]), vb = mk(b[0], b[1], b[2]), vc = mk(c[0], c[1], c[2]);
    Vec3d vd = mk(b[0] + c[0] - a[0], b[1] + c[1] - a[1], b[2] + c[2] - a[2]);  // |.| < 2^23: exact float
    ASSERT_EQ(check_orient3d(va, vb, vc, vd), 0);
    naive_wrong += naive_orient3d(va, vb, vc, vd) != 0;
  }
  EXPECT_GT(naive_wrong, kCases / 20) << "the test set should defeat naive double evaluation";
}

TEST(Orient3d, CoplanarConstructions) {
  // Identical z.
  EXPECT_EQ(orient3d(vf(0.1f, 0.7f, 3.3f), vf(-5e6f, 2.f, 3.3f), vf(1e-7f, 9e5f, 3.3f), vf(7.f, 7.f, 3.3f)),
            0);
  // On x + y + z = 2^20 with small integers scaled by powers of two.
  std::mt19937 rng(2);
  std::uniform_int_distribution<int> small(-1000, 1000);
  for (int i = 0; i < 2000; ++i) {
    auto p = [&] {
      float x = std::ldexp(float(small(rng)), -3), y = std::ldexp(float(small(rng)), 5);
      return vf(x, y, 1048576.f - x - y);  // exact: all terms are multiples of 2^-3 below 2^21
    };
    Vec3d a = p(), b = p(), c = p(), d = p();
    ASSERT_EQ(check_orient3d(a, b, c, d), 0);
    // One ulp off the plane is no longer coplanar (unless a, b, c are degenerate).
    Vec3d e{d.x, d.y, ulp_step(float(d.z), 1)};
    check_orient3d(a, b, c, e);
  }
  // Collinear a, b, c: every d is coplanar with them.
  Vec3d a = vf(1.25f, -3.5f, 1e3f), b = vf(9.75f, 6.5f, -2e3f);
  for (double t : {-4.0, -0.5, 0.25, 0.5, 1.0, 2.0, 1024.0}) {
    Vec3d c{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
    ASSERT_EQ(float(c.x), c.x);
    EXPECT_EQ(check_orient3d(a, b, c, vf(123.f, -77.f, 5e-3f)), 0);
  }
}

// Shewchuk-style: the query point is one ulp away from an exactly coplanar one, where the filter cannot
// decide and the exact stage must.
TEST(Orient3d, UlpPerturbationsNeedExactStage) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> coord(-(1 << 20), (1 << 20));
  std::uniform_int_distribution<int> steps(-3, 3), axis(0, 2);
  reset_predicate_stats();
  int positive = 0, negative = 0;
  for (int i = 0; i < 5000; ++i) {
    auto a = std::array<float, 3>{float(coord(rng)), float(coord(rng)), float(coord(rng))};
    auto b = std::array<float, 3>{float(coord(rng)), float(coord(rng)), float(coord(rng))};
    auto c = std::array<float, 3>{float(coord(rng)), float(coord(rng)), float(coord(rng))};
    std::array<float, 3> d{b[0] + c[0] - a[0], b[1] + c[1] - a[1], b[2] + c[2] - a[2]};
    int ax = axis(rng);
    d[ax] = ulp_step(d[ax], steps(rng));
    // Translate far away: differences stay exact, but the magnitudes defeat the filter even more.
    const float kOffset = 1 << 23;
    auto v = [&](const std::array<float, 3>& p) { return vf(p[0] / 64, p[1] / 64 + kOffset, p[2] / 64); };
    int s = check_orient3d(v(a), v(b), v(c), v(d));
    positive += s > 0;
    negative += s < 0;
  }
  EXPECT_GT(positive, 500);
  EXPECT_GT(negative, 500);
  PredicateStats stats = predicate_stats();
  EXPECT_EQ(stats.orient3d_calls, 5000u * 6u);
  EXPECT_GT(stats.orient3d_exact, 4000u);  // the coplanar ones and many perturbed ones need the exact stage
}

// 10^5 random near-degenerate float queries of several kinds against the big-integer reference.
TEST(Orient3d, RandomNearDegenerateFloatAgainstReference) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> unit(-1, 1), param(-3, 3);
  std::uniform_int_distribution<int> scale(-40, 40), kind(0, 3), ulps(-2, 2), axis(0, 2), bits(1, 24);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 100000; ++i) {
    double sc = std::ldexp(1.0, scale(rng));
    auto rp = [&] { return std::array<double, 3>{unit(rng) * sc, unit(rng) * sc, unit(rng) * sc}; };
    auto a = rp(), b = rp(), c = rp();
    std::array<double, 3> d{};
    switch (kind(rng)) {
      case 0: {  // near the plane: rounding to float moves it off (or not)
        double s = param(rng), t = param(rng);
        for (int j = 0; j < 3; ++j)
          d[j] = a[j] + s * (b[j] - a[j]) + t * (c[j] - a[j]);
        break;
      }
      case 1: {  // near a line through a and b (a, b, c nearly collinear), d anywhere
        double s = param(rng);
        for (int j = 0; j < 3; ++j)
          c[j] = a[j] + s * (b[j] - a[j]);
        d = rp();
        break;
      }
      case 2: {  // coordinates with few significant bits: many exact coplanarities
        int nb = bits(rng);
        auto q = [&](std::array<double, 3>& p) {
          for (double& x : p)
            x = std::ldexp(std::round(std::ldexp(x / sc, nb)), -nb) * sc;
        };
        q(a), q(b), q(c);
        double s = std::round(param(rng) * 4) / 4, t = std::round(param(rng) * 4) / 4;
        for (int j = 0; j < 3; ++j)
          d[j] = a[j] + s * (b[j] - a[j]) + t * (c[j] - a[j]);
        break;
      }
      default: {  // a far translation of a tiny configuration
        double off = std::ldexp(unit(rng), 20);
        for (int j = 0; j < 3; ++j) {
          a[j] = off + a[j] * 1e-6;
          b[j] = off + b[j] * 1e-6;
          c[j] = off + c[j] * 1e-6;
        }
        double s = param(rng), t = param(rng);
        for (int j = 0; j < 3; ++j)
          d[j] = a[j] + s * (b[j] - a[j]) + t * (c[j] - a[j]);
        break;
      }
    }
    auto f = [](const std::array<double, 3>& p) { return vf(float(p[0]), float(p[1]), float(p[2])); };
    Vec3d fd = f(d);
    int u = ulps(rng);
    if (u != 0) {
      double* coord = axis(rng) == 0 ? &fd.x : (axis(rng) == 1 ? &fd.y : &fd.z);
      *coord = ulp_step(float(*coord), u);
    }
    Vec3d fa = f(a), fb = f(b), fc = f(c);
    int s = ref_orient3d(fa, fb, fc, fd);
    ASSERT_EQ(orient3d(fa, fb, fc, fd), s) << "case " << i;
    ASSERT_EQ(orient3d(fb, fa, fc, fd), -s) << "case " << i;
    ++counts[s + 1];
  }
  // Sanity of the generator: all three outcomes well represented.
  EXPECT_GT(counts[0], 10000);
  EXPECT_GT(counts[1], 10000);
  EXPECT_GT(counts[2], 10000);
}

TEST(Orient3d, ExtremeMagnitudes) {
  const float kMax = std::numeric_limits<float>::max();
  const float kDenormMin = std::numeric_limits<float>::denorm_min();  // 1.4e-45
  const float kNormMin = std::numeric_limits<float>::min();
  std::vector<float> pool = {
      0.f,    kMax,    -kMax, kDenormMin, -kDenormMin, 2 * kDenormMin,   kNormMin,           1e30f, -1e30f,
      1e-30f, -1e-30f, 1.f,   -1.f,       3.f,         ulp_step(1.f, 1), ulp_step(kMax, -1), 1e38f, -3e-38f,
      7e-45f, 1e-40f};
  // Scaled copies of the canonical tetrahedron and of a coplanar configuration.
  for (float s : {kDenormMin, kNormMin, 1e-30f, 1e30f, 1e38f}) {
    EXPECT_EQ(check_orient3d(vf(0, 0, 0), vf(s, 0, 0), vf(0, s, 0), vf(0, 0, s)), 1) << s;
    EXPECT_EQ(check_orient3d(vf(0, 0, 0), vf(s, 0, 0), vf(0, s, 0), vf(s, s, 0)), 0) << s;
    EXPECT_EQ(check_orient3d(vf(s, s, s), vf(-s, s, -s), vf(s, -s, -s), vf(-s, -s, s)), 1) << s;
  }
  EXPECT_EQ(check_orient3d(vf(-kMax, -kMax, -kMax), vf(kMax, -kMax, -kMax), vf(-kMax, kMax, -kMax),
                           vf(kDenormMin, kDenormMin, kMax)),
            1);
  EXPECT_EQ(check_orient3d(vf(kDenormMin, 0, 0), vf(0, kDenormMin, 0), vf(0, 0, kDenormMin), vf(0, 0, 0)),
            -1);
  // Random mixtures drawn from the pool, many with huge cancellation.
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
  int nonzero = 0;
  for (int i = 0; i < 20000; ++i) {
    auto p = [&] { return vf(pool[pick(rng)], pool[pick(rng)], pool[pick(rng)]); };
    nonzero += check_orient3d(p(), p(), p(), p()) != 0;
  }
  EXPECT_GT(nonzero, 1000);
}

// Double (not float) inputs, including differences that are not exactly representable (the general exact
// path with two-component differences) and an engine-style double interior point.
TEST(Orient3d, DoubleInputs) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> scale(-60, 60), ulps(-2, 2);
  int zero = 0;
  for (int i = 0; i < 20000; ++i) {
    // Points on x + y + z = 0 with mixed magnitudes, where x + y is exact in double.
    auto p = [&] {
      for (;;) {
        double x = std::ldexp(std::round(std::ldexp(unit(rng), 20)), scale(rng));
        double y = std::ldexp(std::round(std::ldexp(unit(rng), 20)), scale(rng));
        double s = x + y;
        if (s - x == y && s - y == x) return Vec3d{x, y, -s};  // exact sum
      }
    };
    Vec3d a = p(), b = p(), c = p(), d = p();
    zero += check_orient3d(a, b, c, d) == 0;
    int u = ulps(rng);
    double z = d.z;
    for (int k = 0; k < std::abs(u); ++k)
      z = std::nextafter(z, u > 0 ? 1e300 : -1e300);
    check_orient3d(a, b, c, Vec3d{d.x, d.y, z});
  }
  EXPECT_EQ(zero, 20000);
  // Random doubles near a plane, wide exponent spread.
  for (int i = 0; i < 20000; ++i) {
    auto rp = [&] {
      return Vec3d{std::ldexp(unit(rng), scale(rng)), std::ldexp(unit(rng), scale(rng)),
                   std::ldexp(unit(rng), scale(rng))};
    };
    Vec3d a = rp(), b = rp(), c = rp();
    double s = unit(rng), t = unit(rng);
    Vec3d d{a.x + s * (b.x - a.x) + t * (c.x - a.x), a.y + s * (b.y - a.y) + t * (c.y - a.y),
            a.z + s * (b.z - a.z) + t * (c.z - a.z)};
    check_orient3d(a, b, c, d);
  }
  // A double centroid of float points against float faces.
  std::vector<Vec3d> pts;
  std::uniform_real_distribution<float> uf(-1, 1);
  for (int i = 0; i < 200; ++i)
    pts.push_back(vf(uf(rng), uf(rng), uf(rng)));
  Vec3d centroid{};
  for (const Vec3d& q : pts)
    centroid = {centroid.x + q.x / 3, centroid.y + q.y / 3, centroid.z + q.z / 3};
  for (std::size_t i = 0; i + 2 < pts.size(); ++i)
    check_orient3d(pts[i], pts[i + 1], pts[i + 2], centroid);
}

TEST(Orient3d, FastAgreesWhenFarFromDegenerate) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uf(-100, 100);
  for (int i = 0; i < 10000; ++i) {
    auto p = [&] { return vf(uf(rng), uf(rng), uf(rng)); };
    Vec3d a = p(), b = p(), c = p(), d = p();
    double fast = orient3d_fast(a, b, c, d);
    if (std::abs(fast) > 1e-6) {
      EXPECT_EQ((fast > 0) - (fast < 0), orient3d(a, b, c, d));
    }
  }
}

TEST(Orient3d, StatsCountAcrossThreads) {
  reset_predicate_stats();
  Vec3d a{0, 0, 0}, b{1, 0, 1}, c{0, 1, 1};
  auto work = [&] {
    for (int i = 0; i < 1000; ++i) {
      EXPECT_EQ(orient3d(a, b, c, Vec3d{1, 1, 3}), 1);  // filter decides
      EXPECT_EQ(orient3d(a, b, c, Vec3d{1, 1, 2}), 0);  // tilted coplanar: exact stage
      EXPECT_EQ(orient3d(Vec3d{0, 0, 5}, Vec3d{1, 0, 5}, Vec3d{0, 1, 5}, Vec3d{.5, .25, 5}),
                0);  // permanent 0
    }
  };
  std::thread t1(work), t2(work);
  t1.join();
  t2.join();
  work();  // this thread too
  PredicateStats stats = predicate_stats();
  EXPECT_EQ(stats.orient3d_calls, 9000u);
  EXPECT_EQ(stats.orient3d_exact, 3000u);
  reset_predicate_stats();
  EXPECT_EQ(predicate_stats().orient3d_calls, 0u);
  EXPECT_EQ(predicate_stats().orient3d_exact, 0u);
}

// ---------------------------------------------------------------------------------------------------------
// orient2d and collinear3d

// ---------------------------------------------------------------------------------------------------------
// The CUDA backend's prepared planes (routing.hpp, face_verdict_prepared): the same verdict and exit edge as
// face_verdict() and the same height bits as face_height(), on faces and points made to be degenerate.

TEST(PreparedPlanes, SameVerdictAndHeightAsFaceVerdict) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1), param(-2, 2);
  std::uniform_int_distribution<int> scale(-30, 30), kind(0, 5), ulps(-2, 2), bits(1, 12);
  const float kPool[] = {0.f, 1.f, -1.f, 1e30f, -1e30f, 1e-30f, 3e38f, -3e38f, 1e-40f, 7e-45f};
  int verdicts[3] = {0, 0, 0};
  unsigned long long fallbacks = 0;  // orient3d calls made by face_verdict_prepared
  const int cases = 200000;
  for (int i = 0; i < cases; ++i) {
    const double sc = std::ldexp(1.0, scale(rng));
    auto rp = [&] { return std::array<double, 3>{unit(rng) * sc, unit(rng) * sc, unit(rng) * sc}; };
    auto to_float = [](const std::array<double, 3>& p) {
      return Point3{float(p[0]), float(p[1]), float(p[2])};
    };
    FaceGeometry face{};
    Vec3d c;
    Point3 x;
    const int k = kind(rng);
    if (k == 5) {  // extreme magnitudes, mixed
      std::uniform_int_distribution<std::size_t> pick(0, std::size(kPool) - 1);
      auto p = [&] { return Point3{kPool[pick(rng)], kPool[pick(rng)], kPool[pick(rng)]}; };
      face.v[0] = p(), face.v[1] = p(), face.v[2] = p();
      const Point3 q = p();
      c = {(double(face.v[0].x) + face.v[1].x + face.v[2].x + q.x) / 4,
           (double(face.v[0].y) + face.v[1].y + face.v[2].y + q.y) / 4,
           (double(face.v[0].z) + face.v[1].z + face.v[2].z + q.z) / 4};
      x = p();
    } else {
      std::array<double, 3> v[3] = {rp(), rp(), rp()};
      if (k == 4) {  // few significant bits: exact coplanarities everywhere
        const int nb = bits(rng);
        for (auto& p : v)
          for (double& t : p)
            t = std::ldexp(std::round(std::ldexp(t / sc, nb)), -nb) * sc;
      }
      for (int j = 0; j < 3; ++j)
        face.v[j] = to_float(v[j]);
      const std::array<double, 3> q = rp();
      c = {(double(face.v[0].x) + face.v[1].x + face.v[2].x + float(q[0])) / 4,
           (double(face.v[0].y) + face.v[1].y + face.v[2].y + float(q[1])) / 4,
           (double(face.v[0].z) + face.v[1].z + face.v[2].z + float(q[2])) / 4};
      std::array<double, 3> target{};
      const double s = param(rng), t = param(rng);
      double inside[3] = {std::fabs(unit(rng)), std::fabs(unit(rng)), std::fabs(unit(rng))};
      const double sum = inside[0] + inside[1] + inside[2] + std::fabs(unit(rng));
      for (double& w : inside)
        w /= sum;
      const double cc[3] = {c.x, c.y, c.z};
      const int edge = static_cast<int>(rng() % 3);
      for (int j = 0; j < 3; ++j) {
        const double a = j == 0 ? face.v[edge].x : (j == 1 ? face.v[edge].y : face.v[edge].z);
        const int e2 = (edge + 1) % 3;
        const double b = j == 0 ? face.v[e2].x : (j == 1 ? face.v[e2].y : face.v[e2].z);
        const double v0 = j == 0 ? face.v[0].x : (j == 1 ? face.v[0].y : face.v[0].z);
        const double v1 = j == 0 ? face.v[1].x : (j == 1 ? face.v[1].y : face.v[1].z);
        const double v2 = j == 0 ? face.v[2].x : (j == 1 ? face.v[2].y : face.v[2].z);
        switch (k) {
          case 0:  // near the face's plane
          case 4:
            target[j] = v0 + s * (v1 - v0) + t * (v2 - v0);
            break;
          case 1:  // near a radial plane (c, v[edge], v[edge + 1])
            target[j] = cc[j] + s * (a - cc[j]) + t * (b - cc[j]);
            break;
          case 2:  // near the line from c through a corner
            target[j] = cc[j] + s * (a - cc[j]);
            break;
          default:  // inside the tetrahedron of c and the face (the internal verdict)
            target[j] =
                cc[j] + inside[0] * (v0 - cc[j]) + inside[1] * (v1 - cc[j]) + inside[2] * (v2 - cc[j]);
        }
      }
      x = to_float(target);
      float* coord = (rng() % 3 == 0) ? &x.x : (rng() % 2 ? &x.y : &x.z);
      *coord = ulp_step(*coord, ulps(rng));
    }
    face_tetrahedron_signs(c, face.v, face.tet);
    FacePlanes planes;
    prepare_face_planes(face, c, planes);
    int want_edge = 0, got_edge = 0;
    double height = 0;
    const PointVerdict want = face_verdict(face, c, x, &want_edge);
    const unsigned long long calls_before = predicate_stats().orient3d_calls;
    const PointVerdict got = face_verdict_prepared(face, planes, c, x, &got_edge, &height);
    fallbacks += predicate_stats().orient3d_calls - calls_before;
    ASSERT_EQ(got, want) << "case " << i << " kind " << k;
    ASSERT_EQ(got_edge, want_edge) << "case " << i << " kind " << k;
    const double expected_height = face_height(face, x);
    ASSERT_EQ(std::memcmp(&height, &expected_height, sizeof height), 0) << "case " << i << " kind " << k;
    ++verdicts[got];
  }
  // Both paths ran: most decisions without orient3d, and some (the degenerate cases) through it.
  std::printf("%d cases: %d internal, %d external, %d stray; %llu orient3d fallbacks\n", cases, verdicts[0],
              verdicts[1], verdicts[2], fallbacks);
  EXPECT_GT(fallbacks, 1000u);
  EXPECT_LT(fallbacks, static_cast<unsigned long long>(cases));
  EXPECT_GT(verdicts[0], cases / 50);
  EXPECT_GT(verdicts[1], cases / 10);
  EXPECT_GT(verdicts[2], cases / 50);
}

TEST(Orient2d, SignConventionAndBasics) {
  EXPECT_EQ(orient2d(0, 0, 1, 0, 0, 1), 1);
  EXPECT_EQ(orient2d(0, 0, 0, 1, 1, 0), -1);
  EXPECT_EQ(orient2d(0, 0, 1, 1, 2, 2), 0);
  EXPECT_EQ(orient2d(3, 3, 3, 3, 3, 3), 0);
  EXPECT_EQ(orient2d(1, 2, 1, 2, 5, 7), 0);
}

// Shewchuk's classic failure of the naive 2D test: a tiny grid near (0.5, 0.5) against the line through
// (12, 12) and (24, 24).
TEST(Orient2d, ShewchukGridAgainstReference) {
  int naive_wrong = 0;
  for (int i = 0; i < 256; ++i) {
    for (int j = 0; j < 256; ++j) {
      double x = 0.5 + i * std::ldexp(1.0, -53), y = 0.5 + j * std::ldexp(1.0, -53);
      int s = ref_orient2d(x, y, 12, 12, 24, 24);
      ASSERT_EQ(orient2d(x, y, 12, 12, 24, 24), s) << i << " " << j;
      ASSERT_EQ(orient2d(12, 12, 24, 24, x, y), s);
      ASSERT_EQ(orient2d(24, 24, 12, 12, x, y), -s);
      double naive = (12 - x) * (24 - y) - (12 - y) * (24 - x);
      naive_wrong += ((naive > 0) - (naive < 0)) != s;
    }
  }
  EXPECT_GT(naive_wrong, 1000);
}

TEST(Orient2d, RandomNearDegenerateAgainstReference) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> scale(-100, 100), ulps(-2, 2);
  for (int i = 0; i < 50000; ++i) {
    double sc = std::ldexp(1.0, scale(rng));
    float ax = float(unit(rng) * sc), ay = float(unit(rng) * sc), bx = float(unit(rng) * sc),
          by = float(unit(rng) * sc);
    double t = std::round(unit(rng) * 64) / 16;
    float cx = ulp_step(float(ax + t * (double(bx) - ax)), ulps(rng));
    float cy = ulp_step(float(ay + t * (double(by) - ay)), ulps(rng));
    int s = ref_orient2d(ax, ay, bx, by, cx, cy);
    ASSERT_EQ(orient2d(ax, ay, bx, by, cx, cy), s) << i;
    ASSERT_EQ(orient2d(bx, by, cx, cy, ax, ay), s) << i;
    ASSERT_EQ(orient2d(bx, by, ax, ay, cx, cy), -s) << i;
    // Double inputs with inexact differences.
    double dx = ax + std::ldexp(unit(rng), scale(rng)), dy = ay + std::ldexp(unit(rng), scale(rng));
    ASSERT_EQ(orient2d(dx, dy, bx, by, cx, cy), ref_orient2d(dx, dy, bx, by, cx, cy)) << i;
  }
}

TEST(Collinear3d, ExactConstructions) {
  Vec3d a = vf(1.5f, -2.25f, 1e6f), b = vf(-7.f, 3.75f, -3e5f);
  EXPECT_TRUE(collinear3d(a, a, a));
  EXPECT_TRUE(collinear3d(a, a, b));
  EXPECT_TRUE(collinear3d(a, b, b));
  for (double t : {-3.0, -0.125, 0.0, 0.5, 0.75, 1.0, 4.0}) {
    Vec3d c{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
    ASSERT_EQ(float(c.x), c.x);
    ASSERT_EQ(float(c.y), c.y);
    ASSERT_EQ(float(c.z), c.z);
    EXPECT_TRUE(collinear3d(a, b, c)) << t;
    EXPECT_TRUE(collinear3d(c, a, b)) << t;
    for (int axis = 0; axis < 3; ++axis) {
      Vec3d e = c;
      double* coord = axis == 0 ? &e.x : (axis == 1 ? &e.y : &e.z);
      *coord = ulp_step(float(*coord), 1);
      EXPECT_FALSE(collinear3d(a, b, e)) << t << " axis " << axis;
      EXPECT_EQ(collinear3d(a, b, e), ref_collinear3d(a, b, e));
    }
  }
  // Collinear in two projections but not the third.
  EXPECT_FALSE(collinear3d(Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{2, 0, 1e-30}));
  EXPECT_TRUE(collinear3d(Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{2e30, 0, 0}));
}

TEST(Collinear3d, RandomAgainstReference) {
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<int> coord(-(1 << 20), 1 << 20), ulps(-1, 1), scale(-30, 30), tq(-16, 16);
  int collinear = 0;
  for (int i = 0; i < 20000; ++i) {
    int k = scale(rng);
    auto p = [&] {
      return std::array<float, 3>{std::ldexp(float(coord(rng)), k), std::ldexp(float(coord(rng)), k),
                                  std::ldexp(float(coord(rng)), k)};
    };
    auto a = p(), b = p();
    double t = tq(rng) / 8.0;
    Vec3d va = vf(a[0], a[1], a[2]), vb = vf(b[0], b[1], b[2]);
    Vec3d vc = vf(ulp_step(float(a[0] + t * (double(b[0]) - a[0])), ulps(rng)),
                  ulp_step(float(a[1] + t * (double(b[1]) - a[1])), ulps(rng)),
                  ulp_step(float(a[2] + t * (double(b[2]) - a[2])), ulps(rng)));
    bool r = ref_collinear3d(va, vb, vc);
    ASSERT_EQ(collinear3d(va, vb, vc), r) << i;
    ASSERT_EQ(collinear3d(vc, vb, va), r) << i;
    collinear += r;
  }
  EXPECT_GT(collinear, 400);  // about 1/27 of the cases are not perturbed
  EXPECT_LT(collinear, 19000);
}

// ---------------------------------------------------------------------------------------------------------
// Qhull reference

TEST(QhullReference, CubeCornersPlusInteriorPoints) {
  std::vector<Point3> points;
  for (int i = 0; i < 8; ++i)
    points.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
  std::mt19937 rng(10);
  std::uniform_real_distribution<float> inner(0.1f, 0.9f);
  for (int i = 0; i < 500; ++i)
    points.push_back({inner(rng), inner(rng), inner(rng)});
  std::shuffle(points.begin(), points.end(), rng);
  QhullResult r = run_qhull(points);
  ASSERT_EQ(r.vertex_ids.size(), 8u);
  for (PointIndex id : r.vertex_ids) {
    const Point3& p = points.at(id);
    EXPECT_TRUE((p.x == 0 || p.x == 1) && (p.y == 0 || p.y == 1) && (p.z == 0 || p.z == 1));
  }
  EXPECT_TRUE(std::is_sorted(r.vertex_ids.begin(), r.vertex_ids.end()));
  EXPECT_EQ(r.facets, 12u);  // six squares, triangulated by Qt
  EXPECT_GE(r.milliseconds, 0.0);
}

TEST(QhullReference, RandomPointsGiveValidSortedIds) {
  std::mt19937 rng(11);
  std::normal_distribution<float> gauss;
  std::vector<Point3> points;
  for (int i = 0; i < 20000; ++i)
    points.push_back({gauss(rng), gauss(rng), gauss(rng)});
  QhullResult r = run_qhull(points);
  ASSERT_GE(r.vertex_ids.size(), 4u);
  EXPECT_TRUE(std::is_sorted(r.vertex_ids.begin(), r.vertex_ids.end()));
  EXPECT_EQ(std::set<PointIndex>(r.vertex_ids.begin(), r.vertex_ids.end()).size(), r.vertex_ids.size());
  for (PointIndex id : r.vertex_ids)
    EXPECT_LT(id, points.size());
  // A closed triangulated surface: F = 2V - 4.
  EXPECT_EQ(r.facets, 2 * r.vertex_ids.size() - 4);
  // Options are passed through.
  QhullResult again = run_qhull(points, "Qt Qbb");
  EXPECT_EQ(again.vertex_ids, r.vertex_ids);
}

TEST(QhullReference, SpherePointsAreAllVertices) {
  std::mt19937 rng(12);
  std::normal_distribution<double> gauss;
  std::vector<Point3> points;
  for (int i = 0; i < 2000; ++i) {
    double x = gauss(rng), y = gauss(rng), z = gauss(rng), n = std::sqrt(x * x + y * y + z * z);
    points.push_back({float(x / n), float(y / n), float(z / n)});
  }
  EXPECT_EQ(run_qhull(points).vertex_ids.size(), points.size());
}

TEST(QhullReference, DegenerateInputThrowsWithMessage) {
  std::vector<Point3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5f, 0.5f, 0}};
  try {
    run_qhull(flat);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("QH"), std::string::npos) << what;  // Qhull's own error code
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
  }
  EXPECT_THROW(run_qhull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), std::runtime_error);
  EXPECT_THROW(run_qhull({}), std::runtime_error);
}

}  // namespace
}  // namespace cudahull
