// An exact reference for the predicate tests, independent of the expansion arithmetic under test: the signs
// of orient3d, orient2d and collinear3d in a small big integer; and a float moved by whole ulps.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <limits>

#include "cudahull/predicates.hpp"

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

// `x` moved by `steps` floats, up when positive, down when negative.
float ulp_step(float x, int steps) {
  float inf = std::numeric_limits<float>::infinity();
  for (int i = 0; i < std::abs(steps); ++i)
    x = std::nextafter(x, steps > 0 ? inf : -inf);
  return x;
}

}  // namespace
}  // namespace cudahull
