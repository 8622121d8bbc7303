#include "phases/final_check.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>

#include "cudahull/exact_hull.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "phases/decision_array.hpp"

namespace cudahull::phases {

namespace {

// The edges that are not strictly convex, each once (from its lower face id), in id order; on all cores (a
// sphere of 1M points has 3M edges).  With `geometry` (matching the mesh) corners are read from there,
// where they lie next to each other: fewer cache misses on a 2M-face mesh.
template <class Point>
std::vector<Edge> faulty_edges(const Mesh& mesh, const std::vector<Point>& points,
                               const BasicFaceGeometryArray<Point>* geometry) {
  auto P = [&](PointIndex i) { return to_vec3d(points[i]); };
  const auto capacity = static_cast<FaceId>(mesh.face_capacity());
  const unsigned workers = hardware_workers();
  std::vector<std::vector<Edge>> found(workers);
  parallel_chunks(
      capacity, workers,
      [&](std::size_t begin, std::size_t end, unsigned w) {
        for (auto f = static_cast<FaceId>(begin); f < end; ++f) {
          if (!mesh.alive(f)) continue;
          const MeshFace& face = mesh.face(f);
          Vec3d corner[3];
          for (int k = 0; k < 3; ++k)
            corner[k] = geometry ? to_vec3d((*geometry)[f].v[k]) : P(face.v[k]);
          for (int i = 0; i < 3; ++i) {
            const FaceId g = face.n[i];
            if (g < f) continue;
            const int j = mesh.edge_index(g, face.v[(i + 1) % 3], face.v[i]);
            const Vec3d y =
                geometry ? to_vec3d((*geometry)[g].v[(j + 2) % 3]) : P(mesh.face(g).v[(j + 2) % 3]);
            if (orient3d(corner[0], corner[1], corner[2], y) >= 0) found[w].push_back({f, i});
          }
        }
      },
      16384);
  std::vector<Edge> all;
  for (const auto& part : found)
    all.insert(all.end(), part.begin(), part.end());
  return all;
}

// Faulty edges plus faces that c is not strictly below (geometry matches the compacted mesh).
template <class Point>
std::size_t count_faults(const Mesh& mesh, const std::vector<Point>& points,
                         const BasicFaceGeometryArray<Point>& geometry) {
  std::size_t count = faulty_edges(mesh, points, &geometry).size();
  for (const auto& g : geometry)
    count += g.tet[3] >= 0 ? 1 : 0;
  return count;
}

// How many dropped vertices lie outside the convex mesh: each located by a walk from a face of a vertex of
// its old ring, when that is still a vertex (a few steps instead of a walk across the mesh from face 0: on
// a 10M-point ball ~1,200 walks of up to ~700 faces).
template <class Point>
std::size_t dropped_outside(const LocalEdits<Point>& edits, const BasicFaceGeometryArray<Point>& geometry) {
  const Mesh& mesh = edits.mesh;
  std::vector<std::pair<PointIndex, PointIndex>> dropped(edits.dropped.size());
  for (std::size_t k = 0; k < dropped.size(); ++k)
    dropped[k] = {edits.dropped[k], edits.dropped_near[k]};
  std::sort(dropped.begin(), dropped.end());
  dropped.erase(std::unique(dropped.begin(), dropped.end(),
                            [](const auto& a, const auto& b) { return a.first == b.first; }),
                dropped.end());
  const int walk = 64 + 4 * static_cast<int>(std::sqrt(static_cast<double>(geometry.size())));
  std::atomic<std::size_t> outside{0};
  parallel_chunks(
      dropped.size(), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          const auto [r, near] = dropped[k];
          if (mesh.has_vertex(r)) continue;
          const FaceId near_face = mesh.face_of_vertex(near);
          const auto start = near_face < geometry.size() ? static_cast<std::int32_t>(near_face) : 0;
          const std::int32_t found =
              locate_point(edits.points[r], start, geometry.data(),
                           static_cast<std::int32_t>(geometry.size()), edits.interior, walk);
          if (found != kRouteInternal) outside.fetch_add(1, std::memory_order_relaxed);
        }
      },
      64);
  return outside.load();
}

