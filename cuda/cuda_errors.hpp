// One-line DeviceErrors for CUDA failures, shared by the CUDA backend and the resident engine's device
// executor: "<who>: <what>: <error name> (<error text>)", and for a failed allocation the size and the
// device's free and total memory.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <string>

namespace cudahull {

std::string cuda_error_text(cudaError_t e);  // "cudaErrorX (text)"
std::string memory_text(std::size_t bytes);  // "N bytes (M MiB)"

// Throws DeviceError("<who>: <what>: <error>"), clearing a non-sticky error first (a sticky one, a kernel
// fault, stays with the context).
[[noreturn]] void throw_cuda_error(const char* who, const char* what, cudaError_t e);

// Throws DeviceError("<who>: out of device (or pinned host) memory allocating <bytes> for <what> (<free>
// free of <total>): <error>").
[[noreturn]] void throw_out_of_memory(const char* who, const char* what, std::size_t bytes, cudaError_t e,
                                      bool pinned = false);

// The one check of a CUDA call's result, bound to the component that makes the call:
//   constexpr CudaCheck check{"batched hulls"};
//   check(cudaMemcpy(...), "reading the hulls back");  // DeviceError "batched hulls: reading ...: ..."
struct CudaCheck {
  const char* who;
  void operator()(cudaError_t e, const char* what) const {
    if (e != cudaSuccess) throw_cuda_error(who, what, e);
  }
};

}  // namespace cudahull
