// The independent hull checker (`cudahull hull --verify`).  It shares no code with exact_hull: every
// decision is an exact predicate on the input coordinates (and, for containment, on one double interior
// point), and it never builds a hull itself.
//
// Containment of all input points in a 3D hull is proven without the O(n*F) all-pairs test: once the mesh
// is a closed 2-manifold with convex or flat edges, an interior point c strictly below every face plane, and
// every vertex's fan winding once around the ray from c, the cones from c over the faces tile space.  Each
// point is then located in its cone by a walk over the faces and must be below or on that face's plane.
#include "cudahull/hull_checker.hpp"
#include "cudahull/morton.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/wide_predicates.hpp"

namespace cudahull {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

struct Report {
  CheckResult& result;
  std::size_t max;
  // Some coordinate is outside the fast predicates' exact range: every test takes the wide predicates.
  bool wide = false;
  void fail(std::string line) {
    result.ok = false;
    if (result.failures.size() < max) result.failures.push_back(std::move(line));
  }
  bool full() const { return result.failures.size() >= max; }
};

std::string fmt(const char* f, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char* f, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, f);
  std::vsnprintf(buf, sizeof buf, f, ap);
  va_end(ap);
  return buf;
}

// Coordinates in full precision: 9 significant digits identify a float, 17 a double.
std::string coords(const Point3& p) {
  return fmt("(%.9g %.9g %.9g)", p.x, p.y, p.z);
}
std::string coords(const Point3d& p) {
  return fmt("(%.17g %.17g %.17g)", p.x, p.y, p.z);
}

template <class Point>
bool lex_less(const Point& a, const Point& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// Runs fn(i, sink, chunk) for i in [0, n) on several threads, each on one contiguous chunk of indices; fn
// reports with sink(key, line).  The lines are
// merged in key order (so the report does not depend on scheduling) and a thread stops once it holds the
// report limit.  Returns how many failures were found (at least 1 if any).  `work` estimates the cost of one
// item in cheap predicate calls, to decide whether threads pay off.
template <class Fn>
std::size_t parallel_failures(std::size_t n, std::size_t work, Report& rep, const Fn& fn) {
  const std::size_t hc = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t chunks = std::min(hc, n * work / 50000 + 1);
  std::vector<std::vector<std::pair<std::uint64_t, std::string>>> lines(chunks);
  std::vector<std::size_t> counts(chunks, 0);
  auto body = [&](std::size_t t) {
    const std::size_t b = n * t / chunks, e = n * (t + 1) / chunks;
    auto sink = [&](std::uint64_t key, std::string line) {
      ++counts[t];
      lines[t].emplace_back(key, std::move(line));
    };
    for (std::size_t i = b; i < e && lines[t].size() < std::max<std::size_t>(rep.max, 1); ++i)
      fn(i, sink, t);
  };
  if (chunks == 1) {
    body(0);
  } else {
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < chunks; ++t)
      threads.emplace_back(body, t);
    for (std::thread& th : threads)
      th.join();
  }
  std::vector<std::pair<std::uint64_t, std::string>> all;
  for (auto& v : lines)
    for (auto& e : v)
      all.push_back(std::move(e));
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& e : all)
    rep.fail(std::move(e.second));
  std::size_t total = 0;
  for (std::size_t c : counts)
    total += c;
  return total;
}

// The predicates, exact for the coordinates at hand: the fast ones inside their range, else the wide ones.
int orient3d_any(bool wide, const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return wide ? orient3d_wide(a, b, c, d) : orient3d(a, b, c, d);
}
bool collinear3d_any(bool wide, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return wide ? collinear3d_wide(a, b, c) : collinear3d(a, b, c);
}
int orient2d_any(bool wide, double ax, double ay, double bx, double by, double cx, double cy) {
  return wide ? orient2d_wide(ax, ay, bx, by, cx, cy) : orient2d(ax, ay, bx, by, cx, cy);
}

// Affine dimension of the input, exactly (its own small scan: the checker shares no code with exact_hull).
template <class Point>
int input_dimension(const std::vector<Point>& pts, bool wide) {
  if (pts.empty()) return -1;
  const Vec3d a = to_vec3d(pts[0]);
  std::size_t i = 1;
  while (i < pts.size() && pts[i] == pts[0])
    ++i;
  if (i == pts.size()) return 0;
  const Vec3d b = to_vec3d(pts[i]);
  while (i < pts.size() && collinear3d_any(wide, a, b, to_vec3d(pts[i])))
    ++i;
  if (i == pts.size()) return 1;
  const Vec3d c = to_vec3d(pts[i]);
  while (i < pts.size() && orient3d_any(wide, a, b, c, to_vec3d(pts[i])) == 0)
    ++i;
  return i == pts.size() ? 2 : 3;
}

// Coordinates as a hash key; +0 and -0 are the same coordinate.
std::uint32_t bits(float f) {
  if (f == 0) f = 0;
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}
std::uint64_t bits(double f) {
  if (f == 0) f = 0;
  std::uint64_t u;
  std::memcpy(&u, &f, 8);
  return u;
}
template <class Point>
std::uint64_t hash_of(const Point& p) {
  std::uint64_t h = bits(p.x) * 0x9E3779B97F4A7C15ull;
  h ^= (h >> 29) + bits(p.y) * 0xBF58476D1CE4E5B9ull;
  h ^= (h >> 31) + bits(p.z) * 0x94D049BB133111EBull;
  return h ^ (h >> 32);
}

