// The GPU half of the 2-D hull (issue 25): an Akl-Toussaint filter over points in device memory, so that
// only the few points that can be corners cross to the host, where planar_hull() (api/src) finishes.
//
// design:
//   check every point (finite; for double, inside the exact range) and find, in one pass, the points
//     extreme in 32 directions (any input points make an inner polygon: the choice needs no exactness)
//   read back the first bad point's index and the extremes' coordinates: one wait
//   on the host, the inner polygon: the exact 2-D hull of those extremes (at most 32 corners)
//   keep every point not strictly inside it (exact orient2d, as on the host), in input order, and read
//     back the survivors' indices and coordinates: a second wait
//   the host's planar_hull() of the survivors gives the corners: a point strictly inside the inner polygon
//   is inside the hull, so no corner, nor any duplicate of one, is lost, and the order keeps the lowest
//   index of duplicates first
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

// The points of a device array that can be corners of its 2-D hull, in input order.
template <class Scalar>
struct PlanarCandidates {
  std::size_t first_bad = 0;        // the first point the exact hull cannot take, or `count`
  bool degenerate = false;          // the extremes span no polygon: filter on the host instead
  std::vector<PointIndex> indices;  // input indices, ascending
  std::vector<Scalar> xy;           // their coordinates, x, y pairs
  std::uint64_t host_syncs = 0, bytes_from_device = 0;
};

// Filters `count` x, y pairs of Scalar (float or double) at `xy` in the current device's memory.  Waits for
// the device first (the array's producer may have written it on any stream).  Throws DeviceError.
template <class Scalar>
PlanarCandidates<Scalar> planar_candidates(const Scalar* xy, std::size_t count);

// Point `index`'s coordinates (x, y, 0), read back for the error message that names it.
template <class Scalar>
std::array<double, 3> read_device_point_2d(const Scalar* xy, std::size_t index);

}  // namespace cudahull
