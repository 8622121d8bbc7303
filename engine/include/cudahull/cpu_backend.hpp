// The multi-threaded CPU implementation of the backend: the same per-point code as the CUDA backend
// (routing.hpp), run over the index array with one thread per core.
#pragma once

#include <memory>

#include "cudahull/backend.hpp"

namespace cudahull {

std::unique_ptr<Backend> make_cpu_backend(unsigned threads = 0);  // 0: one per hardware thread

}  // namespace cudahull
