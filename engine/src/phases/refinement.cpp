#include "phases/refinement.hpp"

#include "cudahull/parallel.hpp"

namespace cudahull::phases {

Refinement refine(Mesh& mesh, const std::vector<FaceExtreme>& extremes, IterationRecord& record) {
  Refinement out;
  const auto old_faces = static_cast<FaceId>(mesh.face_capacity());
  for (FaceId f = 0; f < old_faces; ++f) {
    if (extremes[f].count != 0) out.refined.push_back(f);
  }
  const std::size_t count = out.refined.size();
  out.entries.resize(count);
  record.refined_apexes.resize(count);
  record.refined_faces.resize(count);
  parallel_chunks(
      count, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          const FaceId f = out.refined[k];
          out.entries[k].face = f;
          out.entries[k].apex = extremes[f].furthest;
          record.refined_apexes[k] = extremes[f].furthest;
          record.refined_faces[k] = mesh.face(f).v;
        }
      },
      16384);
  const FaceId first_child = mesh.split_batch(out.refined, record.refined_apexes, hardware_workers());
  out.children.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    for (FaceId i = 0; i < 3; ++i)
      out.children[k][i] = first_child + 3 * static_cast<FaceId>(k) + i;
  }
  record.faces_refined = count;
  return out;
}

}  // namespace cudahull::phases
