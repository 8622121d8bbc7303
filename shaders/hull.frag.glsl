#version 450 core
// Flat shading with a headlight and a key light from the upper left of the eye (the face normal from
// screen-space derivatives, so no normal buffer), and an anti-aliased wireframe from the barycentric
// coordinates (MSAA smooths the faces' own edges).  Every colour written is the face's base
// colour times a factor, which keeps the states apart at any shade (and lets tests recognise them).

in vec3 v_view_pos;
noperspective in vec3 v_bary;
flat in vec3 v_base;

uniform bool u_show_faces;
uniform bool u_show_wire;
uniform float u_opacity;     // of the faces
uniform float u_wire_width;  // framebuffer pixels

out vec4 frag_color;

void main() {
  vec3 normal = normalize(cross(dFdx(v_view_pos), dFdy(v_view_pos)));
  // At most 1: the face's colour is the brightest it gets.
  float shade = 0.3 + 0.45 * abs(normal.z) + 0.25 * abs(dot(normal, normalize(vec3(-0.35, 0.45, 0.82))));
  vec3 width = fwidth(v_bary) * u_wire_width;
  vec3 ramp = smoothstep(width * 0.5, width, v_bary);
  float edge = u_show_wire ? 1.0 - min(min(ramp.x, ramp.y), ramp.z) : 0.0;
  if (u_show_faces) {
    vec3 color = v_base * mix(shade, 0.45, edge);
    frag_color = vec4(color, mix(u_opacity, 1.0, edge));
  } else {
    if (edge < 0.01) discard;
    frag_color = vec4(v_base * 0.9, edge);
  }
}
