// Exact 3D convex hull: exact QuickHull with outside sets (conflict lists) on the exact predicates, then a
// polish pass that merges coplanar faces into facets and keeps only strict corners.  Lower-dimensional
// inputs get an exact segment or an exact 2D hull (Andrew's monotone chain).
//
// Every combinatorial decision is an exact predicate (orient3d, orient2d, collinear3d) on the input's own
// coordinates, float (Point3) or double (Point3d): one implementation, instantiated for both.  Other
// arithmetic appears only to rank candidates (furthest point), which needs no exactness: a wrong ranking
// costs time, never correctness, because every choice is re-checked exactly.  (Ranking may overflow to
// infinity or NaN, or underflow to zero, on huge or tiny doubles; every such pick is re-checked too.)
//
// The predicates are a policy (FastPredicates, WidePredicates): exact_hull() is the fast one;
// exact_hull_any() takes every finite double, scaling the input by a power of two where that is enough, else
// on the wide predicates.
#include "cudahull/exact_hull.hpp"
#include "cudahull/morton.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cudahull/predicates.hpp"
#include "cudahull/wide_predicates.hpp"

namespace cudahull {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

// The exact predicates behind every combinatorial decision are a policy (wide_predicates.hpp):
// FastPredicates (exact_hull) calls the inline predicates themselves, so its instantiations compile to the
// same code as direct calls; WidePredicates (exact_hull_any, when no power-of-two scale brings the input
// into the fast range) is exact for every finite double, slower.

// A distinct input point: coordinates (float for Point3, double for Point3d) plus the lowest input index
// among the points with these coordinates.
template <class Point>
struct Site {
  using Coord = decltype(Point::x);
  Coord x, y, z;
  PointIndex id;
};

bool lex_less(const Vec3d& a, const Vec3d& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

bool same(const Vec3d& a, const Vec3d& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Up to four affinely independent points, found exactly.  a/b are the lexicographic extremes; c and d are
// picked by approximate distance (for a fat initial simplex) and confirmed (or replaced) exactly.
struct Basis {
  int dim = -1;
  std::uint32_t a = kNone, b = kNone, c = kNone, d = kNone;
};

template <class Pred, class Get>
Basis find_basis(std::size_t n, const Get& get) {
  Basis r;
  if (n == 0) return r;
  std::uint32_t lo = 0, hi = 0;
  for (std::uint32_t i = 1; i < n; ++i) {
    if (lex_less(get(i), get(lo))) lo = i;
    if (lex_less(get(hi), get(i))) hi = i;
  }
  r.a = lo;
  r.dim = 0;
  const Vec3d a = get(lo), b = get(hi);
  if (same(a, b)) return r;  // lexicographic min == max: all points identical
  r.b = hi;
  r.dim = 1;

  const Vec3d ab = sub(b, a);
  std::uint32_t best = kNone;
  double best_d = -1;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Vec3d w = cross(sub(get(i), a), ab);
    const double d = dot(w, w);
    if (d > best_d) best_d = d, best = i;
  }
  // The approximate pick may be exactly collinear (or missing, when a huge double input overflows the
  // ranking to NaN): scan exactly.
  if (best == kNone || Pred::collinear3d(a, b, get(best))) {
    best = kNone;
    for (std::uint32_t i = 0; i < n && best == kNone; ++i)
      if (!Pred::collinear3d(a, b, get(i))) best = i;
    if (best == kNone) return r;
  }
  r.c = best;
  r.dim = 2;

  const Vec3d c = get(best);
  const Vec3d nrm = cross(ab, sub(c, a));
  best = kNone;
  best_d = -1;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double d = std::fabs(dot(nrm, sub(get(i), a)));
    if (d > best_d) best_d = d, best = i;
  }
  if (best == kNone || Pred::orient3d(a, b, c, get(best)) == 0) {
    best = kNone;
    for (std::uint32_t i = 0; i < n && best == kNone; ++i)
      if (Pred::orient3d(a, b, c, get(i)) != 0) best = i;
    if (best == kNone) return r;
  }
  r.d = best;
  r.dim = 3;
  return r;
}

// Builds the mesh from local site indices `keep` (each a strict extreme point): vertex_ids ascending.
// Returns the map site -> output vertex (kNone for sites not kept) through `out_index`.
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

// Sorts sites along a Morton curve of their bounding box and removes duplicates, keeping the lowest id of
// each coordinate triple.  The Morton order is for memory locality only: QuickHull touches the points of a
// region together.  Identical coordinates get identical keys, so duplicates end up in one run of equal keys,
// sorted there by coordinates and id.  (+0 and -0 compare equal and get equal keys.)
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

// ---------------------------------------------------------------------------------------------------------
// Exact QuickHull on distinct points, deciding with the predicates of Pred.
template <class Pred>
class QuickHull {
 public:
  explicit QuickHull(const std::vector<Vec3d>& p) : p_(p), start_face_(p.size(), kNone) {}

