#version 450 core
// The point cloud (Fig. 1): one vertex per input point.  a_state is the per-point state buffer
// (render_data.hpp): >= 0 the face an external point belongs to, -1 internal, -2 hull vertex.
// u_pass 0 draws the cloud; u_pass 1 draws the hull vertices (an index buffer of vertex ids), larger.

layout(location = 0) in vec3 a_position;
layout(location = 1) in int a_state;

uniform mat4 u_view_proj;
uniform float u_point_size;  // framebuffer pixels
uniform int u_pass;
uniform int u_color_mode;  // 0: by state (internal red, external brown), 1: by associated face
uniform bool u_show_internal;
uniform bool u_show_external;
uniform vec3 u_internal_color;
uniform vec3 u_external_color;
uniform vec3 u_vertex_color;
uniform int u_selected_face;  // -1: none; else its cell's points are drawn in u_selected_color (Fig. 2)
uniform vec3 u_selected_color;
uniform vec2 u_cue_range;  // view depths of the nearest and the furthest data: full and dimmest shade

flat out vec3 v_color;
flat out int v_visible;
out float v_cue;

void main() {
  gl_Position = u_view_proj * vec4(a_position, 1.0);
  gl_PointSize = u_point_size;
  v_visible = 1;
  float depth = (gl_Position.w - u_cue_range.x) / max(u_cue_range.y - u_cue_range.x, 1e-20);
  v_cue = mix(1.0, 0.5, clamp(depth, 0.0, 1.0));
  if (u_pass == 1) {
    v_color = u_vertex_color;
    gl_PointSize = u_point_size * 1.4 + 1.0;
    return;
  }
  if (a_state == -2) {
    v_visible = 0;  // the vertices pass draws hull vertices
  } else if (a_state < 0) {
    // By face, internal points step back to grey: the cells' colours are what matters there.
    v_color = u_color_mode == 1 ? vec3(0.32) : u_internal_color;
    v_visible = u_show_internal ? 1 : 0;
  } else {
    v_color = u_color_mode == 1 ? face_color(a_state) : u_external_color;
    v_visible = u_show_external ? 1 : 0;
    if (a_state == u_selected_face) {
      v_color = u_selected_color;
      v_visible = 1;
      gl_PointSize = u_point_size + 2.0;
    }
  }
  // Outside the clip volume: hidden points cost no fragments.
  if (v_visible == 0) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}