// Open-addressing table from vertex coordinates to vertex index (read-only after building, so the point
// scan can share it between threads).
template <class Point>
class VertexTable {
 public:
  explicit VertexTable(const std::vector<Point>& vertices) : v_(vertices) {
    std::size_t cap = 16;
    while (cap < 2 * vertices.size())
      cap *= 2;
    slots_.assign(cap, kNone);
    mask_ = cap - 1;
  }
  // Inserts v; returns the vertex already there with identical coordinates, or kNone.
  std::uint32_t insert(std::uint32_t v) {
    for (std::size_t s = hash_of(v_[v]) & mask_;; s = (s + 1) & mask_) {
      if (slots_[s] == kNone) {
        slots_[s] = v;
        return kNone;
      }
      if (v_[slots_[s]] == v_[v]) return slots_[s];
    }
  }
  std::uint32_t find(const Point& p) const {
    for (std::size_t s = hash_of(p) & mask_;; s = (s + 1) & mask_) {
      if (slots_[s] == kNone || v_[slots_[s]] == p) return slots_[s];
    }
  }

 private:
  const std::vector<Point>& v_;
  std::vector<std::uint32_t> slots_;
  std::size_t mask_;
};

template <class Point>
class Checker {
 public:
  Checker(const std::vector<Point>& pts, const BasicHullMesh<Point>& hull, Report& rep)
      : pts_(pts), h_(hull), rep_(rep) {}
  void run();

 private:
  std::string vname(std::uint32_t v) const {
    return fmt("%" PRIu32 " %s", h_.vertex_ids[v], coords(h_.vertices[v]).c_str());
  }
  std::string pname(std::size_t i) const { return fmt("point %zu %s", i, coords(pts_[i]).c_str()); }

  bool check_vertices();
  void check_lowest_index();
  void check_segment();
  void check_polygon();

  const std::vector<Point>& pts_;
  const BasicHullMesh<Point>& h_;
  Report& rep_;
};

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

// Dimension 1: the input is collinear (checked), so a point is inside the segment iff it lies between the
// ends in lexicographic order, which is monotone along a line.
template <class Point>
void Checker<Point>::check_segment() {
  Point lo = h_.vertices[0], hi = h_.vertices[1];
  if (lo == hi) return;  // reported as coincident vertices
  if (lex_less(hi, lo)) std::swap(lo, hi);
  std::size_t reported = 0;
  for (std::size_t i = 0; i < pts_.size() && reported < rep_.max; ++i)
    if (lex_less(pts_[i], lo) || lex_less(hi, pts_[i])) {
      rep_.fail(pname(i) + " lies on the line beyond the segment's ends");
      ++reported;
    }
}

// Dimension 2: the input is coplanar (checked) and the corners are input points, so the polygon lies in the
// input's plane.  Checks strict convexity, simplicity, and that every point is inside or on the polygon.
template <class Point>
void Checker<Point>::check_polygon() {
  const std::vector<std::uint32_t>& poly = h_.polygon;
  const std::size_t k = poly.size(), nv = h_.vertex_ids.size();
  if (k < 3) {
    rep_.fail(fmt("a hull of dimension 2 has a polygon of %zu corners", k));
    return;
  }
  std::vector<int> uses(nv, 0);
  for (std::uint32_t v : poly) {
    if (v >= nv) {
      rep_.fail(fmt("polygon corner index %" PRIu32 " is beyond the %zu vertices", v, nv));
      return;
    }
    ++uses[v];
  }
  bool ok = true;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (uses[v] != 1) {
      rep_.fail(fmt("vertex %" PRIu32 " (id %" PRIu32 ") appears %d times in the polygon (expected once)", v,
                    h_.vertex_ids[v], uses[v]));
      ok = false;
    }
  if (!ok) return;

  // Project by dropping an axis along which the plane's normal has an exactly non-zero component.  Any three
  // consecutive corners of a strictly convex polygon give that normal's direction; find a non-collinear
  // triple.
  auto coord = [](const Point& p, int a) -> double { return a == 0 ? p.x : a == 1 ? p.y : p.z; };
  int axis = -1;
  for (std::size_t i = 0; i < k && axis < 0; ++i) {
    const Point &a = h_.vertices[poly[i]], &b = h_.vertices[poly[(i + 1) % k]],
                &c = h_.vertices[poly[(i + 2) % k]];
    for (int t = 0; t < 3 && axis < 0; ++t) {
      const int u = (t + 1) % 3, w = (t + 2) % 3;
      if (orient2d_any(rep_.wide, coord(a, u), coord(a, w), coord(b, u), coord(b, w), coord(c, u),
                       coord(c, w)) != 0)
        axis = t;
    }
  }
  if (axis < 0) {
    rep_.fail("the polygon's corners are collinear");
    return;
  }
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  std::vector<std::array<double, 2>> q(k);
  for (std::size_t i = 0; i < k; ++i)
    q[i] = {coord(h_.vertices[poly[i]], u), coord(h_.vertices[poly[i]], w)};
  auto turn = [&](const std::array<double, 2>& a, const std::array<double, 2>& b,
                  const std::array<double, 2>& c) {
    return orient2d_any(rep_.wide, a[0], a[1], b[0], b[1], c[0], c[1]);
  };
  // Orientation from the first strictly turning corner; every corner must turn the same way.
  int sign = 0;
  for (std::size_t i = 0; i < k && sign == 0; ++i)
    sign = turn(q[i], q[(i + 1) % k], q[(i + 2) % k]);
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t j = (i + 1) % k;
    const int s = turn(q[i], q[j], q[(i + 2) % k]);
    if (s == 0) {
      rep_.fail(
          fmt("polygon corner %zu, vertex %s, is not strictly extreme: it is collinear with its neighbours",
              j, vname(poly[j]).c_str()));
      ok = false;
    } else if (s != sign) {
      rep_.fail(fmt("polygon corner %zu, vertex %s, is reflex: the polygon is not convex", j,
                    vname(poly[j]).c_str()));
      ok = false;
    }
  }
  if (!ok) return;
  // Same turn everywhere and one lexicographic maximum along the cycle: total turning 2*pi, a simple convex
  // polygon (a star polygon turns the same way everywhere too, but has several maxima).
  auto lexq = [](const std::array<double, 2>& a, const std::array<double, 2>& b) { return a < b; };
  std::size_t maxima = 0;
  for (std::size_t i = 0; i < k; ++i)
    if (lexq(q[(i + k - 1) % k], q[i]) && lexq(q[(i + 1) % k], q[i])) ++maxima;
  if (maxima != 1) {
    rep_.fail(fmt("the polygon winds %zu times around its interior (not simple)", maxima));
    return;
  }
  if (sign < 0) std::reverse(q.begin(), q.end());  // counter-clockwise in the projection from here on

  // Point in convex polygon: binary search for the wedge at q[0], then the edge test.  O(log k) per point.
  parallel_failures(pts_.size(), 2, rep_, [&](std::size_t i, auto& sink, std::size_t) {
    const std::array<double, 2> x = {coord(pts_[i], u), coord(pts_[i], w)};
    bool in = turn(q[0], q[1], x) >= 0 && turn(q[0], q[k - 1], x) <= 0;
    if (in) {
      std::size_t lo = 1, hi = k - 1;
      while (hi - lo > 1) {
        const std::size_t mid = (lo + hi) / 2;
        (turn(q[0], q[mid], x) >= 0 ? lo : hi) = mid;
      }
      in = turn(q[lo], q[hi], x) >= 0;
    }
    if (!in) sink(i, pname(i) + " is outside the polygon");
  });
}

