// The exact hull's QuickHull (QuickHull<Pred>, exact_quickhull.cpp): outside sets (conflict lists) on the
// exact predicates of Pred, then a polish pass that merges coplanar faces into facets and keeps only strict
// corners.  Internal to reference/.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/types.hpp"
#include "cudahull/wide_predicates.hpp"
#include "exact_vector.hpp"

namespace cudahull::exact {

// Exact QuickHull on distinct points, deciding with the predicates of Pred.
template <class Pred>
class QuickHull {
 public:
  explicit QuickHull(const std::vector<Vec3d>& p) : p_(p), start_face_(p.size(), kNone) {}

  void build(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d);
  // Merges coplanar faces into facets and returns the fan triangulation of every facet over its strict
  // corners (site indices).
  std::vector<Triangle> polish() const;

 private:
  struct Face {
    std::array<std::uint32_t, 3> v;   // counter-clockwise seen from outside
    std::array<std::uint32_t, 3> nb;  // nb[i]: the face across edge v[i] -> v[i+1]
    Vec3d normal;                     // approximate, for ranking outside points only
    std::uint32_t out_begin = 0;      // outside set: arena_[out_begin, out_begin + out_count)
    std::uint32_t out_count = 0;
    std::uint32_t far = kNone;  // the outside point furthest from the plane (approximately)
    double far_dist = 0;
    std::uint32_t stamp = 0;
    bool visible = false;
    bool alive = false;
  };

  int side(const Face& f, std::uint32_t q) const {
    return Pred::orient3d(p_[f.v[0]], p_[f.v[1]], p_[f.v[2]], p_[q]);
  }
  std::uint32_t new_face(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  // Assigns each point of `pts` to the first face of `cands` it is strictly above (or drops it), storing
  // every face's new outside set contiguously at the end of the arena.
  void distribute(const std::vector<std::uint32_t>& pts, const std::vector<std::uint32_t>& cands);
  void compact_arena();
  void add_point(std::uint32_t f);
  static int edge_index(const Face& g, std::uint32_t from, std::uint32_t to) {
    for (int j = 0; j < 3; ++j)
      if (g.v[j] == from && g.v[(j + 1) % 3] == to) return j;
    throw std::logic_error("exact_hull: broken face adjacency");
  }

  const std::vector<Vec3d>& p_;
  // Outside sets live in slices of one arena (contiguous reads when a face is removed); removed slices are
  // garbage until the next compaction.
  std::vector<std::uint32_t> arena_;
  std::size_t live_ = 0;
  std::vector<std::uint32_t> start_face_;  // per horizon vertex: the new face whose base edge starts there
  std::vector<Face> faces_;
  std::vector<std::uint32_t> free_;  // reusable dead face slots
  std::vector<std::uint32_t> stack_;
  std::uint32_t stamp_ = 0;

  // Scratch for add_point, kept to avoid reallocation.
  std::vector<std::uint32_t> visible_;
  std::vector<std::uint32_t> pending_;
  struct HorizonEdge {
    std::uint32_t a, b, other;
  };
  std::vector<HorizonEdge> horizon_;
  std::vector<std::uint32_t> created_;
  std::vector<std::uint32_t> which_, counts_;
};

extern template class QuickHull<FastPredicates>;
extern template class QuickHull<WidePredicates>;

}  // namespace cudahull::exact
