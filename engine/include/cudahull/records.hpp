// What one step of the engine did, for the debugger, the trace and the tests: the records of Algorithm 1's
// phases.  The engine fills them (engine/src/phases/), trace.cpp writes them as JSON lines, the viewer draws
// them (the swaps and refinement layers, the Debugger panel).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cudahull/mesh.hpp"
#include "cudahull/routing.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

enum class SwapKind : std::uint8_t {
  kRegular,             // a concave edge of a refined face, swapped (Fig. 3b)
  kComplementary,       // a concave edge made by an earlier swap or removal of the same iteration (Fig. 4)
  kRejectedFoldover,    // swapping would fold the surface over: a vertex lies beneath a new triangle (Fig. 5)
  kRejectedEdgeExists,  // the new edge is already an edge of the mesh (would not be a 2-manifold)
  kRejectedDegenerate,  // the four points are coplanar in the projection from the interior point
};
const char* swap_kind_name(SwapKind kind);

struct SwapRecord {
  SwapKind kind = SwapKind::kRegular;
  int sequence = 0;                      // order within the iteration, over all swaps and rejections
  PointIndex old_edge[2] = {0, 0};       // u, v
  PointIndex new_edge[2] = {0, 0};       // x, y (the edge it would become, for rejected ones)
  PointIndex beneath_vertex = kNoPoint;  // foldover: the vertex of the old edge lying beneath ...
  PointIndex beneath_triangle[3] = {kNoPoint, kNoPoint, kNoPoint};  // ... this would-be triangle
  std::int32_t decision_index = -1;  // its entry in the decision array, for performed swaps
};

struct RemovalRecord {
  int sequence = 0;  // order within the iteration, shared with the swaps
  PointIndex vertex = 0;
  PointIndex ring[3] = {0, 0, 0};  // the new face
  std::int32_t decision_index = -1;
  bool rejected = false;  // concave but removal would fold over or create congruent triangles
};

struct IterationRecord {
  int iteration = 0;  // 0 is the initial tetrahedron and first distribution (section 3.1)
  std::size_t faces_before = 0, faces_after = 0, faces_refined = 0;
  std::size_t swaps_regular = 0, swaps_complementary = 0, swaps_rejected = 0;
  std::size_t vertices_removed = 0, removals_rejected = 0;
  std::size_t decision_entries = 0;
  std::size_t external_before = 0, external_after = 0;  // points still outside the current hull
  std::size_t repairs = 0;  // exact fixes where the local procedure fell short (0 in general position)
  double host_ms = 0, backend_ms = 0;
  double upload_ms = 0;  // iteration 0: putting the points on the backend (part of backend_ms)
  std::uint64_t bytes_to_backend = 0, bytes_from_backend = 0;
  std::vector<SwapRecord> swaps;
  std::vector<RemovalRecord> removals;
  std::vector<PointIndex> refined_apexes;                // the extreme points used, one per refined face
  std::vector<std::array<PointIndex, 3>> refined_faces;  // each refined face's corners, as refined_apexes
  std::vector<DecisionEntry> decisions;                  // the decision array (Fig. 7) sent this iteration
  std::string note;                                      // e.g. "degenerate input: dimension 2"
};

// An edit the engine kept in an iteration: a performed swap (regular or complementary) or a removal that was
// not rejected; one of the two is set.
struct KeptEdit {
  int sequence = 0;
  const SwapRecord* swap = nullptr;
  const RemovalRecord* removal = nullptr;
};

// The record's kept edits in the order the engine made them: replayed one at a time on the mesh after the
// refinement (redo_swap(), Mesh::remove_degree3()), they make the mesh after the step.
std::vector<KeptEdit> kept_edits(const IterationRecord& record);

// A recorded swap done again on `mesh`: its old edge, found around its first vertex, swapped.  The faces it
// made (as Mesh::swap() returns them), or nothing where the mesh has no such edge.
std::optional<std::array<FaceId, 2>> redo_swap(Mesh& mesh, const SwapRecord& swap);

// Every count of a record with its name, in declaration order: visit(name, value) with an int, std::size_t,
// double or std::uint64_t (upload_ms on iteration 0 only).  The trace's JSON and the Python module's dict are
// made from it, so a count added here shows in both.
template <class Visit>
void for_each_count(const IterationRecord& r, Visit&& visit) {
  visit("iteration", r.iteration);
  visit("faces_before", r.faces_before);
  visit("faces_after", r.faces_after);
  visit("faces_refined", r.faces_refined);
  visit("swaps_regular", r.swaps_regular);
  visit("swaps_complementary", r.swaps_complementary);
  visit("swaps_rejected", r.swaps_rejected);
  visit("vertices_removed", r.vertices_removed);
  visit("removals_rejected", r.removals_rejected);
  visit("decision_entries", r.decision_entries);
  visit("external_before", r.external_before);
  visit("external_after", r.external_after);
  visit("repairs", r.repairs);
  visit("host_ms", r.host_ms);
  visit("backend_ms", r.backend_ms);
  if (r.iteration == 0) visit("upload_ms", r.upload_ms);
  visit("bytes_to_backend", r.bytes_to_backend);
  visit("bytes_from_backend", r.bytes_from_backend);
}

}  // namespace cudahull
