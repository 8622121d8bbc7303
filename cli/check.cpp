// `cudahull check POINTS HULL`: an exact certificate for a hull from any tool.  The hull's faces (OBJ, OFF,
// PLY, Qhull's `o` output) are matched to the input points by coordinates and judged by check_hull(), the
// checker behind `hull --verify`; a list of point ids is compared with exact_hull()'s vertex set.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "commands.hpp"
#include "cudahull/convex_hull.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/face_io.hpp"
#include "cudahull/hull_checker.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/predicates.hpp"
#include "cudahull/wide_predicates.hpp"

namespace cudahull::cli {
namespace {

// Qhull prints coordinates with %.16g: a double that needs 17 digits comes back within a relative 5e-16.
// Such a vertex is the input point within this relative distance on every axis, where exactly one is.
constexpr double kQhullRelativeTolerance = 0x1p-49;  // about 1.8e-15

std::string coords(const Point3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.9g %.9g %.9g)", p.x, p.y, p.z);
  return buf;
}
std::string coords(const Point3d& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g %.17g %.17g)", p.x, p.y, p.z);
  return buf;
}

// Coordinates as a hash key; +0 and -0 are one coordinate, as == says.
template <class Point>
struct PointHash {
  static std::uint64_t bits(double v) {
    if (v == 0) v = 0;
    std::uint64_t u;
    std::memcpy(&u, &v, 8);
    return u;
  }
  std::size_t operator()(const Point& p) const {
    std::uint64_t h = bits(p.x) * 0x9E3779B97F4A7C15ull;
    h ^= (h >> 29) + bits(p.y) * 0xBF58476D1CE4E5B9ull;
    h ^= (h >> 31) + bits(p.z) * 0x94D049BB133111EBull;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};
template <class Point>
struct PointEq {
  bool operator()(const Point& a, const Point& b) const { return a == b; }
};
template <class Point>
using PointMap = std::unordered_map<Point, std::uint32_t, PointHash<Point>, PointEq<Point>>;

// One "x y z" as the point readers read it (float rounded once, double as given).
Point3 parse_point(std::istream& in, const std::string& name, Point3*) {
  return read_points(in, PointFormat::kXyz, name).at(0);
}
Point3d parse_point(std::istream& in, const std::string& name, Point3d*) {
  return read_points_double(in, PointFormat::kXyz, name).points.at(0);
}

bool close(double a, double b) {
  return a == b || std::fabs(a - b) <= kQhullRelativeTolerance * std::max(std::fabs(a), std::fabs(b));
}

// The input point within Qhull's printing tolerance of q, where there is exactly one (up to duplicates);
// `by_x` is the points' indices sorted by x.
template <class Point>
std::int64_t nearest_within_tolerance(const std::vector<Point>& pts, const std::vector<std::uint32_t>& by_x,
                                      const Point& q) {
  const double slack = kQhullRelativeTolerance * 2 * std::fabs(static_cast<double>(q.x));
  auto lo = std::lower_bound(by_x.begin(), by_x.end(), q.x - slack,
                             [&](std::uint32_t i, double x) { return pts[i].x < x; });
  std::int64_t found = -1;
  for (auto it = lo; it != by_x.end() && pts[*it].x <= q.x + slack; ++it) {
    const Point& p = pts[*it];
    if (!close(p.x, q.x) || !close(p.y, q.y) || !close(p.z, q.z)) continue;
    if (found >= 0 && !(pts[found] == p)) return -2;  // two different points: ambiguous
    if (found < 0 || *it < found) found = *it;
  }
  return found;
}

struct Outcome {
  std::vector<std::string> failures;
  std::string summary;
};

// Polygon face f (its corners as hull vertices): corners coplanar and turning one way, so that its fan
// covers it once.  Returns the problem, or empty.
template <class Point>
std::string polygon_problem(const std::vector<Point>& v, const std::uint32_t* c, std::size_t n, bool wide) {
  auto V = [&](std::size_t k) { return to_vec3d(v[c[k]]); };
  auto orient = [&](const Vec3d& a, const Vec3d& b, const Vec3d& cc, const Vec3d& d) {
    return wide ? orient3d_wide(a, b, cc, d) : orient3d(a, b, cc, d);
  };
  auto collinear = [&](const Vec3d& a, const Vec3d& b, const Vec3d& cc) {
    return wide ? collinear3d_wide(a, b, cc) : collinear3d(a, b, cc);
  };
  std::size_t third = n;
  for (std::size_t k = 2; k < n && third == n; ++k)
    if (!collinear(V(0), V(1), V(k))) third = k;
  if (third == n) return "its corners are collinear";
  for (std::size_t k = 2; k < n; ++k)
    if (orient(V(0), V(1), V(third), V(k)) != 0)
      return "it is not planar: corner " + std::to_string(k) + " is off the plane of corners 0, 1 and " +
             std::to_string(third);
  // Project along an axis the plane is not parallel to; the turns must all have one sign (or be 0).
  auto coord = [](const Vec3d& p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; };
  int axis = -1;
  for (int t = 0; t < 3 && axis < 0; ++t) {
    const int a = (t + 1) % 3, b = (t + 2) % 3;
    const Vec3d p = V(0), q = V(1), r = V(third);
    const int s =
        wide ? orient2d_wide(coord(p, a), coord(p, b), coord(q, a), coord(q, b), coord(r, a), coord(r, b))
             : orient2d(coord(p, a), coord(p, b), coord(q, a), coord(q, b), coord(r, a), coord(r, b));
    if (s != 0) axis = t;
  }
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  auto turn = [&](std::size_t i, std::size_t j, std::size_t k) {
    const Vec3d p = V(i), q = V(j), r = V(k);
    return wide ? orient2d_wide(coord(p, a), coord(p, b), coord(q, a), coord(q, b), coord(r, a), coord(r, b))
                : orient2d(coord(p, a), coord(p, b), coord(q, a), coord(q, b), coord(r, a), coord(r, b));
  };
  int sign = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const int s = turn(k, (k + 1) % n, (k + 2) % n);
    if (s != 0 && sign != 0 && s != sign)
      return "it is not convex: it turns the other way at corner " + std::to_string((k + 1) % n);
    if (s != 0) sign = s;
  }
  // Turning one way everywhere and once round: one lexicographic maximum along the cycle.
  auto key = [&](std::size_t k) { return std::make_pair(coord(V(k), a), coord(V(k), b)); };
  std::size_t maxima = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (key((k + n - 1) % n) < key(k) && key((k + 1) % n) < key(k)) ++maxima;
  if (maxima != 1) return "it winds " + std::to_string(maxima) + " times around its interior";
  return {};
}

