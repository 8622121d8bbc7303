// Synthetic point distributions.  The generator and the transforms are written here because the std::
// distributions are implementation-defined: the same seed must give the same points everywhere.  (The libm
// functions used, log/sqrt/sin/cos, are correctly rounded or nearly so on the usual C libraries.)
#include "cudahull/generators.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cudahull {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t rotl(std::uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

// xoshiro256** (Blackman and Vigna), seeded through splitmix64 as its authors recommend.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    for (std::uint64_t& word : s_)
      word = splitmix64(seed);
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  // Uniform in [0, 1) from the top 53 bits: every value is a multiple of 2^-53, exactly representable.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  // Uniform in [-1, 1).
  double symmetric() { return 2.0 * uniform() - 1.0; }

  // Standard normal by Box-Muller; the second value of each pair is kept for the next call.
  double normal() {
    if (have_spare_) {
      have_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform();  // (0, 1]: log never sees 0
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(kTwoPi * u2);
    have_spare_ = true;
    return r * std::cos(kTwoPi * u2);
  }

 private:
  std::uint64_t s_[4];
  bool have_spare_ = false;
  double spare_ = 0;
};

Point3 to_point(double x, double y, double z) {
  return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
}

// Smallest s with s^3 >= n.
std::size_t cube_side(std::size_t n) {
  std::size_t s = static_cast<std::size_t>(std::cbrt(static_cast<double>(n)));
  while (s * s * s < n)
    ++s;
  while (s > 0 && (s - 1) * (s - 1) * (s - 1) >= n)
    --s;
  return s;
}

std::size_t square_side(std::size_t n) {
  std::size_t s = static_cast<std::size_t>(std::sqrt(static_cast<double>(n)));
  while (s * s < n)
    ++s;
  return s;
}

struct NamedDistribution {
  Distribution dist;
  const char* name;
};

constexpr NamedDistribution kNames[] = {
    {Distribution::kCube, "cube"},
    {Distribution::kBall, "ball"},
    {Distribution::kSphere, "sphere"},
    {Distribution::kGauss, "gauss"},
    {Distribution::kParaboloid, "paraboloid"},
    {Distribution::kCylinder, "cylinder"},
    {Distribution::kGrid, "grid"},
};

}  // namespace

Distribution distribution_from_name(const std::string& name) {
  for (const NamedDistribution& d : kNames) {
    if (name == d.name) return d.dist;
  }
  std::string valid;
  for (const NamedDistribution& d : kNames)
    valid += (valid.empty() ? "" : ", ") + std::string(d.name);
  throw std::invalid_argument("unknown distribution '" + name + "' (valid: " + valid + ")");
}

std::string distribution_name(Distribution dist) {
  for (const NamedDistribution& d : kNames) {
    if (d.dist == dist) return d.name;
  }
  throw std::invalid_argument("unknown distribution value " + std::to_string(static_cast<int>(dist)));
}

std::vector<std::string> distribution_names() {
  std::vector<std::string> names;
  for (const NamedDistribution& d : kNames)
    names.emplace_back(d.name);
  return names;
}

std::vector<Point3> generate_points(Distribution dist, std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Point3> points;
  points.reserve(count);
  // `count` points of x, y, z drawn in that order from `draw`.
  auto independent_coordinates = [&](auto draw) {
    for (std::size_t i = 0; i < count; ++i) {
      const double x = draw(), y = draw(), z = draw();
      points.push_back(to_point(x, y, z));
    }
  };
  switch (dist) {
    case Distribution::kCube:
      independent_coordinates([&] { return rng.symmetric(); });
      break;
    case Distribution::kBall:
      while (points.size() < count) {
        const double x = rng.symmetric(), y = rng.symmetric(), z = rng.symmetric();
        if (x * x + y * y + z * z < 1.0) points.push_back(to_point(x, y, z));
      }
      break;
    case Distribution::kSphere:
      while (points.size() < count) {
        const double x = rng.normal(), y = rng.normal(), z = rng.normal();
        const double r = std::sqrt(x * x + y * y + z * z);
        if (r < 1e-30) continue;  // no direction to project; practically never happens
        points.push_back(to_point(x / r, y / r, z / r));
      }
      break;
    case Distribution::kGauss:
      independent_coordinates([&] { return rng.normal(); });
      break;
    case Distribution::kParaboloid:
      while (points.size() < count) {
        // x and y are rounded first so that z is the paraboloid at the stored x and y.
        const float x = static_cast<float>(rng.symmetric());
        const float y = static_cast<float>(rng.symmetric());
        const double r2 = double(x) * x + double(y) * y;
        if (r2 <= 1.0) points.push_back({x, y, static_cast<float>(r2)});
      }
      break;
    case Distribution::kCylinder: {
      // k rings of m points at the same angles: every ring is coplanar and every angle gives a vertical line
      // of k collinear points.  The seed only turns the whole cylinder about its axis.
      const std::size_t m = std::max<std::size_t>(3, square_side(count));
      const std::size_t k = (count + m - 1) / m;
      const double phase = kTwoPi * rng.uniform();
      for (std::size_t ring = 0; ring < k && points.size() < count; ++ring) {
        const double z = k == 1 ? 0.0 : -1.0 + 2.0 * double(ring) / double(k - 1);
        for (std::size_t j = 0; j < m && points.size() < count; ++j) {
          const double angle = phase + kTwoPi * double(j) / double(m);
          points.push_back(to_point(std::cos(angle), std::sin(angle), z));
        }
      }
      break;
    }
    case Distribution::kGrid: {
      // Integer coordinates, x fastest; the lattice has no randomness, so the seed is unused.
      const std::size_t side = cube_side(count);
      for (std::size_t i = 0; i < count; ++i) {
        points.push_back(to_point(double(i % side), double((i / side) % side), double(i / (side * side))));
      }
      break;
    }
  }
  return points;
}

}  // namespace cudahull
