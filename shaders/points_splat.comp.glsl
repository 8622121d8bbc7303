#version 450 core
// Compute splatting for large clouds (Schuetz, Kerbl, Wimmer 2021, "Rendering Point Clouds with Compute
// Shaders"): the H100 pushes only about 1G points a second through the GL point pipeline, even culled, so
// 20M GL_POINTS cannot make 60 fps.  Pass 0 keeps each pixel's nearest depth (32-bit atomicMin on the float
// bits, which order like the floats for depths in [0, 1]); pass 1 writes the colour of the point at that
// depth.  splat_resolve.frag.glsl then draws both into the framebuffer.  Same colours and layers as
// points.vert.glsl; hull vertices (state -2) are left to the vertices pass.
layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Positions { float positions[]; };
layout(std430, binding = 1) readonly buffer States { int states[]; };
layout(std430, binding = 2) buffer Depths { uint depths[]; };
layout(std430, binding = 3) buffer Colors { uint colors[]; };

uniform mat4 u_view_proj;
uniform uint u_count;
uniform ivec2 u_size;       // framebuffer pixels
uniform float u_point_size;  // framebuffer pixels
uniform int u_pass;
uniform int u_color_mode;  // 0: by state, 1: by associated face
uniform bool u_show_internal;
uniform bool u_show_external;
uniform vec3 u_internal_color;
uniform vec3 u_external_color;
uniform int u_selected_face;  // as in points.vert.glsl
uniform vec3 u_selected_color;

void main() {
  // Dispatched as a 2-d grid (at most 65535 groups a row): the point index runs across the rows.
  uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
  if (i >= u_count) return;
  int state = states[i];
  if (state == -2) return;
  bool internal = state < 0;
  bool selected = state == u_selected_face;
  if (internal ? !u_show_internal : !(u_show_external || selected)) return;
  vec4 clip = u_view_proj * vec4(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2], 1.0);
  if (clip.w <= 0.0) return;
  vec3 ndc = clip.xyz / clip.w;
  if (any(greaterThan(abs(ndc), vec3(1.0)))) return;
  uint key = floatBitsToUint(ndc.z * 0.5 + 0.5);
  // The pixels whose centres lie in the point's square, as GL rasterizes a point of that size.
  vec2 centre = (ndc.xy * 0.5 + 0.5) * vec2(u_size);
  float half_size = 0.5 * max(u_point_size, 1.0);
  ivec2 lo = max(ivec2(ceil(centre - half_size - 0.5)), ivec2(0));
  ivec2 hi = min(ivec2(floor(centre + half_size - 0.5)), u_size - 1);
  hi = min(hi, lo + 7);  // at most 8 x 8 pixels
  uint rgba = 0u;
  if (u_pass == 1) {
    vec3 c = internal   ? (u_color_mode == 1 ? vec3(0.32) : u_internal_color)
             : selected ? u_selected_color
                        : (u_color_mode == 1 ? face_color(state) : u_external_color);
    rgba = packUnorm4x8(vec4(c, 1.0));
  }
  for (int y = lo.y; y <= hi.y; ++y) {
    for (int x = lo.x; x <= hi.x; ++x) {
      uint index = uint(y * u_size.x + x);
      if (u_pass == 0) {
        atomicMin(depths[index], key);
      } else if (depths[index] == key) {
        colors[index] = rgba;
      }
    }
  }
}
