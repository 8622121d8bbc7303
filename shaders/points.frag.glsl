#version 450 core
// Round points with a darker rim, so dense clouds keep some structure.

flat in vec3 v_color;
flat in int v_visible;

uniform float u_opacity;

out vec4 frag_color;

void main() {
  if (v_visible == 0) discard;
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  frag_color = vec4(v_color * (r2 > 0.6 ? 0.7 : 1.0), u_opacity);
}
