// The cells and their separating planes (section 3, Fig. 2).
//
// design:
//   Each face t owns the cell bounded by three separating planes, one per edge: the plane through the edge
//   that contains the average of the unit normals of the edge's two faces.  A point in t's cell that is
//   above t belongs to t.  The planes only route points (Algorithm 2); every decision that changes the hull
//   is exact elsewhere, so they may be inexact as long as each point lands in exactly one cell.
//   A refinement splits a cell into three by planes through the apex and the old corners (Fig. 3a); a swap
//   splits the union of two cells by the plane of its new edge (Fig. 3b).  Those planes go into the tables
//   (Fig. 7) after the iteration's edits, on all cores, because they read only faces that stay in storage
//   until compaction.
#pragma once

#include <array>
#include <vector>

#include "cudahull/mesh.hpp"
#include "cudahull/routing.hpp"

namespace cudahull::phases {

// The plane through a and b that contains direction `along`, positive on the side of `inside`.
SeparatingPlane plane_through_edge(const Vec3d& a, const Vec3d& b, const Vec3d& along, const Vec3d& inside);

// The unit outward normal of face f.
template <class Point>
Vec3d unit_normal(const Mesh& mesh, const std::vector<Point>& points, FaceId f);

// Face f's cell: its plane and the separating planes of its three edges.
template <class Point>
FaceCell face_cell(const Mesh& mesh, const std::vector<Point>& points, FaceId f);

// The three planes of each refinement (children[k] are refinement[k]'s children, work ids): plane[i]
// through the apex and old corner i separates child i-1 from child i, child i on its positive side.
template <class Point>
void refinement_planes(const Mesh& mesh, const std::vector<Point>& points,
                       std::vector<RefinementEntry>& refinement,
                       const std::vector<std::array<FaceId, 3>>& children);

// The separating plane of a swap's new edge: n1 = (x, u, y) and n2 = (y, v, x), positive on u's side.
template <class Point>
SeparatingPlane swap_plane(const Mesh& mesh, const std::vector<Point>& points, FaceId n1, FaceId n2,
                           PointIndex u);

}  // namespace cudahull::phases