  void build(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d);
  // Merges coplanar faces into facets and returns the fan triangulation of every facet over its strict
  // corners (site indices).
  std::vector<Triangle> polish() const;

 private:
  struct Face {
    std::array<std::uint32_t, 3> v;   // counter-clockwise seen from outside
    std::array<std::uint32_t, 3> nb;  // nb[i]: the face across edge v[i] -> v[i+1]
    Vec3d normal;                     // approximate, for ranking outside points only
    std::uint32_t out_begin = 0;      // outside set: arena_[out_begin, out_begin + out_count)
    std::uint32_t out_count = 0;
    std::uint32_t far = kNone;  // the outside point furthest from the plane (approximately)
    double far_dist = 0;
    std::uint32_t stamp = 0;
    bool visible = false;
    bool alive = false;
  };

  int side(const Face& f, std::uint32_t q) const {
    return Pred::orient3d(p_[f.v[0]], p_[f.v[1]], p_[f.v[2]], p_[q]);
  }
  std::uint32_t new_face(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  // Assigns each point of `pts` to the first face of `cands` it is strictly above (or drops it), storing
  // every face's new outside set contiguously at the end of the arena.
  void distribute(const std::vector<std::uint32_t>& pts, const std::vector<std::uint32_t>& cands);
  void compact_arena();
  void add_point(std::uint32_t f);
  static int edge_index(const Face& g, std::uint32_t from, std::uint32_t to) {
    for (int j = 0; j < 3; ++j)
      if (g.v[j] == from && g.v[(j + 1) % 3] == to) return j;
    throw std::logic_error("exact_hull: broken face adjacency");
  }

  const std::vector<Vec3d>& p_;
  // Outside sets live in slices of one arena (contiguous reads when a face is removed); removed slices are
  // garbage until the next compaction.
  std::vector<std::uint32_t> arena_;
  std::size_t live_ = 0;
  std::vector<std::uint32_t> start_face_;  // per horizon vertex: the new face whose base edge starts there
  std::vector<Face> faces_;
  std::vector<std::uint32_t> free_;  // reusable dead face slots
  std::vector<std::uint32_t> stack_;
  std::uint32_t stamp_ = 0;

  // Scratch for add_point, kept to avoid reallocation.
  std::vector<std::uint32_t> visible_;
  std::vector<std::uint32_t> pending_;
  struct HorizonEdge {
    std::uint32_t a, b, other;
  };
  std::vector<HorizonEdge> horizon_;
  std::vector<std::uint32_t> created_;
  std::vector<std::uint32_t> which_, counts_;
};

template <class Pred>
std::uint32_t QuickHull<Pred>::new_face(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  std::uint32_t f;
  if (!free_.empty()) {
    f = free_.back();
    free_.pop_back();
  } else {
    f = static_cast<std::uint32_t>(faces_.size());
    faces_.emplace_back();
  }
  Face& face = faces_[f];
  face = Face{};
  face.v = {a, b, c};
  face.nb = {kNone, kNone, kNone};
  face.normal = cross(sub(p_[b], p_[a]), sub(p_[c], p_[a]));
  face.far_dist = -std::numeric_limits<double>::infinity();
  face.alive = true;
  return f;
}

template <class Pred>
void QuickHull<Pred>::distribute(const std::vector<std::uint32_t>& pts,
                                 const std::vector<std::uint32_t>& cands) {
  const std::size_t nc = cands.size();
  which_.resize(pts.size());
  counts_.assign(nc, 0);
  std::size_t hint = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    which_[i] = kNone;
    for (std::size_t t = 0; t < nc; ++t) {
      const std::size_t k = (hint + t) % nc;  // neighbouring points tend to see the same face
      Face& F = faces_[cands[k]];
      if (side(F, pts[i]) > 0) {
        which_[i] = static_cast<std::uint32_t>(k);
        ++counts_[k];
        const double d = dot(F.normal, sub(p_[pts[i]], p_[F.v[0]]));
        if (F.far == kNone || d > F.far_dist) F.far_dist = d, F.far = pts[i];
        hint = k;
        break;
      }
    }
  }
  // Slices in the arena, then scatter.
  std::size_t pos = arena_.size(), total = 0;
  for (std::size_t k = 0; k < nc; ++k) {
    Face& F = faces_[cands[k]];
    F.out_begin = static_cast<std::uint32_t>(pos + total);
    F.out_count = 0;
    total += counts_[k];
    if (counts_[k] > 0) stack_.push_back(cands[k]);
  }
  arena_.resize(pos + total);
  live_ += total;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (which_[i] != kNone) {
      Face& F = faces_[cands[which_[i]]];
      arena_[F.out_begin + F.out_count++] = pts[i];
    }
}

template <class Pred>
void QuickHull<Pred>::compact_arena() {
  std::vector<std::uint32_t> fresh;
  fresh.reserve(live_ + live_ / 2);
  for (Face& F : faces_) {
    if (!F.alive || F.out_count == 0) continue;
    const std::uint32_t b = static_cast<std::uint32_t>(fresh.size());
    fresh.insert(fresh.end(), arena_.begin() + F.out_begin, arena_.begin() + F.out_begin + F.out_count);
    F.out_begin = b;
  }
  arena_.swap(fresh);
}

template <class Pred>
void QuickHull<Pred>::build(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  faces_.reserve(2 * p_.size() + 8);
  if (Pred::orient3d(p_[a], p_[b], p_[c], p_[d]) > 0) std::swap(b, c);  // now d is below (a, b, c)
  const std::uint32_t f0 = new_face(a, b, c), f1 = new_face(b, a, d), f2 = new_face(c, b, d),
                      f3 = new_face(a, c, d);
  // Link the tetrahedron by matching opposite edges.
  const std::uint32_t fs[4] = {f0, f1, f2, f3};
  for (std::uint32_t f : fs)
    for (int i = 0; i < 3; ++i)
      for (std::uint32_t g : fs) {
        if (g == f) continue;
        const Face& F = faces_[f];
        for (int j = 0; j < 3; ++j)
          if (faces_[g].v[j] == F.v[(i + 1) % 3] && faces_[g].v[(j + 1) % 3] == F.v[i]) faces_[f].nb[i] = g;
      }

  pending_.clear();
  for (std::uint32_t q = 0; q < p_.size(); ++q)
    if (q != a && q != b && q != c && q != d) pending_.push_back(q);
  distribute(pending_, {f0, f1, f2, f3});

  while (!stack_.empty()) {
    const std::uint32_t f = stack_.back();
    stack_.pop_back();
    if (faces_[f].alive && faces_[f].out_count != 0) add_point(f);
    if (arena_.size() > 2 * live_ + (1u << 20)) compact_arena();
  }
}

// Adds the furthest outside point of face f: removes every face it is strictly above (a connected set
// bounded by one simple horizon cycle, by convexity), and connects the horizon to it.
template <class Pred>
void QuickHull<Pred>::add_point(std::uint32_t f0) {
  const std::uint32_t eye = faces_[f0].far;
  const std::uint32_t stamp = ++stamp_;

  visible_.assign(1, f0);
  horizon_.clear();
  faces_[f0].stamp = stamp;
  faces_[f0].visible = true;
  for (std::size_t k = 0; k < visible_.size(); ++k) {
    const std::uint32_t f = visible_[k];
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = faces_[f].nb[i];
      Face& G = faces_[g];
      if (G.stamp != stamp) {
        G.stamp = stamp;
        G.visible = side(G, eye) > 0;
        if (G.visible) visible_.push_back(g);
      }
      if (!G.visible) horizon_.push_back({faces_[f].v[i], faces_[f].v[(i + 1) % 3], g});
    }
  }

