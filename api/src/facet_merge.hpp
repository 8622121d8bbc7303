// Qhull-like merging of an exact hull's near-coplanar facets, with a certified result.
//
// design:
//   The exact hull keeps every strictly extreme point, including points that stand 1e-16 proud of a flat
//   face only because a rotation rounded them there: slivers of area ~1e-16 that Qhull merges away.
//   merge_facets() reproduces Qhull's merging in the one way that keeps the result provably convex: it
//   drops vertices and never moves any, so the merged hull is again an exact convex hull, of a subset S of
//   the exact hull's vertices (a subset of strictly extreme points stays strictly extreme).
//   1. Heights.  Dropping a vertex v of hull(S) replaces its star by facets of hull(S - v) that v is
//      strictly above, and their corners are v's neighbours: they are facets of hull(link(v)).  h(v) = v's
//      largest distance above the facets of hull(link(v)) that v is strictly above (exact orient3d decides
//      "above"; the distance is in double, from plane_through()) is therefore at least how far above
//      hull(S - v) v ends up.  A flat link gives v's distance to its plane.
//   2. Rounds.  The vertices with h(v) <= tolerance, lowest first, are dropped as an independent set (no two
//      adjacent: their stars are disjoint, so each h stays valid), and hull(S) is recomputed exactly; until a
//      round drops nothing.  A round never makes the hull flat (its drops are halved until it is not).  A
//      vertex whose link did not change keeps its height from the round before.
//   3. Facets.  The triangles of hull(S) are grouped, largest first: a group grows across edges into
//      triangles that face the same side (positive dot product of the normals) and whose corners all lie
//      within the tolerance of the group's plane (the plane of its largest triangle; corners exactly
//      coplanar with it always qualify), Qhull's coplanar merge.  The group's
//      offset is then raised so that every group vertex is on or below the plane.  Each group keeps
//      hull(S)'s own triangles rather than Qhull's 'Qt' fan: the same merged polygon, triangulated with its
//      corners only (other diagonals), exactly convex, and free of slivers: the apex of a triangle's smallest
//      altitude projects inside the opposite side, so an altitude within the tolerance would have let step 2
//      drop that apex.
//   4. Certificate.  Later rounds can leave an early-dropped point further out than its h, so nothing above
//      is trusted for the bound: max_outside = the largest n . p + d over every exact-hull vertex p (every
//      input point is a convex combination of them) and every merged facet's plane, plus a rigorous bound
//      on the rounding of that evaluation.  Not by V x F evaluations (quadratic in the hull's size): over
//      the kept vertices, the maximum of a linear function is found exactly by an ascent along hull(S)'s
//      edges with exact comparisons, from the facet's own corner (a few steps); over the dropped points, a
//      bounding-box tree prunes all but the points near each plane.
//   Cost: the rounds dominate where they drop (a small exact hull per vertex whose link changed, and an
//   exact hull of S per round; a handful of rounds).  Where nothing drops, each step is a linear pass, taken
//   in a spatial order of the vertices so that a large hull's scattered indices read from the cache
//   (merge/mesh_order.hpp, VisitOrder); timings in docs/benchmarks.md.
//   Where: steps 1-2 in merge/low_vertices.hpp, 3 in merge/grouping.hpp, 4 in merge/certificate.hpp, the
//   mesh's views they share in merge/mesh_order.hpp, and the steps in order in facet_merge.cpp.
//   Against Qhull (scipy's default, "Qt"): on rotated CAD parts (tests/test_facet_merge.cpp) the vertex sets
//   are Qhull's exactly.  Where points lie within a few tolerances of a face (noise of the order of Qhull's
//   own roundoff), Qhull's choices depend on its insertion order and even keep points that are not extreme
//   at all; there the counts differ by a few percent.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cudahull/parallel.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

