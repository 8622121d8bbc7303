// Refinement (Fig. 3a).
//
// design:
//   for every face f with external points (in id order), at its furthest point p (the apex):
//     f = (a, b, c) becomes (a, b, p), (b, c, p), (c, a, p); child i keeps f's edge i as its edge 0
//     refinement[k] = {f, p}; its three planes come later (cells.hpp), its children's route codes after
//       compaction (decision_array.hpp)
//   All faces split at once (Mesh::split_batch), each child linking through its neighbours' children.
//   The old edges (edge 0 of every child) are the candidates of the regular swaps.
#pragma once

#include <array>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/mesh.hpp"
#include "cudahull/records.hpp"

namespace cudahull::phases {

struct Refinement {
  std::vector<FaceId> refined;                  // the old faces, in id order
  std::vector<RefinementEntry> entries;         // Fig. 7's refinement[], one per refined face
  std::vector<std::array<FaceId, 3>> children;  // work ids, one triple per entry
};

// Splits every face with external points at its furthest point; fills record.refined_apexes,
// refined_faces and faces_refined.
Refinement refine(Mesh& mesh, const std::vector<FaceExtreme>& extremes, IterationRecord& record);

}  // namespace cudahull::phases
