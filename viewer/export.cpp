#include "export.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <unordered_map>

#include "cudahull/errors.hpp"
#include "cudahull/mesh_io.hpp"
#include "cudahull/trace.hpp"

namespace cudahull::viewer {

namespace {

std::string route(std::int32_t code) {
  if (code == kRouteInternal) return "internal";
  if (code < 0) return "entry " + std::to_string(-code - 1);
  return std::to_string(code);
}

std::string number(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// The polyhedron `faces` (outward triangles of input indices), with the engine's coordinates in Point's
// precision (point() widens them exactly, so the cast back is exact).
template <class Point>
void write_faces(const SteppingEngine& engine, const std::vector<std::array<PointIndex, 3>>& faces,
                 const std::string& path) {
  BasicHullMesh<Point> hull;
  hull.dimension = 3;
  for (const auto& f : faces)
    hull.vertex_ids.insert(hull.vertex_ids.end(), f.begin(), f.end());
  std::sort(hull.vertex_ids.begin(), hull.vertex_ids.end());
  hull.vertex_ids.erase(std::unique(hull.vertex_ids.begin(), hull.vertex_ids.end()), hull.vertex_ids.end());
  std::unordered_map<PointIndex, std::uint32_t> local;
  using Coordinate = decltype(Point::x);
  for (std::uint32_t k = 0; k < hull.vertex_ids.size(); ++k) {
    local[hull.vertex_ids[k]] = k;
    const Vec3d p = engine.point(hull.vertex_ids[k]);
    hull.vertices.push_back(
        {static_cast<Coordinate>(p.x), static_cast<Coordinate>(p.y), static_cast<Coordinate>(p.z)});
  }
  for (const auto& f : faces)
    hull.triangles.push_back({local[f[0]], local[f[1]], local[f[2]]});
  write_mesh(path, hull);
}

}  // namespace

void export_mesh(const Scene& scene, const std::string& path) {
  const SteppingEngine& engine = scene.engine();
  if (scene.position() == 0) throw OutputError(path + ": nothing to export before the first step");
  if (engine.done() && scene.substep() < 0) {
    // The engine's result itself (any dimension), in its precision.
    if (const auto* e = dynamic_cast<const BasicEngine<Point3d>*>(&engine)) {
      write_mesh(path, e->result());
      return;
    }
    if (const auto* e = dynamic_cast<const Engine*>(&engine)) {
      write_mesh(path, e->result());
      return;
    }
  }
  // The polyhedron shown: the step's mesh, or the sub-step's.
  if (engine.precision() == Precision::kDouble) {
    write_faces<Point3d>(engine, scene.displayed_faces(), path);
  } else {
    write_faces<Point3>(engine, scene.displayed_faces(), path);
  }
}

void export_trace(const Scene& scene, const std::string& path) {
  const std::vector<IterationRecord> records = scene.replay_records();
  write_file_atomically(path, [&](std::ostream& out) {
    for (const IterationRecord& r : records)
      out << iteration_to_json(r).dump() << '\n';
  });
}

void export_decisions(const Scene& scene, const std::string& path) {
  const IterationRecord* record = scene.current_record();
  if (record == nullptr) throw OutputError(path + ": no step yet, so no decision array");
  write_file_atomically(path, [&](std::ostream& out) {
    out << "index,kind,nx,ny,nz,d,above,below\n";
    for (std::size_t k = 0; k < record->decisions.size(); ++k) {
      const DecisionEntry& d = record->decisions[k];
      if (d.kind == kDecisionSwap) {
        out << k << ",swap," << number(d.plane.nx) << ',' << number(d.plane.ny) << ',' << number(d.plane.nz)
            << ',' << number(d.plane.d) << ',' << route(d.above) << ',' << route(d.below) << '\n';
      } else {
        out << k << ",removal,,,,," << route(d.above) << ',' << route(d.above) << '\n';
      }
    }
  });
}

}  // namespace cudahull::viewer
