#include "overlay.hpp"

#include <algorithm>
#include <cmath>

namespace cudahull::viewer {

namespace {

glm::dvec3 at(const Engine& engine, PointIndex i) {
  const Point3& p = engine.points()[i];
  return {p.x, p.y, p.z};
}

glm::dvec3 unit_normal(const Engine& engine, FaceId f) {
  const MeshFace& face = engine.mesh().face(f);
  const glm::dvec3 a = at(engine, face.v[0]), b = at(engine, face.v[1]), c = at(engine, face.v[2]);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double length = glm::length(n);
  return length > 0 ? n / length : glm::dvec3(0.0);
}

// The direction the separating plane of edge i of face f rises along from the edge: the average normal of
// the edge's two faces, made perpendicular to the edge.
glm::dvec3 edge_normal(const Engine& engine, FaceId f, int i) {
  const MeshFace& face = engine.mesh().face(f);
  const glm::dvec3 a = at(engine, face.v[i]), b = at(engine, face.v[(i + 1) % 3]);
  glm::dvec3 along = unit_normal(engine, f) + unit_normal(engine, face.n[i]);
  const glm::dvec3 e = b - a;
  const double e2 = glm::dot(e, e);
  if (e2 > 0) along -= e * (glm::dot(along, e) / e2);
  const double length = glm::length(along);
  return length > 0 ? along / length : glm::dvec3(0.0);
}

void push(std::vector<OverlayVertex>& out, const glm::dvec3& p, std::uint32_t rgba) {
  out.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z), rgba});
}

bool has_mesh(const Engine& engine) {
  return engine.dimension() == 3 && engine.mesh().live_faces() > 0;
}

}  // namespace

void build_overlay(const Engine& engine, long long selected, bool cells, bool normals, Overlay& out) {
  out.triangles.clear();
  out.lines.clear();
  if (!has_mesh(engine)) return;
  const Mesh& mesh = engine.mesh();
  const auto faces = static_cast<long long>(mesh.face_capacity());

  if (cells && selected >= 0 && selected < faces) {
    const auto f = static_cast<FaceId>(selected);
    const MeshFace& face = mesh.face(f);
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
      const glm::dvec3 up = edge_normal(engine, f, i) * height;
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
      const double r = 0.08 * longest;
      const std::uint32_t marker = pack_rgba(1.0f, 1.0f, 1.0f, 1.0f);
      for (const glm::dvec3& d : {glm::dvec3(r, 0, 0), glm::dvec3(0, r, 0), glm::dvec3(0, 0, r)}) {
        push(out.lines, p - d, marker);
        push(out.lines, p + d, marker);
      }
    }
  }

  if (normals) {
    const std::uint32_t shaft = pack_rgba(0.55f, 0.85f, 1.0f, 1.0f);
    for (FaceId f = 0; f < mesh.face_capacity(); ++f) {
      if (!mesh.alive(f)) continue;
      const MeshFace& face = mesh.face(f);
      for (int i = 0; i < 3; ++i) {
        if (face.n[i] < f) continue;  // each edge once
        const glm::dvec3 a = at(engine, face.v[i]), b = at(engine, face.v[(i + 1) % 3]);
        const double length = 0.3 * glm::length(b - a);
        const glm::dvec3 mid = 0.5 * (a + b), n = edge_normal(engine, f, i), tip = mid + length * n;
        const glm::dvec3 side = glm::normalize(b - a) * (0.25 * length);
        for (const glm::dvec3& p :
             {mid, tip, tip, tip - 0.35 * length * n + side, tip, tip - 0.35 * length * n - side})
          push(out.lines, p, shaft);
      }
    }
  }
}

long long pick_face(const Engine& engine, const glm::dvec3& origin, const glm::dvec3& direction) {
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