  pending_.clear();
  for (std::uint32_t f : visible_) {
    Face& F = faces_[f];
    for (std::uint32_t k = F.out_begin, e = F.out_begin + F.out_count; k < e; ++k)
      if (arena_[k] != eye) pending_.push_back(arena_[k]);
    live_ -= F.out_count;
    F.out_count = 0;
    F.alive = false;
    free_.push_back(f);
  }

  // Cone of new faces (a, b, eye) over the horizon edges a -> b; the old face across keeps edge b -> a.
  created_.clear();
  for (const HorizonEdge& h : horizon_) {
    if (start_face_[h.a] != kNone) throw std::logic_error("exact_hull: horizon is not a simple cycle");
    const std::uint32_t nf = new_face(h.a, h.b, eye);
    faces_[nf].nb[0] = h.other;
    Face& other = faces_[h.other];
    other.nb[edge_index(other, h.b, h.a)] = nf;
    start_face_[h.a] = nf;
    created_.push_back(nf);
  }
  for (std::uint32_t nf : created_) {
    const std::uint32_t g = start_face_[faces_[nf].v[1]];
    if (g == kNone) throw std::logic_error("exact_hull: horizon is not a closed cycle");
    faces_[nf].nb[1] = g;  // edge b -> eye
    faces_[g].nb[2] = nf;  // edge eye -> b of the face starting at b
  }
  for (std::uint32_t nf : created_)
    start_face_[faces_[nf].v[0]] = kNone;

