// Edge swaps and the foldover test (Figs. 3b and 5).
//
// design:
//   swap of edge u - v (faces f = (u, v, x) and g = (v, u, y)) into x - y:
//     nothing to do   unless the edge is concave: orient3d(u, v, x, y) > 0 (exact)
//     rejected        when x - y is already an edge (not a 2-manifold), when the four points are coplanar
//                     in the view below, or when it folds over (Fig. 5): seen from far below the edge along
//                     the average normal of f and g, the old and the new edge must cross; otherwise a vertex
//                     of the old edge lies beneath a new triangle.  A vertex beneath that is proven inside
//                     the hull (inside the tetrahedron of c and that triangle) is doomed: taken out later.
//     made            faces n1 = (x, u, y), n2 = (y, v, x); decision entry with the plane of x - y; record
//   Every swap goes one way: try (trial_swap, the mesh unchanged), then make (make_swaps: the mesh edit,
//   the decision entries and the records of a batch of swaps).  One at a time (try_swap) the batch is one
//   swap; in rounds (swap_edges, thousands of candidates) every candidate is tried on all cores, and those
//   that hold every claim on the faces they kill and the edge they make are made together.  Claims go to
//   the lowest candidate, so the result does not depend on the number of threads.
#pragma once

#include <initializer_list>
#include <vector>

#include "phases/local_edits.hpp"

namespace cudahull::phases {

// Is x inside the cone from viewpoint c over triangle (a, b, d)?  Exact.
bool in_cone_from(const Vec3d& c, const Vec3d& a, const Vec3d& b, const Vec3d& d, const Vec3d& x);
// The viewpoint far below `at` along direction `up` (scaled to `size`): seen from there, orientation tests
// are the parallel projection along `up` (the height-field view of Fig. 5), yet still exact predicates.
Vec3d far_below(const Vec3d& at, const Vec3d& up, double size);
// The largest extent of the points' bounding box.
double extent(std::initializer_list<Vec3d> points);

// The validity of the swap of u - v into x - y (see the design): kRegular when valid, else the reason; a
// foldover fills swap.beneath_*.  Seen from far below the edge, or from `view` when given (one common
// viewpoint for the swaps around a vertex being taken out).
template <class Point>
SwapKind swap_validity(const LocalEdits<Point>& edits, PointIndex u, PointIndex v, PointIndex x, PointIndex y,
                       SwapRecord& swap, const Vec3d* view = nullptr);

// A candidate edge for a swap, and the kind it is recorded as when made.
struct SwapCandidate {
  Edge edge;
  SwapKind kind;
};

// Fig. 3b: swap edge i of face f.  Only a concave edge, unless `around_doomed` (a complementary swap that
// lowers the degree of a vertex being taken out, seen from that view).  Returns true if swapped; the four
// edges around the new faces are queued and its vertices touched.
template <class Point>
bool try_swap(LocalEdits<Point>& edits, FaceId f, int i, SwapKind kind, const Vec3d* around_doomed = nullptr);

// Tries every candidate: in rounds on all cores while at least edits.batched_swaps_from remain (edges
// around the swaps made go to the next round as complementary candidates), then one at a time (regular
// candidates now; the others are queued for settle()).
template <class Point>
void swap_edges(LocalEdits<Point>& edits, std::vector<SwapCandidate> candidates);

}  // namespace cudahull::phases
