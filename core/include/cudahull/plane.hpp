// The plane of a hull facet from its three exact corners, accurate whatever the triangle's shape.
//
// design:
//   A facet of an exact hull can be a sliver or a needle: two corners 1e-12 apart and the third far away.
//   There the double-precision cross(b - a, c - a) cancels: each component is the small difference of two
//   large products, their rounding (about 1e-16 of the products) is a large part of the result, the normal
//   tilts, and a vertex can lie 1e-6 x scale outside its own facet's plane.  So the cross product is
//   evaluated exactly instead, in the predicates' expansion arithmetic (cudahull/predicates.hpp), and each
//   component is rounded once, to the nearest double.  The unit normal is then within a few units in the last
//   place of the exact one for every triangle, and a point on or below the exact plane evaluates to
//   n . p + d < 3.1e-15 x scale (the largest coordinate magnitude) in double; the bound is in plane.cpp.
//
//   It runs once per output facet, after the hull is built (a small share of the hull's time: docs/
//   benchmarks.md, "The measurements behind the code's constants"), on the host, and on the device for the
//   batch kernel's hulls (the code: cudahull/detail/plane_impl.hpp).
#pragma once

#include <array>

#include "cudahull/predicates.hpp"

namespace cudahull {

// (b - a) x (c - a) with each component the exact value rounded to the nearest double (ties to even).  All
// three components are zero exactly when a, b, c are collinear or two of them coincide.  Exact for all finite
// inputs whose products of coordinate differences neither overflow nor underflow (as orient3d); in particular
// for every float32 input.
std::array<double, 3> cross_rounded(const Vec3d& a, const Vec3d& b, const Vec3d& c);

// The plane through a, b, c (counter-clockwise seen from the side the normal points to), as a unit normal
// (nx, ny, nz) and offset d, n . x + d <= 0 below: the normal is cross_rounded(a, b, c) normalised (a few
// ulps from the exact unit normal), d = -max(n . a, n . b, n . c) in double, so the corners lie on the plane
// or just below it, by rounding only.  A degenerate triangle (collinear or coincident corners, exactly) has
// no plane: it gives {0, 0, 0, 0}.  Same input range as cross_rounded().
std::array<double, 4> plane_through(const Vec3d& a, const Vec3d& b, const Vec3d& c);

}  // namespace cudahull
