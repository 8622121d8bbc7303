// The stepping engine's phases that the resident engine shares: section 3.1's tetrahedron, and the
// separating plane through an edge (section 3) that the stepper's records draw.  They are compiled in
// shared_phases.cpp, so that the headers the device compiles (cuda/resident_cuda.cu) need none of the
// engine's private sources.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cudahull/backend.hpp"

namespace cudahull::resident {

// Section 3.1's tetrahedron over `points`, the backend's queries (on the executor) confirmed exactly: its
// faces and neighbours into fv and fn (4 faces, 3 each) and its centroid into c.  Returns "" on success,
// else why the input is lower-dimensional (or the tetrahedron too flat for an interior point).
template <class Point>
std::string first_tetrahedron(const std::vector<Point>& points, BasicBackend<Point>& queries,
                              std::vector<std::uint32_t>& fv, std::vector<std::uint32_t>& fn, Vec3d& c);

// The plane through a, b, d (unit normal), positive on the side of `inside`.
SeparatingPlane plane_through(const Vec3d& a, const Vec3d& b, const Vec3d& d, const Vec3d& inside);

}  // namespace cudahull::resident
