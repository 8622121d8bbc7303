// What the renderer draws, as plain CPU arrays (libigl's ViewerData): the scene fills it from the engine
// state, the renderer uploads what the dirty bits name and clears them.  No GL and no engine types here
// beyond Point3, so either side can change without the other.
//
// Per-point state (one int32 per point, the layout of the GL buffer the CUDA backend will write through
// CUDA-GL interop): >= 0 is the point's face in the current mesh (an external point), kPointInternal a point
// proven inside, kPointVertex a point that is a vertex of the current polyhedron.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/types.hpp"

namespace cudahull::viewer {

inline constexpr std::int32_t kPointInternal = -1;
inline constexpr std::int32_t kPointVertex = -2;
static_assert(kPointInternal == kPointStateInternal && kPointVertex == kPointStateVertex,
              "the backend writes the same codes through interop");

// What happened to a face in the last iteration (Algorithm 1), for the colour-by-state mode.
enum class FaceState : std::uint8_t {
  kUnchanged = 0,
  kRefined = 1,  // made by splitting a face at its extreme point (Fig. 3a)
  kSwapped = 2,  // made by a regular or complementary edge swap (Figs. 3b, 4)
  kRemoval = 3,  // made by removing a concave degree-3 vertex (Fig. 4)
};
inline constexpr int kFaceStateCount = 4;

// One corner of a face; faces are unindexed triangles (3 corners each) so that each face keeps its own
// state and the fragment shader can find its edges from the corner number (gl_VertexID % 3).
struct HullCorner {
  float x = 0, y = 0, z = 0;
  std::uint32_t info = 0;  // FaceState in the low 8 bits, the face's age in iterations above them
};
inline std::uint32_t pack_face_info(FaceState state, std::uint32_t age) {
  return static_cast<std::uint32_t>(state) | (std::min<std::uint32_t>(age, 0xffffffu) << 8);
}

// A vertex of the debugger's overlay (issue 6): translucent triangles and lines, each vertex coloured.
struct OverlayVertex {
  float x = 0, y = 0, z = 0;
  std::uint32_t rgba = 0;  // R in the low byte
};
// A number drawn next to a point of the scene (the swaps' sequence numbers), in screen space.
struct OverlayLabel {
  float x = 0, y = 0, z = 0;
  std::uint32_t rgba = 0;
  int number = 0;
};
// Text beside a point (the labels layer's vertex and face ids), centred `dx`, `dy` pixels right and down of
// it; left out where `n` (the outward direction, zero for always) faces clearly away from the eye.
struct TextLabel {
  float x = 0, y = 0, z = 0;
  float nx = 0, ny = 0, nz = 0;
  std::uint32_t rgba = 0;
  std::string text;
  float dx = 0, dy = 0;
};
inline std::uint32_t pack_rgba(float r, float g, float b, float a) {
  auto byte = [](float v) { return static_cast<std::uint32_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
  return byte(r) | byte(g) << 8 | byte(b) << 16 | byte(a) << 24;
}

enum DirtyBits : std::uint32_t {
  kDirtyPositions = 1u << 0,    // a new point set (reallocates the point buffers)
  kDirtyPointState = 1u << 1,   // point_state changed (same size)
  kDirtyHull = 1u << 2,         // hull corners or hull vertex ids changed
  kDirtyDeviceState = 1u << 3,  // point state to be written on the device (CUDA-GL interop); not upload()'s
  kDirtyAll = kDirtyPositions | kDirtyPointState | kDirtyHull,
};

struct RenderData {
  std::shared_ptr<const std::vector<Point3>> positions;  // shared with the scene, never copied
  std::vector<std::int32_t> point_state;                 // one per position
  std::vector<HullCorner> hull;                          // 3 per face of the current polyhedron
  std::vector<std::uint32_t> hull_vertex_ids;            // indices into positions
  // The input model's triangles, indices into positions (uploaded with kDirtyPositions); may be null.
  std::shared_ptr<const std::vector<std::array<std::uint32_t, 3>>> surface;
  std::uint32_t dirty = kDirtyAll;
};

}  // namespace cudahull::viewer