// ---------------------------------------------------------------------------------------------------------
// Dimension 3.
//
// Works on its own numbering: vertices along a Morton curve and faces by their smallest vertex, so that the
// O(F) passes touch memory in order even when the vertex ids are spatially random (a sphere's hull has as
// many vertices as points).  Messages use the caller's face indices and input ids.

template <class Point>
class MeshChecker {
 public:
  MeshChecker(const std::vector<Point>& pts, const BasicHullMesh<Point>& h, Report& rep)
      : pts_(pts), h_(h), rep_(rep) {}
  void run();

 private:
  PointIndex id(std::uint32_t v) const { return h_.vertex_ids[lv2v_[v]]; }
  std::string vname(std::uint32_t v) const {
    return fmt("%" PRIu32 " %s", id(v), coords(h_.vertices[lv2v_[v]]).c_str());
  }
  std::string fname(std::uint32_t f) const {
    const Triangle& t = h_.triangles[lf2f_[f]];
    return fmt("face %" PRIu32 " (ids %" PRIu32 " %" PRIu32 " %" PRIu32 ")", lf2f_[f], h_.vertex_ids[t[0]],
               h_.vertex_ids[t[1]], h_.vertex_ids[t[2]]);
  }
  std::string pname(std::size_t i) const { return fmt("point %zu %s", i, coords(pts_[i]).c_str()); }
  const Vec3d& P(std::uint32_t v) const { return vp_[v]; }
  int above(std::uint32_t f, const Vec3d& q) const {
    const Triangle& t = tri_[f];
    return orient3d_any(rep_.wide, P(t[0]), P(t[1]), P(t[2]), q);
  }
  // The corner after corner (f, k) around vertex tri_[f][k]: across the edge entering the vertex.
  std::uint32_t next_corner(std::uint32_t corner) const {
    const std::uint32_t f = corner / 3, k = corner % 3;
    const std::uint32_t s = 3 * f + (k + 2) % 3;
    return 3 * nb_[s] + twin_[s];
  }

  bool renumber();
  bool build_adjacency();
  bool check_topology();
  bool check_edges();
  bool find_interior_point();
  void build_facets();
  bool check_vertex_fans(bool polytope);
  void locate_points();
  void brute_force_points();
  std::uint32_t walk(const Vec3d& q, std::uint32_t f, std::uint32_t& rng, std::size_t cap) const;

  const std::vector<Point>& pts_;
  const BasicHullMesh<Point>& h_;
  Report& rep_;
  std::uint32_t nv_ = 0, nf_ = 0;
  std::vector<std::uint32_t> lv2v_, lf2f_;  // local vertex/face -> the caller's index
  std::vector<Vec3d> vp_;                   // local vertex coordinates
  std::vector<Triangle> tri_;               // local faces over local vertices
  // Outgoing half-edges grouped by origin vertex (CSR), sorted by target within a vertex.
  std::vector<std::uint32_t> start_, he_to_, he_corner_;
  // Per corner/half-edge 3f+i (edge tri_[f][i] -> tri_[f][i+1]): the face across, its slot there, and
  // whether the edge is flat.
  std::vector<std::uint32_t> nb_;
  std::vector<std::uint8_t> twin_, flat_;
  std::vector<std::uint32_t> facet_;  // per face: a representative face of its coplanar facet
  Vec3d c_{};
};

