// The renderer's thin GL helpers (gl_helpers.cpp): programs from the embedded shaders, vertex layouts,
// buffers that grow, uniforms by name.
#pragma once

#include <glad/gl.h>

#include <cstddef>
#include <initializer_list>
#include <vector>

namespace cudahull::viewer {

// A compute program of the embedded shaders (colors.glsl prepended); throws DeviceError with the driver's
// log.  link_program() (renderer.hpp) makes the vertex + fragment ones.
unsigned link_compute(const char* source, const char* name);

// Enables attribute `attribute` of `vao`: `size` values of `type` at `offset` in the vertices of binding
// `binding`, read as floats (`normalized`: RGBA8 colours to 0..1).
void float_attribute(GLuint vao, GLuint attribute, GLuint binding, GLint size, GLenum type,
                     GLboolean normalized, GLuint offset);

// The same, read as integers.
void int_attribute(GLuint vao, GLuint attribute, GLuint binding, GLint size, GLenum type, GLuint offset);

// Creates one GL object a name in `names` with one call of `create` (glCreateBuffers, glCreateVertexArrays).
template <class Create>
void create_objects(Create create, std::initializer_list<GLuint*> names) {
  std::vector<GLuint> ids(names.size());
  create(static_cast<GLsizei>(ids.size()), ids.data());
  const GLuint* id = ids.data();
  for (GLuint* name : names)
    *name = *id++;
}

// Position + RGBA8 colour per vertex (OverlayVertex), from `buffer`: the overlay and the labels.
void bind_overlay_layout(GLuint vao, GLuint buffer);

GLint loc(unsigned program, const char* name);

// Grows a buffer to at least `bytes` (doubling), so per-step hull uploads rarely reallocate.
void ensure_capacity(unsigned buffer, std::size_t& capacity, std::size_t bytes);

}  // namespace cudahull::viewer
