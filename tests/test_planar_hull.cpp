// planar_hull() (api/src/planar_hull.hpp), the exact 2-D hull behind the API's 2-D input, against a
// brute-force oracle: a point is a strict corner when some line through it and another point has every
// point on or left of it and none on it behind it.  Small random inputs (uniform, integer grids full of
// collinear points and duplicates, circles, near-collinear doubles a few ulps apart, float input, magnitudes
// from 2^-250 to 2^250) and every degenerate case; large inputs, which take the parallel paths and the
// sampled rounds, against a linear check of the result (every point on or inside every edge).
#include "../api/src/planar_hull.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cudahull/predicates.hpp"

namespace cudahull {
namespace {

using Key = std::pair<double, double>;  // (x, y): its order is the (x, y) order the contract names

template <class T>
Key key_of(const std::vector<T>& xy, std::size_t i) {
  return {static_cast<double>(xy[2 * i]), static_cast<double>(xy[2 * i + 1])};
}

int orient(const Key& a, const Key& b, const Key& c) {
  return orient2d(a.first, a.second, b.first, b.second, c.first, c.second);
}

// The lowest index of each distinct point.
template <class T>
std::map<Key, PointIndex> lowest_indices(const std::vector<T>& xy) {
  std::map<Key, PointIndex> lowest;
  for (std::size_t i = 0; i < xy.size() / 2; ++i)
    lowest.emplace(key_of(xy, i), static_cast<PointIndex>(i));  // emplace keeps the first
  return lowest;
}

// The oracle, O(d^3) in the d distinct points.
struct Expected {
  int dimension = -1;
  std::set<Key> corners;
};

Expected brute_force(const std::vector<Key>& distinct) {
  Expected e;
  const std::size_t d = distinct.size();
  if (d == 0) return e;
  if (d == 1) {
    e.dimension = 0;
    e.corners.insert(distinct[0]);
    return e;
  }
  e.dimension = 1;
  for (const Key& r : distinct)
    if (orient(distinct[0], distinct[1], r) != 0) e.dimension = 2;
  for (const Key& v : distinct) {
    for (const Key& w : distinct) {
      if (w == v) continue;
      // v is an end of the face that the line v w supports, on the side away from w: a vertex.
      bool supports = true;
      for (const Key& r : distinct) {
        const int side = orient(v, w, r);
        const bool behind = side == 0 && (w < v ? v < r : r < v);
        if (side < 0 || behind) {
          supports = false;
          break;
        }
      }
      if (supports) {
        e.corners.insert(v);
        break;
      }
    }
  }
  return e;
}

// Checks `hull` for `xy` against the oracle; `what` names the case in failures.
template <class T>
void check_small(const std::vector<T>& xy, const PlanarHull& hull, const std::string& what) {
  SCOPED_TRACE(what);
  const std::map<Key, PointIndex> lowest = lowest_indices(xy);
  std::vector<Key> distinct;
  for (const auto& entry : lowest)
    distinct.push_back(entry.first);
  const Expected expected = brute_force(distinct);
  ASSERT_EQ(hull.dimension, expected.dimension);
  std::set<Key> got;
  for (PointIndex v : hull.polygon) {
    ASSERT_LT(v, xy.size() / 2);
    const Key k = key_of(xy, v);
    EXPECT_EQ(v, lowest.at(k)) << "not the lowest index of its coordinates";
    EXPECT_TRUE(got.insert(k).second) << "a corner twice";
  }
  EXPECT_EQ(got, expected.corners);
  if (hull.dimension == -1) {
    EXPECT_TRUE(hull.polygon.empty());
  }
  if (hull.dimension == 0) {
    EXPECT_EQ(hull.polygon.size(), 1u);
  }
  if (hull.dimension == 1) {
    ASSERT_EQ(hull.polygon.size(), 2u);
    EXPECT_LT(key_of(xy, hull.polygon[0]), key_of(xy, hull.polygon[1]));
  }
  if (hull.dimension != 2) return;
  const std::size_t m = hull.polygon.size();
  ASSERT_GE(m, 3u);
  EXPECT_EQ(key_of(xy, hull.polygon[0]), *expected.corners.begin()) << "not started at the lowest corner";
  for (std::size_t k = 0; k < m; ++k) {
    const Key a = key_of(xy, hull.polygon[k]), b = key_of(xy, hull.polygon[(k + 1) % m]);
    EXPECT_GT(orient(a, b, key_of(xy, hull.polygon[(k + 2) % m])), 0) << "not a left turn at " << k;
    // Every other corner strictly left of each edge: a convex polygon, once around (a star polygon turns
    // left at every corner too).
    for (std::size_t j = 0; j < m; ++j)
      if (j != k && j != (k + 1) % m) {
        EXPECT_GT(orient(a, b, key_of(xy, hull.polygon[j])), 0);
      }
  }
}

// For large inputs: the result is a strictly convex counter-clockwise polygon of input points (each the
// lowest index of its coordinates, the first the lowest) with every input point on or inside it.  Then its
// corners are exactly the strictly extreme points.  O(n log n): each point located in the fan from corner 0.
template <class T>
void check_large(const std::vector<T>& xy, const PlanarHull& hull, const std::string& what) {
  SCOPED_TRACE(what);
  const std::size_t n = xy.size() / 2;
  ASSERT_EQ(hull.dimension, 2);
  const std::size_t m = hull.polygon.size();
  ASSERT_GE(m, 3u);
  std::vector<Key> c(m);
  for (std::size_t k = 0; k < m; ++k) {
    ASSERT_LT(hull.polygon[k], n);
    c[k] = key_of(xy, hull.polygon[k]);
  }
  for (std::size_t k = 1; k < m; ++k)
    ASSERT_LT(c[0], c[k]) << "not started at the lowest corner";
  for (std::size_t k = 0; k < m; ++k)
    ASSERT_GT(orient(c[k], c[(k + 1) % m], c[(k + 2) % m]), 0) << "not a left turn at " << k;
  // Once around: the corners' directions from corner 0 turn counter-clockwise, less than half a turn in all
  // (corner 0 is the lowest, so the others lie in a half-plane).
  for (std::size_t k = 1; k + 1 < m; ++k)
    ASSERT_GT(orient(c[0], c[k], c[k + 1]), 0);
  auto inside_or_on = [&](const Key& p) {
    if (orient(c[0], c[1], p) < 0 || orient(c[0], c[m - 1], p) > 0) return false;
    // The last k in [1, m - 1] with p on or left of the ray c0 -> ck.
    std::size_t lo = 1, hi = m - 1;
    while (lo < hi) {
      const std::size_t mid = (lo + hi + 1) / 2;
      if (orient(c[0], c[mid], p) >= 0)
        lo = mid;
      else
        hi = mid - 1;
    }
    if (lo == m - 1) return !(p < std::min(c[0], c[m - 1])) && !(std::max(c[0], c[m - 1]) < p);
    return orient(c[lo], c[lo + 1], p) >= 0;
  };
  std::size_t outside = 0;
  for (std::size_t i = 0; i < n && outside < 10; ++i)
    if (!inside_or_on(key_of(xy, i))) {
      ++outside;
      ADD_FAILURE() << "point " << i << " outside";
    }
  // The lowest index of each corner's coordinates.
  std::vector<std::pair<Key, PointIndex>> sorted(n);
  for (std::size_t i = 0; i < n; ++i)
    sorted[i] = {key_of(xy, i), static_cast<PointIndex>(i)};
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < m; ++k) {
    const auto first = std::lower_bound(sorted.begin(), sorted.end(), std::pair{c[k], PointIndex{0}});
    EXPECT_EQ(hull.polygon[k], first->second) << "not the lowest index at corner " << k;
  }
}

template <class T>
PlanarHull run(const std::vector<T>& xy) {
  return planar_hull(xy.data(), xy.size() / 2);
}

// --- small inputs against the oracle -------------------------------------------------------------------

TEST(PlanarHull, NoPoints) {
  const PlanarHull hull = planar_hull(static_cast<const double*>(nullptr), 0);
  EXPECT_EQ(hull.dimension, -1);
  EXPECT_TRUE(hull.polygon.empty());
  EXPECT_EQ(planar_hull(static_cast<const float*>(nullptr), 0).dimension, -1);
}

TEST(PlanarHull, DegenerateInputs) {
  const std::vector<std::pair<std::string, std::vector<double>>> cases = {
      {"one point", {3, 4}},
      {"all identical", {1.5, -2, 1.5, -2, 1.5, -2, 1.5, -2}},
      {"two distinct", {1, 1, 0, 0}},
      {"two distinct with duplicates", {1, 1, 0, 0, 1, 1, 0, 0, 0, 0}},
      {"vertical segment", {0, 3, 0, 1, 0, 2, 0, 1, 0, 3}},
      {"horizontal segment", {5, 0, -1, 0, 2, 0, 5, 0}},
      {"diagonal segment with its middle first", {2, 2, 1, 1, 3, 3, 0, 0, 3, 3}},
      {"triangle", {0, 0, 1, 0, 0, 1}},
      {"clockwise triangle", {0, 0, 0, 1, 1, 0}},
      {"square with its centre and edge midpoints",
       {0.5, 0.5, 0, 0, 1, 0, 1, 1, 0, 1, 0.5, 0, 1, 0.5, 0.5, 1, 0, 0.5}},
      {"collinear but one", {0, 0, 1, 1, 2, 2, 3, 3, 1, 2}},
      {"a corner repeated, the later copy first in x", {1, 0, 0, 0, 0, 1, 0, 0}},
  };
  for (const auto& [what, xy] : cases)
    check_small(xy, run(xy), what);
  // The named indices, spelled out.
  EXPECT_EQ(run(std::vector<double>{1.5, -2, 1.5, -2}).polygon, (std::vector<PointIndex>{0}));
  EXPECT_EQ(run(std::vector<double>{1, 1, 0, 0, 1, 1, 0, 0}).polygon, (std::vector<PointIndex>{1, 0}));
  EXPECT_EQ(run(std::vector<double>{0, 3, 0, 1, 0, 2, 0, 1, 0, 3}).polygon, (std::vector<PointIndex>{1, 0}));
  EXPECT_EQ(run(std::vector<double>{0, 0, 0, 1, 1, 0}).polygon, (std::vector<PointIndex>{0, 2, 1}));
  EXPECT_EQ(
      run(std::vector<double>{0.5, 0.5, 0, 0, 1, 0, 1, 1, 0, 1, 0.5, 0, 1, 0.5, 0.5, 1, 0, 0.5}).polygon,
      (std::vector<PointIndex>{1, 2, 3, 4}));
}

// Random small inputs of many kinds, each against the oracle.
TEST(PlanarHull, RandomSmallAgainstBruteForce) {
  std::mt19937_64 rng(20250601);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  auto integer = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  int cases = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int kind = trial % 10;
    const std::size_t n = static_cast<std::size_t>(integer(1, 28));
    std::vector<double> xy;
    std::string what;
    switch (kind) {
      case 0:  // uniform in a square
        what = "uniform";
        for (std::size_t i = 0; i < n; ++i)
          xy.insert(xy.end(), {uniform(-1, 1), uniform(-1, 1)});
        break;
      case 1:  // a small integer grid: collinear points and duplicates everywhere
        what = "grid";
        for (std::size_t i = 0; i < n; ++i)
          xy.insert(xy.end(), {double(integer(0, 3)), double(integer(0, 3))});
        break;
      case 2: {  // a few points, each repeated
        what = "duplicates";
        std::vector<double> base;
        const int distinct = integer(1, 5);
        for (int k = 0; k < distinct; ++k)
          base.insert(base.end(), {uniform(-1, 1), uniform(-1, 1)});
        for (std::size_t i = 0; i < n; ++i) {
          const int k = integer(0, distinct - 1);
          xy.insert(xy.end(), {base[2 * k], base[2 * k + 1]});
        }
        break;
      }
      case 3: {  // near a circle (cos and sin rounded), and its centre
        what = "circle";
        const double r = uniform(0.5, 4);
        for (std::size_t i = 0; i < n; ++i) {
          const double t = uniform(0, 2 * std::numbers::pi);
          xy.insert(xy.end(), {r * std::cos(t), r * std::sin(t)});
        }
        xy.insert(xy.end(), {0, 0});
        break;
      }
      case 4: {  // near-collinear: coordinates a few ulps from 1, on and off the diagonal
        what = "near-collinear";
        const double eps = std::ldexp(1.0, -52);
        for (std::size_t i = 0; i < n; ++i) {
          const int k = integer(0, 6);
          xy.insert(xy.end(), {1 + k * eps, 1 + (k + integer(-1, 1) * (integer(0, 3) == 0)) * eps});
        }
        break;
      }
      case 5: {  // collinear along a random line through integer points, in exact double steps
        what = "collinear";
        const double ax = integer(-5, 5), ay = integer(-5, 5), dx = integer(-3, 3), dy = integer(-3, 3);
        for (std::size_t i = 0; i < n; ++i) {
          const int t = integer(-4, 4);
          xy.insert(xy.end(), {ax + t * dx, ay + t * dy});
        }
        break;
      }
      case 6: {  // magnitudes from 2^-250 to 2^250: a grid scaled by a power of two, and mixed scales
        what = "scaled";
        const int e = integer(-250 + 2, 250 - 2);
        for (std::size_t i = 0; i < n; ++i)
          xy.insert(xy.end(), {std::ldexp(integer(-2, 2), e), std::ldexp(integer(-2, 2), e)});
        break;
      }
      case 7: {
        what = "mixed magnitudes";
        for (std::size_t i = 0; i < n; ++i) {
          auto coordinate = [&] {
            const int which = integer(0, 3);
            if (which == 0) return 0.0;
            return std::ldexp(uniform(1, 2) * (integer(0, 1) ? 1 : -1), which == 1   ? -250
                                                                        : which == 2 ? 0
                                                                                     : 249);
          };
          xy.insert(xy.end(), {coordinate(), coordinate()});
        }
        break;
      }
      case 8: {  // collinear but for one point a hair off the line
        what = "collinear but one";
        for (std::size_t i = 0; i < n; ++i) {
          const double t = integer(-8, 8);
          xy.insert(xy.end(), {t * 3, t * 5});
        }
        const std::size_t at = static_cast<std::size_t>(integer(0, static_cast<int>(n) - 1));
        xy[2 * at + 1] += std::ldexp(1.0, -40) * (integer(0, 1) ? 1 : -1);
        break;
      }
      default: {  // large uniform magnitudes with small offsets: rounding in the filter's choices
        what = "offset";
        const double base = std::ldexp(1.0, integer(20, 50));
        for (std::size_t i = 0; i < n; ++i)
          xy.insert(xy.end(), {base + integer(-3, 3), base + integer(-3, 3) * 2.0});
        break;
      }
    }
    check_small(xy, run(xy), what + " #" + std::to_string(trial));
    // The same points as float where that is exact for the kinds whose coordinates floats hold.
    if (kind == 0 || kind == 1 || kind == 3 || kind == 5 || kind == 8) {
      const std::vector<float> xf(xy.begin(), xy.end());
      check_small(xf, run(xf), what + " as float #" + std::to_string(trial));
    }
    ++cases;
    if (HasFailure()) break;
  }
  EXPECT_EQ(cases, 3000);
}

