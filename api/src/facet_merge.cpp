// Qhull-like facet merging of an exact hull (design: facet_merge.hpp).
#include "facet_merge.hpp"

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "cudahull/detail/plane_impl.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/morton.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/plane.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull {

namespace {

using Plane = std::array<double, 4>;
constexpr std::uint32_t kNone = 0xffffffffu;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kUnitRoundoff = 0x1p-53;

// n . p + d in double, in this order (the certificate's error bound assumes it).
double plane_value(const Plane& plane, const Vec3d& p) {
  return plane[0] * p.x + plane[1] * p.y + plane[2] * p.z + plane[3];
}

double dot3(const Plane& plane, const Vec3d& p) {
  return plane[0] * p.x + plane[1] * p.y + plane[2] * p.z;
}

Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Squared Euclidean distance from p to triangle abc (closest point by Voronoi regions, Ericson 5.1.5).
double triangle_distance2(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  auto dist2 = [&](const Vec3d& q) { return dot(sub(p, q), sub(p, q)); };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return dist2(a);
  const Vec3d bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dist2(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return dist2({a.x + v * ab.x, a.y + v * ab.y, a.z + v * ab.z});
  }
  const Vec3d cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dist2(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return dist2({a.x + w * ac.x, a.y + w * ac.y, a.z + w * ac.z});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return dist2({b.x + w * (c.x - b.x), b.y + w * (c.y - b.y), b.z + w * (c.z - b.z)});
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return dist2({a.x + ab.x * v + ac.x * w, a.y + ab.y * v + ac.y * w, a.z + ab.z * v + ac.z * w});
}

// A bounding-box tree over items (points or triangles) for the two all-pairs passes, the certificate and
// the nearest triangles: without it they cost V x F (docs/benchmarks.md, "The measurements behind the code's
// constants").  Items are sorted by the Morton code of their boxes' centres and split in halves down to
// leaves of at most kLeaf items.
struct Box {
  double lo[3] = {kInfinity, kInfinity, kInfinity}, hi[3] = {-kInfinity, -kInfinity, -kInfinity};
  void add(const Box& b) {
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], b.lo[k]), hi[k] = std::max(hi[k], b.hi[k]);
  }
};

class BoxTree {
 public:
  static constexpr std::uint32_t kLeaf = 8;
  struct Node {
    Box box;
    std::uint32_t begin = 0, end = 0;           // items order[begin, end)
    std::uint32_t left = kNone, right = kNone;  // children, kNone for a leaf
  };
  explicit BoxTree(std::vector<Box> boxes) : boxes_(std::move(boxes)) {
    if (boxes_.empty()) return;
    Box all;
    for (const Box& b : boxes_)
      all.add(b);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(boxes_.size());
    for (std::uint32_t i = 0; i < boxes_.size(); ++i) {
      std::uint64_t code = 0;
      for (int k = 0; k < 3; ++k) {
        const double width = all.hi[k] - all.lo[k];
        double t = width > 0 ? ((boxes_[i].lo[k] + boxes_[i].hi[k]) / 2 - all.lo[k]) / width : 0;
        if (!(t > 0)) t = 0;  // NaN too: the order only affects speed
        code |= spread3(static_cast<std::uint64_t>(std::min(t, 1.0) * 2097151.0)) << k;
      }
      keyed[i] = {code, i};
    }
    std::sort(keyed.begin(), keyed.end());
    order_.resize(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i)
      order_[i] = keyed[i].second;
    nodes_.reserve(2 * (boxes_.size() / kLeaf + 1));
    build(0, static_cast<std::uint32_t>(order_.size()));
  }
  const std::vector<Node>& nodes() const { return nodes_; }
  std::uint32_t item(std::uint32_t position) const { return order_[position]; }
  bool empty() const { return nodes_.empty(); }

 private:
  std::uint32_t build(std::uint32_t begin, std::uint32_t end) {
    const std::uint32_t id = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    Box box;
    for (std::uint32_t i = begin; i < end; ++i)
      box.add(boxes_[order_[i]]);
    std::uint32_t left = kNone, right = kNone;
    if (end - begin > kLeaf) {
      const std::uint32_t middle = begin + (end - begin) / 2;
      left = build(begin, middle);
      right = build(middle, end);
    }
    nodes_[id] = {box, begin, end, left, right};
    return id;
  }
  std::vector<Box> boxes_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

// Sorts (key, value) pairs by key, stably (equal keys keep their order): a least-significant-digit radix
// sort of the keys' high halves in 11-bit digits (passing over digits in which every key is the same), then
// each run of equal high halves by insertion on the low half.  The keys here are doubles' bits, whose high
// halves (sign, exponent and 20 bits of mantissa) rarely tie: half the passes of a sort on all 64 bits.
void radix_sort_by_key(std::vector<std::pair<std::uint64_t, std::uint32_t>>& items) {
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> spare(items.size());
  std::vector<std::size_t> count(kBuckets + 1);
  for (int shift = 32; shift < 64; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0);
    auto digit = [shift](std::uint64_t key) { return (key >> shift) & (kBuckets - 1); };
    for (const auto& item : items)
      ++count[digit(item.first) + 1];
    if (!items.empty() && count[digit(items[0].first) + 1] == items.size()) continue;
    for (std::size_t b = 0; b < kBuckets; ++b)
      count[b + 1] += count[b];
    for (const auto& item : items)
      spare[count[digit(item.first)]++] = item;
    items.swap(spare);
  }
  for (std::size_t k = 1; k < items.size(); ++k)
    for (std::size_t x = k;
         x > 0 && (items[x - 1].first >> 32) == (items[x].first >> 32) && items[x - 1].first > items[x].first;
         --x)
      std::swap(items[x - 1], items[x]);
}

// The directed edges of a closed triangulated surface: per vertex a, its out-edges (b, the triangle holding
// a -> b), ascending in b (and in the triangle for equal b, on a surface that is not a manifold).  Each
// neighbour of a appears once (the other triangle holds b -> a).
struct EdgeIndex {
  std::vector<std::uint32_t> start;                          // per vertex, into `out`; one more at the end
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;  // (to, triangle)

  // Two stable counting sorts, by end, then by start: every vertex's run ascending in its end, equal ends in
  // triangle order.  Each worker owns a range of vertices, whose entries it places reading every item, so
  // that no two write one place: the counts (a vertex ends as many half-edges as it starts, one each a
  // triangle it is in, so both sorts place from `start`), the starts on one core, the half-edges ending in
  // the range, then those starting in it.
  template <class Point>
  explicit EdgeIndex(const BasicHullMesh<Point>& mesh) : start(mesh.vertices.size() + 1, 0) {
    const std::size_t n = mesh.vertices.size();
    const unsigned workers =
        static_cast<unsigned>(std::clamp<std::size_t>(n / kVerticesAWorker, 1, hardware_workers()));
    auto each_range = [&](auto&& body) {
      parallel_chunks(
          workers, workers,
          [&](std::size_t begin, std::size_t end, unsigned) {
            for (std::size_t w = begin; w < end; ++w)
              body(static_cast<std::uint32_t>(n * w / workers),
                   static_cast<std::uint32_t>(n * (w + 1) / workers));
          },
          1);
    };
    each_range([&](std::uint32_t low, std::uint32_t high) {
      for (const Triangle& t : mesh.triangles)
        for (std::uint32_t v : t)
          if (v - low < high - low) ++start[v + 1];
    });
    for (std::size_t v = 0; v < n; ++v)
      start[v + 1] += start[v];
    struct HalfEdge {
      std::uint32_t from, to, triangle;
    };
    std::vector<HalfEdge> by_end(start.back());
    each_range([&](std::uint32_t low, std::uint32_t high) {
      std::vector<std::uint32_t> fill(start.begin() + low, start.begin() + high);
      for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
          if (const std::uint32_t to = mesh.triangles[t][(k + 1) % 3]; to - low < high - low)
            by_end[fill[to - low]++] = {mesh.triangles[t][k], to, t};
    });
    out.resize(start.back());
    each_range([&](std::uint32_t low, std::uint32_t high) {
      std::vector<std::uint32_t> fill(start.begin() + low, start.begin() + high);
      for (const HalfEdge& e : by_end)
        if (e.from - low < high - low) out[fill[e.from - low]++] = {e.to, e.triangle};
    });
  }
  static constexpr std::size_t kVerticesAWorker = 256;  // fewer: a worker's wake-up costs more than its share
  std::uint32_t degree(std::uint32_t v) const { return start[v + 1] - start[v]; }
  std::uint32_t neighbour(std::uint32_t v, std::uint32_t k) const { return out[start[v] + k].first; }
  // The triangle holding the directed edge a -> b, kNone if none.
  std::uint32_t triangle(std::uint32_t a, std::uint32_t b) const {
    for (std::uint32_t k = start[a]; k < start[a + 1]; ++k)
      if (out[k].first == b) return out[k].second;
    return kNone;
  }
};

