// Step 4 of the merge (design: facet_merge.hpp): max_outside, a proven bound on how far any exact-hull
// vertex stands above a merged facet's plane, and the thinnest depth (Qhull's flatness test).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "box_tree.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/predicates.hpp"
#include "geometry.hpp"
#include "mesh_order.hpp"

namespace cudahull::merge {

// Step 4, the certificate: a proven upper bound on n . p + d over the exact hull's vertices and every
// merged facet's plane, in two parts.
//
// Rounding of one evaluation.  plane_value() is a dot product of length 4 (d times an exact 1) evaluated
// left to right, so its error is at most gamma_4 x S (Higham, Accuracy and Stability, 3.1), gamma_4 =
// 4u / (1 - 4u), S = sum |n_i p_i| + |d|.  S as computed is within gamma_3 of the exact sum, and the last
// addition below rounds once more (by at most u (|fl(value)| + e) <= u (1 + 13u) S).  So value + 8u x fl(S)
// exceeds the exact n . p + d: 8u fl(S) (1 - u) - u (1 + 13u) S > gamma_4 (1 + 4u) S.  The final maximum is
// stepped up one double, for underflow.
inline double bound_at(const Plane& plane, const Vec3d& p) {
  const double value = plane_value(plane, p);
  const double sum =
      std::fabs(plane[0] * p.x) + std::fabs(plane[1] * p.y) + std::fabs(plane[2] * p.z) + std::fabs(plane[3]);
  const double bound = value + 8 * kUnitRoundoff * sum;
  return std::isnan(bound) ? kInfinity : bound;  // overflow: no bound, not a silently lost one
}

// Sign of n . (q - p), exactly.  A filter first (each of the three terms is within gamma_4 of its value: the
// difference, the product and two sums; 6u of the computed magnitudes covers that), then expansion
// arithmetic: the differences are exact pairs, their products with n exact expansions, whose sum's sign is
// exact (where plane_safe() and in_fast_exact_range() hold: no underflow).
// Out of line, so that the filter inlines small (a template: a header's function that is not `inline`).
template <int = 0>
[[gnu::noinline]] int compare_along_closely(const Plane& n, const Vec3d& q, const Vec3d& p);

inline int compare_along(const Plane& n, const Vec3d& q, const Vec3d& p) {
  const double d0 = q.x - p.x, d1 = q.y - p.y, d2 = q.z - p.z;
  const double value = n[0] * d0 + n[1] * d1 + n[2] * d2;
  const double magnitude = std::fabs(n[0] * d0) + std::fabs(n[1] * d1) + std::fabs(n[2] * d2);
  const double bound = 6 * kUnitRoundoff * magnitude;
  if (magnitude > 0x1p-900) {
    if (value > bound) return 1;
    if (value < -bound) return -1;
  }
  return compare_along_closely(n, q, p);
}

// compare_along() where its filter cannot tell: the points about level along n.
template <int>
int compare_along_closely(const Plane& n, const Vec3d& q, const Vec3d& p) {
  // A second filter, in about double-double (a facet's own corners always reach it: their n . (q - p) is
  // of the order of the normal's rounding): the differences as exact pairs h + l, n h exact as P + e, so
  // that the value is P0 + P1 + P2 (summed into s with its errors exactly) plus a tail of terms each within
  // a few u of the value's scale, whose computed sum T is within E = 16u of their magnitudes (recursive
  // summation of 8 terms, and the products n l rounded once).  s decides where it outweighs |T| + E, T where
  // s is zero; else the exact sign.
  {
    const double qs[3] = {q.x, q.y, q.z}, ps[3] = {p.x, p.y, p.z};
    double big[3], tail[8];
    for (int k = 0; k < 3; ++k) {
      double h, l;
      detail::two_diff(qs[k], ps[k], h, l);
      detail::two_product(n[k], h, big[k], tail[k]);
      tail[3 + k] = n[k] * l;
    }
    double s1, s2;
    detail::two_sum(big[0], big[1], s1, tail[6]);
    detail::two_sum(s1, big[2], s2, tail[7]);
    double sum = 0, spread = 0;
    for (const double t : tail)
      sum += t, spread += std::fabs(t);
    const double error = 16 * kUnitRoundoff * spread * (1 + 0x1p-40);
    if (s2 != 0 && std::fabs(s2) > (std::fabs(sum) + error) * (1 + 0x1p-40)) return s2 > 0 ? 1 : -1;
    if (s2 == 0 && std::fabs(sum) > error * (1 + 0x1p-40)) return sum > 0 ? 1 : -1;
  }
  double terms[3][4];
  int lengths[3];
  const double qs[3] = {q.x, q.y, q.z}, ps[3] = {p.x, p.y, p.z};
  for (int k = 0; k < 3; ++k) {
    const detail::Pair difference = detail::exact_diff(qs[k], ps[k]);
    lengths[k] = detail::scale_expansion(difference.len, difference.v, n[k], terms[k]);
  }
  double first_two[8];
  const int length = detail::expansion_sum(lengths[0], terms[0], lengths[1], terms[1], first_two);
  return detail::expansion_sum_sign(length, first_two, lengths[2], terms[2]);
}

// Whether compare_along() is exact for these points and this plane.  With coordinates in the predicates'
// fast range (0 or 2^-250..2^250) every component of a difference's exact pair is a multiple of 2^-302
// (each coordinate is a multiple of its ulp, at least 2^-302), and with every nonzero normal component at
// least 2^-600 (so a multiple of 2^-652) every exact product is a multiple of 2^-954, far above the
// subnormal resolution 2^-1074: products, their errors and all the sums are exact, none underflows.
inline bool plane_safe(const Plane& plane) {
  for (int k = 0; k < 3; ++k)
    if (plane[k] != 0 && std::fabs(plane[k]) < 0x1p-600) return false;
  return true;
}

// The kept vertices: the maximum of the exact linear function n . p + d over the vertices of hull(S) is at
// a vertex that no neighbour exceeds (every vertex of a convex polytope lies in the cone from any vertex
// along its edges, which the triangulation's edges include), so an ascent from the facet's own corner along
// hull(S)'s edges with exact comparisons finds it in a few steps; its evaluation is then bounded.  A plane or
// coordinates outside the exact range take all vertices instead.  Per plane: the bound over S.
//
// MergedHull::thinnest, in the same pass (it reads the same planes and mesh): per facet, the depth of the
// vertices' centroid below its plane, which no vertex falls short of; within `near` of the plane (a thin
// hull), the deepest vertex itself, by a descent from the facet's start (its seed's corner 0) along the
// edges against the plane's normal, with exact comparisons, to the first neighbour found deeper.
//
// The planes are taken in `order` (their starts' visit order, Facets::in_visit_order), each from `starts`
// (its seed's corners as positions of g, in that order), not in the facets' (largest first, scattered): the
// same results, from the cache.  `side()` runs beside them on one core, and alongside(begin, end) over
// [0, alongside_items) shares their pass (work that does not depend on them: the merged faces).
struct KeptBounds {
  PassVector<double> bounds;    // per plane, in `order`'s order
  double largest = -kInfinity;  // of the bounds (found in their pass, where the workers' lines still are)
  double thinnest = kInfinity;
};

template <class Side, class Alongside>
KeptBounds kept_bounds(const Relabelled& g, const std::vector<Plane>& planes,
                       const PassVector<std::uint32_t>& order,
                       const PassVector<std::array<std::uint32_t, 3>>& starts, const Vec3d& centroid,
                       double near, Side&& side, std::size_t alongside_items, Alongside&& alongside) {
  // The ascents on the relabelled mesh (each vertex's neighbours in EdgeIndex's order, so that every ascent
  // takes the same steps): the ascents read what their neighbours read, not scattered lines.
  const std::vector<Vec3d>& at = g.at;
  const std::size_t count = order.size();
  PassVector<double> found(count);
  const unsigned workers = hardware_workers();
  PhaseLaps laps("kept_bounds");  // CUDAHULL_PHASE_TIMES=1
  std::vector<double> least(workers, kInfinity), largest(workers, -kInfinity);
  auto ascents = [&](std::size_t begin, std::size_t end, unsigned worker) {
    // The ascent from v: to the neighbour of the largest value among those exactly above, until none
    // is; `tie` tells whether a neighbour of the end is exactly level with it.  The vertex it came from
    // is exactly below, so it is not compared again.
    auto ascend = [&](const Plane& plane, std::uint32_t v, bool& tie) {
      std::uint32_t from = kNone;
      for (;;) {
        std::uint32_t next = kNone;
        double next_value = -kInfinity;
        tie = false;
        for (std::uint32_t k = g.start[v]; k < g.start[v + 1]; ++k) {
          const std::uint32_t q = g.to[k];
          if (q == from) continue;
          const int side = compare_along(plane, at[q], at[v]);
          tie = tie || side == 0;
          if (side > 0) {
            const double value = plane_value(plane, at[q]);
            if (next == kNone || value > next_value) next = q, next_value = value;
          }
        }
        if (next == kNone) return v;
        from = v;
        v = next;  // n . p + d grows strictly, exactly: the ascent ends
      }
    };
    // The block's least depth, kept here and written once: the workers' entries share cache lines, and
    // a write a facet from every worker kept them moving between the cores.
    double block_least = kInfinity, block_largest = -kInfinity;
    for (std::size_t i = begin; i < end; ++i) {
      const Plane& plane = planes[order[i]];
      const bool exact = g.coordinates_safe && plane_safe(plane);
      double depth = -plane_value(plane, centroid);
      if (!exact) {
        const bool thin = depth <= near;
        found[i] = -kInfinity;
        for (const Vec3d& p : at) {
          found[i] = std::max(found[i], bound_at(plane, p));
          if (thin) depth = std::max(depth, -plane_value(plane, p));
        }
        block_least = std::min(block_least, depth);
        block_largest = std::max(block_largest, found[i]);
        continue;
      }
      // First from the seed's corner of the largest value, where the maximum usually is: an end with
      // every neighbour exactly below is the unique maximum, which the ascent from corner 0 (the
      // bound's definition) also ends at.  Otherwise (a tie) that ascent itself.
      const std::array<std::uint32_t, 3>& c = starts[i];
      std::uint32_t best = c[0];
      for (int k = 1; k < 3; ++k)
        if (plane_value(plane, at[c[k]]) > plane_value(plane, at[best])) best = c[k];
      bool tie = false;
      std::uint32_t v = ascend(plane, best, tie);
      if (tie && best != c[0]) v = ascend(plane, c[0], tie);
      found[i] = bound_at(plane, at[v]);
      if (depth <= near) {
        const Plane against{-plane[0], -plane[1], -plane[2], plane[3]};
        std::uint32_t u = c[0];
        for (bool moved = true; moved;) {
          moved = false;
          for (std::uint32_t k = g.start[u]; k < g.start[u + 1] && !moved; ++k)
            if (const std::uint32_t q = g.to[k]; compare_along(against, at[q], at[u]) > 0)
              u = q, moved = true;  // deeper, exactly: the descent ends
        }
        depth = -plane_value(plane, at[u]);
      }
      block_least = std::min(block_least, depth);
      block_largest = std::max(block_largest, found[i]);
    }
    least[worker] = std::min(least[worker], block_least);
    largest[worker] = std::max(largest[worker], block_largest);
  };
  // The ascents' blocks first, then `alongside`'s: one pass, one wait.
  parallel_blocks_beside(
      count + alongside_items, workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        if (begin < count) ascents(begin, std::min(end, count), worker);
        if (end > count) alongside(std::max(begin, count) - count, end - count);
      },
      side, 256);
  laps.lap("ascents");
  KeptBounds kept;
  kept.bounds = std::move(found);
  kept.thinnest = *std::min_element(least.begin(), least.end());
  kept.largest = *std::max_element(largest.begin(), largest.end());
  return kept;
}

