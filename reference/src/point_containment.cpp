// Every input point below or on the mesh (item 2): located in its cone by a walk over the faces when the
// mesh is a verified convex polytope, else tested against every face.
#include "mesh_checker.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <thread>
#include <vector>

namespace cudahull::checking {

// Walks from face f towards the face whose cone from c contains q: crosses an edge whose radial plane has q
// strictly outside, choosing among such edges from a random start (a deterministic walk can cycle).
// Returns kNone after `cap` steps.
template <class Point>
std::uint32_t MeshChecker<Point>::walk(const Vec3d& q, std::uint32_t f, std::uint32_t& rng,
                                       std::size_t cap) const {
  int entered = -1;  // the slot we came through: q is on its inner side already
  for (std::size_t step = 0; step < cap; ++step) {
    rng ^= rng << 13, rng ^= rng >> 17, rng ^= rng << 5;
    const int off = static_cast<int>(rng % 3);
    const Triangle& t = tri_[f];
    int cross = -1;
    for (int j = 0; j < 3 && cross < 0; ++j) {
      const int i = (off + j) % 3;
      if (i != entered && orient3d_any(rep_.wide, c_, P(t[i]), P(t[(i + 1) % 3]), q) < 0) cross = i;
    }
    if (cross < 0) return f;
    entered = twin_[3 * f + cross];
    f = nb_[3 * f + cross];
  }
  return kNone;
}

// Item 2 for a verified convex polytope: locate each point's cone and test it against that face only.
template <class Point>
void MeshChecker<Point>::locate_points() {
  const std::size_t cap = static_cast<std::size_t>(4 * std::sqrt(static_cast<double>(nf_))) + 100;
  // Start faces from a cube map of directions around c, filled by one sweep of short walks.
  const int g = std::clamp(static_cast<int>(std::sqrt(nf_ / 12.0)), 1, 256);
  // Directions in long double, so that wide coordinates (1e308 apart) stay finite; only the start faces
  // depend on them, never a verdict.
  using L = long double;
  L radius = 0;
  for (const Vec3d& p : vp_)
    radius = std::max({radius, std::fabs(L(p.x) - c_.x), std::fabs(L(p.y) - c_.y), std::fabs(L(p.z) - c_.z)});
  auto clamp_double = [](L x) {
    const L big = std::numeric_limits<double>::max();
    return static_cast<double>(std::clamp(x, -big, big));
  };
  auto cell_of = [&](L dx, L dy, L dz) -> std::size_t {
    const L ax = std::fabs(dx), ay = std::fabs(dy), az = std::fabs(dz);
    int side;
    L s, t, m;
    if (ax >= ay && ax >= az)
      side = dx >= 0 ? 0 : 1, s = dy, t = dz, m = ax;
    else if (ay >= az)
      side = dy >= 0 ? 2 : 3, s = dz, t = dx, m = ay;
    else
      side = dz >= 0 ? 4 : 5, s = dx, t = dy, m = az;
    if (!(m > 0)) return 0;
    const int i = std::clamp(static_cast<int>((s / m + 1) * 0.5 * g), 0, g - 1);
    const int j = std::clamp(static_cast<int>((t / m + 1) * 0.5 * g), 0, g - 1);
    return (static_cast<std::size_t>(side) * g + i) * g + j;
  };
  std::vector<std::uint32_t> cell_face(6 * static_cast<std::size_t>(g) * g, 0);
  {
    std::uint32_t rng = 0x9E3779B9u, f = 0;
    for (int side = 0; side < 6; ++side)
      for (int i = 0; i < g; ++i)
        for (int j0 = 0; j0 < g; ++j0) {
          const int j = (i % 2) ? g - 1 - j0 : j0;  // serpentine: consecutive cells are neighbours
          const double s = ((i + 0.5) / g) * 2 - 1, t = ((j + 0.5) / g) * 2 - 1;
          const Vec3d d = side == 0   ? Vec3d{1, s, t}
                          : side == 1 ? Vec3d{-1, s, t}
                          : side == 2 ? Vec3d{t, 1, s}
                          : side == 3 ? Vec3d{t, -1, s}
                          : side == 4 ? Vec3d{s, t, 1}
                                      : Vec3d{s, t, -1};
          const Vec3d q = {clamp_double(c_.x + d.x * radius), clamp_double(c_.y + d.y * radius),
                           clamp_double(c_.z + d.z * radius)};
          const std::uint32_t r = walk(q, f, rng, cap);
          if (r != kNone) f = r;
          cell_face[(static_cast<std::size_t>(side) * g + i) * g + j] = f;
        }
  }
  // A mesh too large for the caches: visit the points grouped by cell (a counting sort), so that consecutive
  // walks touch the same faces.  A small mesh: input order, which reads the points sequentially.  Each
  // chunk walks on from its previous point's face while the cell stays the same.
  const std::size_t n = pts_.size(), ncells = cell_face.size();
  std::vector<std::uint32_t> cell(n), order(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = pts_[i];
    cell[i] = static_cast<std::uint32_t>(cell_of(L(p.x) - c_.x, L(p.y) - c_.y, L(p.z) - c_.z));
  }
  if (nf_ > 32768) {
    std::vector<std::uint32_t> first(ncells + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      ++first[cell[i] + 1];
    for (std::size_t k = 0; k < ncells; ++k)
      first[k + 1] += first[k];
    for (std::size_t i = 0; i < n; ++i)
      order[first[cell[i]]++] = static_cast<std::uint32_t>(i);
  } else {
    std::iota(order.begin(), order.end(), 0u);
  }
  struct State {
    std::uint32_t rng, cell = kNone, face = 0;
  };
  std::vector<State> state(std::max(1u, std::thread::hardware_concurrency()));
  for (std::size_t t = 0; t < state.size(); ++t)
    state[t].rng = 0x2545F491u * static_cast<std::uint32_t>(t + 1) | 1u;
  parallel_failures(n, 4, rep_, [&](std::size_t k, auto& sink, std::size_t t) {
    State& st = state[t];
    const std::size_t i = order[k];
    const Vec3d q = to_vec3d(pts_[i]);
    if (cell[i] != st.cell) st.cell = cell[i], st.face = cell_face[cell[i]];
    const std::uint32_t f = walk(q, st.face, st.rng, cap);
    if (f != kNone) {
      st.face = f;
      if (above(f, q) > 0) sink(i, pname(i) + " is above " + fname(f));
      return;
    }
    for (std::uint32_t h = 0; h < nf_; ++h)  // the walk did not settle: test every face
      if (above(h, q) > 0) {
        sink(i, pname(i) + " is above " + fname(h));
        return;
      }
  });
}

// Item 2 when the mesh is not a verified convex polytope: every point against every face (first face only).
template <class Point>
void MeshChecker<Point>::brute_force_points() {
  if (static_cast<double>(pts_.size()) * static_cast<double>(nf_) > 4e9) {
    rep_.fail(
        "containment of the input points was not checked: the mesh is not a valid convex polytope and "
        "the all-pairs test is too large");
    return;
  }
  parallel_failures(pts_.size(), std::max<std::size_t>(nf_ / 16, 1), rep_,
                    [&](std::size_t i, auto& sink, std::size_t) {
                      const Vec3d q = to_vec3d(pts_[i]);
                      for (std::uint32_t f = 0; f < nf_; ++f)
                        if (above(f, q) > 0) {
                          sink(i, pname(i) + " is above " + fname(f));
                          return;
                        }
                    });
}

// The two point types; the callers are in other files.
template void MeshChecker<Point3>::locate_points();
template void MeshChecker<Point3>::brute_force_points();
template void MeshChecker<Point3d>::locate_points();
template void MeshChecker<Point3d>::brute_force_points();

}  // namespace cudahull::checking
