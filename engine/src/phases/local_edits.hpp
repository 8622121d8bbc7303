// The state that one iteration's local edits share: swaps (swaps.hpp, Figs. 3b and 5) and vertex removals
// (vertex_removal.hpp, Fig. 4), and settle(), which runs them until the mesh is convex again.
//
// design:
//   regular swaps:   each refined face's old edge (edge 0 of each child) is tried once: swapped when
//                    concave and valid, recorded when rejected (swap_edges)
//   settle:          repeat until nothing changes
//                      complementary swaps of every edge a swap or removal queued
//                      take out every vertex proven inside (complementary swaps around it down to degree
//                        3, then its removal, Fig. 4)
//                      remove every touched vertex of degree 3 that is concave or flat
//   Each edit appends its decision entry (decision_array.hpp) and its record (records.hpp), queues the
//   edges around it and touches its vertices.  A budget bounds the edits (degenerate input can cycle); the
//   final exact check repairs what is left.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "cudahull/mesh.hpp"
#include "cudahull/point_map.hpp"
#include "cudahull/records.hpp"
#include "phases/decision_array.hpp"

namespace cudahull::phases {

struct Edge {
  FaceId face;
  int index;
};

// Per-point flags of the edits (LocalEdits::vertex_flags).
inline constexpr std::uint8_t kDoomed = 1;       // a vertex proven inside the hull, being taken out
inline constexpr std::uint8_t kRemovedOnce = 2;  // removed as concave before: a fold made it look concave
inline constexpr std::uint8_t kTouched = 4;      // queued as a removal candidate

struct SwapScratch;  // swaps.hpp: the batched rounds' buffers, kept from one iteration to the next

// What the edits read (points, interior point, options) and what they change (mesh, flags, decision
// entries, record, dropped vertices), and their work lists.
template <class Point>
struct LocalEdits {
  LocalEdits(const std::vector<Point>& points, const Vec3d& interior, std::size_t batched_swaps_from,
             Mesh& mesh, PointMap<std::uint8_t>& vertex_flags, DecisionArrayBuilder& decisions,
             IterationRecord& record, std::vector<PointIndex>& dropped, std::vector<PointIndex>& dropped_near,
             SwapScratch& scratch)
      : points(points),
        interior(interior),
        batched_swaps_from(batched_swaps_from),
        mesh(mesh),
        vertex_flags(vertex_flags),
        decisions(decisions),
        record(record),
        dropped(dropped),
        dropped_near(dropped_near),
        scratch(scratch) {}

  const std::vector<Point>& points;
  const Vec3d& interior;  // c: every foldover test and every "proven inside" is relative to it
  std::size_t batched_swaps_from;
  Mesh& mesh;
  PointMap<std::uint8_t>& vertex_flags;
  DecisionArrayBuilder& decisions;
  IterationRecord& record;
  // Vertices that removals dropped from the mesh, each with a vertex of its ring (where the final check
  // looks for it); over the whole run.
  std::vector<PointIndex>& dropped;
  std::vector<PointIndex>& dropped_near;
  SwapScratch& scratch;

  std::deque<Edge> queue;           // edges to try as complementary swaps
  std::vector<PointIndex> touched;  // vertices whose neighbourhood changed: removal candidates
  // Batched edits append to `touched` on all cores without the kTouched flag, repeats and all; settle()
  // then sorts and dedupes it (an order that does not depend on the number of threads).
  bool touched_unsorted = false;
  std::vector<PointIndex> doomed;  // vertices proven not extreme, to be taken out (Fig. 4)
  std::size_t doomed_now = 0;      // most iterations doom none: then no lookup per tried swap
  std::set<std::pair<PointIndex, PointIndex>> rejected_edges;  // each recorded once an iteration
  std::vector<PointIndex> ring;                                // scratch
  std::vector<FaceId> ring_faces;                              // scratch
  int sequence = 0;  // the next record's sequence number (swaps and removals share it)
  // Edits left before settle() gives up (a guard against cycling on degenerate input; the exact finish
  // repairs what is left).  Every swap counts, those of take_out() included.
  std::size_t budget = 0;

  Vec3d P(PointIndex i) const { return to_vec3d(points[i]); }
  bool is_doomed(PointIndex v) const { return doomed_now != 0 && (vertex_flags.get(v) & kDoomed) != 0; }
  // Queues v once as a removal candidate.
  void touch(PointIndex v) {
    std::uint8_t& flags = vertex_flags[v];
    if (flags & kTouched) return;
    flags |= kTouched;
    touched.push_back(v);
  }
  void reset_budget() { budget = 20 * mesh.face_capacity() + 1000; }
};

// Complementary swaps and removals until nothing changes (see the design above).  Concave swaps add
// volume and take-outs lower the vertex count, so this terminates in exact arithmetic; the budget guards
// against cycling on degenerate input (the property test found one: a cluster 1e6 from the origin).
template <class Point>
void settle(LocalEdits<Point>& edits);

}  // namespace cudahull::phases
