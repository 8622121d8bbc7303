// The CUDA implementation of the backend (the paper's GPU module, section 4): the points, the index array of
// active points, each point's face and the per-face counts and extreme keys live on the device; each
// iteration only the O(faces) tables go over, and only the O(faces) counts and extremes come back.  Every
// per-point decision is the same routing.hpp code the CPU backend runs, so both give identical hulls.
//
// Plain C++ header (no CUDA headers): the command line and the tests include it.
#pragma once

#include <memory>

#include "cudahull/backend.hpp"

namespace cudahull {

// Uses CUDA device `device`.  Throws DeviceError with a one-line message when there is no usable device or
// a CUDA call fails (also later, from any Backend call: out of memory with the byte count, a kernel fault).
// Point3 (float) or Point3d (double) coordinates, as make_cpu_backend().
template <class Point = Point3>
std::unique_ptr<BasicBackend<Point>> make_cuda_backend(int device = 0);

}  // namespace cudahull
