// The checker of one hull against its input: the vertices, the lowest-index rule, dimensions 0 to 2, and
// dimension 3 handed to MeshChecker (mesh_checker.hpp).  Internal to reference/.
#pragma once

#include <cinttypes>
#include <cstdint>
#include <string>
#include <vector>

#include "check_report.hpp"
#include "cudahull/types.hpp"

namespace cudahull::checking {

inline constexpr std::uint32_t kNone = 0xffffffffu;

template <class Point>
class Checker {
 public:
  Checker(const std::vector<Point>& pts, const BasicHullMesh<Point>& hull, Report& rep)
      : pts_(pts), h_(hull), rep_(rep) {}
  void run();

 private:
  std::string vname(std::uint32_t v) const {
    return fmt("%" PRIu32 " %s", h_.vertex_ids[v], coords(h_.vertices[v]).c_str());
  }
  std::string pname(std::size_t i) const { return fmt("point %zu %s", i, coords(pts_[i]).c_str()); }

  bool check_vertices();
  void check_lowest_index();
  void check_segment();
  void check_polygon();

  const std::vector<Point>& pts_;
  const BasicHullMesh<Point>& h_;
  Report& rep_;
};

}  // namespace cudahull::checking
