// Point sets in: read_input() for every command, `cudahull info` (a file described) and `cudahull gen` (a
// distribution generated).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/point_writer.hpp"

namespace cudahull::cli {

namespace {

// A progress line on stderr for long loads, only when stderr is a terminal.
ProgressFn stderr_progress(const std::string& what, bool quiet) {
  if (quiet || !isatty(STDERR_FILENO)) return {};
  return [what, last = -1](double fraction) mutable {
    const int percent = static_cast<int>(fraction * 100);
    if (percent == last) return;
    last = percent;
    std::fprintf(stderr, "\r%s %3d%%%s", what.c_str(), percent, percent >= 100 ? "\n" : "");
    std::fflush(stderr);
  };
}

}  // namespace

// hull_in() takes coordinates outside the engines' exact range to exact_hull_any().
template <>
std::vector<Point3> read_input<Point3>(const std::string& path, bool quiet) {
  return read_points(path, stderr_progress("reading " + path, quiet));
}

template <>
std::vector<Point3d> read_input<Point3d>(const std::string& path, bool quiet) {
  DoublePoints read = read_points_double(path, stderr_progress("reading " + path, quiet));
  return std::move(read.points);
}

int run_info(const InfoOptions& o) {
  const auto t0 = Clock::now();
  const std::vector<Point3> points = read_points(o.input, stderr_progress("reading " + o.input, false));
  const double read_ms = ms_since(t0);
  nlohmann::json j;
  j["file"] = o.input;
  j["points"] = points.size();
  if (!points.empty()) {
    Point3 lo = points[0], hi = points[0];
    for (const Point3& p : points) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    j["bbox"] = {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}};
  } else {
    j["bbox"] = nullptr;
  }
  j["dimension"] = affine_dimension(points);
  // What `--precision auto` picks for this file (from its format and PLY header; the points above are float).
  j["precision"] = precision_name(auto_precision(o.input));
  j["read_ms"] = read_ms;
  std::cout << j.dump() << "\n";
  return kExitOk;
}

int run_gen(const GenOptions& o) {
  const Distribution dist = distribution_from_name(o.distribution);
  const std::vector<Point3> points = generate_points(dist, o.count, o.seed);
  write_points(o.output, points);
  std::fprintf(stderr, "gen: %zu %s points (seed %llu) -> %s\n", points.size(), o.distribution.c_str(),
               static_cast<unsigned long long>(o.seed), o.output.c_str());
  return kExitOk;
}

}  // namespace cudahull::cli