// check_hull() names a triangle as "face T"; where polygons were split into fans, T becomes the file's face.
std::string renumber_faces(const std::string& line, const std::vector<std::uint32_t>& face_of) {
  std::string out;
  std::size_t i = 0;
  while (i < line.size()) {
    const std::size_t at = line.find("face ", i);
    if (at == std::string::npos || (at > 0 && std::isalpha(static_cast<unsigned char>(line[at - 1])))) {
      const std::size_t end = at == std::string::npos ? line.size() : at + 5;
      out.append(line, i, end - i);
      i = end;
      continue;
    }
    out.append(line, i, at + 5 - i);
    std::size_t j = at + 5;
    std::uint64_t t = 0;
    while (j < line.size() && std::isdigit(static_cast<unsigned char>(line[j])))
      t = t * 10 + static_cast<std::uint64_t>(line[j++] - '0');
    if (j > at + 5 && t < face_of.size())
      out += std::to_string(face_of[t]);
    else
      out.append(line, at + 5, j - at - 5);
    i = j;
  }
  return out;
}

// HULL as faces: matched to POINTS, polygons checked and split into fans, then check_hull().
template <class Point>
Outcome check_faces(const std::vector<Point>& pts, const CheckOptions& o) {
  Outcome r;
  const BasicFaceMesh<Point> mesh = read_faces<Point>(o.hull);
  const std::size_t nf = mesh.face_count();
  // The hull's vertices: the file's vertices that a face uses (all of them without faces), welded by
  // coordinates.  Qhull's `o` lists every input point, so unused ones are no error.
  std::vector<std::uint8_t> used(mesh.vertex_count, nf == 0 ? 1 : 0);
  for (std::uint32_t c : mesh.corners)
    used[c] = 1;
  PointMap<Point> weld;
  std::vector<std::uint32_t> file_to_hull(mesh.vertex_count, 0xffffffffu);
  std::vector<Point> hv;          // the hull's vertices as the file gives them
  std::vector<std::uint32_t> fv;  // and a file vertex of each, for messages
  for (std::uint32_t i = 0; i < mesh.vertex_count; ++i) {
    if (!used[i]) continue;
    const auto [it, fresh] = weld.emplace(mesh.vertices[i], static_cast<std::uint32_t>(hv.size()));
    if (fresh) hv.push_back(mesh.vertices[i]), fv.push_back(i);
    file_to_hull[i] = it->second;
  }
  // Each hull vertex's input point: the lowest index with its coordinates.
  std::vector<std::int64_t> id(hv.size(), -1);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto it = weld.find(pts[i]);
    if (it != weld.end() && id[it->second] < 0) id[it->second] = static_cast<std::int64_t>(i);
  }
  std::size_t rounded = 0;
  std::vector<std::uint32_t> by_x;
  for (std::size_t v = 0; v < hv.size(); ++v) {
    if (id[v] >= 0) continue;
    if (mesh.qhull_off) {
      if (by_x.empty()) {
        by_x.resize(pts.size());
        for (std::uint32_t i = 0; i < pts.size(); ++i)
          by_x[i] = i;
        std::sort(by_x.begin(), by_x.end(),
                  [&](std::uint32_t a, std::uint32_t b) { return pts[a].x < pts[b].x; });
      }
      const std::int64_t near = nearest_within_tolerance(pts, by_x, hv[v]);
      if (near >= 0) {
        id[v] = near, ++rounded;
        continue;
      }
      if (near == -2) {
        r.failures.push_back("hull vertex " + std::to_string(fv[v]) + " " + coords(hv[v]) + " of " + o.hull +
                             " is within Qhull's printing precision of two different input points");
        continue;
      }
    }
    r.failures.push_back("hull vertex " + std::to_string(fv[v]) + " " + coords(hv[v]) + " of " + o.hull +
                         " is not an input point");
  }
  if (!r.failures.empty()) return r;

  BasicHullMesh<Point> hull;
  for (std::size_t v = 0; v < hv.size(); ++v) {
    hull.vertex_ids.push_back(static_cast<PointIndex>(id[v]));
    hull.vertices.push_back(pts[static_cast<std::size_t>(id[v])]);
  }
  bool wide = false;
  if constexpr (std::is_same_v<Point, Point3d>) wide = !in_fast_exact_range(hull.vertices);
  // The dimension the file claims, from its faces alone (check_hull compares it with the points'): one
  // face is a polygon, none a segment or a point.
  std::vector<std::uint32_t> face_of;  // per triangle, the file's face
  bool split = false;
  if (nf == 1) {
    hull.dimension = 2;
    for (std::size_t c = mesh.face_start[0]; c < mesh.face_start[1]; ++c)
      hull.polygon.push_back(file_to_hull[mesh.corners[c]]);
  } else if (nf == 0) {
    hull.dimension = hv.size() == 1 ? 0 : 1;
  } else {
    hull.dimension = 3;
    std::vector<std::uint32_t> poly;
    for (std::size_t f = 0; f < nf; ++f) {
      poly.clear();
      for (std::size_t c = mesh.face_start[f]; c < mesh.face_start[f + 1]; ++c)
        poly.push_back(file_to_hull[mesh.corners[c]]);
      // Qhull's `o` lists a facet's vertices clockwise seen from outside: counter-clockwise is outward here.
      if (mesh.qhull_off) std::reverse(poly.begin(), poly.end());
      if (poly.size() > 3) {
        split = true;
        const std::string problem = polygon_problem(hull.vertices, poly.data(), poly.size(), wide);
        if (!problem.empty()) {
          r.failures.push_back("face " + std::to_string(f) + " (" + std::to_string(poly.size()) +
                               " corners) is no convex polygon: " + problem);
          continue;
        }
      }
      for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
        hull.triangles.push_back({poly[0], poly[k], poly[k + 1]});
        face_of.push_back(static_cast<std::uint32_t>(f));
      }
    }
    if (!r.failures.empty()) return r;
  }
  const CheckResult check = check_hull(pts, hull);
  for (const std::string& line : check.failures)
    r.failures.push_back(split ? renumber_faces(line, face_of) : line);
  if (check.ok && r.failures.empty()) {
    char buf[512];
    if (hull.dimension == 3)
      std::snprintf(
          buf, sizeof buf,
          "%zu vertices, %zu faces (%zu triangles): the exact hull of the %zu points (closed, outward, "
          "convex, every vertex strictly extreme, every point inside)",
          hv.size(), nf, hull.triangles.size(), pts.size());
    else
      std::snprintf(buf, sizeof buf, "%zu vertices: the exact hull of the %zu points, which are %s",
                    hv.size(), pts.size(),
                    hull.dimension == 2   ? "coplanar (a convex polygon)"
                    : hull.dimension == 1 ? "collinear (a segment)"
                                          : "one point");
    r.summary = buf;
    if (rounded > 0)
      r.summary += "; " + std::to_string(rounded) +
                   " vertices matched their input point within Qhull's 16 printed digits";
  }
  if (!check.ok && r.failures.empty()) r.failures.push_back("the checker found the hull wrong");
  return r;
}