// parallel_chunks() with its range dealt out in blocks of `block` items to whichever thread is free, for
// passes whose items are independent: on a shared machine a worker the scheduler holds back takes fewer
// blocks, where an even split left the caller waiting for that worker's half.  `block` is the largest
// block: a pass of few items gets at least four blocks a worker (of kLeastBlock items or more), so that a
// hull of some thousand vertices keeps every core of a large machine busy, not as many as its blocks.
constexpr std::size_t kLeastBlock = 48;

// parallel_blocks() with `side()` run once, by the first thread to start, while the others take the blocks:
// a one-core step overlapped with a pass it does not depend on.
template <class Body, class Side>
void parallel_blocks_beside(std::size_t n, unsigned workers, Body&& body, Side&& side,
                            std::size_t block = 4096) {
  block = std::min(block, std::max(kLeastBlock, n / (4 * std::max(1u, workers))));
  const std::size_t blocks = (n + block - 1) / block;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> side_taken{false};
  // One more chunk than blocks, so that the side task has a worker even for a single block.
  parallel_chunks(
      blocks + 1, workers,
      [&](std::size_t, std::size_t, unsigned worker) {
        if (!side_taken.exchange(true, std::memory_order_relaxed)) side();
        for (std::size_t b; (b = next.fetch_add(1, std::memory_order_relaxed)) < blocks;)
          body(b * block, std::min(n, (b + 1) * block), worker);
      },
      1);
}

// parallel_blocks() beside nothing.
template <class Body>
void parallel_blocks(std::size_t n, unsigned workers, Body&& body, std::size_t block = 4096) {
  parallel_blocks_beside(
      n, workers, std::forward<Body>(body), [] {}, block);
}

// The vertices of `mesh` along a Morton curve of their box, and its triangles by their first corner in that
// order.  The per-vertex, per-triangle and per-facet passes take their independent items in these orders,
// so that neighbours on the hull are neighbours in time: in index order (the engine's, spatially random)
// nearly every read of a corner, a link or a plane missed the cache, most of a 100,000-vertex sphere's
// merge.  Only the order of independent items changes, never a result.  Small meshes keep index order.
struct VisitOrder {
  std::vector<std::uint32_t> vertices, triangles;
  std::vector<std::uint32_t> triangle_rank;  // per triangle: its place in `triangles`
};

template <class Point>
VisitOrder visit_order(const BasicHullMesh<Point>& mesh) {
  const std::size_t n = mesh.vertices.size();
  VisitOrder order;
  order.vertices.resize(n);
  std::iota(order.vertices.begin(), order.vertices.end(), 0u);
  if (n >= 4096) {
    Box all;
    for (const Point& p : mesh.vertices)
      all.add({{double(p.x), double(p.y), double(p.z)}, {double(p.x), double(p.y), double(p.z)}});
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
    parallel_chunks(n, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
      for (std::size_t i = begin; i < end; ++i) {
        const double at[3] = {double(mesh.vertices[i].x), double(mesh.vertices[i].y),
                              double(mesh.vertices[i].z)};
        std::uint64_t code = 0;
        for (int k = 0; k < 3; ++k) {
          const double width = all.hi[k] - all.lo[k];
          double t = width > 0 ? (at[k] - all.lo[k]) / width : 0;
          if (!(t > 0)) t = 0;  // NaN too: the order only affects speed
          code |= spread3(static_cast<std::uint64_t>(std::min(t, 1.0) * 2097151.0)) << k;
        }
        keyed[i] = {code, static_cast<std::uint32_t>(i)};
      }
    });
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t i = 0; i < n; ++i)
      order.vertices[i] = keyed[i].second;
  }
  // Each vertex's triangles (those it is the first corner of) in its out-edges' order (a triangle a -> b -> c
  // holds out-edge a -> b): by their second corner, then stably by their first corner's place, two counting
  // sorts.
  std::vector<std::uint32_t> rank_of(n);
  for (std::uint32_t j = 0; j < n; ++j)
    rank_of[order.vertices[j]] = j;
  const std::size_t nt = mesh.triangles.size();
  std::vector<std::uint32_t> second_start(n + 1, 0), first_start(n + 1, 0);
  for (const Triangle& t : mesh.triangles)
    ++second_start[t[1] + 1], ++first_start[rank_of[t[0]] + 1];
  for (std::uint32_t j = 0; j < n; ++j)
    second_start[j + 1] += second_start[j], first_start[j + 1] += first_start[j];
  std::vector<std::uint32_t> by_second(nt);
  for (std::uint32_t t = 0; t < nt; ++t)
    by_second[second_start[mesh.triangles[t][1]]++] = t;
  order.triangles.resize(nt);
  for (std::uint32_t t : by_second)
    order.triangles[first_start[rank_of[mesh.triangles[t][0]]]++] = t;
  order.triangle_rank.resize(order.triangles.size());
  for (std::uint32_t j = 0; j < order.triangles.size(); ++j)
    order.triangle_rank[order.triangles[j]] = j;
  return order;
}

// A mesh's vertices and edges relabelled by a VisitOrder: position j is vertex visit.vertices[j], at[j] its
// coordinates, to[start[j]..start[j + 1]) its neighbours' positions in EdgeIndex's order (ascending original
// index, so that every loop over them takes the same steps).  Built in one pass of scattered reads that
// overlap; the passes then read their neighbours' data from the cache.
struct Relabelled {
  std::vector<std::uint32_t> rank, start, to;
  std::vector<std::uint32_t> face;  // per out-edge: the place in VisitOrder::triangles of its triangle
  std::vector<Vec3d> at;
  bool coordinates_safe = true;  // every coordinate in compare_along()'s exact range
};

template <class Point>
Relabelled relabelled(const BasicHullMesh<Point>& mesh, const EdgeIndex& edges, const VisitOrder& visit) {
  const std::size_t n = mesh.vertices.size();
  Relabelled g;
  g.rank.resize(n);
  g.start.assign(n + 1, 0);
  g.to.resize(edges.out.size());
  g.face.resize(edges.out.size());
  g.at.resize(n);
  for (std::uint32_t j = 0; j < n; ++j) {
    const std::uint32_t v = visit.vertices[j];
    g.rank[v] = j;
    g.start[j + 1] = g.start[j] + edges.degree(v);
  }
  std::atomic<bool> safe{true};
  parallel_blocks(n, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
    bool block_safe = true;
    for (std::size_t j = begin; j < end; ++j) {
      const std::uint32_t v = visit.vertices[j];
      g.at[j] = to_vec3d(mesh.vertices[v]);
      block_safe = block_safe && in_fast_exact_range(g.at[j].x) && in_fast_exact_range(g.at[j].y) &&
                   in_fast_exact_range(g.at[j].z);
      for (std::uint32_t k = 0; k < edges.degree(v); ++k) {
        g.to[g.start[j] + k] = g.rank[edges.neighbour(v, k)];
        g.face[g.start[j] + k] = visit.triangle_rank[edges.out[edges.start[v] + k].second];
      }
    }
    if (!block_safe) safe.store(false, std::memory_order_relaxed);
  });
  g.coordinates_safe = safe.load();
  return g;
}

