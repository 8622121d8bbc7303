#include "cuda_errors.hpp"

#include "cudahull/errors.hpp"

namespace cudahull {

std::string cuda_error_text(cudaError_t e) {
  return std::string(cudaGetErrorName(e)) + " (" + cudaGetErrorString(e) + ")";
}

std::string memory_text(std::size_t bytes) {
  return std::to_string(bytes) + " bytes (" + std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB)";
}

void throw_cuda_error(const char* who, const char* what, cudaError_t e) {
  cudaGetLastError();
  throw DeviceError(std::string(who) + ": " + what + ": " + cuda_error_text(e));
}

void throw_out_of_memory(const char* who, const char* what, std::size_t bytes, cudaError_t e, bool pinned) {
  cudaGetLastError();
  std::string msg = std::string(who) + ": out of " + (pinned ? "pinned host" : "device") +
                    " memory allocating " + memory_text(bytes) + " for " + what;
  std::size_t free_bytes = 0, total_bytes = 0;
  if (!pinned && cudaMemGetInfo(&free_bytes, &total_bytes) == cudaSuccess)
    msg += " (" + memory_text(free_bytes) + " free of " + memory_text(total_bytes) + ")";
  cudaGetLastError();
  if (pinned) throw DeviceError(msg + ": " + cuda_error_text(e));
  throw OutOfDeviceMemory(msg + ": " + cuda_error_text(e));
}

}  // namespace cudahull
