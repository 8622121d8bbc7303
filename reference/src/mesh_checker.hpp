// The checker of a hull of dimension 3 (MeshChecker): a closed 2-manifold of convex or flat edges and
// strictly extreme vertices that holds every input point.  Internal to reference/.
//
// Containment of all input points in a 3D hull is proven without the O(n*F) all-pairs test: once the mesh
// is a closed 2-manifold with convex or flat edges, an interior point c strictly below every face plane, and
// every vertex's fan winding once around the ray from c, the cones from c over the faces tile space.  Each
// point is then located in its cone by a walk over the faces and must be below or on that face's plane.
#pragma once

#include <cinttypes>
#include <cstdint>
#include <string>
#include <vector>

#include "check_predicates.hpp"
#include "check_report.hpp"
#include "checker.hpp"
#include "cudahull/types.hpp"

namespace cudahull::checking {

// Works on its own numbering: vertices along a Morton curve and faces by their smallest vertex, so that the
// O(F) passes touch memory in order even when the vertex ids are spatially random (a sphere's hull has as
// many vertices as points).  Messages use the caller's face indices and input ids.

template <class Point>
class MeshChecker {
 public:
  MeshChecker(const std::vector<Point>& pts, const BasicHullMesh<Point>& h, Report& rep)
      : pts_(pts), h_(h), rep_(rep) {}
  void run();

 private:
  PointIndex id(std::uint32_t v) const { return h_.vertex_ids[lv2v_[v]]; }
  std::string vname(std::uint32_t v) const {
    return fmt("%" PRIu32 " %s", id(v), coords(h_.vertices[lv2v_[v]]).c_str());
  }
  std::string fname(std::uint32_t f) const {
    const Triangle& t = h_.triangles[lf2f_[f]];
    return fmt("face %" PRIu32 " (ids %" PRIu32 " %" PRIu32 " %" PRIu32 ")", lf2f_[f], h_.vertex_ids[t[0]],
               h_.vertex_ids[t[1]], h_.vertex_ids[t[2]]);
  }
  std::string pname(std::size_t i) const { return fmt("point %zu %s", i, coords(pts_[i]).c_str()); }
  const Vec3d& P(std::uint32_t v) const { return vp_[v]; }
  int above(std::uint32_t f, const Vec3d& q) const {
    const Triangle& t = tri_[f];
    return orient3d_any(rep_.wide, P(t[0]), P(t[1]), P(t[2]), q);
  }
  // The corner after corner (f, k) around vertex tri_[f][k]: across the edge entering the vertex.
  std::uint32_t next_corner(std::uint32_t corner) const {
    const std::uint32_t f = corner / 3, k = corner % 3;
    const std::uint32_t s = 3 * f + (k + 2) % 3;
    return 3 * nb_[s] + twin_[s];
  }

  bool renumber();
  bool build_adjacency();
  bool check_topology();
  bool check_edges();
  bool find_interior_point();
  void build_facets();
  bool check_vertex_fans(bool polytope);
  void locate_points();
  void brute_force_points();
  std::uint32_t walk(const Vec3d& q, std::uint32_t f, std::uint32_t& rng, std::size_t cap) const;

  const std::vector<Point>& pts_;
  const BasicHullMesh<Point>& h_;
  Report& rep_;
  std::uint32_t nv_ = 0, nf_ = 0;
  std::vector<std::uint32_t> lv2v_, lf2f_;  // local vertex/face -> the caller's index
  std::vector<Vec3d> vp_;                   // local vertex coordinates
  std::vector<Triangle> tri_;               // local faces over local vertices
  // Outgoing half-edges grouped by origin vertex (CSR), sorted by target within a vertex.
  std::vector<std::uint32_t> start_, he_to_, he_corner_;
  // Per corner/half-edge 3f+i (edge tri_[f][i] -> tri_[f][i+1]): the face across, its slot there, and
  // whether the edge is flat.
  std::vector<std::uint32_t> nb_;
  std::vector<std::uint8_t> twin_, flat_;
  std::vector<std::uint32_t> facet_;  // per face: a representative face of its coplanar facet
  Vec3d c_{};
};

}  // namespace cudahull::checking
