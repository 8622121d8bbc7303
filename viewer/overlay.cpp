#include "overlay.hpp"

#include <algorithm>
#include <cmath>

namespace cudahull::viewer {

namespace {

glm::dvec3 at(const SteppingEngine& engine, PointIndex i) {
  const Vec3d p = engine.point(i);
  return {p.x, p.y, p.z};
}

glm::dvec3 plane_normal(const SeparatingPlane& p) {
  return {p.nx, p.ny, p.nz};
}

// The direction the engine's separating plane of edge i of face f (SteppingEngine::face_cell(), `cell`) rises
// along from the edge: the unit direction in that plane perpendicular to the edge, pointing outward (with the
// face's outward normal).
glm::dvec3 wall_direction(const SteppingEngine& engine, const FaceCell& cell, FaceId f, int i) {
  const MeshFace& face = engine.mesh().face(f);
  const glm::dvec3 e = at(engine, face.v[(i + 1) % 3]) - at(engine, face.v[i]);
  glm::dvec3 up = glm::cross(plane_normal(cell.edge_plane[i]), e);
  if (glm::dot(up, plane_normal(cell.face_plane)) < 0) up = -up;
  const double length = glm::length(up);
  return length > 0 ? up / length : glm::dvec3(0.0);
}

void push(std::vector<OverlayVertex>& out, const glm::dvec3& p, std::uint32_t rgba) {
  out.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z), rgba});
}

bool has_mesh(const SteppingEngine& engine) {
  return engine.dimension() == 3 && engine.mesh().live_faces() > 0;
}

void cross(std::vector<OverlayVertex>& out, const glm::dvec3& p, double r, std::uint32_t rgba) {
  for (const glm::dvec3& d : {glm::dvec3(r, 0, 0), glm::dvec3(0, r, 0), glm::dvec3(0, 0, r)}) {
    push(out, p - d, rgba);
    push(out, p + d, rgba);
  }
}

void segment(std::vector<OverlayVertex>& out, const glm::dvec3& a, const glm::dvec3& b, std::uint32_t rgba) {
  push(out, a, rgba);
  push(out, b, rgba);
}

void triangle_outline(std::vector<OverlayVertex>& out, const glm::dvec3& a, const glm::dvec3& b,
                      const glm::dvec3& c, std::uint32_t rgba) {
  segment(out, a, b, rgba);
  segment(out, b, c, rgba);
  segment(out, c, a, rgba);
}

// A marker size for the whole step: a fraction of the points' extent.
double marker_size(const SteppingEngine& engine) {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  const std::vector<PointIndex> vertices = engine.mesh().vertices();
  for (PointIndex v : vertices) {
    lo = glm::min(lo, at(engine, v));
    hi = glm::max(hi, at(engine, v));
  }
  const glm::dvec3 extent = hi - lo;
  return 0.012 * std::max({extent.x, extent.y, extent.z, 1e-30});
}

void refinement_overlay(const SteppingEngine& engine, double r, Overlay& out) {
  const IterationRecord& record = engine.last_record();
  const std::uint32_t parent = pack_rgba(1.0f, 1.0f, 1.0f, 0.9f), spoke = pack_rgba(1.0f, 0.62f, 0.16f, 1.0f);
  for (std::size_t k = 0; k < record.refined_apexes.size(); ++k) {
    const glm::dvec3 apex = at(engine, record.refined_apexes[k]);
    cross(out.lines, apex, r, spoke);
    if (k >= record.refined_faces.size()) continue;  // the tetrahedron of section 3.1 has no parents
    const auto& f = record.refined_faces[k];
    const glm::dvec3 a = at(engine, f[0]), b = at(engine, f[1]), c = at(engine, f[2]);
    triangle_outline(out.lines, a, b, c, parent);
    for (const glm::dvec3& corner : {a, b, c})
      segment(out.lines, apex, corner, spoke);
  }
}

void swaps_overlay(const SteppingEngine& engine, double r, int limit, Overlay& out) {
  const IterationRecord& record = engine.last_record();
  for (const SwapRecord& s : record.swaps) {
    if (s.sequence > limit) continue;
    const glm::dvec3 u = at(engine, s.old_edge[0]), v = at(engine, s.old_edge[1]);
    const glm::dvec3 x = at(engine, s.new_edge[0]), y = at(engine, s.new_edge[1]);
    const bool made = s.kind == SwapKind::kRegular || s.kind == SwapKind::kComplementary;
    const glm::dvec3 mid = made ? 0.5 * (x + y) : 0.5 * (u + v);
    out.labels.push_back({static_cast<float>(mid.x), static_cast<float>(mid.y), static_cast<float>(mid.z),
                          made ? pack_rgba(0.9f, 1.0f, 0.9f, 1.0f) : kFoldoverRgba, s.sequence});
    if (made) {
      segment(out.lines, u, v, kOldEdgeRgba);
      segment(out.lines, x, y, s.kind == SwapKind::kRegular ? kRegularSwapRgba : kComplementarySwapRgba);
      continue;
    }
    segment(out.lines, u, v, kFoldoverRgba);
    segment(out.lines, x, y, pack_rgba(0.6f, 0.6f, 0.6f, 0.8f));
    if (s.beneath_vertex != kNoPoint) {
      cross(out.lines, at(engine, s.beneath_vertex), r, kBeneathRgba);
      triangle_outline(out.lines, at(engine, s.beneath_triangle[0]), at(engine, s.beneath_triangle[1]),
                       at(engine, s.beneath_triangle[2]), kBeneathRgba);
    }
  }
  for (const RemovalRecord& m : record.removals) {
    if (m.sequence > limit) continue;
    const std::uint32_t rgba = m.rejected ? pack_rgba(0.6f, 0.6f, 0.6f, 0.8f) : kRemovalRgba;
    cross(out.lines, at(engine, m.vertex), r, rgba);
    const glm::dvec3 p = at(engine, m.vertex);
    out.labels.push_back(
        {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z), rgba, m.sequence});
    triangle_outline(out.lines, at(engine, m.ring[0]), at(engine, m.ring[1]), at(engine, m.ring[2]), rgba);
  }
}

}  // namespace

