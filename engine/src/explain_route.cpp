// The debugger's "explain point" (issue 6): Algorithm 2's routing of one point through the last step's
// tables (Fig. 7), told hop by hop, with the exact verdict that ended it.
#include <algorithm>
#include <string>

#include "cudahull/engine.hpp"

namespace cudahull {

template <class Point>
std::vector<std::string> BasicEngine<Point>::explain_route(PointIndex point, std::int32_t old_face) const {
  std::vector<std::string> lines;
  const BasicIterationTables<Point>& t = tables_;
  if (!started_ || dimension_ != 3 || point >= points_->size()) return {"no 3-d step to explain"};
  const Point& x = (*points_)[point];
  auto route = [](std::int32_t code) {
    return code == kRouteInternal ? std::string("internal")
           : code < 0             ? "decision[" + std::to_string(-code - 1) + "]"
                                  : "face " + std::to_string(code);
  };
  auto sign = [&](const SeparatingPlane& p) { return plane_value(p, x) >= 0 ? '+' : '-'; };
  if (std::find(t.retired.begin(), t.retired.end(), point) != t.retired.end()) {
    return {"point " + std::to_string(point) + " was the apex of a refined face: it became a vertex",
            "vertex"};
  }
  std::int32_t code;
  if (!t.initial_cells.empty()) {
    code = 0;
    for (std::int32_t f = 0; f < 4; ++f) {
      const SeparatingPlane* cell = t.initial_cells.data() + 3 * f;
      if (sign(cell[0]) == '+' && sign(cell[1]) == '+' && sign(cell[2]) == '+') {
        code = f;
        break;
      }
    }
    lines.push_back("first distribution (section 3.1): in the cell of tetrahedron face " +
                    std::to_string(code));
  } else {
    if (old_face < 0 || static_cast<std::size_t>(old_face) >= t.old_face_split.size())
      return {"point " + std::to_string(point) +
              " had no face before this step (it was internal or a vertex)"};
    const std::int32_t split = t.old_face_split[old_face];
    if (split < 0) {
      code = t.old_face_route[old_face];
      lines.push_back("old face " + std::to_string(old_face) + " was not refined; its points go to " +
                      route(code));
    } else {
      const RefinementEntry& r = t.refinement[split];
      const char s0 = sign(r.plane[0]), s1 = sign(r.plane[1]), s2 = sign(r.plane[2]);
      const int child = (s0 == '+' && s1 == '-')   ? 0
                        : (s1 == '+' && s2 == '-') ? 1
                        : (s2 == '+' && s0 == '-') ? 2
                                                   : 0;
      code = r.child[child];
      lines.push_back("old face " + std::to_string(old_face) + " was refined at apex " +
                      std::to_string(r.apex) + " (refinement[" + std::to_string(split) + "]): planes " + s0 +
                      s1 + s2 + " -> child " + std::to_string(child) + " -> " + route(code));
    }
    while (code < 0 && code != kRouteInternal) {
      const std::int32_t k = -code - 1;
      const DecisionEntry& e = t.decision[k];
      if (e.kind == kDecisionRemoval) {
        code = e.above;
        lines.push_back("decision[" + std::to_string(k) + "]: a vertex removal -> " + route(code));
      } else {
        const bool above = plane_value(e.plane, x) >= 0;
        code = above ? e.above : e.below;
        lines.push_back("decision[" + std::to_string(k) + "]: " + (above ? "above" : "below") +
                        " the swap's separating plane -> " + route(code));
      }
    }
  }
  if (code == kRouteInternal) {
    lines.push_back("internal");
    return lines;
  }
  // The exact verdict (routing.hpp): strictly above the face, inside the tetrahedron (c, face), or a stray
  // that walks on to a neighbour.
  std::int32_t g = code;
  for (int step = 0; step < kMaxStrayWalk; ++step) {
    int exit_edge = -1;
    const PointVerdict verdict = face_verdict(geometry_[g], interior_, x, &exit_edge);
    if (verdict == kVerdictExternal) {
      lines.push_back("exact: strictly above face " + std::to_string(g) + ": external");
      lines.push_back("face " + std::to_string(g));
      return lines;
    }
    if (verdict == kVerdictInternal) {
      lines.push_back("exact: inside the tetrahedron of face " + std::to_string(g) +
                      " and the interior point: proven inside the hull");
      lines.push_back("internal");
      return lines;
    }
    if (exit_edge < 0) break;
    g = geometry_[g].neighbor[exit_edge];
    lines.push_back("exact: below that face but beyond its radial plane " + std::to_string(exit_edge) +
                    ": walks to face " + std::to_string(g));
  }
  const std::int32_t found =
      locate_point(x, g, geometry_.data(), static_cast<std::int32_t>(geometry_.size()), interior_, 0);
  lines.push_back("exact: exhaustive search over all faces -> " + route(found));
  lines.push_back(found == kRouteInternal ? "internal" : "face " + std::to_string(found));
  return lines;
}

template class BasicEngine<Point3>;
template class BasicEngine<Point3d>;

}  // namespace cudahull
