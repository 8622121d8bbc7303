// Independent oracles for the tests: a brute-force exact extreme-point finder for small sets (it shares
// nothing with the engine or exact_hull but the exact predicates), and helpers around Qhull.
#pragma once

#include <algorithm>
#include <map>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"

namespace cudahull::testing {

// Strictly extreme points of a 3D-full set by brute force, O(n^4): a point is extreme iff it is a strict
// corner of the coplanar set on some supporting plane through three of the points.  Among duplicates the
// lowest index.  Only for n up to ~60.
inline std::vector<PointIndex> brute_force_extreme(const std::vector<Point3>& p) {
  const std::size_t n = p.size();
  auto V = [&](std::size_t i) { return to_vec3d(p[i]); };
  std::vector<bool> extreme(n, false);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        if (collinear3d(V(i), V(j), V(k))) continue;
        int side = 0;
        bool supporting = true;
        std::vector<std::size_t> on;
        for (std::size_t m = 0; m < n && supporting; ++m) {
          const int s = orient3d(V(i), V(j), V(k), V(m));
          if (s == 0) {
            on.push_back(m);
          } else if (side == 0) {
            side = s;
          } else if (s != side) {
            supporting = false;
          }
        }
        if (!supporting) continue;
        // The facet: the coplanar points on this supporting plane.  A point q of it is a strict corner iff
        // no other facet points a, b, c (possibly equal to each other) contain q in their closed triangle /
        // segment; test with a projection that drops the dominant axis of the plane normal.
        const Vec3d a = V(i), b = V(j), c = V(k);
        const double nx = (b.y - a.y) * (c.z - a.z) - (b.z - a.z) * (c.y - a.y);
        const double ny = (b.z - a.z) * (c.x - a.x) - (b.x - a.x) * (c.z - a.z);
        const double nz = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        const int drop = std::abs(nx) >= std::abs(ny) && std::abs(nx) >= std::abs(nz)
                             ? 0
                             : (std::abs(ny) >= std::abs(nz) ? 1 : 2);
        auto proj = [&](std::size_t m, double& u, double& v) {
          const Vec3d q = V(m);
          u = drop == 0 ? q.y : q.x;
          v = drop == 2 ? q.y : q.z;
        };
        for (std::size_t q : on) {
          bool corner = true;
          double qu, qv;
          proj(q, qu, qv);
          // q is not a corner if it equals a lower-index point, or lies in the closed triangle of three
          // others.
          for (std::size_t r : on) {
            if (r != q && p[r] == p[q] && r < q) corner = false;
          }
          for (std::size_t r1 = 0; r1 < on.size() && corner; ++r1)
            for (std::size_t r2 = r1; r2 < on.size() && corner; ++r2)
              for (std::size_t r3 = r2; r3 < on.size() && corner; ++r3) {
                const std::size_t A = on[r1], B = on[r2], C = on[r3];
                if (p[A] == p[q] || p[B] == p[q] || p[C] == p[q]) continue;
                double au, av, bu, bv, cu, cv;
                proj(A, au, av);
                proj(B, bu, bv);
                proj(C, cu, cv);
                const int s1 = orient2d(au, av, bu, bv, qu, qv), s2 = orient2d(bu, bv, cu, cv, qu, qv),
                          s3 = orient2d(cu, cv, au, av, qu, qv);
                const int o = orient2d(au, av, bu, bv, cu, cv);
                if (o != 0) {
                  if (s1 * o >= 0 && s2 * o >= 0 && s3 * o >= 0) corner = false;
                } else {
                  // Degenerate triple: q on a segment between two of them?
                  auto between = [&](double xu, double xv, double yu, double yv) {
                    return orient2d(xu, xv, yu, yv, qu, qv) == 0 && std::min(xu, yu) <= qu &&
                           qu <= std::max(xu, yu) && std::min(xv, yv) <= qv && qv <= std::max(xv, yv);
                  };
                  if (between(au, av, bu, bv) || between(bu, bv, cu, cv) || between(au, av, cu, cv))
                    corner = false;
                }
              }
          if (corner) extreme[q] = true;
        }
      }
  std::vector<PointIndex> out;
  for (std::size_t i = 0; i < n; ++i)
    if (extreme[i]) out.push_back(static_cast<PointIndex>(i));
  return out;
}

}  // namespace cudahull::testing
