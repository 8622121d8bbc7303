// A mesh's live faces as a set that survives renumbering: each face rotated to start at its smallest
// corner (orientation kept), sorted.  Two meshes with the same faces compare equal.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "cudahull/mesh.hpp"

namespace cudahull::testing {

inline std::vector<std::array<PointIndex, 3>> face_set(const Mesh& mesh) {
  std::vector<std::array<PointIndex, 3>> faces;
  for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
    if (!mesh.alive(f)) continue;
    std::array<PointIndex, 3> v = mesh.face(f).v;
    std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
    faces.push_back(v);
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

}  // namespace cudahull::testing