// Permuting the input changes only which duplicate is named; shuffled copies against the oracle.
TEST(PlanarHull, ShuffledGridsWithDuplicates) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> xy;
    for (int x = 0; x < 5; ++x)
      for (int y = 0; y < 5; ++y)
        if ((x + 2 * y + trial) % 3 != 0)
          for (int copies = 0; copies <= (x * y + trial) % 3; ++copies)
            xy.insert(xy.end(), {double(x), double(y)});
    std::vector<std::size_t> order(xy.size() / 2);
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<double> shuffled;
    for (std::size_t i : order)
      shuffled.insert(shuffled.end(), {xy[2 * i], xy[2 * i + 1]});
    check_small(shuffled, run(shuffled), "shuffled grid #" + std::to_string(trial));
  }
}

// --- large inputs: the parallel passes, the sampled rounds and the fallbacks -----------------------------

std::vector<double> uniform_points(std::size_t n, bool disc, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> xy;
  xy.reserve(2 * n);
  while (xy.size() < 2 * n) {
    const double x = u(rng), y = u(rng);
    if (!disc || x * x + y * y <= 1) xy.insert(xy.end(), {x, y});
  }
  return xy;
}

TEST(PlanarHull, LargeUniform) {
  std::mt19937_64 rng(11);
  for (bool disc : {false, true}) {
    const std::vector<double> xy = uniform_points(300000, disc, rng);
    check_large(xy, run(xy), disc ? "disc" : "square");
    const std::vector<float> xf(xy.begin(), xy.end());
    check_large(xf, run(xf), disc ? "float disc" : "float square");
  }
}