// Step 1: how far above hull(link) the vertex v stands (see facet_merge.hpp); `link` indexes `points`.
template <class Point>
double vertex_height(const std::vector<Point>& points, const Vec3d& v, const std::vector<PointIndex>& link) {
  const BasicHullMesh<Point> hull = exact_hull(points, link);
  if (hull.dimension == 3) {
    double height = -kInfinity;
    for (const Triangle& t : hull.triangles) {
      const Vec3d a = to_vec3d(hull.vertices[t[0]]), b = to_vec3d(hull.vertices[t[1]]),
                  c = to_vec3d(hull.vertices[t[2]]);
      if (orient3d(a, b, c, v) > 0) height = std::max(height, plane_value(plane_through(a, b, c), v));
    }
    // None above: v is not strictly extreme, which a vertex of an exact hull always is.
    return height == -kInfinity ? kInfinity : height;
  }
  if (hull.dimension == 2) {
    // Strict corners of a convex polygon: any three are affinely independent.
    const Plane plane =
        plane_through(to_vec3d(hull.vertices[hull.polygon[0]]), to_vec3d(hull.vertices[hull.polygon[1]]),
                      to_vec3d(hull.vertices[hull.polygon[2]]));
    return std::fabs(plane_value(plane, v));
  }
  return kInfinity;
}

// Whether v's height over hull(link) (vertex_height()) is certainly above `limit`, found without that hull
// (which, with its planes, was most of a merge: almost every vertex stands far above its link).  A plane
// through three link points with every link point on or below it (exact orient3d) and v strictly above is
// the plane of a facet of hull(link) that v is above, so v's distance to it is at most the height; a lower
// bound on that distance (the determinant's error by Shewchuk's orient3d bound, the edges' lengths rounded
// up) beyond the limit plus a margin for the height's own rounding (under 2^-46 of the largest coordinate)
// decides.  False where no triple shows it: the exact height then decides, as it always did.
constexpr std::size_t kMaxLink = 12;  // C(12, 3) triples at most; a larger link takes the exact height

bool clearly_above(const Vec3d& v, const Vec3d* link, std::size_t k, double limit) {
  if (k < 3 || k > kMaxLink) return false;
  Vec3d q[kMaxLink];
  double scale = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  for (std::size_t j = 0; j < k; ++j) {
    q[j] = link[j];
    scale = std::max({scale, std::fabs(q[j].x), std::fabs(q[j].y), std::fabs(q[j].z)});
  }
  // The facets of hull(link) that v stands above face about the way from the link's centroid to v: their
  // triples are tried first, with the link point furthest that way in every one of the first C(k - 1, 2).
  Vec3d centre{0, 0, 0};
  for (std::size_t j = 0; j < k; ++j)
    centre = {centre.x + q[j].x, centre.y + q[j].y, centre.z + q[j].z};
  const Vec3d way = sub(v, {centre.x / k, centre.y / k, centre.z / k});
  std::size_t furthest = 0;
  for (std::size_t j = 1; j < k; ++j)
    if (dot(way, q[j]) > dot(way, q[furthest])) furthest = j;
  std::swap(q[0], q[furthest]);
  const double needed = limit + 0x1p-40 * scale;
  auto length_up = [](const Vec3d& a, const Vec3d& b) {
    const Vec3d d = sub(b, a);
    return std::sqrt(dot(d, d)) * (1 + 0x1p-40);
  };
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b)
      for (std::size_t c = b + 1; c < k; ++c) {
        // v's side of a, b, c: the filter below where it decides (as exact as orient3d), else orient3d.
        const detail::DoubleCross abc = detail::double_cross(q[a], q[b], q[c]);
        int side;
        {
          const Vec3d w = sub(v, q[a]);
          const double det = w.x * abc.n[0] + w.y * abc.n[1] + w.z * abc.n[2];
          const double error =
              detail::kO3dErrBoundA * (1 + 0x1p-40) *
              (std::fabs(w.x) * abc.p[0] + std::fabs(w.y) * abc.p[1] + std::fabs(w.z) * abc.p[2]);
          side = det > error ? 1 : det < -error ? -1 : orient3d(q[a], q[b], q[c], v);
        }
        if (side == 0) continue;
        const Vec3d &pa = q[a], &pb = side > 0 ? q[b] : q[c], &pc = side > 0 ? q[c] : q[b];
        const detail::DoubleCross cross = side > 0 ? abc : detail::double_cross(pa, pb, pc);
        // A link point certainly below by the same filter as v's test below needs no orient3d.
        auto certainly_below = [&](const Vec3d& p) {
          const Vec3d w = sub(p, pa);
          const double det = w.x * cross.n[0] + w.y * cross.n[1] + w.z * cross.n[2];
          const double permanent =
              std::fabs(w.x) * cross.p[0] + std::fabs(w.y) * cross.p[1] + std::fabs(w.z) * cross.p[2];
          return det + detail::kO3dErrBoundA * permanent * (1 + 0x1p-40) < 0;
        };
        bool supports = true;
        for (std::size_t j = 0; j < k && supports; ++j)
          supports = j == a || j == b || j == c || certainly_below(q[j]) || orient3d(pa, pb, pc, q[j]) <= 0;
        if (!supports) continue;
        const Vec3d w = sub(v, pa);
        const double det = w.x * cross.n[0] + w.y * cross.n[1] + w.z * cross.n[2];
        const double permanent =
            std::fabs(w.x) * cross.p[0] + std::fabs(w.y) * cross.p[1] + std::fabs(w.z) * cross.p[2];
        const double low = det - detail::kO3dErrBoundA * permanent * (1 + 0x1p-40);
        if (low > 0 && low / (length_up(pa, pb) * length_up(pa, pc)) * (1 - 0x1p-40) > needed) return true;
      }
  return false;
}

