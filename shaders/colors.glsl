// Colour functions shared by the viewer's shaders.  GLSL has no #include: gl_helpers.cpp's compile() puts
// this file after the #version line of every shader it compiles (no #version here).

vec3 hsv_to_rgb(float h, float s, float v) {
  vec3 k = clamp(abs(mod(h * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
  return v * mix(vec3(1.0), k, s);
}

// A stable, well spread colour per face id, so neighbouring cells differ (cf. the cells of Fig. 10).
vec3 face_color(int face) {
  uint h = uint(face) * 2654435761u;
  h ^= h >> 15;
  h *= 2246822519u;
  h ^= h >> 13;
  float hue = float(h & 1023u) / 1024.0;
  float value = 0.65 + 0.3 * float((h >> 10) & 3u) / 3.0;
  return hsv_to_rgb(hue, 0.7, value);
}
