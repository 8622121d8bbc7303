// The batch's result in device memory: assembled there from the kernel's meshes and the hosted hulls
// (assemble_on_device(), batch_on_device.hpp), and read back for a host result (DeviceConvexHullBatch::
// to_host()).
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "batch_on_device.hpp"
#include "cudahull/convex_hull_batch_results.hpp"

namespace cudahull {

namespace batch {

namespace {

template <class T>
DeviceColumn<T> device_column(std::size_t size, const char* what) {
  return {std::static_pointer_cast<T>(batch_column(size * sizeof(T), what)), size};
}

}  // namespace

template <class Point>
DeviceConvexHullBatch assemble_on_device(const BatchRun<Point>& run, HostedHulls&& hosted,
                                         std::size_t clouds) {
  PhaseLaps laps("batch assembly");
  DeviceConvexHullBatch batch;
  batch.device = current_cuda_device();
  batch.clouds_batched = run.clouds_done;
  // The backends in the order first met, cloud by cloud: the kernel's before the first hosted cloud after
  // its first done one.
  const std::size_t first_done =
      run.clouds_done == 0
          ? clouds
          : static_cast<std::size_t>(std::find(run.done.begin(), run.done.end(), 1) - run.done.begin());
  std::vector<HostedSizes> sizes;
  sizes.reserve(hosted.size());
  for (const auto& [c, hull] : hosted) {
    if (c > first_done) add_backend(batch, "cuda-resident");
    add_backend(batch, hull.backend);
    sizes.push_back({c, hull.vertices.size(), hull.faces.size(), hull.polygon.size()});
  }
  if (first_done < clouds) add_backend(batch, "cuda-resident");
  batch.device_vertex_offsets = device_column<std::int64_t>(clouds + 1, "the vertex offsets");
  batch.device_face_offsets = device_column<std::int64_t>(clouds + 1, "the face offsets");
  batch.device_polygon_offsets = device_column<std::int64_t>(clouds + 1, "the polygon offsets");
  const BatchTotals totals =
      lay_out_batch_offsets(run, sizes, clouds, batch.device_vertex_offsets.data.get(),
                            batch.device_face_offsets.data.get(), batch.device_polygon_offsets.data.get());
  const std::size_t vertices = totals.vertices, faces = totals.faces, polygons = totals.polygons;
  laps.lap("offsets");
  batch.vertices = device_column<std::int32_t>(vertices, "the vertices");
  batch.faces = device_column<std::int32_t>(3 * faces, "the faces");
  batch.polygons = device_column<std::int32_t>(polygons, "the polygons");
  batch.dimensions = device_column<std::int32_t>(clouds, "the dimensions");
  batch.planes = device_column<double>(4 * faces, "the planes");
  batch.volumes = device_column<double>(clouds, "the volumes");
  batch.areas = device_column<double>(clouds, "the areas");
  laps.lap("columns");
  if (batch.clouds_batched != 0) {
    const BatchColumns columns{batch.device_vertex_offsets.data.get(),
                               batch.device_face_offsets.data.get(),
                               batch.vertices.data.get(),
                               batch.faces.data.get(),
                               batch.dimensions.data.get(),
                               batch.planes.data.get(),
                               batch.volumes.data.get(),
                               batch.areas.data.get()};
    describe_batch_cuda(run, columns);
    laps.lap("describe");
  }
  // The hosted clouds, a run of consecutive ones at a time, at the offsets of each run's first cloud (read
  // back for these alone).
  std::vector<std::size_t> run_starts;
  for (std::size_t k = 0; k < hosted.size(); ++k)
    if (k == 0 || hosted[k].first != hosted[k - 1].first + 1) run_starts.push_back(hosted[k].first);
  // Per run: its first cloud's vertex, face and polygon offsets.
  const std::vector<std::array<std::int64_t, 3>> run_at =
      read_offsets_at(batch.device_vertex_offsets.data.get(), batch.device_face_offsets.data.get(),
                      batch.device_polygon_offsets.data.get(), run_starts);
  const auto up = [](auto& column, const auto& values, std::size_t at = 0) {
    copy_to_device(column.data.get() + at, values.data(), values.size() * sizeof(values[0]));
  };
  for (std::size_t first = 0, r = 0; first < hosted.size(); ++r) {
    std::size_t end = first + 1;
    while (end < hosted.size() && hosted[end].first == hosted[end - 1].first + 1)
      ++end;
    const std::size_t c0 = hosted[first].first;
    std::vector<std::int32_t> ids, corners, polygon, dimensions;
    std::vector<double> planes, volumes, areas;
    for (std::size_t k = first; k < end; ++k) {
      ConvexHull& hull = hosted[k].second;
      ids.insert(ids.end(), hull.vertices.begin(), hull.vertices.end());
      for (const auto& face : hull.faces)
        corners.insert(corners.end(), face.begin(), face.end());
      for (const auto& plane : hull.planes)
        planes.insert(planes.end(), plane.begin(), plane.end());
      polygon.insert(polygon.end(), hull.polygon.begin(), hull.polygon.end());
      volumes.push_back(hull.volume);
      areas.push_back(hull.area);
      dimensions.push_back(hull.dimension);
      hull = ConvexHull{};  // its memory back now
    }
    up(batch.vertices, ids, static_cast<std::size_t>(run_at[r][0]));
    up(batch.faces, corners, 3 * static_cast<std::size_t>(run_at[r][1]));
    up(batch.planes, planes, 4 * static_cast<std::size_t>(run_at[r][1]));
    up(batch.polygons, polygon, static_cast<std::size_t>(run_at[r][2]));
    up(batch.volumes, volumes, c0);
    up(batch.areas, areas, c0);
    up(batch.dimensions, dimensions, c0);
    first = end;
  }
  std::size_t result_bytes = 0;
  for (const std::size_t bytes : {3 * (clouds + 1) * sizeof(std::int64_t),
                                  (vertices + 3 * faces + polygons + clouds) * sizeof(std::int32_t),
                                  (4 * faces + 2 * clouds) * sizeof(double)})
    result_bytes += bytes;
  batch.device_bytes_peak = std::max(run.device_bytes, run.kept_bytes + result_bytes);
  finish_device_work();  // the last copies landed before a library on another stream reads the columns
  laps.lap("hosted up");
  return batch;
}

template DeviceConvexHullBatch assemble_on_device(const BatchRun<Point3>&, HostedHulls&&, std::size_t);
template DeviceConvexHullBatch assemble_on_device(const BatchRun<Point3d>&, HostedHulls&&, std::size_t);

}  // namespace batch

void copy_to_host(const DeviceConvexHullBatch& batch, const BatchHostColumns& into) {
  const std::size_t clouds = batch.size();
  for (auto [to, from] : {std::pair{into.vertex_offsets, &batch.device_vertex_offsets},
                          std::pair{into.face_offsets, &batch.device_face_offsets},
                          std::pair{into.polygon_offsets, &batch.device_polygon_offsets}}) {
    if (from->data)
      copy_to_host(to, from->data.get(), (clouds + 1) * sizeof(std::int64_t));
    else
      std::fill_n(to, clouds + 1, std::int64_t{0});
  }
  copy_to_host(into.vertices, batch.vertices.data.get(), batch.vertices.size * sizeof(std::int32_t));
  copy_to_host(into.faces, batch.faces.data.get(), batch.faces.size * sizeof(std::int32_t));
  copy_to_host(into.planes, batch.planes.data.get(), batch.planes.size * sizeof(double));
  copy_to_host(into.polygons, batch.polygons.data.get(), batch.polygons.size * sizeof(std::int32_t));
  copy_to_host(into.volumes, batch.volumes.data.get(), clouds * sizeof(double));
  copy_to_host(into.areas, batch.areas.data.get(), clouds * sizeof(double));
  copy_to_host(into.dimensions, batch.dimensions.data.get(), clouds * sizeof(std::int32_t));
}

ConvexHullBatch DeviceConvexHullBatch::to_host() const {
  ConvexHullBatch batch;
  static_cast<ConvexHullBatchReport&>(batch) = *this;
  const std::size_t clouds = size();
  std::vector<std::int64_t> offsets[3];
  for (auto& column : offsets)
    column.resize(clouds + 1);
  batch.vertices.resize(vertices.size);
  batch.faces.resize(faces.size / 3);
  batch.planes.resize(planes.size / 4);
  batch.polygons.resize(polygons.size);
  batch.volumes.resize(clouds);
  batch.areas.resize(clouds);
  batch.dimensions.resize(clouds);
  // int32 indices into PointIndex (uint32: the same bytes for indices under 2^31).
  static_assert(sizeof(PointIndex) == sizeof(std::int32_t) &&
                sizeof(batch.faces[0]) == 3 * sizeof(PointIndex));
  copy_to_host(*this,
               {offsets[0].data(), offsets[1].data(), offsets[2].data(),
                reinterpret_cast<std::int32_t*>(batch.vertices.data()),
                reinterpret_cast<std::int32_t*>(batch.faces.data()),
                reinterpret_cast<std::int32_t*>(batch.polygons.data()), batch.dimensions.data(),
                reinterpret_cast<double*>(batch.planes.data()), batch.volumes.data(), batch.areas.data()});
  batch.vertex_offsets.assign(offsets[0].begin(), offsets[0].end());
  batch.face_offsets.assign(offsets[1].begin(), offsets[1].end());
  batch.polygon_offsets.assign(offsets[2].begin(), offsets[2].end());
  return batch;
}

}  // namespace cudahull