// Indices valid and faces non-degenerate; then the local numbering.  False when the faces are unusable.
template <class Point>
bool MeshChecker<Point>::renumber() {
  nv_ = static_cast<std::uint32_t>(h_.vertices.size());
  nf_ = static_cast<std::uint32_t>(h_.triangles.size());
  bool ok = true;
  for (std::uint32_t f = 0; f < nf_ && ok; ++f) {
    const Triangle& t = h_.triangles[f];
    if (t[0] >= nv_ || t[1] >= nv_ || t[2] >= nv_) {
      rep_.fail(fmt("face %" PRIu32 " has a vertex index beyond the %" PRIu32 " vertices", f, nv_));
      ok = false;
    }
  }
  if (!ok) return false;
  for (std::uint32_t f = 0; f < nf_; ++f) {
    const Triangle& t = h_.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      rep_.fail(fmt("face %" PRIu32 " repeats a vertex", f));
      ok = false;
    } else if (collinear3d_any(rep_.wide, to_vec3d(h_.vertices[t[0]]), to_vec3d(h_.vertices[t[1]]),
                               to_vec3d(h_.vertices[t[2]]))) {
      rep_.fail(fmt("face %" PRIu32 " (ids %" PRIu32 " %" PRIu32 " %" PRIu32
                    ") is degenerate: its corners are collinear",
                    f, h_.vertex_ids[t[0]], h_.vertex_ids[t[1]], h_.vertex_ids[t[2]]));
      ok = false;
    }
  }
  if (!ok) return false;

  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
    lo[k] = INFINITY, hi[k] = -INFINITY;
  for (const Point& p : h_.vertices) {
    const double c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(nv_);
  for (std::uint32_t v = 0; v < nv_; ++v) {
    const Point& p = h_.vertices[v];
    const double c[3] = {p.x, p.y, p.z};
    std::uint64_t key = 0;
    for (int k = 0; k < 3; ++k) {
      const double ext = hi[k] - lo[k];
      // An overflowing double extent (inf, NaN) goes to cell 0.
      const double t = ext > 0 ? (c[k] - lo[k]) / ext * 2097151.0 : 0;
      key |= spread3(t > 0 ? static_cast<std::uint64_t>(std::min(t, 2097151.0)) : 0) << k;
    }
    keys[v] = {key, v};
  }
  std::sort(keys.begin(), keys.end());
  lv2v_.resize(nv_);
  std::vector<std::uint32_t> v2lv(nv_);
  vp_.resize(nv_);
  for (std::uint32_t l = 0; l < nv_; ++l) {
    lv2v_[l] = keys[l].second;
    v2lv[keys[l].second] = l;
    vp_[l] = to_vec3d(h_.vertices[keys[l].second]);
  }
  // Faces by smallest local vertex (counting sort).
  std::vector<std::uint32_t> count(nv_ + 1, 0);
  auto min_vertex = [&](const Triangle& t) { return std::min({v2lv[t[0]], v2lv[t[1]], v2lv[t[2]]}); };
  for (const Triangle& t : h_.triangles)
    ++count[min_vertex(t) + 1];
  for (std::uint32_t v = 0; v < nv_; ++v)
    count[v + 1] += count[v];
  lf2f_.resize(nf_);
  tri_.resize(nf_);
  for (std::uint32_t f = 0; f < nf_; ++f) {
    const Triangle& t = h_.triangles[f];
    const std::uint32_t l = count[min_vertex(t)]++;
    lf2f_[l] = f;
    tri_[l] = {v2lv[t[0]], v2lv[t[1]], v2lv[t[2]]};
  }
  return true;
}

// Item 1, edges: every directed edge once, each with its opposite.  Fills nb_/twin_.  Returns whether the
// mesh is walkable (closed, no edge used twice in one direction).
template <class Point>
bool MeshChecker<Point>::build_adjacency() {
  start_.assign(nv_ + 1, 0);
  for (const Triangle& t : tri_)
    for (std::uint32_t v : t)
      ++start_[v + 1];
  for (std::uint32_t v = 0; v < nv_; ++v)
    start_[v + 1] += start_[v];
  he_to_.resize(3 * static_cast<std::size_t>(nf_));
  he_corner_.resize(he_to_.size());
  {
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t f = 0; f < nf_; ++f)
      for (std::uint32_t i = 0; i < 3; ++i) {
        const std::uint32_t a = tri_[f][i], pos = fill[a]++;
        he_to_[pos] = tri_[f][(i + 1) % 3];
        he_corner_[pos] = 3 * f + i;
      }
  }
  nb_.assign(3 * static_cast<std::size_t>(nf_), kNone);
  twin_.assign(nb_.size(), 0);

  // Sort each vertex's half-edges by target, then report same-direction duplicates.
  const std::size_t dups = parallel_failures(nv_, 8, rep_, [&](std::size_t v, auto& sink, std::size_t) {
    const std::uint32_t b = start_[v], e = start_[v + 1];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> list(e - b);
    for (std::uint32_t k = b; k < e; ++k)
      list[k - b] = {he_to_[k], he_corner_[k]};
    std::sort(list.begin(), list.end());
    for (std::uint32_t k = b; k < e; ++k)
      he_to_[k] = list[k - b].first, he_corner_[k] = list[k - b].second;
    for (std::uint32_t k = b + 1; k < e; ++k)
      if (he_to_[k] == he_to_[k - 1]) {
        const std::uint32_t f1 = he_corner_[k - 1] / 3, f2 = he_corner_[k] / 3;
        sink(std::min(lf2f_[f1], lf2f_[f2]),
             fmt("edge (%" PRIu32 ", %" PRIu32 ") is used in the same direction by face %" PRIu32
                 " and face %" PRIu32 ": not an oriented 2-manifold",
                 id(static_cast<std::uint32_t>(v)), id(he_to_[k]), std::min(lf2f_[f1], lf2f_[f2]),
                 std::max(lf2f_[f1], lf2f_[f2])));
      }
  });
  const std::size_t open = parallel_failures(nv_, 8, rep_, [&](std::size_t a, auto& sink, std::size_t) {
    for (std::uint32_t k = start_[a]; k < start_[a + 1]; ++k) {
      const std::uint32_t b = he_to_[k];
      const auto first = he_to_.begin() + start_[b], last = he_to_.begin() + start_[b + 1];
      const auto it = std::lower_bound(first, last, static_cast<std::uint32_t>(a));
      const std::uint32_t corner = he_corner_[k];
      if (it == last || *it != a) {
        sink(lf2f_[corner / 3], fmt("edge (%" PRIu32 ", %" PRIu32 ") of face %" PRIu32
                                    " has no opposite edge in another face: the mesh is not closed",
                                    id(static_cast<std::uint32_t>(a)), id(b), lf2f_[corner / 3]));
        continue;
      }
      const std::uint32_t other = he_corner_[it - he_to_.begin()];
      nb_[corner] = other / 3;
      twin_[corner] = static_cast<std::uint8_t>(other % 3);
    }
  });
  return dups == 0 && open == 0;
}

