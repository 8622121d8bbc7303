// The checks of the vertices: each equals its input point, none is listed twice, none coincides with
// another, and each has the lowest index among input points with its coordinates (item 5).
#include "checker.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdint>
#include <thread>
#include <utility>
#include <vector>

#include "vertex_table.hpp"

namespace cudahull::checking {

template <class Point>
bool Checker<Point>::check_vertices() {
  bool ok = true;
  if (h_.vertices.size() != h_.vertex_ids.size()) {
    rep_.fail(
        fmt("vertices has %zu entries but vertex_ids has %zu", h_.vertices.size(), h_.vertex_ids.size()));
    return false;
  }
  for (std::uint32_t v = 0; v < h_.vertex_ids.size(); ++v) {
    const PointIndex id = h_.vertex_ids[v];
    if (id >= pts_.size()) {
      rep_.fail(
          fmt("vertex %" PRIu32 " has id %" PRIu32 ", beyond the %zu input points", v, id, pts_.size()));
      ok = false;
    } else if (!(h_.vertices[v] == pts_[id])) {
      rep_.fail(fmt("vertex %" PRIu32 " has coordinates %s but input point %" PRIu32 " is %s", v,
                    coords(h_.vertices[v]).c_str(), id, coords(pts_[id]).c_str()));
      ok = false;
    }
  }
  std::vector<PointIndex> ids = h_.vertex_ids;
  std::sort(ids.begin(), ids.end());
  for (std::size_t i = 1; i < ids.size(); ++i)
    if (ids[i] == ids[i - 1]) {
      rep_.fail(fmt("input point %" PRIu32 " is listed as a vertex more than once", ids[i]));
      ok = false;
    }
  return ok;
}

// Item 5: no two vertices coincide, and no input point with a lower index has a vertex's coordinates.
template <class Point>
void Checker<Point>::check_lowest_index() {
  VertexTable<Point> table(h_.vertices);
  for (std::uint32_t v = 0; v < h_.vertices.size(); ++v) {
    const std::uint32_t w = table.insert(v);
    if (w != kNone)
      rep_.fail(fmt("vertices %" PRIu32 " and %" PRIu32 " (ids %" PRIu32 " and %" PRIu32
                    ") have identical coordinates %s: a duplicate is not strictly extreme",
                    w, v, h_.vertex_ids[w], h_.vertex_ids[v], coords(h_.vertices[v]).c_str()));
  }
  // An input point with a vertex's coordinates and a lower index than the vertex's id breaks the rule.
  // Threads collect hits (none for a valid hull; capped otherwise), reported per vertex, lowest index first.
  const std::size_t n = pts_.size();
  const std::size_t chunks =
      std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()), n / 100000 + 1);
  std::vector<std::vector<std::pair<std::uint32_t, std::size_t>>> hits(chunks);
  auto scan = [&](std::size_t t) {
    for (std::size_t i = n * t / chunks, e = n * (t + 1) / chunks; i < e && hits[t].size() < 4096; ++i) {
      const std::uint32_t v = table.find(pts_[i]);
      if (v != kNone && i < h_.vertex_ids[v]) hits[t].emplace_back(v, i);
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t t = 1; t < chunks; ++t)
    threads.emplace_back(scan, t);
  scan(0);
  for (std::thread& th : threads)
    th.join();
  std::vector<std::pair<std::uint32_t, std::size_t>> all;
  for (auto& h : hits)
    all.insert(all.end(), h.begin(), h.end());
  std::sort(all.begin(), all.end());
  for (std::size_t k = 0; k < all.size(); ++k)
    if (k == 0 || all[k].first != all[k - 1].first)
      rep_.fail(fmt("vertex %" PRIu32 " (id %" PRIu32
                    ") is not the lowest index with its coordinates: input point "
                    "%zu is identical",
                    all[k].first, h_.vertex_ids[all[k].first], all[k].second));
}

// The two point types; the callers are in other files.
template bool Checker<Point3>::check_vertices();
template void Checker<Point3>::check_lowest_index();
template bool Checker<Point3d>::check_vertices();
template void Checker<Point3d>::check_lowest_index();

}  // namespace cudahull::checking