struct MergedHull {
  std::vector<PointIndex> vertices;  // kept input indices, ascending
  // Outward counter-clockwise triangles (input indices), grouped by merged facet (facet ids ascending).
  // Each merged facet is triangulated with its corners only: hull(S)'s own triangles of the facet.
  std::vector<std::array<PointIndex, 3>> faces;
  // The same triangles as positions in the exact hull's `vertices` (what its measures read).
  PassVector<Triangle> face_positions;
  // Per triangle: its merged facet's unit outward normal and offset (n . x + d <= 0 inside); triangles of
  // one merged facet share it.
  std::vector<std::array<double, 4>> planes;
  std::vector<std::uint32_t> facet_of_face;  // merged facet id per triangle
  // neighbors[f][k]: the triangle across the edge opposite faces[f][k] (scipy's convention).
  std::vector<std::array<std::int32_t, 3>> neighbors;
  // Per exact-hull vertex that merging dropped, ascending: {point, nearest triangle (Euclidean distance to
  // the triangle), nearest corner of that triangle}, as scipy's ConvexHull.coplanar.
  std::vector<std::array<PointIndex, 3>> coplanar;
  double tolerance = 0;  // the tolerance used (absolute)
  // Proven: for every input point p and every triangle t, n_t . p + d_t <= max_outside in exact arithmetic
  // on the stored doubles (the rounding of the evaluation is included).
  double max_outside = 0;
  // Qhull's flatness test (QH6154: a merged hull thinner than its tolerance is flat at it): the hull's least
  // depth below a facet's plane, min over facets of max over its vertices of -(n . p + d) in double, exactly
  // where some facet's depth is within 4 x the tolerance; above that, a lower bound above it (the depth of
  // the vertices' centroid), so that a thick hull costs no search.
  double thinnest = 0;
};

// The Qhull-like merged hull of `points` (Point3 or Point3d) from their exact hull `exact` (exact_hull();
// its vertex_ids index `points`), merging within the absolute `tolerance` (finite, >= 0; 0 merges only
// exactly coplanar triangles and drops nothing).  An exact hull of dimension below 3 is returned as is:
// its vertices, no faces.  Throws std::invalid_argument for a negative or non-finite tolerance.
// `angle_sine` (Qhull's An, as the sine of the angle; 0 for none) widens each vertex's and facet corner's
// limit by that times its distance to its neighbours (drop_low_vertices, group_facets).
//
// `work` (optional): what a caller adds to the merge's pass over the merged faces, so that it needs no pass
// of its own (describe_merged(): the measures' per-face terms).
struct MergedFacesWork {
  virtual ~MergedFacesWork() = default;
  // Once the faces' order is known, before any is written: face 0's corners (positions in exact.vertices)
  // and the number of faces.
  virtual void start(const Triangle& first_face, std::size_t faces) = 0;
  // On any worker, once faces [begin, end) are written (MergedHull::face_positions).
  virtual void faces(const MergedHull& merged, std::size_t begin, std::size_t end) = 0;
};
template <class Point>
MergedHull merge_facets(const std::vector<Point>& points, const BasicHullMesh<Point>& exact, double tolerance,
                        double angle_sine = 0, MergedFacesWork* work = nullptr);

// Qhull's default merging tolerance for these points in 3-D (what scipy's ConvexHull gets with its default
// options, "Qt", and Qhull's default pre-merge 'C-0'): qh.MINoutside = 4 x qh.DISTround, the distance a
// point must stand above a facet for Qhull to make it a vertex (nearer, it stays a coplanar point).  0 for
// no points.  The formula, from Qhull 2020.2 (geom2_r.c), and why MINoutside, are in facet_merge.cpp.
template <class Point>
double qhull_default_tolerance(const std::vector<Point>& points);

extern template MergedHull merge_facets(const std::vector<Point3>&, const HullMesh&, double, double,
                                        MergedFacesWork*);
extern template MergedHull merge_facets(const std::vector<Point3d>&, const HullMeshd&, double, double,
                                        MergedFacesWork*);
extern template double qhull_default_tolerance(const std::vector<Point3>&);
extern template double qhull_default_tolerance(const std::vector<Point3d>&);

}  // namespace cudahull
