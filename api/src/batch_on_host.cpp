// The per-cloud hulls packed into the batch's flat arrays on all cores (batch_on_host.hpp).
#include "batch_on_host.hpp"

#include <algorithm>

namespace cudahull::batch {

ConvexHullBatch pack(std::vector<ConvexHull>&& hulls, Precision precision) {
  ConvexHullBatch batch;
  batch.precision = precision;
  const std::size_t clouds = hulls.size();
  batch.vertex_offsets.assign(clouds + 1, 0);
  batch.face_offsets.assign(clouds + 1, 0);
  batch.polygon_offsets.assign(clouds + 1, 0);
  batch.volumes.resize(clouds);
  batch.areas.resize(clouds);
  batch.dimensions.resize(clouds);
  for (std::size_t c = 0; c < clouds; ++c) {
    const ConvexHull& hull = hulls[c];
    batch.vertex_offsets[c + 1] = batch.vertex_offsets[c] + hull.vertices.size();
    batch.face_offsets[c + 1] = batch.face_offsets[c] + hull.faces.size();
    batch.polygon_offsets[c + 1] = batch.polygon_offsets[c] + hull.polygon.size();
    batch.volumes[c] = hull.volume;
    batch.areas[c] = hull.area;
    batch.dimensions[c] = hull.dimension;
    add_backend(batch, hull.backend);
  }
  batch.vertices.resize(batch.vertex_offsets[clouds]);
  batch.faces.resize(batch.face_offsets[clouds]);
  batch.planes.resize(batch.face_offsets[clouds]);
  batch.polygons.resize(batch.polygon_offsets[clouds]);
  parallel_chunks(
      clouds, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t c = begin; c < end; ++c) {
          ConvexHull& hull = hulls[c];
          std::copy(hull.vertices.begin(), hull.vertices.end(),
                    batch.vertices.begin() + static_cast<std::ptrdiff_t>(batch.vertex_offsets[c]));
          std::copy(hull.faces.begin(), hull.faces.end(),
                    batch.faces.begin() + static_cast<std::ptrdiff_t>(batch.face_offsets[c]));
          std::copy(hull.planes.begin(), hull.planes.end(),
                    batch.planes.begin() + static_cast<std::ptrdiff_t>(batch.face_offsets[c]));
          std::copy(hull.polygon.begin(), hull.polygon.end(),
                    batch.polygons.begin() + static_cast<std::ptrdiff_t>(batch.polygon_offsets[c]));
          hull = ConvexHull{};  // its memory back now
        }
      },
      256);
  return batch;
}

}  // namespace cudahull::batch