// Steps 1-2: drops the vertices of `current` (its vertex_ids index `points`) whose height is within
// `limit`, in rounds of independent sets, until a round drops nothing or only the flat remains.  Returns
// the final mesh's edges, its visit order and relabelled mesh into `visit` and `graph`.
// With an angle (`angle_sine` > 0, Qhull's An), a vertex's limit grows by angle_sine times half its
// distance r to its farthest neighbour in the exact hull (taken once, so that the drops do not compound: a
// later, wider link would let the angle grow): a vertex h above its link makes facets that meet at about
// 2h / r, so the dropped ones are those whose facets' normals differ by less than about the angle, Qhull's
// test for a pair of facets.
template <class Point>
EdgeIndex drop_low_vertices(const std::vector<Point>& points, BasicHullMesh<Point>& current, double limit,
                            double angle_sine, VisitOrder& visit, Relabelled& graph) {
  // Per vertex of `points`: its link (ascending) when its height was computed, and that height; a vertex
  // whose link did not change keeps its height (it depends on nothing else).  The links lie in one pool,
  // each vertex's latest at link_at[id] (link_size[id] of them; a vertex a round did not touch keeps its
  // place): no allocation a vertex.
  std::vector<PointIndex> link_pool;
  std::vector<std::size_t> link_at(points.size(), 0);
  std::vector<std::uint32_t> link_size(points.size(), kNone);  // kNone: no height yet
  std::vector<double> cached_height(points.size(), kInfinity), first_reach(points.size(), -1);
  PhaseLaps laps("drop_low_vertices");  // CUDAHULL_PHASE_TIMES=1
  for (;;) {
    const std::size_t n = current.vertices.size();
    EdgeIndex edges(current);
    laps.lap("edges");
    visit = visit_order(current);
    laps.lap("visit order");
    graph = relabelled(current, edges, visit);
    laps.lap("relabelled");
    const Relabelled& g = graph;
    std::vector<PointIndex> ids(n);  // by position
    for (std::uint32_t j = 0; j < n; ++j)
      ids[j] = current.vertex_ids[visit.vertices[j]];
    // By position, turned back into vertex order below.
    std::vector<double> heights_at(n, kInfinity), reach_at(n, 0);
    std::vector<std::uint8_t> relinked_at(n, 0);
    parallel_blocks(
        n, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          std::vector<PointIndex> link;
          std::vector<Vec3d> link_at_points;
          for (std::size_t j = begin; j < end; ++j) {
            const PointIndex id = ids[j];
            const Vec3d v = g.at[j];
            link.clear();
            link_at_points.clear();
            for (std::uint32_t k = g.start[j]; k < g.start[j + 1]; ++k) {
              link.push_back(ids[g.to[k]]);
              link_at_points.push_back(g.at[g.to[k]]);
            }
            if (angle_sine > 0 && first_reach[id] < 0) {
              first_reach[id] = 0;
              for (const Vec3d& w : link_at_points) {
                const Vec3d d = sub(w, v);
                first_reach[id] = std::max(first_reach[id], std::sqrt(dot(d, d)));
              }
            }
            if (angle_sine > 0) reach_at[j] = first_reach[id];
            if (link_size[id] != link.size() ||
                !std::equal(link.begin(), link.end(), link_pool.begin() + link_at[id])) {
              // Above its limit: never dropped, whatever its exact height (infinity stands for it).
              cached_height[id] = clearly_above(v, link_at_points.data(), link_at_points.size(),
                                                limit + angle_sine * reach_at[j] / 2)
                                      ? kInfinity
                                      : vertex_height(points, v, link);
              relinked_at[j] = 1;  // each entry is only this chunk's
            }
            heights_at[j] = cached_height[id];
          }
        },
        256);  // blocks of some hundreds of microseconds: a worker woken for less costs more
    laps.lap("heights");
    // Nothing low enough (most hulls' first round): done, with no bookkeeping for a next round.
    bool any_low = false;
    for (std::uint32_t j = 0; j < n && !any_low; ++j)
      any_low = heights_at[j] <= limit + angle_sine * reach_at[j] / 2;
    if (!any_low) {
      laps.lap("round");
      return edges;
    }
    std::vector<double> heights(n), reach(n);
    std::vector<std::uint8_t> relinked(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t j = g.rank[i];
      heights[i] = heights_at[j], reach[i] = reach_at[j], relinked[i] = relinked_at[j];
    }
    for (std::uint32_t i = 0; i < n; ++i) {
      if (!relinked[i]) continue;
      const PointIndex id = current.vertex_ids[i];
      link_at[id] = link_pool.size();
      link_size[id] = edges.degree(i);
      for (std::uint32_t k = 0; k < edges.degree(i); ++k)
        link_pool.push_back(current.vertex_ids[edges.neighbour(i, k)]);
    }
    // Lowest first, no two adjacent: their stars are disjoint, so each one's height stays what it was.
    std::vector<std::uint32_t> order;
    for (std::uint32_t i = 0; i < n; ++i)
      if (heights[i] <= limit + angle_sine * reach[i] / 2) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return heights[a] < heights[b] || (heights[a] == heights[b] && a < b);
    });
    std::vector<std::uint8_t> blocked(n, 0), drop(n, 0);
    std::vector<std::uint32_t> dropped;
    for (std::uint32_t i : order) {
      if (blocked[i]) continue;
      dropped.push_back(i);
      blocked[i] = 1;
      for (std::uint32_t k = 0; k < edges.degree(i); ++k)
        blocked[edges.neighbour(i, k)] = 1;
    }
    // Never flat: halve the round's drops (the highest go first) until the rest stays three-dimensional.
    while (!dropped.empty()) {
      std::fill(drop.begin(), drop.end(), 0);
      for (std::uint32_t i : dropped)
        drop[i] = 1;
      std::vector<PointIndex> keep;
      for (std::uint32_t i = 0; i < n; ++i)
        if (!drop[i]) keep.push_back(current.vertex_ids[i]);
      BasicHullMesh<Point> next = exact_hull(points, keep);
      if (next.dimension == 3) {
        current = std::move(next);
        break;
      }
      dropped.resize(dropped.size() / 2);
    }
    laps.lap("round");
    if (dropped.empty()) return edges;  // the mesh's, unchanged by this round
  }
}

struct Facets {
  std::vector<std::uint32_t> facet_of;  // per triangle of the mesh
  std::vector<Plane> planes;            // per facet
  std::vector<std::uint32_t> seeds;     // per facet: its largest triangle
  std::vector<std::uint32_t> across;    // per triangle t and edge k: the triangle holding its reverse
};

