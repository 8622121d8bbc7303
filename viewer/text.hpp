// Text in the picture (issue 17): vertex and face ids, the swaps' sequence numbers and the legend, in a real
// font, drawn by OpenGL alone so that headless screenshots have them as the window does.
//
// The font is a TrueType file from a Debian package (fonts-dejavu-core's DejaVuSans.ttf;
// $CUDAHULL_VIEWER_FONT overrides), read when the renderer starts and baked by stb_truetype into one atlas
// texture of the printable ASCII characters.  Without a font file, available() is false and the renderer says
// so once in font_note(); it then draws the sequence numbers as line digits, and no ids or legend.
//
// Contract: as Renderer's (a GL context current, glad loaded).  Coordinates are framebuffer pixels of the
// view, origin top left; queue text and rectangles, then draw() them all over the picture.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cudahull::viewer {

// The font file: $CUDAHULL_VIEWER_FONT, else fonts-dejavu-core's DejaVuSans.ttf (the path CMake found).
std::string viewer_font_path();

class TextRenderer {
 public:
  explicit TextRenderer(float pixel_height = 15.0f);
  ~TextRenderer();
  TextRenderer(const TextRenderer&) = delete;
  TextRenderer& operator=(const TextRenderer&) = delete;

  bool available() const { return texture_ != 0; }
  const std::string& font_note() const { return note_; }
  float pixel_height() const { return pixel_height_; }
  float line_height() const { return pixel_height_ * 1.25f; }
  float ascent() const { return ascent_; }
  float width(const std::string& text) const;

  void clear() { quads_.clear(); }
  // A filled rectangle, RGBA8 with R in the low byte.
  void add_rect(float x0, float y0, float x1, float y1, std::uint32_t rgba);
  // Text whose baseline starts at (x, y).
  void add_text(float x, float y, const std::string& text, std::uint32_t rgba);
  // Text with a dark outline (readable on any colour), centred on (x, y).
  void add_label(float x, float y, const std::string& text, std::uint32_t rgba);
  // Draws what was queued into the bound framebuffer's current viewport (width x height pixels).
  void draw(int width, int height) const;

 private:
  struct Vertex {
    float x, y, u, v;  // u < 0: a solid rectangle
    std::uint32_t rgba;
  };
  struct Glyph {
    float x0, y0, x1, y1;       // in the atlas, pixels
    float xoff, yoff, advance;  // pixels
  };
  void quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1,
            std::uint32_t rgba);

  float pixel_height_;
  float ascent_ = 0;
  std::string note_;
  std::vector<Glyph> glyphs_;  // characters 32..126
  int atlas_width_ = 512, atlas_height_ = 256;
  unsigned texture_ = 0, program_ = 0, vao_ = 0, buffer_ = 0;
  mutable std::size_t capacity_ = 0;
  std::vector<Vertex> quads_;
};

}  // namespace cudahull::viewer
