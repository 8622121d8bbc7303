#include "phases/local_edits.hpp"

#include <algorithm>

#include "cudahull/parallel.hpp"
#include "phases/swaps.hpp"
#include "phases/vertex_removal.hpp"

namespace cudahull::phases {

template <class Point>
void settle(LocalEdits<Point>& edits) {
  Mesh& mesh = edits.mesh;
  IterationRecord& record = edits.record;
  edits.reset_budget();
  bool changed = true;
  while (changed && edits.budget > 0) {
    changed = false;
    // Complementary swaps of the queued edges: in rounds when there are many.
    if (edits.queue.size() >= edits.batched_swaps_from) {
      std::vector<SwapCandidate> candidates;
      candidates.reserve(edits.queue.size());
      for (const Edge& edge : edits.queue)
        candidates.push_back({edge, SwapKind::kComplementary});
      edits.queue.clear();
      const std::size_t before = record.swaps_complementary;
      swap_edges(edits, std::move(candidates));
      if (record.swaps_complementary != before) changed = true;
    }
    while (!edits.queue.empty() && edits.budget > 0) {
      const Edge edge = edits.queue.front();
      edits.queue.pop_front();
      if (mesh.alive(edge.face) && try_swap(edits, edge.face, edge.index, SwapKind::kComplementary)) {
        changed = true;
        --edits.budget;
      }
    }
    // Vertices proven inside: taken out (Fig. 4).
    std::vector<PointIndex> out = std::move(edits.doomed);
    edits.doomed.clear();
    for (PointIndex w : out) {
      if (take_out(edits, w)) changed = true;
      edits.vertex_flags[w] &= static_cast<std::uint8_t>(~kDoomed);
      --edits.doomed_now;
    }
    // Touched vertices of degree 3 that are concave or flat: removed (Fig. 4).
    std::vector<PointIndex> candidates = std::move(edits.touched);
    edits.touched.clear();
    if (edits.touched_unsorted) {
      parallel_sort(candidates);
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      edits.touched_unsorted = false;
    }
    if (candidates.size() >= edits.batched_swaps_from) {
      // Many candidates (a batched iteration): find those of degree 3 on all cores first.  One whose
      // degree falls to 3 by an earlier removal here was touched by it, so the next pass sees it.
      std::vector<std::uint8_t> degree3(candidates.size());
      parallel_chunks(
          candidates.size(), hardware_workers(),
          [&](std::size_t begin, std::size_t end, unsigned) {
            for (std::size_t k = begin; k < end; ++k) {
              const PointIndex v = candidates[k];
              if (std::uint8_t* flags = edits.vertex_flags.find(v))
                *flags &= static_cast<std::uint8_t>(~kTouched);
              degree3[k] = mesh.has_vertex(v) && mesh.degree(v, 4) == 3;
            }
          },
          1024);
      for (std::size_t k = 0; k < candidates.size(); ++k) {
        const PointIndex v = candidates[k];
        if (degree3[k] && mesh.degree(v, 4) == 3 && try_remove(edits, v, false)) changed = true;
      }
    } else {
      for (PointIndex v : candidates)
        edits.vertex_flags[v] &= static_cast<std::uint8_t>(~kTouched);
      for (PointIndex v : candidates) {
        if (mesh.has_vertex(v) && mesh.degree(v, 4) == 3 && try_remove(edits, v, false)) changed = true;
      }
    }
    if (!edits.queue.empty()) changed = true;
    if (edits.budget > 0) --edits.budget;  // unsigned: at 0 a plain decrement wrapped round and never ended
  }
}

// The two coordinate types (README, "Precision").
template void settle(LocalEdits<Point3>&);
template void settle(LocalEdits<Point3d>&);

}  // namespace cudahull::phases
