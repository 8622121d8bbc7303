#version 450 core
// The current polyhedron as unindexed triangles: corner k of a face is vertex 3f + k, which gives each
// fragment its barycentric coordinates for the wireframe without a second pass.

layout(location = 0) in vec3 a_position;
layout(location = 1) in uint a_info;  // FaceState in the low 8 bits, age (iterations) above

uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec3 u_state_colors[4];  // unchanged, refined, swapped, removal (render_data.hpp, FaceState)
uniform int u_color_mode;        // 0: by state in the last iteration, 1: by age
uniform float u_age_span;        // iterations over which the age colour fades

out vec3 v_view_pos;
noperspective out vec3 v_bary;
flat out vec3 v_base;

void main() {
  vec4 view_pos = u_view * vec4(a_position, 1.0);
  v_view_pos = view_pos.xyz;
  gl_Position = u_proj * view_pos;
  int corner = gl_VertexID % 3;
  v_bary = vec3(corner == 0, corner == 1, corner == 2);
  uint state = a_info & 255u;
  if (u_color_mode == 1) {
    // New faces orange, through green, to blue for those older than u_age_span iterations.
    float t = clamp(float(a_info >> 8) / max(u_age_span, 1.0), 0.0, 1.0);
    v_base = hsv_to_rgb(mix(0.08, 0.62, t), 0.7, 0.92);
  } else {
    v_base = u_state_colors[min(state, 3u)];
  }
}