  // A pending point strictly above no new face is inside the new hull (it was above a removed face only).
  distribute(pending_, created_);
}

template <class Pred>
std::vector<Triangle> QuickHull<Pred>::polish() const {
  const std::uint32_t nf = static_cast<std::uint32_t>(faces_.size());
  // Union-find over faces: adjacent faces with exactly coplanar planes belong to one facet.
  std::vector<std::uint32_t> parent(nf);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::uint32_t f = 0; f < nf; ++f) {
    const Face& F = faces_[f];
    if (!F.alive) continue;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = F.nb[i];
      if (g < f) continue;  // each edge once
      const Face& G = faces_[g];
      const int j = edge_index(G, F.v[(i + 1) % 3], F.v[i]);
      if (side(F, G.v[(j + 2) % 3]) == 0) {
        const std::uint32_t rf = find(f), rg = find(g);
        if (rf != rg) parent[rf] = rg;
      }
    }
  }
  auto boundary = [&](std::uint32_t f, int i) { return find(f) != find(faces_[f].nb[i]); };

  // Each facet is a convex polygon (a disk): walk its boundary cycle counter-clockwise (seen from outside),
  // keep the strict corners and fan-triangulate over them.
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(nf) * 3, 0);
  std::vector<Triangle> tris;
  std::vector<std::uint32_t> cycle, corners;
  for (std::uint32_t f0 = 0; f0 < nf; ++f0) {
    if (!faces_[f0].alive) continue;
    for (int i0 = 0; i0 < 3; ++i0) {
      if (seen[f0 * 3 + i0] || !boundary(f0, i0)) continue;
      cycle.clear();
      std::uint32_t f = f0;
      int i = i0;
      do {
        seen[f * 3 + i] = 1;
        cycle.push_back(faces_[f].v[i]);
        // Rotate around the edge's end vertex through the facet to the next boundary edge leaving it.
        int k = (i + 1) % 3;
        while (!boundary(f, k)) {
          const std::uint32_t g = faces_[f].nb[k];
          const int j = edge_index(faces_[g], faces_[f].v[(k + 1) % 3], faces_[f].v[k]);
          f = g;
          k = (j + 1) % 3;
        }
        i = k;
      } while (f != f0 || i != i0);

      const std::size_t len = cycle.size();
      corners.clear();
      for (std::size_t t = 0; t < len; ++t) {
        const std::uint32_t prev = cycle[(t + len - 1) % len], cur = cycle[t], next = cycle[(t + 1) % len];
        if (!Pred::collinear3d(p_[prev], p_[cur], p_[next])) corners.push_back(cur);
      }
      if (corners.size() < 3) throw std::logic_error("exact_hull: degenerate facet");
      for (std::size_t t = 1; t + 1 < corners.size(); ++t)
        tris.push_back({corners[0], corners[t], corners[t + 1]});
    }
  }
  return tris;
}

