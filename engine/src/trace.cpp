#include "cudahull/trace.hpp"

namespace cudahull {

namespace {

nlohmann::json plane_json(const SeparatingPlane& p) {
  return {p.nx, p.ny, p.nz, p.d};
}

// Route codes as the trace shows them: {"face": id}, {"entry": k} or "internal".
nlohmann::json route_json(std::int32_t code) {
  if (code == kRouteInternal) return "internal";
  if (code >= 0) return {{"face", code}};
  return {{"entry", -code - 1}};
}

}  // namespace

nlohmann::json iteration_to_json(const IterationRecord& r) {
  nlohmann::json j;
  for_each_count(r, [&](const char* name, const auto& value) { j[name] = value; });
  if (!r.note.empty()) j["note"] = r.note;
  j["apexes"] = r.refined_apexes;
  j["refined_faces"] = r.refined_faces;
  auto& swaps = j["swaps"] = nlohmann::json::array();
  for (const SwapRecord& s : r.swaps) {
    nlohmann::json e{{"seq", s.sequence},
                     {"kind", swap_kind_name(s.kind)},
                     {"old_edge", {s.old_edge[0], s.old_edge[1]}},
                     {"new_edge", {s.new_edge[0], s.new_edge[1]}}};
    if (s.decision_index >= 0) e["decision"] = s.decision_index;
    if (s.beneath_vertex != kNoPoint) {
      e["reason"] = "vertex " + std::to_string(s.beneath_vertex) + " lies beneath triangle (" +
                    std::to_string(s.beneath_triangle[0]) + ", " + std::to_string(s.beneath_triangle[1]) +
                    ", " + std::to_string(s.beneath_triangle[2]) + ")";
      e["beneath_vertex"] = s.beneath_vertex;
      e["beneath_triangle"] = {s.beneath_triangle[0], s.beneath_triangle[1], s.beneath_triangle[2]};
    } else if (s.kind == SwapKind::kRejectedEdgeExists) {
      e["reason"] = "the new edge already exists";
    } else if (s.kind == SwapKind::kRejectedDegenerate) {
      e["reason"] = "the edges are coplanar with the interior point";
    } else if (s.kind == SwapKind::kRejectedFoldover) {
      e["reason"] = "the old and new edges do not cross seen from the interior point";
    }
    swaps.push_back(std::move(e));
  }
  auto& removals = j["removals"] = nlohmann::json::array();
  for (const RemovalRecord& m : r.removals) {
    nlohmann::json e{{"seq", m.sequence},
                     {"vertex", m.vertex},
                     {"new_face", {m.ring[0], m.ring[1], m.ring[2]}},
                     {"rejected", m.rejected}};
    if (m.decision_index >= 0) e["decision"] = m.decision_index;
    removals.push_back(std::move(e));
  }
  auto& decisions = j["decisions"] = nlohmann::json::array();
  for (std::size_t k = 0; k < r.decisions.size(); ++k) {
    const DecisionEntry& d = r.decisions[k];
    nlohmann::json e{{"index", k}, {"kind", d.kind == kDecisionSwap ? "swap" : "removal"}};
    if (d.kind == kDecisionSwap) {
      e["plane"] = plane_json(d.plane);
      e["above"] = route_json(d.above);
      e["below"] = route_json(d.below);
    } else {
      e["to"] = route_json(d.above);
    }
    decisions.push_back(std::move(e));
  }
  return j;
}

}  // namespace cudahull