void build_overlay(const SteppingEngine& engine, long long selected, const OverlayLayers& layers,
                   Overlay& out) {
  out.triangles.clear();
  out.lines.clear();
  out.labels.clear();
  if (!has_mesh(engine)) return;
  const Mesh& mesh = engine.mesh();
  const auto faces = static_cast<long long>(mesh.face_capacity());
  if (layers.refinement || layers.swaps) {
    const double r = marker_size(engine);
    if (layers.refinement) refinement_overlay(engine, r, out);
    if (layers.swaps) swaps_overlay(engine, r, layers.sequence_limit, out);
  }

  if (layers.cells && selected >= 0 && selected < faces) {
    const auto f = static_cast<FaceId>(selected);
    const MeshFace& face = mesh.face(f);
    const FaceCell cell = engine.face_cell(f);
    double longest = 0;
    for (int i = 0; i < 3; ++i)
      longest = std::max(longest, glm::length(at(engine, face.v[(i + 1) % 3]) - at(engine, face.v[i])));
    const double height = 0.75 * longest;
    // One colour per separating plane, as the three cell walls of Fig. 2.
    const std::uint32_t wall[3] = {pack_rgba(0.2f, 0.85f, 0.95f, 0.28f),
                                   pack_rgba(0.95f, 0.35f, 0.85f, 0.28f),
                                   pack_rgba(0.95f, 0.85f, 0.2f, 0.28f)};
    const std::uint32_t outline = pack_rgba(1.0f, 1.0f, 1.0f, 1.0f);
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3 a = at(engine, face.v[i]), b = at(engine, face.v[(i + 1) % 3]);
      const glm::dvec3 up = wall_direction(engine, cell, f, i) * height;
      for (const glm::dvec3& p : {a, b, b + up, a, b + up, a + up})
        push(out.triangles, p, wall[i]);
      for (const glm::dvec3& p : {a, b, a + up, b + up})
        push(out.lines, p, wall[i] | 0xff000000u);
      push(out.lines, a, outline);
      push(out.lines, b, outline);
    }
    const std::vector<FaceExtreme>& extremes = engine.face_extremes();
    if (f < extremes.size() && extremes[f].count > 0) {
      const glm::dvec3 p = at(engine, extremes[f].furthest);
      cross(out.lines, p, 0.08 * longest, pack_rgba(1.0f, 1.0f, 1.0f, 1.0f));
    }
  }

  if (layers.normals) {
    const std::uint32_t shaft = pack_rgba(0.55f, 0.85f, 1.0f, 1.0f);
    for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
      if (!mesh.alive(f)) continue;
      const MeshFace& face = mesh.face(f);
      const FaceCell cell = engine.face_cell(f);
      for (int i = 0; i < 3; ++i) {
        if (face.n[i] < f) continue;  // each edge once
        const glm::dvec3 a = at(engine, face.v[i]), b = at(engine, face.v[(i + 1) % 3]);
        const double length = 0.3 * glm::length(b - a);
        const glm::dvec3 mid = 0.5 * (a + b), n = wall_direction(engine, cell, f, i), tip = mid + length * n;
        const glm::dvec3 side = glm::normalize(b - a) * (0.25 * length);
        for (const glm::dvec3& p :
             {mid, tip, tip, tip - 0.35 * length * n + side, tip, tip - 0.35 * length * n - side})
          push(out.lines, p, shaft);
      }
    }
  }
}

long long pick_face(const SteppingEngine& engine, const glm::dvec3& origin, const glm::dvec3& direction) {
  if (!has_mesh(engine)) return -1;
  const Mesh& mesh = engine.mesh();
  long long best = -1;
  double best_t = HUGE_VAL;
  for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
    if (!mesh.alive(f)) continue;
    const MeshFace& face = mesh.face(f);
    // Moeller-Trumbore.
    const glm::dvec3 a = at(engine, face.v[0]), e1 = at(engine, face.v[1]) - a,
                     e2 = at(engine, face.v[2]) - a;
    const glm::dvec3 p = glm::cross(direction, e2);
    const double det = glm::dot(e1, p);
    if (std::fabs(det) < 1e-300) continue;
    const glm::dvec3 s = origin - a;
    const double u = glm::dot(s, p) / det;
    if (u < 0 || u > 1) continue;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(direction, q) / det;
    if (v < 0 || u + v > 1) continue;
    const double t = glm::dot(e2, q) / det;
    if (t > 0 && t < best_t) {
      best_t = t;
      best = f;
    }
  }
  return best;
}

}  // namespace cudahull::viewer