// Step 3: groups the triangles of `mesh` into merged facets.
// With an angle (`angle_sine` > 0), a corner also fits where it lies within angle_sine times its distance
// from the seed's nearest corner of the seed's plane (a tilt of at most about that angle).
//
// Each triangle's plane, its neighbours across its edges, which of them would join it as a seed and, for a
// group of it alone, the plane's offset are found first, on all cores: the seeds come largest first,
// scattered over the mesh, and most of them stay alone (every one on a ball), so that the sequential
// grouping then reads four words for such a seed, where it read both triangles' corners and planes for each
// of its edges (a cache miss each, most of the grouping's time on a large hull).  All of it works on the
// triangles renumbered by their visit order (position j for visit.triangles[j]) and the relabelled mesh
// `g`, so that neighbours' data lies together; the seeds' order (largest first, ties by the mesh's index)
// and every test are the mesh's, so the facets are too.
template <class Point>
Facets group_facets(const BasicHullMesh<Point>& mesh, const Relabelled& g, const VisitOrder& visit,
                    double tolerance, double angle_sine) {
  PhaseLaps laps("group_facets");  // CUDAHULL_PHASE_TIMES=1
  const std::size_t nt = mesh.triangles.size();
  const std::vector<std::uint32_t>& jrank = visit.triangle_rank;  // per mesh triangle: its position
  std::vector<std::array<std::uint32_t, 3>> tri(nt);              // per position: its corners' positions
  auto corner = [&](std::uint32_t j, int k) { return g.at[tri[j][k]]; };
  // The triangle holding the directed edge a -> b (positions), kNone if none.
  auto holder = [&](std::uint32_t a, std::uint32_t b) {
    for (std::uint32_t e = g.start[a]; e < g.start[a + 1]; ++e)
      if (g.to[e] == b) return g.face[e];
    return kNone;
  };
  std::vector<Plane> plane(nt);
  std::vector<double> twice_area(nt);
  // Largest first, ties by the mesh's index: (the area's bits inverted, index) keys, which order as the
  // areas do (no area is negative or NaN), listed by index and sorted stably on the bits alone (a radix
  // sort, beside the joining pass below).
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(nt);
  std::vector<std::uint32_t> across(3 * nt);  // the triangle across edge k of j: the one holding its reverse
  parallel_blocks(
      nt, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t j = begin; j < end; ++j) {
          const Triangle& corners = mesh.triangles[visit.triangles[j]];
          tri[j] = {g.rank[corners[0]], g.rank[corners[1]], g.rank[corners[2]]};
          const Vec3d a = corner(j, 0), b = corner(j, 1), c = corner(j, 2);
          plane[j] = plane_through(a, b, c);
          const Vec3d n = cross(sub(b, a), sub(c, a));
          twice_area[j] = std::sqrt(dot(n, n));
          std::uint64_t area_bits;
          std::memcpy(&area_bits, &twice_area[j], sizeof area_bits);
          keyed[visit.triangles[j]] = {~area_bits, visit.triangles[j]};
          for (int k = 0; k < 3; ++k)
            across[3 * j + k] = holder(tri[j][(k + 1) % 3], tri[j][k]);
        }
      },
      1024);
  laps.lap("planes");
  // Whether `vertex` (a position) fits the group of `seed`: within the tolerance of the seed's plane, or
  // exactly on it (a point exactly on it evaluates to within a few ulps of the coordinates' scale, under 28u
  // by plane.cpp's analysis; the exact orient3d decides).
  auto fits = [&](std::uint32_t seed, std::uint32_t vertex) {
    const Vec3d sa = corner(seed, 0), sb = corner(seed, 1), sc = corner(seed, 2);
    const Vec3d p = g.at[vertex];
    const double value = std::fabs(plane_value(plane[seed], p));
    if (value <= tolerance) return true;
    if (angle_sine > 0) {
      double nearest = kInfinity;
      for (const Vec3d& s : {sa, sb, sc}) {
        const Vec3d d = sub(p, s);
        nearest = std::min(nearest, std::sqrt(dot(d, d)));
      }
      if (value <= tolerance + angle_sine * nearest) return true;
    }
    const double scale = std::max({std::fabs(sa.x), std::fabs(sa.y), std::fabs(sa.z), std::fabs(sb.x),
                                   std::fabs(sb.y), std::fabs(sb.z), std::fabs(sc.x), std::fabs(sc.y),
                                   std::fabs(sc.z), std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    return value <= 64 * kUnitRoundoff * scale && orient3d(sa, sb, sc, p) == 0;
  };
  // Whether triangle u joins the group of `seed` across an edge: facing the group's way too (across a body
  // thinner than the tolerance, the far side's triangles fit the plane but face away from it), every corner
  // fitting.
  auto joins = [&](std::uint32_t seed, std::uint32_t u) {
    if (dot3(plane[seed], {plane[u][0], plane[u][1], plane[u][2]}) <= 0) return false;
    return fits(seed, tri[u][0]) && fits(seed, tri[u][1]) && fits(seed, tri[u][2]);
  };
  // Per triangle as a seed: which neighbours would join (bit k: across edge k), and the offset of its plane
  // were it alone (the top of its corners).
  std::vector<std::uint8_t> joining(nt);
  std::vector<double> alone_top(nt);
  parallel_blocks_beside(
      nt, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t j = begin; j < end; ++j) {
          std::uint8_t bits = 0;
          for (int k = 0; k < 3; ++k)
            if (const std::uint32_t u = across[3 * j + k]; u != kNone && joins(j, u)) bits |= 1u << k;
          joining[j] = bits;
          alone_top[j] = std::max(
              {dot3(plane[j], corner(j, 0)), dot3(plane[j], corner(j, 1)), dot3(plane[j], corner(j, 2))});
        }
      },
      [&] { radix_sort_by_key(keyed); }, 1024);
  laps.lap("joining and sort");
  Facets facets;
  if (std::none_of(joining.begin(), joining.end(), [](std::uint8_t bits) { return bits != 0; })) {
    // No triangle joins another (a ball's hull): every seed is a facet alone, numbered in the seeds' order,
    // placed on all cores, where the grouping below would take them one by one.
    facets.facet_of.resize(nt);
    facets.seeds.resize(nt);
    facets.planes.resize(nt);
    facets.across.resize(3 * nt);
    parallel_blocks(nt, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
      for (std::size_t id = begin; id < end; ++id) {
        const std::uint32_t t = keyed[id].second, j = jrank[t];
        facets.facet_of[t] = static_cast<std::uint32_t>(id);
        facets.seeds[id] = t;
        facets.planes[id] = {plane[j][0], plane[j][1], plane[j][2], -alone_top[j]};
        for (int k = 0; k < 3; ++k)
          facets.across[3 * t + k] = across[3 * j + k] == kNone ? kNone : visit.triangles[across[3 * j + k]];
      }
    });
    laps.lap("alone");
    return facets;
  }
  std::vector<std::uint32_t> facet_of(nt, kNone), seeds;  // by position
  seeds.reserve(nt);
  facets.planes.reserve(nt);
  std::vector<std::uint32_t> queue, vertices;
  std::vector<std::uint8_t> in_group(g.at.size(), 0);
  for (const auto& key : keyed) {
    const std::uint32_t seed = jrank[key.second];
    if (facet_of[seed] != kNone) continue;
    const std::uint32_t id = static_cast<std::uint32_t>(facets.planes.size());
    const Plane& seed_plane = plane[seed];
    facet_of[seed] = id;
    seeds.push_back(seed);
    if (joining[seed] == 0) {  // alone: no neighbour fits, whichever are free
      facets.planes.push_back({seed_plane[0], seed_plane[1], seed_plane[2], -alone_top[seed]});
      continue;
    }
    queue.assign(1, seed);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = across[3 * queue[q] + k];
        if (u == kNone || facet_of[u] != kNone) continue;
        if (queue[q] == seed ? !(joining[seed] >> k & 1u) : !joins(seed, u)) continue;
        facet_of[u] = id;
        queue.push_back(u);
      }
    }
    // The offset: every group vertex on or below the plane, as evaluated (fl(x - max) <= 0 for x <= max).
    vertices.clear();
    for (std::uint32_t t : queue)
      for (std::uint32_t v : tri[t])
        if (!in_group[v]) {
          in_group[v] = 1;
          vertices.push_back(v);
        }
    double top = -kInfinity;
    for (std::uint32_t v : vertices) {
      top = std::max(top, dot3(seed_plane, g.at[v]));
      in_group[v] = 0;
    }
    facets.planes.push_back({seed_plane[0], seed_plane[1], seed_plane[2], -top});
  }
  laps.lap("grouping");
  // Back to the mesh's triangles.
  facets.facet_of.resize(nt);
  facets.across.resize(3 * nt);
  parallel_blocks(nt, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t t = begin; t < end; ++t) {
      const std::uint32_t j = jrank[t];
      facets.facet_of[t] = facet_of[j];
      for (int k = 0; k < 3; ++k)
        facets.across[3 * t + k] = across[3 * j + k] == kNone ? kNone : visit.triangles[across[3 * j + k]];
    }
  });
  facets.seeds.reserve(seeds.size());
  for (std::uint32_t j : seeds)
    facets.seeds.push_back(visit.triangles[j]);
  return facets;
}

// Step 4, the certificate: a proven upper bound on n . p + d over the exact hull's vertices and every
// merged facet's plane, in two parts.
//
// Rounding of one evaluation.  plane_value() is a dot product of length 4 (d times an exact 1) evaluated
// left to right, so its error is at most gamma_4 x S (Higham, Accuracy and Stability, 3.1), gamma_4 =
// 4u / (1 - 4u), S = sum |n_i p_i| + |d|.  S as computed is within gamma_3 of the exact sum, and the last
// addition below rounds once more (by at most u (|fl(value)| + e) <= u (1 + 13u) S).  So value + 8u x fl(S)
// exceeds the exact n . p + d: 8u fl(S) (1 - u) - u (1 + 13u) S > gamma_4 (1 + 4u) S.  The final maximum is
// stepped up one double, for underflow.
double bound_at(const Plane& plane, const Vec3d& p) {
  const double value = plane_value(plane, p);
  const double sum =
      std::fabs(plane[0] * p.x) + std::fabs(plane[1] * p.y) + std::fabs(plane[2] * p.z) + std::fabs(plane[3]);
  const double bound = value + 8 * kUnitRoundoff * sum;
  return std::isnan(bound) ? kInfinity : bound;  // overflow: no bound, not a silently lost one
}

// Sign of n . (q - p), exactly.  A filter first (each of the three terms is within gamma_4 of its value: the
// difference, the product and two sums; 6u of the computed magnitudes covers that), then expansion
// arithmetic: the differences are exact pairs, their products with n exact expansions, whose sum's sign is
// exact (where plane_safe() and in_fast_exact_range() hold: no underflow).
[[gnu::noinline]] int compare_along_closely(const Plane& n, const Vec3d& q, const Vec3d& p);