// 2D hull of coplanar distinct points: Andrew's monotone chain on the projection that drops one axis of the
// plane's normal N = (b - a) x (c - a) (the basis points), with exact orient2d.  The projection keeps the
// axes in cyclic order ((y,z), (z,x), (x,y)), so its orientation is sign(N_k) for the dropped axis k.
//
// Output: the strict corners, counter-clockwise seen from the side of the plane's canonical normal n, which
// is the normal whose first non-zero component (x, then y, then z) is positive; the polygon starts at its
// lexicographically smallest corner.
template <class Pred>
std::vector<std::uint32_t> hull_2d(const std::vector<Vec3d>& p, const Basis& bs) {
  const Vec3d a = p[bs.a], b = p[bs.b], c = p[bs.c];
  auto coord = [](const Vec3d& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
  int sign_n[3];
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    sign_n[k] = Pred::orient2d(coord(a, u), coord(a, v), coord(b, u), coord(b, v), coord(c, u), coord(c, v));
  }
  const int sigma = sign_n[0] != 0 ? sign_n[0] : sign_n[1] != 0 ? sign_n[1] : sign_n[2];
  // Drop the dominant axis (better conditioned projection) among those with an exactly non-zero component.
  const Vec3d nrm = cross(sub(b, a), sub(c, a));
  int k = -1;
  double best = -1;
  for (int t = 0; t < 3; ++t) {
    const double mag = std::fabs(coord(nrm, t));
    if (sign_n[t] != 0 && (k < 0 || mag > best)) best = mag, k = t;  // k < 0: NaN for huge doubles
  }
  const int u = (k + 1) % 3, v = (k + 2) % 3;

  const std::uint32_t m = static_cast<std::uint32_t>(p.size());
  std::vector<std::uint32_t> order(m);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
    const double iu = coord(p[i], u), ju = coord(p[j], u);
    if (iu != ju) return iu < ju;
    return coord(p[i], v) < coord(p[j], v);
  });
  auto turn = [&](std::uint32_t i, std::uint32_t j, std::uint32_t l) {
    return Pred::orient2d(coord(p[i], u), coord(p[i], v), coord(p[j], u), coord(p[j], v), coord(p[l], u),
                          coord(p[l], v));
  };
  // Distinct coplanar points project to distinct points, so the chain is well defined; popping on <= 0
  // removes collinear points, leaving strict corners.
  std::vector<std::uint32_t> h(2 * m);
  std::size_t len = 0;
  for (std::uint32_t i = 0; i < m; ++i) {
    while (len >= 2 && turn(h[len - 2], h[len - 1], order[i]) <= 0)
      --len;
    h[len++] = order[i];
  }
  for (std::size_t i = m - 1, lower = len + 1; i-- > 0;) {
    while (len >= lower && turn(h[len - 2], h[len - 1], order[i]) <= 0)
      --len;
    h[len++] = order[i];
  }
  h.resize(len - 1);  // the last point repeats the first
  if (sigma * sign_n[k] < 0) std::reverse(h.begin(), h.end());
  // Start at the lexicographically smallest corner.
  std::rotate(h.begin(),
              std::min_element(h.begin(), h.end(),
                               [&](std::uint32_t i, std::uint32_t j) { return lex_less(p[i], p[j]); }),
              h.end());
  return h;
}

