// The headless backend around the renderer: an OpenGL 4.5 core context with no window, through EGL.
//
// Features:
//   - the EGL device platform first (eglQueryDevicesEXT + eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT)),
//     which gives an NVIDIA GPU with no X server (docs/benchmarks.md, "Measurements behind the code") and
//     Mesa's software device elsewhere;
//   - then Mesa's surfaceless platform, then the default display;
//   - surfaceless contexts where EGL_KHR_surfaceless_context allows, else a 16x16 pbuffer: rendering goes
//     into an OffscreenTarget (renderer.hpp) anyway;
//   - glad loaded through eglGetProcAddress.
//
// Contract: create() makes the context current on the calling thread and throws DeviceError (exit 4) with a
// one-line reason when no display gives a GL 4.5 core context.  Destroy GL objects before the context.
#pragma once

#include <memory>
#include <string>

namespace cudahull::viewer {

class HeadlessContext {
 public:
  static std::unique_ptr<HeadlessContext> create();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  // Which platform and device, e.g. "EGL device 0 (EGL_MESA_device_software)".
  const std::string& description() const { return description_; }

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  void* surface_ = nullptr;
  std::string description_;
};

}  // namespace cudahull::viewer