inline int compare_along(const Plane& n, const Vec3d& q, const Vec3d& p) {
  const double d0 = q.x - p.x, d1 = q.y - p.y, d2 = q.z - p.z;
  const double value = n[0] * d0 + n[1] * d1 + n[2] * d2;
  const double magnitude = std::fabs(n[0] * d0) + std::fabs(n[1] * d1) + std::fabs(n[2] * d2);
  const double bound = 6 * kUnitRoundoff * magnitude;
  if (magnitude > 0x1p-900) {
    if (value > bound) return 1;
    if (value < -bound) return -1;
  }
  return compare_along_closely(n, q, p);
}

// compare_along() where its filter cannot tell: the points about level along n.
int compare_along_closely(const Plane& n, const Vec3d& q, const Vec3d& p) {
  // A second filter, in about double-double (a facet's own corners always reach it: their n . (q - p) is
  // of the order of the normal's rounding): the differences as exact pairs h + l, n h exact as P + e, so
  // that the value is P0 + P1 + P2 (summed into s with its errors exactly) plus a tail of terms each within
  // a few u of the value's scale, whose computed sum T is within E = 16u of their magnitudes (recursive
  // summation of 8 terms, and the products n l rounded once).  s decides where it outweighs |T| + E, T where
  // s is zero; else the exact sign.
  {
    const double qs[3] = {q.x, q.y, q.z}, ps[3] = {p.x, p.y, p.z};
    double big[3], tail[8];
    for (int k = 0; k < 3; ++k) {
      double h, l;
      detail::two_diff(qs[k], ps[k], h, l);
      detail::two_product(n[k], h, big[k], tail[k]);
      tail[3 + k] = n[k] * l;
    }
    double s1, s2;
    detail::two_sum(big[0], big[1], s1, tail[6]);
    detail::two_sum(s1, big[2], s2, tail[7]);
    double sum = 0, spread = 0;
    for (const double t : tail)
      sum += t, spread += std::fabs(t);
    const double error = 16 * kUnitRoundoff * spread * (1 + 0x1p-40);
    if (s2 != 0 && std::fabs(s2) > (std::fabs(sum) + error) * (1 + 0x1p-40)) return s2 > 0 ? 1 : -1;
    if (s2 == 0 && std::fabs(sum) > error * (1 + 0x1p-40)) return sum > 0 ? 1 : -1;
  }
  double terms[3][4];
  int lengths[3];
  const double qs[3] = {q.x, q.y, q.z}, ps[3] = {p.x, p.y, p.z};
  for (int k = 0; k < 3; ++k) {
    const detail::Pair difference = detail::exact_diff(qs[k], ps[k]);
    lengths[k] = detail::scale_expansion(difference.len, difference.v, n[k], terms[k]);
  }
  double first_two[8];
  const int length = detail::expansion_sum(lengths[0], terms[0], lengths[1], terms[1], first_two);
  return detail::expansion_sum_sign(length, first_two, lengths[2], terms[2]);
}

// Whether compare_along() is exact for these points and this plane.  With coordinates in the predicates'
// fast range (0 or 2^-250..2^250) every component of a difference's exact pair is a multiple of 2^-302
// (each coordinate is a multiple of its ulp, at least 2^-302), and with every nonzero normal component at
// least 2^-600 (so a multiple of 2^-652) every exact product is a multiple of 2^-954, far above the
// subnormal resolution 2^-1074: products, their errors and all the sums are exact, none underflows.
bool plane_safe(const Plane& plane) {
  for (int k = 0; k < 3; ++k)
    if (plane[k] != 0 && std::fabs(plane[k]) < 0x1p-600) return false;
  return true;
}

// The kept vertices: the maximum of the exact linear function n . p + d over the vertices of hull(S) is at
// a vertex that no neighbour exceeds (every vertex of a convex polytope lies in the cone from any vertex
// along its edges, which the triangulation's edges include), so an ascent from the facet's own corner along
// hull(S)'s edges with exact comparisons finds it in a few steps; its evaluation is then bounded.  A plane or
// coordinates outside the exact range take all vertices instead.  Per plane: the bound over S.
//
// MergedHull::thinnest, in the same pass (it reads the same planes and mesh): per facet, the depth of the
// vertices' centroid below its plane, which no vertex falls short of; within `near` of the plane (a thin
// hull), the deepest vertex itself, by a descent from the facet's start (its seed's corner 0) along the
// edges against the plane's normal, with exact comparisons, to the first neighbour found deeper.
//
// The planes are taken in `order` (their starts' visit order, VisitOrder), not in the facets' (largest
// first, scattered): the same results, from the cache.  `side()` runs beside them on one core.
struct KeptBounds {
  std::vector<double> bounds;  // per plane
  double thinnest = kInfinity;
};

template <class Side>
KeptBounds kept_bounds(const Relabelled& g, const std::vector<Plane>& planes,
                       const std::vector<Triangle>& seed_corners, const std::vector<std::uint32_t>& order,
                       const Vec3d& centroid, double near, Side&& side) {
  // The planes and starts gathered in `order` and the ascents on the relabelled mesh (each vertex's
  // neighbours in EdgeIndex's order, so that every ascent takes the same steps): the ascents read what
  // their neighbours read, not scattered lines.
  const std::vector<Vec3d>& at = g.at;
  const std::size_t count = order.size();
  std::vector<Plane> ordered(count);
  std::vector<Triangle> corners(count);
  for (std::size_t i = 0; i < count; ++i) {
    ordered[i] = planes[order[i]];
    for (int k = 0; k < 3; ++k)
      corners[i][k] = g.rank[seed_corners[order[i]][k]];
  }
  std::vector<double> found(count, -kInfinity);
  const unsigned workers = hardware_workers();
  std::vector<double> least(workers, kInfinity);
  parallel_blocks_beside(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        // The ascent from v: to the neighbour of the largest value among those exactly above, until none
        // is; `tie` tells whether a neighbour of the end is exactly level with it.  The vertex it came from
        // is exactly below, so it is not compared again.
        auto ascend = [&](const Plane& plane, std::uint32_t v, bool& tie) {
          std::uint32_t from = kNone;
          for (;;) {
            std::uint32_t next = kNone;
            double next_value = -kInfinity;
            tie = false;
            for (std::uint32_t k = g.start[v]; k < g.start[v + 1]; ++k) {
              const std::uint32_t q = g.to[k];
              if (q == from) continue;
              const int side = compare_along(plane, at[q], at[v]);
              tie = tie || side == 0;
              if (side > 0) {
                const double value = plane_value(plane, at[q]);
                if (next == kNone || value > next_value) next = q, next_value = value;
              }
            }
            if (next == kNone) return v;
            from = v;
            v = next;  // n . p + d grows strictly, exactly: the ascent ends
          }
        };
        for (std::size_t i = begin; i < end; ++i) {
          const Plane& plane = ordered[i];
          const bool exact = g.coordinates_safe && plane_safe(plane);
          double depth = -plane_value(plane, centroid);
          if (!exact) {
            const bool thin = depth <= near;
            for (const Vec3d& p : at) {
              found[i] = std::max(found[i], bound_at(plane, p));
              if (thin) depth = std::max(depth, -plane_value(plane, p));
            }
            least[worker] = std::min(least[worker], depth);
            continue;
          }
          // First from the seed's corner of the largest value, where the maximum usually is: an end with
          // every neighbour exactly below is the unique maximum, which the ascent from corner 0 (the
          // bound's definition) also ends at.  Otherwise (a tie) that ascent itself.
          const Triangle& c = corners[i];
          std::uint32_t best = c[0];
          for (int k = 1; k < 3; ++k)
            if (plane_value(plane, at[c[k]]) > plane_value(plane, at[best])) best = c[k];
          bool tie = false;
          std::uint32_t v = ascend(plane, best, tie);
          if (tie && best != c[0]) v = ascend(plane, c[0], tie);
          found[i] = bound_at(plane, at[v]);
          if (depth <= near) {
            const Plane against{-plane[0], -plane[1], -plane[2], plane[3]};
            std::uint32_t u = c[0];
            for (bool moved = true; moved;) {
              moved = false;
              for (std::uint32_t k = g.start[u]; k < g.start[u + 1] && !moved; ++k)
                if (const std::uint32_t q = g.to[k]; compare_along(against, at[q], at[u]) > 0)
                  u = q, moved = true;  // deeper, exactly: the descent ends
            }
            depth = -plane_value(plane, at[u]);
          }
          least[worker] = std::min(least[worker], depth);
        }
      },
      side, 256);
  KeptBounds kept;
  kept.bounds.assign(planes.size(), -kInfinity);
  for (std::size_t i = 0; i < count; ++i)
    kept.bounds[order[i]] = found[i];
  kept.thinnest = *std::min_element(least.begin(), least.end());
  return kept;
}