// The dropped points: a bounding-box tree over them, searched per plane from the kept vertices' bound.  A
// box is skipped when no point in it can exceed the best bound so far: every p in it is within R of the
// box's computed centre c (R: half the computed diagonal plus the centre's rounding, inflated), so
// n . p + d <= [n . c + d] + |n| R, the bracket bounded as for a point, |n| by its computed value inflated,
// and the sum's own rounding covered by a further 4u of its terms.  `kept`: per plane, the kept vertices'
// bound (read only where there are points), `kept_largest` the largest of them.  Returns the largest bound.
inline double dropped_bound(const std::vector<Vec3d>& points, const std::vector<Plane>& planes,
                            const std::vector<double>& kept, double kept_largest) {
  double result = kept_largest;
  std::vector<Box> boxes(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    boxes[i] = {{points[i].x, points[i].y, points[i].z}, {points[i].x, points[i].y, points[i].z}};
  const BoxTree tree(std::move(boxes));
  if (tree.empty()) return result;
  const auto& nodes = tree.nodes();
  std::vector<Vec3d> centre(nodes.size());
  std::vector<double> radius(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Box& b = nodes[k].box;
    const Vec3d c{(b.lo[0] + b.hi[0]) / 2, (b.lo[1] + b.hi[1]) / 2, (b.lo[2] + b.hi[2]) / 2};
    const double dx = b.hi[0] - b.lo[0], dy = b.hi[1] - b.lo[1], dz = b.hi[2] - b.lo[2];
    const double off_centre = 2 * kUnitRoundoff * (std::fabs(c.x) + std::fabs(c.y) + std::fabs(c.z));
    centre[k] = c;
    radius[k] = (std::sqrt(dx * dx + dy * dy + dz * dz) / 2 + off_centre) * (1 + 0x1p-40);
  }
  const unsigned workers = hardware_workers();
  std::vector<double> worst(workers, -kInfinity);
  parallel_chunks(
      planes.size(), workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        double best = worst[worker];
        std::vector<std::uint32_t> stack;
        for (std::size_t f = begin; f < end; ++f) {
          const Plane& plane = planes[f];
          const double norm =
              std::sqrt(plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2]) * (1 + 0x1p-40);
          auto box_bound = [&](std::uint32_t k) {
            const double at_centre = bound_at(plane, centre[k]);
            const double r = radius[k] * norm * (1 + 0x1p-40);
            return at_centre + r + 4 * kUnitRoundoff * (std::fabs(at_centre) + r);
          };
          best = std::max(best, kept[f]);
          stack.assign(1, 0);
          while (!stack.empty()) {
            const std::uint32_t k = stack.back();
            stack.pop_back();
            const auto& node = nodes[k];
            if (box_bound(k) <= best) continue;
            if (node.left == kNone) {
              for (std::uint32_t i = node.begin; i < node.end; ++i)
                best = std::max(best, bound_at(plane, points[tree.item(i)]));
              continue;
            }
            // The more promising child last, so that it is searched first.
            const bool left_first = box_bound(node.left) > box_bound(node.right);
            stack.push_back(left_first ? node.right : node.left);
            stack.push_back(left_first ? node.left : node.right);
          }
        }
        worst[worker] = std::max(worst[worker], best);
      },
      64);
  return std::max(result, *std::max_element(worst.begin(), worst.end()));
}

}  // namespace cudahull::merge
