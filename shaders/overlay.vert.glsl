#version 450 core
// The debugger's overlay (issue 6): translucent separating-plane quads (Fig. 2), the selected face's outline,
// its extreme point's marker and the edge-normal arrows, each vertex with its own colour.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_color;  // RGBA8, normalised

uniform mat4 u_view_proj;

out vec4 v_color;

void main() {
  gl_Position = u_view_proj * vec4(a_position, 1.0);
  v_color = a_color;
}