// exact_hull() deciding with the predicates of Pred.
template <class Pred, class Point>
BasicHullMesh<Point> hull_with(const std::vector<Point>& points, const std::vector<PointIndex>& ids) {
  const std::size_t n = ids.empty() ? points.size() : ids.size();
  if (n >= kNone) throw std::length_error("exact_hull: too many points");

  // Distinct points, each carrying the lowest input index of its coordinates: only that index may become a
  // vertex.
  std::vector<Site<Point>> sites(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PointIndex id = ids.empty() ? static_cast<PointIndex>(i) : ids[i];
    if (id >= points.size())
      throw std::out_of_range("exact_hull: id " + std::to_string(id) + " out of range");
    const Point& q = points[id];
    sites[i] = {q.x, q.y, q.z, id};
  }
  sort_and_dedupe(sites);
  const std::size_t m = sites.size();
  // The vertex coordinates are those of the vertex's own input point (+0 and -0 compared equal above).
  for (Site<Point>& s : sites) {
    const Point& q = points[s.id];
    s.x = q.x, s.y = q.y, s.z = q.z;
  }

  std::vector<Vec3d> p(m);
  for (std::size_t i = 0; i < m; ++i)
    p[i] = {sites[i].x, sites[i].y, sites[i].z};
  const Basis bs = find_basis<Pred>(m, [&](std::uint32_t i) { return p[i]; });

  std::vector<std::uint32_t> out_index;
  switch (bs.dim) {
    case -1: {
      BasicHullMesh<Point> empty;
      empty.dimension = -1;
      return empty;
    }
    case 0:
      return make_mesh<Point>(sites, {bs.a}, 0, out_index);
    case 1:
      return make_mesh<Point>(sites, {bs.a, bs.b}, 1, out_index);
    case 2: {
      const std::vector<std::uint32_t> poly = hull_2d<Pred>(p, bs);
      BasicHullMesh<Point> mesh = make_mesh(sites, poly, 2, out_index);
      for (std::uint32_t s : poly)
        mesh.polygon.push_back(out_index[s]);
      return mesh;
    }
    default:
      break;
  }

  QuickHull<Pred> qh(p);
  qh.build(bs.a, bs.b, bs.c, bs.d);
  std::vector<Triangle> tris = qh.polish();
  std::vector<std::uint8_t> used(m, 0);
  for (const Triangle& t : tris)
    for (std::uint32_t v : t)
      used[v] = 1;
  std::vector<std::uint32_t> keep;
  for (std::uint32_t i = 0; i < m; ++i)
    if (used[i]) keep.push_back(i);
  BasicHullMesh<Point> mesh = make_mesh(sites, std::move(keep), 3, out_index);
  mesh.triangles.reserve(tris.size());
  for (const Triangle& t : tris)
    mesh.triangles.push_back({out_index[t[0]], out_index[t[1]], out_index[t[2]]});
  return mesh;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------

template <class Point>
int affine_dimension(const std::vector<Point>& points) {
  return find_basis<FastPredicates>(points.size(), [&](std::uint32_t i) { return to_vec3d(points[i]); }).dim;
}

template <class Point>
BasicHullMesh<Point> exact_hull(const std::vector<Point>& points, const std::vector<PointIndex>& ids) {
  return hull_with<FastPredicates>(points, ids);
}

bool in_fast_exact_range(const Point3d* points, std::size_t count) {
  // Every point tested, without a branch a coordinate: a small cloud's check costs a few comparisons.
  bool in_range = true;
  for (std::size_t i = 0; i < count; ++i)
    in_range &= in_fast_exact_range(points[i].x) & in_fast_exact_range(points[i].y) &
                in_fast_exact_range(points[i].z);
  return in_range;
}

bool in_fast_exact_range(const std::vector<Point3d>& points) {
  return in_fast_exact_range(points.data(), points.size());
}

HullMeshd exact_hull_any(const std::vector<Point3d>& points, const std::vector<PointIndex>& ids) {
  const std::size_t n = ids.empty() ? points.size() : ids.size();
  // The binades (floor(log2 |c|)) of the nonzero coordinates that take part; ids out of range are left to
  // exact_hull(), which reports them.
  bool fast = true;
  int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
  for (std::size_t i = 0; i < n; ++i) {
    const PointIndex id = ids.empty() ? static_cast<PointIndex>(i) : ids[i];
    if (id >= points.size()) continue;
    for (const double c : {points[id].x, points[id].y, points[id].z}) {
      if (!std::isfinite(c))
        throw std::invalid_argument("exact_hull_any: point " + std::to_string(id) +
                                    " has a coordinate that is not finite");
      fast = fast && in_fast_exact_range(c);
      if (c == 0.0) continue;
      const int b = std::ilogb(c);  // exact for subnormals too
      lo = std::min(lo, b), hi = std::max(hi, b);
    }
  }
  if (fast) return hull_with<FastPredicates>(points, ids);

  // One power of two 2^k that moves every binade into -250..249 (the fast range) exists when
  // -250 - lo <= 249 - hi; the scaled coordinates are normal doubles, so the scaling is exact, keeps
  // equality and order (dedupe, tie-breaks, the lexicographic extremes) and the sign of every predicate.
  const int k_min = -250 - lo, k_max = 249 - hi;
  if (k_min <= k_max) {
    const int k = k_min + (k_max - k_min) / 2;   // centred: leaves the ranking arithmetic room both ways
    std::vector<Point3d> scaled(points.size());  // only the points taking part are read
    for (std::size_t i = 0; i < n; ++i) {
      const PointIndex id = ids.empty() ? static_cast<PointIndex>(i) : ids[i];
      if (id >= points.size()) continue;
      const Point3d& q = points[id];
      scaled[id] = {std::ldexp(q.x, k), std::ldexp(q.y, k), std::ldexp(q.z, k)};
    }
    HullMeshd mesh = hull_with<FastPredicates>(scaled, ids);
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      mesh.vertices[v] = points[mesh.vertex_ids[v]];  // the input's own coordinates, -0 included
    return mesh;
  }
  return hull_with<WidePredicates>(points, ids);
}

// The two point types; one implementation.
template HullMesh exact_hull(const std::vector<Point3>&, const std::vector<PointIndex>&);
template HullMeshd exact_hull(const std::vector<Point3d>&, const std::vector<PointIndex>&);
template int affine_dimension(const std::vector<Point3>&);
template int affine_dimension(const std::vector<Point3d>&);

}  // namespace cudahull