// Every point on the hull (near a circle, integer points on an exact one): nothing is filtered.
TEST(PlanarHull, LargeCircle) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(0, 2 * std::numbers::pi);
  std::vector<double> xy;
  for (int i = 0; i < 100000; ++i) {
    const double t = u(rng);
    xy.insert(xy.end(), {std::cos(t), std::sin(t)});
  }
  check_large(xy, run(xy), "near a circle");
  // x^2 + y^2 = 5^2 * 13^2 * 17^2 has many integer solutions; with duplicates and the centre.
  std::vector<double> lattice;
  const long r2 = 5L * 5 * 13 * 13 * 17 * 17;
  for (long x = -1105; x <= 1105; ++x) {
    const long y = std::lround(std::sqrt(double(r2 - x * x)));
    if (x * x + y * y == r2)
      for (long s : {1L, -1L})
        for (int copy = 0; copy < 3; ++copy)
          lattice.insert(lattice.end(), {double(x), double(s * y)});
  }
  lattice.insert(lattice.end(), {0, 0});
  check_large(lattice, run(lattice), "lattice circle");
  check_small(lattice, run(lattice), "lattice circle against the oracle");
}

// An unlucky sample: every 5th point (the sample's stride for this count) is near the centre, so round
// one's polygon is tiny and round two must do the filtering.
TEST(PlanarHull, UnluckySample) {
  std::mt19937_64 rng(13);
  std::vector<double> xy = uniform_points(300000, true, rng);
  for (std::size_t i = 0; i < 300000; i += 5)
    xy[2 * i] *= 1e-3, xy[2 * i + 1] *= 1e-3;
  check_large(xy, run(xy), "clustered sample");
  // A sample on a line: round one falls back to the extremes of every point.
  xy = uniform_points(300000, true, rng);
  for (std::size_t i = 0; i < 300000; i += 5)
    xy[2 * i + 1] = 0;
  check_large(xy, run(xy), "sample on a line");
}

