// OffscreenTarget (renderer.hpp): a multisampled framebuffer for screenshots and headless rendering,
// resolved and flipped on readback.
#include <glad/gl.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "renderer.hpp"

namespace cudahull::viewer {

OffscreenTarget::OffscreenTarget(int width, int height, int samples) : width_(width), height_(height) {
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples = std::max(1, std::min(samples, static_cast<int>(max_samples)));

  glCreateRenderbuffers(1, &color_);
  glNamedRenderbufferStorageMultisample(color_, samples, GL_RGBA8, width, height);
  glCreateRenderbuffers(1, &depth_);
  glNamedRenderbufferStorageMultisample(depth_, samples, GL_DEPTH_COMPONENT24, width, height);
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferRenderbuffer(fbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);

  glCreateRenderbuffers(1, &resolve_color_);
  glNamedRenderbufferStorage(resolve_color_, GL_RGBA8, width, height);
  glCreateFramebuffers(1, &resolve_fbo_);
  glNamedFramebufferRenderbuffer(resolve_fbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_color_);

  for (GLuint fb : {fbo_, resolve_fbo_}) {
    const GLenum status = glCheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw DeviceError("OpenGL: offscreen framebuffer " + std::to_string(width) + "x" +
                        std::to_string(height) + " incomplete (status " + std::to_string(status) + ")");
  }
}

OffscreenTarget::~OffscreenTarget() {
  const GLuint fbos[2] = {fbo_, resolve_fbo_};
  glDeleteFramebuffers(2, fbos);
  const GLuint rbs[3] = {color_, depth_, resolve_color_};
  glDeleteRenderbuffers(3, rbs);
}

void OffscreenTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
}

std::vector<std::uint8_t> OffscreenTarget::read_rgba() const {
  glBlitNamedFramebuffer(fbo_, resolve_fbo_, 0, 0, width_, height_, 0, 0, width_, height_,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  const std::size_t row = static_cast<std::size_t>(width_) * 4;
  std::vector<std::uint8_t> pixels(row * height_), flipped(row * height_);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (const GLenum e = glGetError(); e != GL_NO_ERROR)
    throw DeviceError("OpenGL: error " + std::to_string(e) + " while reading the offscreen framebuffer");
  // GL's first row is the bottom one.
  for (int y = 0; y < height_; ++y)
    std::copy_n(pixels.data() + (height_ - 1 - y) * row, row, flipped.data() + y * row);
  return flipped;
}

}  // namespace cudahull::viewer
