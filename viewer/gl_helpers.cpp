// The renderer's GL helpers (design: gl_helpers.hpp): shaders compiled and linked with colors.glsl, vertex
// layouts, growing buffers; and the context's description and glFinish for the session.
#include "gl_helpers.hpp"

#include <algorithm>
#include <cstddef>
#include <string>

#include "cudahull/errors.hpp"
#include "embedded_shaders.hpp"
#include "render_data.hpp"
#include "renderer.hpp"

namespace cudahull::viewer {

namespace {

// Throws DeviceError with `message` and the driver's log when `object` (a shader or a program, with its
// glGet*iv, glGet*InfoLog and glDelete*) failed `status`, deleting it first.
template <class GetIv, class GetLog, class Delete>
void check_built(GLuint object, GLenum status, GetIv get_iv, GetLog get_log, Delete destroy,
                 const std::string& message) {
  GLint ok = 0;
  get_iv(object, status, &ok);
  if (ok) return;
  char log[2048] = {};
  get_log(object, sizeof log, nullptr, log);
  destroy(object);
  throw DeviceError(message + log);
}

// Compiles `source` with shaders/colors.glsl (hsv_to_rgb, face_color) after its #version line: GLSL has
// no #include.  `#line 2` keeps the driver's line numbers those of the file.
unsigned compile(GLenum type, const char* source, const char* name) {
  const std::string text(source);
  const std::size_t first_line_end = text.find('\n') + 1;
  const std::string version = text.substr(0, first_line_end);
  const std::string rest = "#line 2\n" + text.substr(first_line_end);
  const char* parts[] = {version.c_str(), shaders::colors, rest.c_str()};
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 3, parts, nullptr);
  glCompileShader(shader);
  check_built(shader, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, glDeleteShader,
              std::string("OpenGL: shader ") + name + " does not compile: ");
  return shader;
}

// Links the compiled shaders into a program and deletes them; throws DeviceError with the driver's log.
unsigned link_shaders(std::initializer_list<GLuint> shaders, const char* name) {
  const GLuint program = glCreateProgram();
  for (GLuint shader : shaders)
    glAttachShader(program, shader);
  glLinkProgram(program);
  for (GLuint shader : shaders)
    glDeleteShader(shader);
  check_built(program, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, glDeleteProgram,
              std::string("OpenGL: program ") + name + " does not link: ");
  return program;
}

}  // namespace

unsigned link_program(const char* vertex, const char* fragment, const char* name) {
  return link_shaders({compile(GL_VERTEX_SHADER, vertex, name), compile(GL_FRAGMENT_SHADER, fragment, name)},
                      name);
}

unsigned link_compute(const char* source, const char* name) {
  return link_shaders({compile(GL_COMPUTE_SHADER, source, name)}, name);
}

void float_attribute(GLuint vao, GLuint attribute, GLuint binding, GLint size, GLenum type,
                     GLboolean normalized, GLuint offset) {
  glVertexArrayAttribFormat(vao, attribute, size, type, normalized, offset);
  glVertexArrayAttribBinding(vao, attribute, binding);
  glEnableVertexArrayAttrib(vao, attribute);
}

void int_attribute(GLuint vao, GLuint attribute, GLuint binding, GLint size, GLenum type, GLuint offset) {
  glVertexArrayAttribIFormat(vao, attribute, size, type, offset);
  glVertexArrayAttribBinding(vao, attribute, binding);
  glEnableVertexArrayAttrib(vao, attribute);
}

void bind_overlay_layout(GLuint vao, GLuint buffer) {
  glVertexArrayVertexBuffer(vao, 0, buffer, 0, sizeof(OverlayVertex));
  float_attribute(vao, 0, 0, 3, GL_FLOAT, GL_FALSE, offsetof(OverlayVertex, x));
  float_attribute(vao, 1, 0, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(OverlayVertex, rgba));
}

GLint loc(unsigned program, const char* name) {
  return glGetUniformLocation(program, name);
}

void ensure_capacity(unsigned buffer, std::size_t& capacity, std::size_t bytes) {
  if (bytes <= capacity && capacity != 0) return;
  capacity = std::max<std::size_t>({bytes, capacity * 2, 256});
  glNamedBufferData(buffer, static_cast<GLsizeiptr>(capacity), nullptr, GL_DYNAMIC_DRAW);
}

std::string gl_description() {
  auto str = [](GLenum e) {
    const GLubyte* s = glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

void finish_gl() {
  glFinish();
}

}  // namespace cudahull::viewer
