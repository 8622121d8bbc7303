// The multi-threaded CPU implementation of the backend: the same per-point code as the CUDA backend
// (routing.hpp), run over the index array with one thread per core.
#pragma once

#include <memory>

#include "cudahull/backend.hpp"

namespace cudahull {

// `threads` 0: one per hardware thread.  Point3 (float) or Point3d (double) coordinates.
template <class Point = Point3>
std::unique_ptr<BasicBackend<Point>> make_cpu_backend(unsigned threads = 0);

}  // namespace cudahull