// Item 1, the rest: no unused vertex, V - E + F = 2, one component, every vertex's faces one fan.
template <class Point>
bool MeshChecker<Point>::check_topology() {
  bool ok = true;
  std::size_t edges = 0;
  for (std::uint32_t a = 0; a < nv_; ++a)
    for (std::uint32_t k = start_[a]; k < start_[a + 1]; ++k)
      if (a < he_to_[k] || nb_[he_corner_[k]] == kNone) ++edges;  // unmatched edges count once too
  for (std::uint32_t v = 0; v < nv_; ++v)
    if (start_[v] == start_[v + 1]) {
      rep_.fail("vertex " + vname(v) + " is not used by any face");
      ok = false;
    }
  const long long euler =
      static_cast<long long>(nv_) - static_cast<long long>(edges) + static_cast<long long>(nf_);
  if (euler != 2) {
    rep_.fail(fmt("V - E + F = %lld (V = %" PRIu32 ", E = %zu, F = %" PRIu32 "), expected 2", euler, nv_,
                  edges, nf_));
    ok = false;
  }
  return ok;
}

// Needs a walkable mesh.
template <class Point>
bool MeshChecker<Point>::check_edges() {
  bool ok = true;
  // One connected component.
  std::vector<std::uint8_t> seen(nf_, 0);
  std::vector<std::uint32_t> stack = {0};
  seen[0] = 1;
  std::size_t reached = 1;
  while (!stack.empty()) {
    const std::uint32_t f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = nb_[3 * f + i];
      if (!seen[g]) seen[g] = 1, ++reached, stack.push_back(g);
    }
  }
  if (reached != nf_) {
    rep_.fail(fmt("the mesh is not connected: face %" PRIu32 " reaches %zu of %" PRIu32 " faces", lf2f_[0],
                  reached, nf_));
    ok = false;
  }
  // Every vertex's faces form one fan (a vertex where two fans touch is not a manifold point).  Each corner
  // belongs to one vertex, so the marks of different vertices never collide between threads.
  std::vector<std::uint8_t> done(3 * static_cast<std::size_t>(nf_), 0);
  if (parallel_failures(nv_, 8, rep_, [&](std::size_t v, auto& sink, std::size_t) {
        std::uint32_t fans = 0;
        for (std::uint32_t k = start_[v]; k < start_[v + 1]; ++k) {
          if (done[he_corner_[k]]) continue;
          ++fans;
          std::uint32_t c = he_corner_[k];
          do {
            done[c] = 1;
            c = next_corner(c);
          } while (c != he_corner_[k]);
        }
        if (fans > 1)
          sink(lv2v_[v], fmt("vertex %s is not a manifold point: its faces form %" PRIu32 " separate fans",
                             vname(static_cast<std::uint32_t>(v)).c_str(), fans));
      }) != 0)
    ok = false;

  // Item 3: convex or flat edges (each edge once, from its face with the smaller local index), and whether
  // the interior point is strictly below every face.
  flat_.assign(3 * static_cast<std::size_t>(nf_), 0);
  if (parallel_failures(nf_, 16, rep_, [&](std::size_t fi, auto& sink, std::size_t) {
        const std::uint32_t f = static_cast<std::uint32_t>(fi);
        for (int i = 0; i < 3; ++i) {
          const std::uint32_t g = nb_[3 * f + i];
          if (g < f) continue;
          const int j = twin_[3 * f + i];
          const std::uint32_t y = tri_[g][(j + 2) % 3];
          const int s = above(f, P(y));
          flat_[3 * f + i] = flat_[3 * g + j] = s == 0;  // slot 3g+j is written only here
          if (s > 0)
            sink(lf2f_[f],
                 fmt("edge (%" PRIu32 ", %" PRIu32 ") between face %" PRIu32 " and face %" PRIu32
                     " is concave: vertex %" PRIu32 " is above face %" PRIu32,
                     id(tri_[f][i]), id(tri_[f][(i + 1) % 3]), lf2f_[f], lf2f_[g], id(y), lf2f_[f]));
        }
      }) != 0)
    ok = false;
  return ok;
}