// HULL as point ids, one a line ("index" or "index x y z", as --vertices-out writes): exactly the strictly
// extreme points, by exact_hull(); any one index among identical points.
template <class Point>
Outcome check_ids(const std::vector<Point>& pts, const CheckOptions& o) {
  Outcome r;
  std::ifstream in(o.hull, std::ios::binary);
  std::error_code ec;
  if (std::filesystem::is_directory(o.hull, ec)) throw InputError(o.hull + ": is a directory");
  if (!in) throw InputError(o.hull + ": cannot open: " + std::strerror(errno));
  std::vector<std::pair<std::uint64_t, std::uint64_t>> listed;  // (id, line)
  std::string line;
  std::uint64_t ln = 0;
  while (std::getline(in, line)) {
    ++ln;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    char* end = nullptr;
    const char* s = line.c_str();
    while (*s == ' ' || *s == '\t' || *s == '\r')
      ++s;
    if (*s == '\0') continue;
    if (*s < '0' || *s > '9') throw InputError(o.hull + ":" + std::to_string(ln) + ": expected a point id");
    errno = 0;
    const unsigned long long v = std::strtoull(s, &end, 10);
    if (errno != 0) throw InputError(o.hull + ":" + std::to_string(ln) + ": the id is too large");
    const std::string rest = end;
    if (v >= pts.size()) {
      r.failures.push_back("line " + std::to_string(ln) + ": id " + std::to_string(v) + " is beyond the " +
                           std::to_string(pts.size()) + " input points");
      continue;
    }
    // Coordinates after the id (--vertices-out's lines) must be the point's.
    if (rest.find_first_not_of(" \t\r") != std::string::npos) {
      std::istringstream words(rest);
      std::string t[3];
      std::string extra;
      if (!(words >> t[0] >> t[1] >> t[2]) || (words >> extra))
        throw InputError(o.hull + ":" + std::to_string(ln) + ": expected 'id' or 'id x y z'");
      std::istringstream xyz(t[0] + " " + t[1] + " " + t[2]);
      const Point p = parse_point(xyz, o.hull + ":" + std::to_string(ln), static_cast<Point*>(nullptr));
      if (!(p == pts[v]))
        r.failures.push_back("line " + std::to_string(ln) + ": id " + std::to_string(v) +
                             " has coordinates " + coords(p) + " but input point " + std::to_string(v) +
                             " is " + coords(pts[v]));
    }
    listed.emplace_back(v, ln);
  }
  // Each listed id's coordinates as their lowest index.
  PointMap<Point> first;
  for (const auto& [v, l] : listed)
    first.emplace(pts[v], 0xffffffffu);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto it = first.find(pts[i]);
    if (it != first.end() && it->second == 0xffffffffu) it->second = static_cast<std::uint32_t>(i);
  }
  std::unordered_map<std::uint32_t, std::uint64_t> canon;  // lowest index -> the line listing it
  for (const auto& [v, l] : listed) {
    const std::uint32_t c = first.at(pts[v]);
    const auto [it, fresh] = canon.emplace(c, l);
    if (!fresh)
      r.failures.push_back("line " + std::to_string(l) + ": id " + std::to_string(v) + " " + coords(pts[v]) +
                           " is listed again (line " + std::to_string(it->second) +
                           " lists the same coordinates)");
  }
  std::vector<PointIndex> reference;
  if constexpr (std::is_same_v<Point, Point3d>)
    reference = exact_hull_any(pts).vertex_ids;
  else
    reference = exact_hull(pts).vertex_ids;
  std::vector<std::uint8_t> extreme(pts.size(), 0);
  for (PointIndex v : reference)
    extreme[v] = 1;
  std::vector<std::pair<std::uint32_t, std::uint64_t>> sorted(canon.begin(), canon.end());
  std::sort(sorted.begin(), sorted.end());
  for (const auto& [c, l] : sorted)
    if (!extreme[c])
      r.failures.push_back("line " + std::to_string(l) + ": point " + std::to_string(c) + " " +
                           coords(pts[c]) + " is listed but is not strictly extreme");
  for (PointIndex v : reference)
    if (!canon.count(v))
      r.failures.push_back("point " + std::to_string(v) + " " + coords(pts[v]) +
                           " is strictly extreme but is not listed");
  if (r.failures.empty())
    r.summary = std::to_string(canon.size()) + " ids: exactly the strictly extreme points of the " +
                std::to_string(pts.size()) + " points";
  return r;
}

