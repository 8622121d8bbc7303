#version 450 core
// Round points shaded as small spheres (a light from the upper left of the eye, so the cloud reads as a
// surface), darker with depth (the depth cue: v_cue).  Every colour written is the point's colour times a
// factor, as the hull's, so the states stay apart at any shade.  The disc's edge is a coverage ramp: with
// opaque points that is alpha to coverage over the MSAA samples (renderer.cpp), which keeps dense regular
// scans such as the bunny free of moire; translucent points blend it.

flat in vec3 v_color;
flat in int v_visible;
in float v_cue;

uniform float u_opacity;
uniform float u_point_size;  // framebuffer pixels

out vec4 frag_color;

void main() {
  if (v_visible == 0) discard;
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  vec3 normal = vec3(d.x, -d.y, sqrt(1.0 - r2));
  float light = max(dot(normal, normalize(vec3(-0.35, 0.45, 0.82))), 0.0);
  // Sphere shading only where a point is big enough to show it: on small points the bright centres and dark
  // rims would trace the scan's grid (the moire of issue 17).
  float relief = smoothstep(4.0, 10.0, u_point_size);
  float shade = mix(0.85, 0.45 + 0.55 * light, relief) * v_cue;
  // The last pixel of the radius fades out; points of a pixel or two are whole pixels (a ramp across all of
  // them would leave next to no coverage).
  float edge = u_point_size < 3.0 ? 1.0 : 1.0 - smoothstep(1.0 - 2.0 / u_point_size, 1.0, sqrt(r2));
  frag_color = vec4(v_color * shade, u_opacity * edge);
}