// The interior reference point c: the vertex centroid, or else the centroid of face 0 and the vertex
// furthest below it.  Either is strictly inside a valid hull up to rounding; the exact test decides.
template <class Point>
bool MeshChecker<Point>::find_interior_point() {
  auto strictly_inside = [&](const Vec3d& c) {
    // A candidate only; the fast predicates need its coordinates in their range too (or 0).
    auto snap = [&](double x) { return rep_.wide || in_fast_exact_range(x) ? x : 0.0; };
    c_ = {snap(c.x), snap(c.y), snap(c.z)};
    std::atomic<bool> inside{true};
    parallel_failures(nf_, 1, rep_, [&](std::size_t f, auto&, std::size_t) {
      if (inside.load(std::memory_order_relaxed) && above(static_cast<std::uint32_t>(f), c) >= 0)
        inside = false;
    });
    return inside.load();
  };
  long double s[3] = {0, 0, 0};
  for (const Vec3d& p : vp_)
    s[0] += p.x, s[1] += p.y, s[2] += p.z;
  if (strictly_inside({static_cast<double>(s[0] / nv_), static_cast<double>(s[1] / nv_),
                       static_cast<double>(s[2] / nv_)}))
    return true;
  // Long double: its range holds every product of three doubles, so wide coordinates neither overflow nor
  // underflow here.
  using L = long double;
  const Triangle& t = tri_[0];
  const Vec3d &a = P(t[0]), &b = P(t[1]), &c = P(t[2]);
  const L ux = L(b.x) - a.x, uy = L(b.y) - a.y, uz = L(b.z) - a.z;
  const L wx = L(c.x) - a.x, wy = L(c.y) - a.y, wz = L(c.z) - a.z;
  const L nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
  std::uint32_t best = 0;
  L best_d = 0;
  for (std::uint32_t v = 0; v < nv_; ++v) {
    const L d = nx * (L(P(v).x) - a.x) + ny * (L(P(v).y) - a.y) + nz * (L(P(v).z) - a.z);
    if (d < best_d) best_d = d, best = v;
  }
  const Vec3d& d = P(best);
  return strictly_inside({static_cast<double>((L(a.x) + b.x + c.x + d.x) / 4),
                          static_cast<double>((L(a.y) + b.y + c.y + d.y) / 4),
                          static_cast<double>((L(a.z) + b.z + c.z + d.z) / 4)});
}

// Facets: maximal sets of faces joined by flat edges.
template <class Point>
void MeshChecker<Point>::build_facets() {
  facet_.resize(nf_);
  std::iota(facet_.begin(), facet_.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (facet_[x] != x)
      x = facet_[x] = facet_[facet_[x]];
    return x;
  };
  for (std::uint32_t f = 0; f < nf_; ++f)
    for (int i = 0; i < 3; ++i)
      if (flat_[3 * f + i]) {
        const std::uint32_t a = find(f), b = find(nb_[3 * f + i]);
        if (a != b) facet_[std::max(a, b)] = std::min(a, b);
      }
  for (std::uint32_t f = 0; f < nf_; ++f)
    facet_[f] = find(f);
}

// Item 4 and the winding condition, one fan walk per vertex.
//  - Strictly extreme iff a strict corner of every facet it belongs to: around the vertex the faces of one
//    facet form a contiguous run whose first and last edges are the facet's boundary edges at the vertex.
//  - Winding (only when `polytope`): each face (v, a, b) turns by an angle in (0, pi) around the axis from
//    c through v, since c is strictly below it; the fan must cross the half-plane of its first neighbour
//    exactly once.  With the rest, this makes the radial projection from c a homeomorphism, so the cones
//    over the faces tile space exactly once.
template <class Point>
bool MeshChecker<Point>::check_vertex_fans(bool polytope) {
  std::atomic<bool> winding_ok{true};
  parallel_failures(nv_, 8, rep_, [&](std::size_t vi, auto& sink, std::size_t) {
    const std::uint32_t v = static_cast<std::uint32_t>(vi);
    const std::uint32_t c0 = he_corner_[start_[v]];
    // Fan order: corner j is face (v, next_j, prev_j); the next face around v shares the edge (v, prev_j).
    thread_local std::vector<std::uint32_t> fan;
    fan.clear();
    std::uint32_t c = c0;
    do {
      fan.push_back(c);
      c = next_corner(c);
    } while (c != c0);
    const std::size_t n = fan.size();
    auto nxt = [&](std::size_t j) { return tri_[fan[j] / 3][(fan[j] % 3 + 1) % 3]; };
    auto prv = [&](std::size_t j) { return tri_[fan[j] / 3][(fan[j] % 3 + 2) % 3]; };
    auto fct = [&](std::size_t j) { return facet_[fan[j] / 3]; };

    std::size_t start = n;
    for (std::size_t j = 0; j < n && start == n; ++j)
      if (fct(j) != fct((j + n - 1) % n)) start = j;
    if (start == n) {
      sink(lv2v_[v], "vertex " + vname(v) + " is not strictly extreme: it lies inside the facet of " +
                         fname(fan[0] / 3) + " (all its faces are coplanar)");
    } else {
      for (std::size_t r = 0; r < n; ++r) {
        const std::size_t j = (start + r) % n;
        if (fct(j) == fct((j + n - 1) % n)) continue;  // not the first face of a run
        std::size_t e = j;
        while (fct((e + 1) % n) == fct(j))
          e = (e + 1) % n;
        const std::uint32_t a = nxt(j), b = prv(e);
        if (collinear3d_any(rep_.wide, P(a), P(v), P(b))) {
          sink(lv2v_[v],
               fmt("vertex %s is not strictly extreme: it lies on the segment between vertices %" PRIu32
                   " and %" PRIu32 " on the boundary of a facet",
                   vname(v).c_str(), id(a), id(b)));
          break;
        }
      }
    }
    if (!polytope) return;
    // Upper half: angle in [0, pi) from w0 = next_0; lower: [pi, 2 pi).  r = prev_0 is at an angle in
    // (0, pi); a point on the plane (c, v, w0) is at angle 0 iff it is on w0's side of the plane (c, v, r).
    const Vec3d &pv = P(v), &w0 = P(nxt(0)), &r = P(prv(0));
    const int ref = orient3d_any(rep_.wide, c_, pv, r, w0);
    auto upper = [&](const Vec3d& w) {
      const int s = orient3d_any(rep_.wide, c_, pv, w0, w);
      return s > 0 || (s == 0 && orient3d_any(rep_.wide, c_, pv, r, w) == ref);
    };
    int crossings = 0;
    bool up = true;
    for (std::size_t j = 0; j < n; ++j) {
      const bool next_up = upper(P(prv(j)));
      if (!up && next_up) ++crossings;
      up = next_up;
    }
    if (crossings != 1) {
      winding_ok = false;
      sink(lv2v_[v], fmt("vertex %s: its faces wind %d times around it (not a convex vertex)",
                         vname(v).c_str(), crossings));
    }
  });
  return winding_ok;
}