// The dropped points: a bounding-box tree over them, searched per plane from the kept vertices' bound.  A
// box is skipped when no point in it can exceed the best bound so far: every p in it is within R of the
// box's computed centre c (R: half the computed diagonal plus the centre's rounding, inflated), so
// n . p + d <= [n . c + d] + |n| R, the bracket bounded as for a point, |n| by its computed value inflated,
// and the sum's own rounding covered by a further 4u of its terms.  Returns the largest bound.
double dropped_bound(const std::vector<Vec3d>& points, const std::vector<Plane>& planes,
                     const std::vector<double>& kept) {
  double result = *std::max_element(kept.begin(), kept.end());
  std::vector<Box> boxes(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    boxes[i] = {{points[i].x, points[i].y, points[i].z}, {points[i].x, points[i].y, points[i].z}};
  const BoxTree tree(std::move(boxes));
  if (tree.empty()) return result;
  const auto& nodes = tree.nodes();
  std::vector<Vec3d> centre(nodes.size());
  std::vector<double> radius(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Box& b = nodes[k].box;
    const Vec3d c{(b.lo[0] + b.hi[0]) / 2, (b.lo[1] + b.hi[1]) / 2, (b.lo[2] + b.hi[2]) / 2};
    const double dx = b.hi[0] - b.lo[0], dy = b.hi[1] - b.lo[1], dz = b.hi[2] - b.lo[2];
    const double off_centre = 2 * kUnitRoundoff * (std::fabs(c.x) + std::fabs(c.y) + std::fabs(c.z));
    centre[k] = c;
    radius[k] = (std::sqrt(dx * dx + dy * dy + dz * dz) / 2 + off_centre) * (1 + 0x1p-40);
  }
  const unsigned workers = hardware_workers();
  std::vector<double> worst(workers, -kInfinity);
  parallel_chunks(
      planes.size(), workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        double best = worst[worker];
        std::vector<std::uint32_t> stack;
        for (std::size_t f = begin; f < end; ++f) {
          const Plane& plane = planes[f];
          const double norm =
              std::sqrt(plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2]) * (1 + 0x1p-40);
          auto box_bound = [&](std::uint32_t k) {
            const double at_centre = bound_at(plane, centre[k]);
            const double r = radius[k] * norm * (1 + 0x1p-40);
            return at_centre + r + 4 * kUnitRoundoff * (std::fabs(at_centre) + r);
          };
          best = std::max(best, kept[f]);
          stack.assign(1, 0);
          while (!stack.empty()) {
            const std::uint32_t k = stack.back();
            stack.pop_back();
            const auto& node = nodes[k];
            if (box_bound(k) <= best) continue;
            if (node.left == kNone) {
              for (std::uint32_t i = node.begin; i < node.end; ++i)
                best = std::max(best, bound_at(plane, points[tree.item(i)]));
              continue;
            }
            // The more promising child last, so that it is searched first.
            const bool left_first = box_bound(node.left) > box_bound(node.right);
            stack.push_back(left_first ? node.right : node.left);
            stack.push_back(left_first ? node.left : node.right);
          }
        }
        worst[worker] = std::max(worst[worker], best);
      },
      64);
  return std::max(result, *std::max_element(worst.begin(), worst.end()));
}

}  // namespace

