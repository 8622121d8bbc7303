#version 450 core
// Grey and half transparent, lit as the hull is (a headlight and a key light from the upper left), so the
// model's shape reads under the points and inside the hull.

in vec3 v_view_pos;

uniform float u_opacity;

out vec4 frag_color;

void main() {
  vec3 normal = normalize(cross(dFdx(v_view_pos), dFdy(v_view_pos)));
  float shade = 0.3 + 0.45 * abs(normal.z) + 0.25 * abs(dot(normal, normalize(vec3(-0.35, 0.45, 0.82))));
  frag_color = vec4(vec3(0.78) * shade, u_opacity);
}
