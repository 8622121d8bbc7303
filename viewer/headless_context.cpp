#include "headless_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"

namespace cudahull::viewer {

namespace {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

GLADapiproc egl_loader(const char* name) {
  return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name));
}

struct Attempt {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
};

// Initialises `display` and makes a current GL 4.5 core context on it; on failure says why in `why` and
// leaves nothing behind.
bool make_current(EGLDisplay display, Attempt& out, std::string& why) {
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
    why = "eglInitialize failed";
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = "no desktop OpenGL API";
    eglTerminate(display);
    return false;
  }
  const bool surfaceless =
      has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context");
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
                                   surfaceless ? 0 : EGL_PBUFFER_BIT,
                                   EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT,
                                   EGL_RED_SIZE,
                                   8,
                                   EGL_GREEN_SIZE,
                                   8,
                                   EGL_BLUE_SIZE,
                                   8,
                                   EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count < 1) {
    why = "no EGL config for desktop OpenGL";
    eglTerminate(display);
    return false;
  }
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    4,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    5,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
  if (context == EGL_NO_CONTEXT) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
    why = std::string("no OpenGL 4.5 core context (EGL error ") + code + ")";
    eglTerminate(display);
    return false;
  }
  EGLSurface surface = EGL_NO_SURFACE;
  if (!surfaceless) {
    const EGLint pbuffer_attribs[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
    surface = eglCreatePbufferSurface(display, config, pbuffer_attribs);
  }
  if ((!surfaceless && surface == EGL_NO_SURFACE) || !eglMakeCurrent(display, surface, surface, context)) {
    why = "eglMakeCurrent failed";
    if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
    eglDestroyContext(display, context);
    eglTerminate(display);
    return false;
  }
  out = {display, context, surface};
  return true;
}

}  // namespace

std::unique_ptr<HeadlessContext> HeadlessContext::create() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  Attempt attempt;
  std::string description, why, reasons;
  auto note = [&](const std::string& what) { reasons += (reasons.empty() ? "" : "; ") + what + ": " + why; };

  // 1. The EGL device platform: the GPU itself, with no X server.
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_device_string =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (query_devices && get_platform_display && has_extension(client, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices(16, devices, &count)) {
      // Hardware devices before Mesa's software one: CUDA-GL interop needs the context on the GPU.
      for (int pass = 0; pass < 2; ++pass) {
        for (EGLint i = 0; i < count && attempt.context == EGL_NO_CONTEXT; ++i) {
          const char* ext = query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : nullptr;
          if (has_extension(ext, "EGL_MESA_device_software") != (pass == 1)) continue;
          const EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
          if (make_current(d, attempt, why)) {
            description =
                "EGL device " + std::to_string(i) + (ext && *ext ? std::string(" (") + ext + ")" : "");
          } else {
            note("EGL device " + std::to_string(i));
          }
        }
      }
    }
  }
  // 2. Mesa's surfaceless platform (llvmpipe with no display at all).
  if (attempt.context == EGL_NO_CONTEXT && get_platform_display &&
      has_extension(client, "EGL_MESA_platform_surfaceless")) {
    if (make_current(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                     attempt, why)) {
      description = "EGL surfaceless platform (Mesa)";
    } else {
      note("EGL surfaceless platform");
    }
  }
  // 3. Whatever the default display is.
  if (attempt.context == EGL_NO_CONTEXT) {
    if (make_current(eglGetDisplay(EGL_DEFAULT_DISPLAY), attempt, why)) {
      description = "EGL default display";
    } else {
      note("EGL default display");
    }
  }
  if (attempt.context == EGL_NO_CONTEXT)
    throw DeviceError("headless OpenGL: no EGL display gives an OpenGL 4.5 core context (" + reasons + ")");

  std::unique_ptr<HeadlessContext> ctx(new HeadlessContext);
  ctx->display_ = attempt.display;
  ctx->context_ = attempt.context;
  ctx->surface_ = attempt.surface;
  ctx->description_ = description;
  const int version = gladLoadGL(egl_loader);
  if (version == 0 || GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 45)
    throw DeviceError("headless OpenGL: " + description + " gives no usable OpenGL 4.5 core functions");
  return ctx;
}

HeadlessContext::~HeadlessContext() {
  const EGLDisplay display = display_;
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (surface_ != nullptr) eglDestroySurface(display, static_cast<EGLSurface>(surface_));
  eglDestroyContext(display, static_cast<EGLContext>(context_));
  eglTerminate(display);
}

}  // namespace cudahull::viewer
