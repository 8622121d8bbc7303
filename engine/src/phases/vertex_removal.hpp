// Vertex removal (Fig. 4).
//
// design:
//   remove v of degree 3 (ring a, b, d) into the face (a, b, d):
//     when v is concave or flat: orient3d(a, b, d, v) <= 0 (exact), and was not removed before (a vertex
//       that came back sits in a fold, where looking concave proves nothing)
//     or when v is doomed: proven inside the hull by a rejected swap's foldover test
//     valid when the new face covers v seen from far below it (a strictly concave v is the apex of a
//       tetrahedron that removal adds whole, so it is always valid), and the new face's three outer
//       neighbours are three different faces none of which holds the remaining ring vertex
//     made: decision entry {above = below = the new face}; record; the three edges queued
//   take out a doomed vertex w: complementary swaps of edges of its star (concave ones first), each
//     lowering its degree, until it is 3; then remove it.
#pragma once

#include "phases/local_edits.hpp"

namespace cudahull::phases {

// Removes v if it has degree 3 and is concave, flat or `doomed_vertex`, and the removal is valid; records a
// rejected removal.  True if removed.
template <class Point>
bool try_remove(LocalEdits<Point>& edits, PointIndex v, bool doomed_vertex);

// Takes the doomed vertex w out of the mesh; true when it is gone.
template <class Point>
bool take_out(LocalEdits<Point>& edits, PointIndex w);

}  // namespace cudahull::phases