// The mesh as a HullMesh: vertices renumbered on all cores, through a per-point table when most points are
// vertices (a sphere), else through a hash map of the vertices (a binary search in the sorted ids cost 6-12
// ms for the 28K faces of a 10M-point ball: 84K searches, each ~14 mispredicted branches).
template <class Point>
BasicHullMesh<Point> mesh_result(const Mesh& mesh, const std::vector<Point>& points) {
  BasicHullMesh<Point> result;
  result.dimension = 3;
  result.vertex_ids = mesh.vertices();
  const std::vector<PointIndex>& ids = result.vertex_ids;
  const auto faces = static_cast<FaceId>(mesh.face_capacity());
  result.vertices.resize(ids.size());
  result.triangles.resize(faces);
  std::vector<std::uint32_t> dense;
  PointMap<std::uint32_t> sparse;
  if (8 * ids.size() >= points.size()) {
    dense.resize(points.size());
    parallel_chunks(ids.size(), hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
      for (std::size_t k = begin; k < end; ++k)
        dense[ids[k]] = static_cast<std::uint32_t>(k);
    });
  } else {
    sparse.reserve(ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k)
      sparse[ids[k]] = static_cast<std::uint32_t>(k);
  }
  auto local = [&](PointIndex v) { return dense.empty() ? sparse.get(v) : dense[v]; };
  parallel_chunks(
      std::max<std::size_t>(faces, ids.size()), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < std::min<std::size_t>(end, ids.size()); ++k)
          result.vertices[k] = points[ids[k]];
        for (std::size_t f = begin; f < std::min<std::size_t>(end, faces); ++f) {
          const MeshFace& face = mesh.face(static_cast<FaceId>(f));
          result.triangles[f] = {local(face.v[0]), local(face.v[1]), local(face.v[2])};
        }
      },
      65536);
  return result;
}

}  // namespace

template <class Point>
BasicHullMesh<Point> final_check(LocalEdits<Point>& edits, BasicFaceGeometryArray<Point>& geometry,
                                 std::vector<PointIndex>& used_vertices, std::size_t external,
                                 const std::function<std::vector<std::int32_t>()>& point_faces) {
  const auto t0 = Clock::now();
  Mesh& mesh = edits.mesh;
  IterationRecord& record = edits.record;
  std::size_t faults = count_faults(mesh, edits.points, geometry);
  const double tf_check = ms_since(t0);
  if (faults > 0) {
    // The repairs go on the step's record after its own edits: their sequence numbers continue.
    edits.sequence = static_cast<int>(record.swaps.size() + record.removals.size());
    for (int round = 0; round < 8; ++round) {
      const std::vector<Edge> faulty = faulty_edges<Point>(mesh, edits.points, nullptr);
      if (faulty.empty()) break;
      for (const Edge& edge : faulty) {
        edits.queue.push_back(edge);
        for (PointIndex v : mesh.face(edge.face).v)
          edits.touch(v);
      }
      const std::size_t before = record.swaps.size() + record.removals.size();
      edits.rejected_edges.clear();
      settle(edits);
      // settle() stops with edges still queued when its guard budget runs out; compaction renumbers the
      // faces, so those edges would name other faces, or none (the next round starts from the faulty edges).
      edits.queue.clear();
      mesh.compact();
      if (record.swaps.size() + record.removals.size() == before) break;
    }
    build_face_geometry(mesh, edits.points, edits.interior, geometry, nullptr, geometry);
    faults = count_faults(mesh, edits.points, geometry);
  }
  if (faults == 0) faults += dropped_outside(edits, geometry);
  faults += external;  // after a stall: points still outside the mesh
  const double tf_dropped = ms_since(t0);
  BasicHullMesh<Point> result;
  if (faults == 0) {
    result = mesh_result(mesh, edits.points);
  } else {
    std::sort(used_vertices.begin(), used_vertices.end());
    used_vertices.erase(std::unique(used_vertices.begin(), used_vertices.end()), used_vertices.end());
    std::vector<PointIndex> candidates = used_vertices;
    if (external > 0) {
      const std::vector<std::int32_t> faces_of_points = point_faces();
      for (PointIndex i = 0; i < faces_of_points.size(); ++i) {
        if (faces_of_points[i] >= 0) candidates.push_back(i);
      }
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    }
    result = exact_hull(edits.points, candidates);
    record.repairs += faults;
    record.note = "finished by an exact hull of " + std::to_string(candidates.size()) +
                  " candidate vertices (" + std::to_string(faults) + " non-convex edges or outside vertices)";
  }
  if (phase_times_wanted())
    std::fprintf(stderr, "finish host ms %.2f: check %.2f dropped %.2f result %.2f\n", ms_since(t0), tf_check,
                 tf_dropped - tf_check, ms_since(t0) - tf_dropped);
  return result;
}

// The two coordinate types (README, "Precision").
template BasicHullMesh<Point3> final_check(LocalEdits<Point3>&, BasicFaceGeometryArray<Point3>&,
                                           std::vector<PointIndex>&, std::size_t,
                                           const std::function<std::vector<std::int32_t>()>&);
template BasicHullMesh<Point3d> final_check(LocalEdits<Point3d>&, BasicFaceGeometryArray<Point3d>&,
                                            std::vector<PointIndex>&, std::size_t,
                                            const std::function<std::vector<std::int32_t>()>&);

}  // namespace cudahull::phases
