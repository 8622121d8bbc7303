#version 450 core
// Text and legend swatches (text.hpp) in the view's pixels, origin top left.

layout(location = 0) in vec2 a_pixel;
layout(location = 1) in vec2 a_uv;    // in the font atlas; negative: a solid rectangle
layout(location = 2) in vec4 a_color;  // RGBA8, normalised

uniform vec2 u_size;  // the view, pixels

out vec2 v_uv;
out vec4 v_color;

void main() {
  gl_Position = vec4(a_pixel.x / u_size.x * 2.0 - 1.0, 1.0 - a_pixel.y / u_size.y * 2.0, 0.0, 1.0);
  v_uv = a_uv;
  v_color = a_color;
}