template <class Point>
MergedHull merge_facets(const std::vector<Point>& points, const BasicHullMesh<Point>& exact, double tolerance,
                        double angle_sine) {
  if (!(tolerance >= 0) || !std::isfinite(tolerance))
    throw std::invalid_argument("merge_facets: the tolerance must be finite and >= 0, not " +
                                std::to_string(tolerance));
  if (!(angle_sine >= 0 && angle_sine <= 1))
    throw std::invalid_argument("merge_facets: the angle's sine must be in [0, 1], not " +
                                std::to_string(angle_sine));
  (void)points;  // every input point is a convex combination of exact.vertices, which hold their coordinates
  MergedHull merged;
  merged.tolerance = tolerance;
  if (exact.dimension != 3) {
    merged.vertices = exact.vertex_ids;
    std::sort(merged.vertices.begin(), merged.vertices.end());
    return merged;
  }
  // Work on the exact hull's vertices, by their position in exact.vertices.
  const std::vector<Point>& vertices = exact.vertices;
  const std::size_t m = vertices.size();
  PhaseLaps laps("merge_facets");  // CUDAHULL_PHASE_TIMES=1
  BasicHullMesh<Point> current = exact;
  std::iota(current.vertex_ids.begin(), current.vertex_ids.end(), PointIndex{0});

  VisitOrder visit;
  Relabelled graph;
  const EdgeIndex edges = tolerance > 0 || angle_sine > 0
                              ? drop_low_vertices(vertices, current, tolerance, angle_sine, visit, graph)
                              : EdgeIndex(current);
  if (visit.vertices.size() != current.vertices.size()) {
    visit = visit_order(current);
    graph = relabelled(current, edges, visit);
  }
  laps.lap("drop");
  const Facets facets = group_facets(current, graph, visit, tolerance, angle_sine);
  laps.lap("group");

  // Output: triangles grouped by facet, in input indices, on one core beside the kept vertices' bounds
  // (below), which do not depend on it.
  // By facet, each facet's triangles ascending (a counting sort: the stable sort's order).
  const std::size_t nt = current.triangles.size();
  std::vector<std::uint32_t> by_facet(nt), position(nt);
  std::vector<std::uint32_t> dropped;
  auto output = [&] {
    std::vector<std::uint32_t> facet_start(facets.planes.size() + 1, 0);
    for (std::uint32_t f : facets.facet_of)
      ++facet_start[f + 1];
    for (std::size_t f = 0; f + 1 < facet_start.size(); ++f)
      facet_start[f + 1] += facet_start[f];
    for (std::uint32_t t = 0; t < nt; ++t) {
      position[t] = facet_start[facets.facet_of[t]]++;
      by_facet[position[t]] = t;
    }
    merged.vertices.reserve(current.vertex_ids.size());
    for (PointIndex id : current.vertex_ids)
      merged.vertices.push_back(exact.vertex_ids[id]);
    if (!std::is_sorted(merged.vertices.begin(), merged.vertices.end()))
      std::sort(merged.vertices.begin(), merged.vertices.end());
    merged.faces.resize(nt);
    merged.planes.resize(nt);
    merged.facet_of_face.resize(nt);
    merged.neighbors.resize(nt);
    for (std::size_t p = 0; p < nt; ++p) {
      const std::uint32_t t = by_facet[p];
      const Triangle& tri = current.triangles[t];
      merged.faces[p] = {exact.vertex_ids[current.vertex_ids[tri[0]]],
                         exact.vertex_ids[current.vertex_ids[tri[1]]],
                         exact.vertex_ids[current.vertex_ids[tri[2]]]};
      merged.planes[p] = facets.planes[facets.facet_of[t]];
      merged.facet_of_face[p] = facets.facet_of[t];
      for (int k = 0; k < 3; ++k) {
        // The edge opposite corner k runs from corner k + 1 to corner k + 2: across[3t + k + 1] holds it.
        const std::uint32_t u = facets.across[3 * t + (k + 1) % 3];
        if (u == kNone) throw std::logic_error("merge_facets: the mesh is not closed");
        merged.neighbors[p][k] = static_cast<std::int32_t>(position[u]);
      }
    }

    // Coplanar: every exact-hull vertex that was dropped, with its nearest triangle and that one's nearest
    // corner.
    std::vector<std::uint8_t> kept(m, 0);
    for (PointIndex id : current.vertex_ids)
      kept[id] = 1;
    for (std::uint32_t i = 0; i < m; ++i)
      if (!kept[i]) dropped.push_back(i);
    std::sort(dropped.begin(), dropped.end(),
              [&](std::uint32_t a, std::uint32_t b) { return exact.vertex_ids[a] < exact.vertex_ids[b]; });
  };
  std::vector<Triangle> seed_corners;  // per facet: its largest triangle's corners
  seed_corners.reserve(facets.seeds.size());
  for (std::uint32_t seed : facets.seeds) {
    seed_corners.push_back(current.triangles[seed]);
  }
  std::vector<std::uint32_t> in_visit_order;  // the facets by their seeds' places in the visit order
  in_visit_order.reserve(facets.seeds.size());
  for (std::uint32_t t : visit.triangles)
    if (facets.seeds[facets.facet_of[t]] == t) in_visit_order.push_back(facets.facet_of[t]);
  // The vertices' centroid for the thinnest depth, summed in the mesh's order.
  Vec3d centroid{0, 0, 0};
  for (const Point& p : current.vertices) {
    const Vec3d q = to_vec3d(p);
    centroid = {centroid.x + q.x, centroid.y + q.y, centroid.z + q.z};
  }
  const double vertex_count = static_cast<double>(current.vertices.size());
  centroid = {centroid.x / vertex_count, centroid.y / vertex_count, centroid.z / vertex_count};
  const KeptBounds kept =
      kept_bounds(graph, facets.planes, seed_corners, in_visit_order, centroid, 4 * tolerance, output);
  const std::vector<double>& kept_bound = kept.bounds;
  laps.lap("kept bound and output");
  merged.coplanar.resize(dropped.size());
  auto face_corner = [&](std::uint32_t f, int k) {
    return to_vec3d(current.vertices[current.triangles[by_facet[f]][k]]);
  };
  std::vector<Box> face_boxes(dropped.empty() ? 0 : by_facet.size());
  for (std::uint32_t f = 0; f < face_boxes.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3d c = face_corner(f, k);
      face_boxes[f].add({{c.x, c.y, c.z}, {c.x, c.y, c.z}});
    }
  const BoxTree face_tree(std::move(face_boxes));
  parallel_chunks(
      dropped.size(), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        std::vector<std::uint32_t> stack;
        const auto& nodes = face_tree.nodes();
        auto box_distance2 = [&](const Vec3d& p, const Box& b) {
          const double q[3] = {p.x, p.y, p.z};
          double d2 = 0;
          for (int k = 0; k < 3; ++k) {
            const double d = std::max({b.lo[k] - q[k], 0.0, q[k] - b.hi[k]});
            d2 += d * d;
          }
          return d2;
        };
        for (std::size_t k = begin; k < end; ++k) {
          const Vec3d p = to_vec3d(vertices[dropped[k]]);
          // The nearest triangle, the lowest index among equals (the search order does not matter).
          double best = kInfinity;
          std::uint32_t best_face = 0;
          stack.assign(1, 0);
          while (!stack.empty()) {
            const auto& node = nodes[stack.back()];
            stack.pop_back();
            if (box_distance2(p, node.box) > best) continue;
            if (node.left == kNone) {
              for (std::uint32_t i = node.begin; i < node.end; ++i) {
                const std::uint32_t f = face_tree.item(i);
                const double d2 =
                    triangle_distance2(p, face_corner(f, 0), face_corner(f, 1), face_corner(f, 2));
                if (d2 < best || (d2 == best && f < best_face)) best = d2, best_face = f;
              }
              continue;
            }
            stack.push_back(node.left);
            stack.push_back(node.right);
          }
          const Triangle& t = current.triangles[by_facet[best_face]];
          double nearest = kInfinity;
          PointIndex corner = 0;
          for (std::uint32_t v : t) {
            const Vec3d q = sub(p, to_vec3d(current.vertices[v]));
            if (dot(q, q) < nearest) nearest = dot(q, q), corner = exact.vertex_ids[current.vertex_ids[v]];
          }
          merged.coplanar[k] = {exact.vertex_ids[dropped[k]], best_face, corner};
        }
      },
      32);

  laps.lap("coplanar");
  merged.thinnest = facets.planes.empty() ? kInfinity : kept.thinnest;
  std::vector<Vec3d> dropped_points;
  for (std::uint32_t i : dropped)
    dropped_points.push_back(to_vec3d(vertices[i]));
  merged.max_outside = std::nextafter(dropped_bound(dropped_points, facets.planes, kept_bound), kInfinity);
  laps.lap("dropped bound");
  return merged;
}

// Qhull 2020.2 (github.com/qhull/qhull, src/libqhull_r/geom2_r.c: qh_maxmin, qh_distround, qh_detroundoff;
// global_r.c: qh_initqhull_globals), default options in 3-D (no 'Cn', 'An' or 'QJ': pre-merge with 'C-0'):
//   qh_maxmin:      per axis k, maxabs_k = max(max_k, -min_k) over the points;
//                   qh.MAXabs_coord = max_k maxabs_k, qh.MAXsumcoord = sum_k maxabs_k
//   qh_distround:   maxdistsum = min(sqrt(3) x MAXabs_coord, MAXsumcoord)
//                   qh.DISTround = REALepsilon x (3 x maxdistsum x 1.01 + MAXabs_coord),  REALepsilon =
//                   DBL_EPSILON
//   qh_detroundoff: qh.premerge_centrum = 0 ('C-0') + 2 x DISTround ("2 for centrum and distplane()"), the
//                   centrum radius of Qhull's coplanar-facet test; qh.MINvisible = premerge_centrum (3-D);
//                   qh.MINoutside = 2 x MINvisible = 4 x DISTround.
//   qh_findbest / qh_partitionpoint (geom_r.c, libqhull_r.c): a point is outside a facet, so that it can
//   become a vertex, only if its distance is at least qh.MINoutside; otherwise it stays a coplanar point.
// The tolerance returned is qh.MINoutside: merge_facets() drops a vertex when it stands within the tolerance
// of the hull of the others, which is that test (4 x DISTround, not 2, matches Qhull's vertex counts:
// docs/benchmarks.md, "The measurements behind the code's constants").
// Qhull's options 'Qbb' (scale the last coordinate, Delaunay only) and 'Qt' do not change it.
template <class Point>
double qhull_default_tolerance(const std::vector<Point>& points) {
  if (points.empty()) return 0;
  double maxabs[3] = {0, 0, 0};
  for (const Point& p : points) {
    maxabs[0] = std::max(maxabs[0], std::fabs(static_cast<double>(p.x)));
    maxabs[1] = std::max(maxabs[1], std::fabs(static_cast<double>(p.y)));
    maxabs[2] = std::max(maxabs[2], std::fabs(static_cast<double>(p.z)));
  }
  const double max_abs_coord = std::max({maxabs[0], maxabs[1], maxabs[2]});
  const double max_sum_coord = maxabs[0] + maxabs[1] + maxabs[2];
  const double max_dist_sum = std::min(std::sqrt(3.0) * max_abs_coord, max_sum_coord);
  const double dist_round = DBL_EPSILON * (3 * max_dist_sum * 1.01 + max_abs_coord);
  return 4 * dist_round;
}

template MergedHull merge_facets(const std::vector<Point3>&, const HullMesh&, double, double);
template MergedHull merge_facets(const std::vector<Point3d>&, const HullMeshd&, double, double);
template double qhull_default_tolerance(const std::vector<Point3>&);
template double qhull_default_tolerance(const std::vector<Point3d>&);

}  // namespace cudahull
