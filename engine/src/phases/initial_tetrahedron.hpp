// The initial tetrahedron (section 3.1).
//
// design:
//   p0, p1 = the points of least and greatest x (ties to the lowest index)
//   p2 = the point furthest from the line p0 p1
//   p3 = the point furthest from the plane p0 p1 p2
//   The backend ranks in floating point; each choice is confirmed exactly, a "furthest" point that is
//   exactly collinear or coplanar is replaced by any exact witness, and no witness at all means the input
//   is lower-dimensional (dimension 0, 1 or 2: the exact reference hull answers).
//   The interior point c is the tetrahedron's centroid, confirmed strictly inside exactly: every discard
//   of a point, and every foldover test, is relative to it.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/mesh.hpp"

namespace cudahull::phases {

struct InitialTetrahedron {
  int dimension = 3;  // the affine dimension when below 3; then `note` says why and there are no corners
  std::string note;
  std::array<PointIndex, 4> corners{};  // p3 lies below the counter-clockwise triangle (p0, p1, p2)
  double backend_ms = 0;                // spent in the backend's queries
};

// Section 3.1's queries on the backend (which holds the points), confirmed exactly.
template <class Point>
InitialTetrahedron find_initial_tetrahedron(const std::vector<Point>& points, BasicBackend<Point>& backend);

// Makes the tetrahedron in `mesh` and returns its centroid in `interior`; false when the centroid, rounded,
// is not strictly inside every face (a tetrahedron too flat: the caller finishes exactly).
template <class Point>
bool make_initial_tetrahedron(const std::vector<Point>& points, const std::array<PointIndex, 4>& corners,
                              Mesh& mesh, Vec3d& interior);

}  // namespace cudahull::phases
