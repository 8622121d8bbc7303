// CUDA-GL interop for the per-point state buffer (issue 5, item 3): the GL buffer is registered with CUDA
// once (cudaGraphicsGLRegisterBuffer) and mapped for each write, so the CUDA backend writes the colours'
// source straight into it and nothing per point comes back to the host.
//
// Plain C++ header (no GL or CUDA headers), so that glad and cuda_gl_interop.h never meet in one file.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace cudahull::viewer {

// Why the current GL context cannot share buffers with CUDA device 0 ("" when it can): no CUDA device, or
// the context is not on an NVIDIA GPU (Mesa, llvmpipe, CI).  Never throws.
std::string cuda_gl_unavailable_reason();

class CudaGlBuffer {
 public:
  // Registers GL buffer `gl_buffer` (current context) for write-discard mapping.  Throws DeviceError.
  explicit CudaGlBuffer(unsigned gl_buffer);
  ~CudaGlBuffer();
  CudaGlBuffer(const CudaGlBuffer&) = delete;
  CudaGlBuffer& operator=(const CudaGlBuffer&) = delete;

  // Maps the buffer, calls write(device pointer, size in bytes) and unmaps it; once unmapped, GL sees the
  // data.  Throws DeviceError.
  void write(const std::function<void(void* device, std::size_t bytes)>& write);

 private:
  struct Resource;
  Resource* resource_ = nullptr;
};

}  // namespace cudahull::viewer
