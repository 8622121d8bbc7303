#version 450 core
// The input model's own surface (the input layer): its triangles index the point buffer.

layout(location = 0) in vec3 a_position;

uniform mat4 u_view;
uniform mat4 u_proj;

out vec3 v_view_pos;

void main() {
  vec4 view_pos = u_view * vec4(a_position, 1.0);
  v_view_pos = view_pos.xyz;
  gl_Position = u_proj * view_pos;
}
