// The exact hull's sites (exact_sites.hpp): Morton-order sort and deduplication, and the mesh of the sites
// kept.
#include "exact_sites.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "cudahull/morton.hpp"
#include "cudahull/types.hpp"
#include "exact_vector.hpp"

namespace cudahull::exact {
namespace {

// The Morton cell of a coordinate scaled to [0, 2^21): NaN (an overflowing double extent) goes to cell 0.
std::uint64_t morton_cell(double t) {
  return t > 0 ? static_cast<std::uint64_t>(std::min(t, 2097151.0)) : 0;
}

template <class Point>
bool site_less(const Site<Point>& a, const Site<Point>& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  if (a.z != b.z) return a.z < b.z;
  return a.id < b.id;
}

}  // namespace

template <class Point>
BasicHullMesh<Point> make_mesh(const std::vector<Site<Point>>& sites, std::vector<std::uint32_t> keep,
                               int dimension, std::vector<std::uint32_t>& out_index) {
  std::vector<std::pair<PointIndex, std::uint32_t>> by_id(keep.size());
  for (std::size_t k = 0; k < keep.size(); ++k)
    by_id[k] = {sites[keep[k]].id, keep[k]};
  std::sort(by_id.begin(), by_id.end());
  for (std::size_t k = 0; k < keep.size(); ++k)
    keep[k] = by_id[k].second;
  BasicHullMesh<Point> m;
  m.dimension = dimension;
  out_index.assign(sites.size(), kNone);
  m.vertex_ids.reserve(keep.size());
  m.vertices.reserve(keep.size());
  for (std::uint32_t k = 0; k < keep.size(); ++k) {
    const Site<Point>& s = sites[keep[k]];
    out_index[keep[k]] = k;
    m.vertex_ids.push_back(s.id);
    m.vertices.push_back({s.x, s.y, s.z});
  }
  return m;
}

template <class Point>
void sort_and_dedupe(std::vector<Site<Point>>& sites) {
  using Coord = typename Site<Point>::Coord;
  if (sites.empty()) return;
  Coord lo[3] = {sites[0].x, sites[0].y, sites[0].z}, hi[3] = {lo[0], lo[1], lo[2]};
  for (const Site<Point>& s : sites) {
    const Coord c[3] = {s.x, s.y, s.z};
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
  }
  double scale[3];
  for (int k = 0; k < 3; ++k) {
    const double ext = static_cast<double>(hi[k]) - lo[k];
    scale[k] = ext > 0 ? 2097151.0 / ext : 0;
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(sites.size());
  for (std::uint32_t i = 0; i < sites.size(); ++i) {
    const Site<Point>& s = sites[i];
    const double c[3] = {s.x, s.y, s.z};
    std::uint64_t key = 0;
    for (int k = 0; k < 3; ++k)
      key |= spread3(morton_cell((c[k] - lo[k]) * scale[k])) << k;
    keys[i] = {key, i};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<Site<Point>> sorted(sites.size());
  for (std::size_t i = 0; i < keys.size(); ++i)
    sorted[i] = sites[keys[i].second];
  for (std::size_t b = 0; b < keys.size();) {
    std::size_t e = b + 1;
    while (e < keys.size() && keys[e].first == keys[b].first)
      ++e;
    if (e - b > 1) std::sort(sorted.begin() + b, sorted.begin() + e, site_less<Point>);
    b = e;
  }
  sorted.erase(std::unique(sorted.begin(), sorted.end(),
                           [](const Site<Point>& a, const Site<Point>& b) {
                             return a.x == b.x && a.y == b.y && a.z == b.z;
                           }),
               sorted.end());
  sites.swap(sorted);
}

// The two point types; one implementation.
template HullMesh make_mesh(const std::vector<Site<Point3>>&, std::vector<std::uint32_t>, int,
                            std::vector<std::uint32_t>&);
template HullMeshd make_mesh(const std::vector<Site<Point3d>>&, std::vector<std::uint32_t>, int,
                             std::vector<std::uint32_t>&);
template void sort_and_dedupe(std::vector<Site<Point3>>&);
template void sort_and_dedupe(std::vector<Site<Point3d>>&);

}  // namespace cudahull::exact
