#include "cuda_gl_buffer.hpp"

// cuda_gl_interop.h needs the GL types from GL/gl.h; this file must not include glad.
#include <GL/gl.h>
#include <cuda_gl_interop.h>
#include <cuda_runtime.h>

#include "cudahull/errors.hpp"

namespace cudahull::viewer {

namespace {
void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw DeviceError(std::string("CUDA-GL interop: ") + what + ": " + cudaGetErrorString(e));
}
}  // namespace

std::string cuda_gl_unavailable_reason() {
  int devices = 0;
  cudaError_t e = cudaGetDeviceCount(&devices);
  if (e != cudaSuccess || devices == 0) {
    cudaGetLastError();  // clear the sticky error of a machine without a driver
    return std::string("no CUDA device (") + (e != cudaSuccess ? cudaGetErrorString(e) : "none found") + ")";
  }
  unsigned int gl_devices = 0;
  int found[4];
  e = cudaGLGetDevices(&gl_devices, found, 4, cudaGLDeviceListAll);
  if (e != cudaSuccess || gl_devices == 0) {
    cudaGetLastError();
    return "the OpenGL context is not on a CUDA device (" +
           std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + ")";
  }
  for (unsigned i = 0; i < gl_devices; ++i) {
    if (found[i] == 0) return "";
  }
  return "the OpenGL context is on another CUDA device than the backend's (device 0)";
}

struct CudaGlBuffer::Resource {
  cudaGraphicsResource* handle = nullptr;
};

CudaGlBuffer::CudaGlBuffer(unsigned gl_buffer) : resource_(new Resource) {
  const cudaError_t e =
      cudaGraphicsGLRegisterBuffer(&resource_->handle, gl_buffer, cudaGraphicsRegisterFlagsWriteDiscard);
  if (e != cudaSuccess) {
    delete resource_;
    resource_ = nullptr;
    check(e, "registering the point state buffer");
  }
}

CudaGlBuffer::~CudaGlBuffer() {
  if (resource_ == nullptr) return;
  cudaGraphicsUnregisterResource(resource_->handle);
  delete resource_;
}

void CudaGlBuffer::write(const std::function<void(void* device, std::size_t bytes)>& write) {
  check(cudaGraphicsMapResources(1, &resource_->handle), "mapping the point state buffer");
  void* device = nullptr;
  std::size_t bytes = 0;
  try {
    check(cudaGraphicsResourceGetMappedPointer(&device, &bytes, resource_->handle), "getting its pointer");
    write(device, bytes);
  } catch (...) {
    cudaGraphicsUnmapResources(1, &resource_->handle);
    throw;
  }
  check(cudaGraphicsUnmapResources(1, &resource_->handle), "unmapping the point state buffer");
}

}  // namespace cudahull::viewer