TEST(PlanarHull, LargeDegenerate) {
  const std::size_t n = 200000;
  // All identical.
  std::vector<double> same(2 * n, 0.25);
  EXPECT_EQ(run(same).dimension, 0);
  EXPECT_EQ(run(same).polygon, (std::vector<PointIndex>{0}));
  // Collinear, the ends repeated: the lowest index of each end.
  std::vector<double> line;
  std::mt19937_64 rng(14);
  std::uniform_int_distribution<int> t(-1000, 1000);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = t(rng);
    line.insert(line.end(), {7 + 3 * s, -2 + 5 * s});
  }
  PlanarHull hull = run(line);
  ASSERT_EQ(hull.dimension, 1);
  auto first_at = [&](double s) {
    for (std::size_t i = 0; i < n; ++i)
      if (line[2 * i] == 7 + 3 * s) return static_cast<PointIndex>(i);
    return PointIndex{0xffffffff};
  };
  EXPECT_EQ(hull.polygon, (std::vector<PointIndex>{first_at(-1000), first_at(1000)}));
  // Vertical.
  std::vector<double> vertical;
  for (std::size_t i = 0; i < n; ++i)
    vertical.insert(vertical.end(), {-3, double(t(rng))});
  hull = run(vertical);
  ASSERT_EQ(hull.dimension, 1);
  EXPECT_EQ(vertical[2 * hull.polygon[0] + 1], -1000);
  EXPECT_EQ(vertical[2 * hull.polygon[1] + 1], 1000);
  // One point a hair off the line, wherever it is: a thin triangle (or quadrilateral, with both ends).
  for (std::size_t at : {std::size_t{0}, std::size_t{1}, n / 2 + 3, n - 1}) {
    std::vector<double> almost = line;
    almost[2 * at] = 7 + 3 * 17;
    almost[2 * at + 1] = -2 + 5 * 17 + std::ldexp(1.0, -30);
    check_large(almost, run(almost), "collinear but point " + std::to_string(at));
  }
}

// A grid with many duplicates and points inside edges, shuffled: lowest indices and no collinear corners.
TEST(PlanarHull, LargeGrid) {
  std::mt19937_64 rng(15);
  std::uniform_int_distribution<int> c(0, 300);
  std::vector<double> xy;
  for (int i = 0; i < 200000; ++i)
    xy.insert(xy.end(), {double(c(rng)), double(c(rng))});
  // A diamond's edges, |x - 150| + |y - 150| = 500, full of points, around the grid.
  for (int k = 0; k <= 1000; ++k)
    for (auto [x, y] : {std::pair{150 + 0.5 * k, -350 + 0.5 * k}, std::pair{650 - 0.5 * k, 150 + 0.5 * k},
                        std::pair{150 - 0.5 * k, 650 - 0.5 * k}, std::pair{-350 + 0.5 * k, 150 - 0.5 * k}})
      xy.insert(xy.end(), {x, y});
  const PlanarHull hull = run(xy);
  check_large(xy, hull, "grid in a diamond");
  EXPECT_EQ(hull.polygon.size(), 4u);
}

}  // namespace
}  // namespace cudahull
