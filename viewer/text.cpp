#include "text.hpp"

#include <glad/gl.h>
#include <stb/stb_truetype.h>  // the implementation is Debian's libstb

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "cudahull/errors.hpp"
#include "embedded_shaders.hpp"
#include "renderer.hpp"

#ifndef CUDAHULL_VIEWER_FONT_PATH
#define CUDAHULL_VIEWER_FONT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#endif

namespace cudahull::viewer {

namespace {

constexpr int kFirstChar = 32, kCharCount = 95;  // printable ASCII

std::vector<unsigned char> read_font(std::string& path) {
  path = viewer_font_path();
  std::ifstream in(path, std::ios::binary);
  return in ? std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {})
            : std::vector<unsigned char>();
}

}  // namespace

std::string viewer_font_path() {
  const char* from_env = std::getenv("CUDAHULL_VIEWER_FONT");
  return from_env && *from_env ? from_env : CUDAHULL_VIEWER_FONT_PATH;
}

TextRenderer::TextRenderer(float pixel_height) : pixel_height_(pixel_height) {
  std::string path;
  const std::vector<unsigned char> font = read_font(path);
  stbtt_fontinfo info;
  if (font.empty() || !stbtt_InitFont(&info, font.data(), stbtt_GetFontOffsetForIndex(font.data(), 0))) {
    note_ =
        "no font at " + path + " (install fonts-dejavu-core, or set CUDAHULL_VIEWER_FONT): no ids or legend";
    return;
  }
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&info, &ascent, &descent, &gap);
  ascent_ = static_cast<float>(ascent) * stbtt_ScaleForPixelHeight(&info, pixel_height);
  std::vector<unsigned char> atlas(static_cast<std::size_t>(atlas_width_) * atlas_height_);
  stbtt_bakedchar baked[kCharCount];
  if (stbtt_BakeFontBitmap(font.data(), 0, pixel_height, atlas.data(), atlas_width_, atlas_height_,
                           kFirstChar, kCharCount, baked) <= 0) {
    note_ = "the font " + path + " does not fit the atlas: no ids or legend";
    return;
  }
  for (const stbtt_bakedchar& b : baked)
    glyphs_.push_back({static_cast<float>(b.x0), static_cast<float>(b.y0), static_cast<float>(b.x1),
                       static_cast<float>(b.y1), b.xoff, b.yoff, b.xadvance});
  note_ = "font " + path;

  glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
  glTextureStorage2D(texture_, 1, GL_R8, atlas_width_, atlas_height_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture_, 0, 0, 0, atlas_width_, atlas_height_, GL_RED, GL_UNSIGNED_BYTE, atlas.data());
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  program_ = link_program(shaders::text_vert, shaders::text_frag, "text");
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &buffer_);
  glVertexArrayVertexBuffer(vao_, 0, buffer_, 0, sizeof(Vertex));
  glVertexArrayAttribFormat(vao_, 0, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, x));
  glVertexArrayAttribFormat(vao_, 1, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, u));
  glVertexArrayAttribFormat(vao_, 2, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(Vertex, rgba));
  for (GLuint a = 0; a < 3; ++a) {
    glVertexArrayAttribBinding(vao_, a, 0);
    glEnableVertexArrayAttrib(vao_, a);
  }
}

TextRenderer::~TextRenderer() {
  if (texture_ == 0) return;
  glDeleteTextures(1, &texture_);
  glDeleteProgram(program_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &buffer_);
}

float TextRenderer::width(const std::string& text) const {
  float w = 0;
  for (unsigned char c : text) {
    if (c >= kFirstChar && c < kFirstChar + kCharCount && !glyphs_.empty())
      w += glyphs_[c - kFirstChar].advance;
  }
  return w;
}

void TextRenderer::quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1,
                        std::uint32_t rgba) {
  const Vertex a{x0, y0, u0, v0, rgba}, b{x1, y0, u1, v0, rgba}, c{x1, y1, u1, v1, rgba},
      d{x0, y1, u0, v1, rgba};
  quads_.insert(quads_.end(), {a, b, c, a, c, d});
}

void TextRenderer::add_rect(float x0, float y0, float x1, float y1, std::uint32_t rgba) {
  quad(x0, y0, x1, y1, -1, -1, -1, -1, rgba);
}

void TextRenderer::add_text(float x, float y, const std::string& text, std::uint32_t rgba) {
  if (!available()) return;
  const float su = 1.0f / static_cast<float>(atlas_width_), sv = 1.0f / static_cast<float>(atlas_height_);
  for (unsigned char c : text) {
    if (c < kFirstChar || c >= kFirstChar + kCharCount) continue;
    const Glyph& g = glyphs_[c - kFirstChar];
    // Whole pixels: the atlas's texels land on the screen's, so small text stays sharp.
    const float left = std::round(x + g.xoff), top = std::round(y + g.yoff);
    quad(left, top, left + (g.x1 - g.x0), top + (g.y1 - g.y0), g.x0 * su, g.y0 * sv, g.x1 * su, g.y1 * sv,
         rgba);
    x += g.advance;
  }
}

void TextRenderer::add_label(float x, float y, const std::string& text, std::uint32_t rgba) {
  const float left = x - 0.5f * width(text), baseline = y + 0.5f * (ascent_ * 0.75f);
  const std::uint32_t outline = pack_rgba(0.0f, 0.0f, 0.0f, 0.85f);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx != 0 || dy != 0) add_text(left + dx, baseline + dy, text, outline);
    }
  }
  add_text(left, baseline, text, rgba);
}

void TextRenderer::draw(int width, int height) const {
  if (!available() || quads_.empty()) return;
  const std::size_t bytes = quads_.size() * sizeof(Vertex);
  if (bytes > capacity_) {
    capacity_ = std::max(bytes, 2 * capacity_);
    glNamedBufferData(buffer_, static_cast<GLsizeiptr>(capacity_), nullptr, GL_DYNAMIC_DRAW);
  }
  glNamedBufferSubData(buffer_, 0, static_cast<GLsizeiptr>(bytes), quads_.data());
  glUseProgram(program_);
  glUniform2f(glGetUniformLocation(program_, "u_size"), static_cast<float>(width),
              static_cast<float>(height));
  glUniform1i(glGetUniformLocation(program_, "u_atlas"), 0);
  glBindTextureUnit(0, texture_);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(quads_.size()));
  glEnable(GL_DEPTH_TEST);
}

}  // namespace cudahull::viewer