template <class Point>
int check_in(const CheckOptions& o, Precision precision) {
  const std::vector<Point> pts = read_input<Point>(o.points, true);
  const std::string ext = [&] {
    std::string e = std::filesystem::path(o.hull).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
    return e;
  }();
  const bool faces = ext == ".obj" || ext == ".off" || ext == ".ply";
  const Outcome r = faces ? check_faces(pts, o) : check_ids(pts, o);
  if (!r.failures.empty()) {
    for (const std::string& line : r.failures)
      std::fprintf(stderr, "check: %s\n", line.c_str());
    std::fprintf(stderr,
                 "cudahull: error: check failed: %s is not the exact hull of %s (%s): %zu problem(s)\n",
                 o.hull.c_str(), o.points.c_str(), precision_name(precision), r.failures.size());
    return kExitVerifyFailed;
  }
  std::printf("OK: %s: %s (%s)\n", o.hull.c_str(), r.summary.c_str(), precision_name(precision));
  return kExitOk;
}

}  // namespace

int run_check(const CheckOptions& o) {
  const Precision precision = resolve_precision(precision_from_name_strict(o.precision), o.points);
  return precision == Precision::kDouble ? check_in<Point3d>(o, precision) : check_in<Point3>(o, precision);
}

}  // namespace cudahull::cli
