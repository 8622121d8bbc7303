// The exact 2D hull of coplanar sites (hull_2d, exact_lower_dimension.hpp): Andrew's monotone chain on a
// projection, with exact orient2d.
#include "exact_lower_dimension.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/wide_predicates.hpp"
#include "exact_vector.hpp"

namespace cudahull::exact {

template <class Pred>
std::vector<std::uint32_t> hull_2d(const std::vector<Vec3d>& p, const Basis& bs) {
  const Vec3d a = p[bs.a], b = p[bs.b], c = p[bs.c];
  auto coord = [](const Vec3d& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
  int sign_n[3];
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    sign_n[k] = Pred::orient2d(coord(a, u), coord(a, v), coord(b, u), coord(b, v), coord(c, u), coord(c, v));
  }
  const int sigma = sign_n[0] != 0 ? sign_n[0] : sign_n[1] != 0 ? sign_n[1] : sign_n[2];
  // Drop the dominant axis (better conditioned projection) among those with an exactly non-zero component.
  const Vec3d nrm = cross(sub(b, a), sub(c, a));
  int k = -1;
  double best = -1;
  for (int t = 0; t < 3; ++t) {
    const double mag = std::fabs(coord(nrm, t));
    if (sign_n[t] != 0 && (k < 0 || mag > best)) best = mag, k = t;  // k < 0: NaN for huge doubles
  }
  const int u = (k + 1) % 3, v = (k + 2) % 3;

  const std::uint32_t m = static_cast<std::uint32_t>(p.size());
  std::vector<std::uint32_t> order(m);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
    const double iu = coord(p[i], u), ju = coord(p[j], u);
    if (iu != ju) return iu < ju;
    return coord(p[i], v) < coord(p[j], v);
  });
  auto turn = [&](std::uint32_t i, std::uint32_t j, std::uint32_t l) {
    return Pred::orient2d(coord(p[i], u), coord(p[i], v), coord(p[j], u), coord(p[j], v), coord(p[l], u),
                          coord(p[l], v));
  };
  // Distinct coplanar points project to distinct points, so the chain is well defined; popping on <= 0
  // removes collinear points, leaving strict corners.
  std::vector<std::uint32_t> h(2 * m);
  std::size_t len = 0;
  for (std::uint32_t i = 0; i < m; ++i) {
    while (len >= 2 && turn(h[len - 2], h[len - 1], order[i]) <= 0)
      --len;
    h[len++] = order[i];
  }
  for (std::size_t i = m - 1, lower = len + 1; i-- > 0;) {
    while (len >= lower && turn(h[len - 2], h[len - 1], order[i]) <= 0)
      --len;
    h[len++] = order[i];
  }
  h.resize(len - 1);  // the last point repeats the first
  if (sigma * sign_n[k] < 0) std::reverse(h.begin(), h.end());
  // Start at the lexicographically smallest corner.
  std::rotate(h.begin(),
              std::min_element(h.begin(), h.end(),
                               [&](std::uint32_t i, std::uint32_t j) { return lex_less(p[i], p[j]); }),
              h.end());
  return h;
}

// The two predicate policies; one implementation.
template std::vector<std::uint32_t> hull_2d<FastPredicates>(const std::vector<Vec3d>&, const Basis&);
template std::vector<std::uint32_t> hull_2d<WidePredicates>(const std::vector<Vec3d>&, const Basis&);

}  // namespace cudahull::exact