// Walks from face f towards the face whose cone from c contains q: crosses an edge whose radial plane has q
// strictly outside, choosing among such edges from a random start (a deterministic walk can cycle).
// Returns kNone after `cap` steps.
template <class Point>
std::uint32_t MeshChecker<Point>::walk(const Vec3d& q, std::uint32_t f, std::uint32_t& rng,
                                       std::size_t cap) const {
  int entered = -1;  // the slot we came through: q is on its inner side already
  for (std::size_t step = 0; step < cap; ++step) {
    rng ^= rng << 13, rng ^= rng >> 17, rng ^= rng << 5;
    const int off = static_cast<int>(rng % 3);
    const Triangle& t = tri_[f];
    int cross = -1;
    for (int j = 0; j < 3 && cross < 0; ++j) {
      const int i = (off + j) % 3;
      if (i != entered && orient3d_any(rep_.wide, c_, P(t[i]), P(t[(i + 1) % 3]), q) < 0) cross = i;
    }
    if (cross < 0) return f;
    entered = twin_[3 * f + cross];
    f = nb_[3 * f + cross];
  }
  return kNone;
}

// Item 2 for a verified convex polytope: locate each point's cone and test it against that face only.
template <class Point>
void MeshChecker<Point>::locate_points() {
  const std::size_t cap = static_cast<std::size_t>(4 * std::sqrt(static_cast<double>(nf_))) + 100;
  // Start faces from a cube map of directions around c, filled by one sweep of short walks.
  const int g = std::clamp(static_cast<int>(std::sqrt(nf_ / 12.0)), 1, 256);
  // Directions in long double, so that wide coordinates (1e308 apart) stay finite; only the start faces
  // depend on them, never a verdict.
  using L = long double;
  L radius = 0;
  for (const Vec3d& p : vp_)
    radius = std::max({radius, std::fabs(L(p.x) - c_.x), std::fabs(L(p.y) - c_.y), std::fabs(L(p.z) - c_.z)});
  auto clamp_double = [](L x) {
    const L big = std::numeric_limits<double>::max();
    return static_cast<double>(std::clamp(x, -big, big));
  };
  auto cell_of = [&](L dx, L dy, L dz) -> std::size_t {
    const L ax = std::fabs(dx), ay = std::fabs(dy), az = std::fabs(dz);
    int side;
    L s, t, m;
    if (ax >= ay && ax >= az)
      side = dx >= 0 ? 0 : 1, s = dy, t = dz, m = ax;
    else if (ay >= az)
      side = dy >= 0 ? 2 : 3, s = dz, t = dx, m = ay;
    else
      side = dz >= 0 ? 4 : 5, s = dx, t = dy, m = az;
    if (!(m > 0)) return 0;
    const int i = std::clamp(static_cast<int>((s / m + 1) * 0.5 * g), 0, g - 1);
    const int j = std::clamp(static_cast<int>((t / m + 1) * 0.5 * g), 0, g - 1);
    return (static_cast<std::size_t>(side) * g + i) * g + j;
  };
  std::vector<std::uint32_t> cell_face(6 * static_cast<std::size_t>(g) * g, 0);
  {
    std::uint32_t rng = 0x9E3779B9u, f = 0;
    for (int side = 0; side < 6; ++side)
      for (int i = 0; i < g; ++i)
        for (int j0 = 0; j0 < g; ++j0) {
          const int j = (i % 2) ? g - 1 - j0 : j0;  // serpentine: consecutive cells are neighbours
          const double s = ((i + 0.5) / g) * 2 - 1, t = ((j + 0.5) / g) * 2 - 1;
          const Vec3d d = side == 0   ? Vec3d{1, s, t}
                          : side == 1 ? Vec3d{-1, s, t}
                          : side == 2 ? Vec3d{t, 1, s}
                          : side == 3 ? Vec3d{t, -1, s}
                          : side == 4 ? Vec3d{s, t, 1}
                                      : Vec3d{s, t, -1};
          const Vec3d q = {clamp_double(c_.x + d.x * radius), clamp_double(c_.y + d.y * radius),
                           clamp_double(c_.z + d.z * radius)};
          const std::uint32_t r = walk(q, f, rng, cap);
          if (r != kNone) f = r;
          cell_face[(static_cast<std::size_t>(side) * g + i) * g + j] = f;
        }
  }
  // A mesh too large for the caches: visit the points grouped by cell (a counting sort), so that consecutive
  // walks touch the same faces.  A small mesh: input order, which reads the points sequentially.  Each
  // chunk walks on from its previous point's face while the cell stays the same.
  const std::size_t n = pts_.size(), ncells = cell_face.size();
  std::vector<std::uint32_t> cell(n), order(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = pts_[i];
    cell[i] = static_cast<std::uint32_t>(cell_of(L(p.x) - c_.x, L(p.y) - c_.y, L(p.z) - c_.z));
  }
  if (nf_ > 32768) {
    std::vector<std::uint32_t> first(ncells + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      ++first[cell[i] + 1];
    for (std::size_t k = 0; k < ncells; ++k)
      first[k + 1] += first[k];
    for (std::size_t i = 0; i < n; ++i)
      order[first[cell[i]]++] = static_cast<std::uint32_t>(i);
  } else {
    std::iota(order.begin(), order.end(), 0u);
  }
  struct State {
    std::uint32_t rng, cell = kNone, face = 0;
  };
  std::vector<State> state(std::max(1u, std::thread::hardware_concurrency()));
  for (std::size_t t = 0; t < state.size(); ++t)
    state[t].rng = 0x2545F491u * static_cast<std::uint32_t>(t + 1) | 1u;
  parallel_failures(n, 4, rep_, [&](std::size_t k, auto& sink, std::size_t t) {
    State& st = state[t];
    const std::size_t i = order[k];
    const Vec3d q = to_vec3d(pts_[i]);
    if (cell[i] != st.cell) st.cell = cell[i], st.face = cell_face[cell[i]];
    const std::uint32_t f = walk(q, st.face, st.rng, cap);
    if (f != kNone) {
      st.face = f;
      if (above(f, q) > 0) sink(i, pname(i) + " is above " + fname(f));
      return;
    }
    for (std::uint32_t h = 0; h < nf_; ++h)  // the walk did not settle: test every face
      if (above(h, q) > 0) {
        sink(i, pname(i) + " is above " + fname(h));
        return;
      }
  });
}

// Item 2 when the mesh is not a verified convex polytope: every point against every face (first face only).
template <class Point>
void MeshChecker<Point>::brute_force_points() {
  if (static_cast<double>(pts_.size()) * static_cast<double>(nf_) > 4e9) {
    rep_.fail(
        "containment of the input points was not checked: the mesh is not a valid convex polytope and "
        "the all-pairs test is too large");
    return;
  }
  parallel_failures(pts_.size(), std::max<std::size_t>(nf_ / 16, 1), rep_,
                    [&](std::size_t i, auto& sink, std::size_t) {
                      const Vec3d q = to_vec3d(pts_[i]);
                      for (std::uint32_t f = 0; f < nf_; ++f)
                        if (above(f, q) > 0) {
                          sink(i, pname(i) + " is above " + fname(f));
                          return;
                        }
                    });
}

template <class Point>
void MeshChecker<Point>::run() {
  nv_ = static_cast<std::uint32_t>(h_.vertices.size());
  nf_ = static_cast<std::uint32_t>(h_.triangles.size());
  if (nv_ < 4 || nf_ < 4) {
    rep_.fail(fmt("a hull of dimension 3 has %" PRIu32 " vertices and %" PRIu32
                  " faces (at least 4 each expected)",
                  nv_, nf_));
    return;
  }
  if (!h_.polygon.empty()) rep_.fail("a hull of dimension 3 has a polygon");
  if (!renumber()) return;
  const bool walkable = build_adjacency();
  const bool topology = check_topology() && walkable;
  bool polytope = false;
  if (walkable) {
    polytope = check_edges() && topology;
    polytope = polytope && find_interior_point();
    build_facets();
    polytope = check_vertex_fans(polytope) && polytope;
  }
  if (polytope)
    locate_points();
  else
    brute_force_points();
}
template <class Point>
void Checker<Point>::run() {
  if (!check_vertices()) return;
  check_lowest_index();
  const int d = h_.dimension;
  if (d < -1 || d > 3) {
    rep_.fail(fmt("invalid dimension %d", d));
    return;
  }
  const int din = input_dimension(pts_, rep_.wide);
  if (din != d) {
    rep_.fail(
        fmt("dimension mismatch: the hull has dimension %d but the input points have affine dimension %d", d,
            din));
    return;
  }
  if (d != 3 && !h_.triangles.empty())
    rep_.fail(fmt("a hull of dimension %d has %zu triangles (expected none)", d, h_.triangles.size()));
  if (d != 2 && !h_.polygon.empty())
    rep_.fail(
        fmt("a hull of dimension %d has a polygon of %zu corners (expected none)", d, h_.polygon.size()));
  const std::size_t expect_v[] = {0, 1, 2};
  if (d <= 1 && h_.vertex_ids.size() != expect_v[d + 1]) {
    rep_.fail(fmt("a hull of dimension %d has %zu vertices (expected %zu)", d, h_.vertex_ids.size(),
                  expect_v[d + 1]));
    return;
  }
  // Dimension 0: the input is one repeated point and the vertex is an input point; the lowest-index rule
  // was checked above, so nothing is left.
  if (d == 1) check_segment();
  if (d == 2) check_polygon();
  if (d == 3) MeshChecker<Point>(pts_, h_, rep_).run();
}

// Whether a coordinate of p is outside the fast predicates' range; false for every float.
bool outside_fast_range(const Point3&) {
  return false;
}
bool outside_fast_range(const Point3d& p) {
  return !in_fast_exact_range(p.x) || !in_fast_exact_range(p.y) || !in_fast_exact_range(p.z);
}
template <class Point>
bool finite(const Point& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace

template <class Point>
CheckResult check_hull(const std::vector<Point>& points, const BasicHullMesh<Point>& hull,
                       std::size_t max_failures) {
  CheckResult result;
  Report rep{result, max_failures};
  // The wide predicates take every finite double; NaN and infinity are no coordinates at all.
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!finite(points[i])) {
      rep.fail(fmt("point %zu %s is not finite", i, coords(points[i]).c_str()));
      return result;
    }
  for (std::size_t v = 0; v < hull.vertices.size(); ++v)
    if (!finite(hull.vertices[v])) {
      rep.fail(fmt("vertex %zu %s is not finite", v, coords(hull.vertices[v]).c_str()));
      return result;
    }
  rep.wide =
      std::any_of(points.begin(), points.end(), [](const Point& p) { return outside_fast_range(p); }) ||
      std::any_of(hull.vertices.begin(), hull.vertices.end(),
                  [](const Point& p) { return outside_fast_range(p); });
  Checker<Point>(points, hull, rep).run();
  return result;
}

// The two point types; one implementation.
template CheckResult check_hull(const std::vector<Point3>&, const HullMesh&, std::size_t);
template CheckResult check_hull(const std::vector<Point3d>&, const HullMeshd&, std::size_t);

}  // namespace cudahull
