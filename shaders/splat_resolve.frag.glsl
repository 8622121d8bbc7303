#version 450 core
// Draws what points_splat.comp.glsl left per pixel: its colour, at its depth, so that the hull drawn later
// is depth-tested and blended against the points as with GL points.

layout(std430, binding = 2) readonly buffer Depths { uint depths[]; };
layout(std430, binding = 3) readonly buffer Colors { uint colors[]; };

uniform ivec2 u_size;
uniform ivec2 u_origin;  // the view's bottom left corner in the framebuffer

out vec4 frag_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  uint index = uint(p.y * u_size.x + p.x);
  uint depth = depths[index];
  if (depth == 0xffffffffu) discard;
  frag_color = unpackUnorm4x8(colors[index]);
  gl_FragDepth = uintBitsToFloat(depth);
}
