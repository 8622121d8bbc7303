// Points that only the GPU holds (issue 16: a CuPy array, a PyTorch tensor), checked and, where the hull
// is computed in the other precision, converted on the device, so that the resident engine can borrow
// them (ResidentCudaHull::use_device_points) without a coordinate crossing to the host.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

// Whether the process sees a CUDA device, asked cheaply (no device properties are read); `why_not` gets the
// CUDA runtime's reason when not.
bool cuda_device_present(std::string* why_not);

// Throws DeviceError (one line) unless `xyz` points into device (or managed) memory of the current CUDA
// device: a host pointer, or another device's memory, would fault in the engine's first kernel instead.
void require_current_device_memory(const void* xyz);

// A copy of `bytes` at `host` in the current device's memory, freed with the pointer.  Throws DeviceError.
std::shared_ptr<void> upload_to_device(const void* host, std::size_t bytes);

// `count` points, as the hull in Point computes on them, on the current device.
template <class Point>
struct CheckedDevicePoints {
  const Point* points = nullptr;  // the caller's own array, or `converted`'s
  std::size_t count = 0;
  // The index of the first point that the exact hull in Point cannot take (a NaN or infinite coordinate;
  // for Point3d a nonzero magnitude outside 2^-250..2^250; for Point3 from double one that rounds to an
  // infinity), or `count` when there is none.  The caller names it from the point's own coordinates
  // (read_device_point), with the host path's words.
  std::size_t first_bad = 0;
  std::shared_ptr<void> converted;  // the rounded or widened copy, when Scalar is not Point's
  std::uint64_t host_syncs = 0, bytes_from_device = 0;  // what the check read back
};

// Checks `count` x, y, z triples of Scalar (float or double) at `xyz` in the current device's memory for
// Point (Point3 or Point3d), in one pass over them; a float array for Point3d is widened (exactly), a
// double array for Point3 rounded (once, to nearest), into a new device buffer.  Waits for the device
// first: the array's producer may have written it on any stream.  Throws DeviceError.
template <class Point, class Scalar>
CheckedDevicePoints<Point> check_device_points(const Scalar* xyz, std::size_t count);

// Per cloud of a batch (cloud c: points offsets[c] .. offsets[c + 1], B = `clouds`, host offsets), what
// check_device_points() would find in it for Point: kCloudWide where its points are finite and only some
// lie outside the fast exact range (double in double: the wide path takes the cloud), kCloudBad where one
// cannot be taken at all (a NaN or an infinity; from the other precision, a value it cannot hold), else 0.
// One pass over the points (a binary search in the offsets for each bad one).  Throws DeviceError.
enum CloudCheck : std::uint8_t { kCloudGood = 0, kCloudWide = 1, kCloudBad = 2 };
template <class Point, class Scalar>
std::vector<std::uint8_t> check_device_clouds(const Scalar* xyz, std::size_t count,
                                              const std::size_t* offsets, std::size_t clouds);

// The `count` values at `values` in device memory, copied to the host after the device is idle (for the
// paths that finish on the host: the wide range, a degenerate 2-D input).  Float or double.
template <class Scalar>
std::vector<Scalar> download_values(const Scalar* values, std::size_t count);

// Blocks of `threads` for a grid-stride loop over `count` items: enough to fill the current device
// `per_sm` times over, no more than the items need.  Throws DeviceError.
unsigned grid_stride_blocks(std::size_t count, unsigned threads, unsigned per_sm);

// Point `index`'s coordinates, read back (24 bytes at most), for the error message that names it.
template <class Scalar>
std::array<double, 3> read_device_point(const Scalar* xyz, std::size_t index);

}  // namespace cudahull
