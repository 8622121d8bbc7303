// The package's options as ConvexHullOptions, a ConvexHull as its dict (hull_conversions.hpp).
#include "hull_conversions.hpp"

#include <iterator>
#include <optional>
#include <type_traits>
#include <vector>

#include "cudahull/hull_options.hpp"
#include "cudahull/resident.hpp"

namespace cudahull::python {

namespace {

nb::object stats_to_dict(const std::optional<ResidentStats>& stats) {
  if (!stats) return nb::none();
  nb::dict d;
  for_each_stat(*stats, [&](const char* name, const auto& value) {
    if constexpr (std::is_array_v<std::remove_reference_t<decltype(value)>>) {
      d[name] = std::vector<double>(std::begin(value), std::end(value));
    } else {
      d[name] = value;
    }
  });
  return d;
}

}  // namespace

nb::dict hull_to_dict(ConvexHull&& hull) {
  nb::dict d;
  nb::object stats = stats_to_dict(hull.resident_stats);
  if (!stats.is_none() && hull.engine_ms > 0) {
    stats["engine_ms"] = hull.engine_ms;
    stats["describe_ms"] = hull.describe_ms;
  }
  if (!stats.is_none()) stats["plan"] = hull.plan;
  d["stats"] = stats;
  d["plan"] = hull.plan;
  d["dimension"] = hull.dimension;
  d["precision"] = precision_name(hull.precision);
  d["backend"] = hull.backend;
  d["volume"] = hull.volume;
  d["area"] = hull.area;
  d["input_dimension"] = hull.input_dimension;
  d["tolerance"] = hull.tolerance;
  d["max_outside"] = hull.max_outside;
  d["thinnest"] = hull.thinnest;
  d["vertices"] = to_numpy(std::move(hull.vertices));
  d["polygon"] = to_numpy(std::move(hull.polygon));
  d["coplanar"] = take_rows(std::move(hull.coplanar));
  if (hull.input_dimension == 2) {
    d["simplices"] = take_rows(std::move(hull.edges));
    d["neighbors"] = take_rows(std::move(hull.edge_neighbors));
    d["equations"] = take_rows(std::move(hull.lines));
  } else {
    d["simplices"] = take_rows(std::move(hull.faces));
    d["neighbors"] = take_rows(std::move(hull.neighbors));
    d["equations"] = take_rows(std::move(hull.planes));
  }
  return d;
}

ConvexHullOptions options_from(const std::string& backend, const std::string& precision,
                               const std::string& engine, const Merge& merge) {
  ConvexHullOptions options;
  options.backend = backend_from_name(backend);
  options.precision = precision_from_name_strict(precision);
  options.engine = engine_from_name(engine);
  options.merge = merge_from_name(merge.mode);
  options.tolerance = merge.tolerance;
  options.angle_cosine = merge.angle_cosine;
  return options;
}

}  // namespace cudahull::python
