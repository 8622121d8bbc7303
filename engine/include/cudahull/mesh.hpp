// The hull mesh: triangles with adjacency in flat index arrays, not pointer graphs, so that the same arrays
// can live on the device (docs/architecture.md).
//
// Face f has vertices v[0..2] (input point indices, counter-clockwise seen from outside) and neighbours
// n[0..2], where n[i] is the face across the directed edge v[i] -> v[(i+1) % 3].  Faces are created by the
// three local edits of the paper (split at an apex, edge swap, degree-3 vertex removal) and killed when
// replaced; compact() renumbers the live faces 0..F-1 between iterations.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cudahull/point_map.hpp"
#include "cudahull/types.hpp"

namespace cudahull {

using FaceId = std::uint32_t;
inline constexpr FaceId kNoFace = 0xffffffffu;
inline constexpr PointIndex kNoPoint = 0xffffffffu;

struct MeshFace {
  std::array<PointIndex, 3> v{};
  std::array<FaceId, 3> n{kNoFace, kNoFace, kNoFace};
};

class Mesh {
 public:
  // The initial tetrahedron (section 3.1); (p0, p1, p2) must be clockwise seen from p3, i.e. p3 below the
  // counter-clockwise triangle (p0, p1, p2).
  void make_tetrahedron(PointIndex p0, PointIndex p1, PointIndex p2, PointIndex p3);

  std::size_t face_capacity() const { return faces_.size(); }  // ids in use, live or dead
  std::size_t live_faces() const { return live_count_; }
  bool alive(FaceId f) const { return alive_[f] != 0; }
  const MeshFace& face(FaceId f) const { return faces_[f]; }
  std::size_t vertex_count() const { return vertex_count_; }
  bool has_vertex(PointIndex v) const { return vertex_face_.get(v) != 0; }
  // Some live face that holds v, or kNoFace when v is not a vertex.
  FaceId face_of_vertex(PointIndex v) const { return vertex_face_.get(v) - 1; }
  // The number of edges at v, counting no further than `limit`.
  std::size_t degree(PointIndex v, std::size_t limit = SIZE_MAX) const;
  std::vector<PointIndex> vertices() const;  // sorted

  // Index i such that face f has the directed edge a -> b as v[i] -> v[i+1], or -1.
  int edge_index(FaceId f, PointIndex a, PointIndex b) const;

  // Refinement (Fig. 3a): face (a, b, c) becomes (a, b, p), (b, c, p), (c, a, p), returned in that order.
  // Edge 0 of each child is the child's edge of the old face.
  std::array<FaceId, 3> split(FaceId f, PointIndex p);

  // split() of faces[k] at apexes[k] for every k, on `workers` threads, with the same ids, links and
  // vertex faces as calling split() in that order (children of faces[k] are first + 3k .. first + 3k + 2,
  // where `first` is the returned id).  The faces must be different live faces, the apexes new vertices.
  FaceId split_batch(const std::vector<FaceId>& faces, const std::vector<PointIndex>& apexes,
                     unsigned workers);

  // Edge swap (Fig. 3b): the edge v[i] -> v[i+1] of f (u -> v, opposite x) and its twin in g (opposite y)
  // are replaced by the edge x - y: returns N1 = (x, u, y) and N2 = (y, v, x).  Caller checks validity.
  std::array<FaceId, 2> swap(FaceId f, int i);

  // Vertex removal (Fig. 4): the degree-3 vertex v with ring a, b, d becomes one face (a, b, d).
  FaceId remove_degree3(PointIndex v);

  // The vertices around v, counter-clockwise seen from outside, and the faces (face k holds v, ring[k],
  // ring[k+1]).  Empty when v is not a vertex.
  void ring(PointIndex v, std::vector<PointIndex>& ring_vertices, std::vector<FaceId>& ring_faces) const;
  bool adjacent(PointIndex a, PointIndex b) const;  // is a - b an edge?

  // Batched swaps (the engine's parallel rounds): swap edge swaps[k].second of face swaps[k].first for
  // every k at once, on `workers` threads.  The swaps must kill pairwise different faces and make pairwise
  // different new edges (then the result is what swap() in any order gives); each new face's neighbours
  // are linked through the faces the other swaps made.  Swap k's faces N1, N2 get ids first + 2k and
  // first + 2k + 1, where `first` is the returned id.
  FaceId swap_batch(const std::vector<std::pair<FaceId, int>>& swaps, unsigned workers);

  // The mesh `faces` (corners and links, as a closed 2-manifold), all live, replacing this one: a mesh
  // built elsewhere (the resident engine's, read back for the records) with this class's queries.
  void assign(const std::vector<MeshFace>& faces);

  // Renumbers live faces 0..F-1 in id order; returns old id -> new id (kNoFace for dead faces), valid until
  // the next compact().
  const std::vector<FaceId>& compact();

 private:
  FaceId add_face(PointIndex a, PointIndex b, PointIndex c);
  // A swap of edge i of f as swap() and swap_batch() read it: f = (u, v, x), g = (v, u, y) across the edge,
  // and the four faces around them.
  struct SwapQuad {
    FaceId f, g;
    PointIndex u, v, x, y;
    FaceId across_vx, across_xu, across_uy, across_yv;
  };
  SwapQuad swap_quad(FaceId f, int i) const;
  // The swap's new faces n1 = (x, u, y) and n2 = (y, v, x), linked to each other and to the faces around.
  void make_swapped_faces(const SwapQuad& q, FaceId n1, FaceId n2);
  template <class Visit>
  void walk_around(PointIndex v, Visit&& visit) const;
  void kill(FaceId f);
  // In face g, point the neighbour slot of directed edge a -> b at `to`.
  void relink(FaceId g, PointIndex a, PointIndex b, FaceId to);

  std::vector<MeshFace> faces_;
  std::vector<std::uint8_t> alive_;
  std::vector<FaceId> remap_;           // compact()'s answer
  std::vector<MeshFace> compacted_;     // compact()'s second buffer
  std::vector<FaceId> dead_into_;       // swap_batch(): a face it killed -> the first new face of its swap
  std::vector<std::int32_t> split_of_;  // split_batch(): a face -> its index in the batch, or -1
  std::size_t live_count_ = 0;
  // Per input point: 1 + some live face that holds it, or 0 when it is not a vertex.
  PointMap<FaceId> vertex_face_;
  std::size_t vertex_count_ = 0;
};

}  // namespace cudahull
