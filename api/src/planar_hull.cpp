// planar_hull(): an Akl-Toussaint filter on all cores, then Andrew's monotone chain on the few points left
// (design in planar_hull.hpp).
#include "planar_hull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "cudahull/parallel.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull {

namespace {

// A point as the chain sorts it: coordinates widened to double (exact for float input), then the index,
// so that among identical coordinates the lowest index comes first.
struct Entry {
  double x, y;
  PointIndex index;
  friend bool operator<(const Entry& a, const Entry& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.index < b.index;
  }
};

int orient(const Entry& a, const Entry& b, const Entry& c) {
  return orient2d(a.x, a.y, b.x, b.y, c.x, c.y);
}

template <class T>
struct Cloud {
  const T* xy;
  double x(std::size_t i) const { return static_cast<double>(xy[2 * i]); }
  double y(std::size_t i) const { return static_cast<double>(xy[2 * i + 1]); }
  Entry entry(PointIndex i) const { return {x(i), y(i), i}; }
};

// The points a pass visits: all of them (round one), or the survivors of the last round.
struct AllPoints {
  std::size_t count;
  std::size_t size() const { return count; }
  PointIndex operator[](std::size_t k) const { return static_cast<PointIndex>(k); }
};
struct SomePoints {
  const std::vector<PointIndex>* list;
  std::size_t size() const { return list->size(); }
  PointIndex operator[](std::size_t k) const { return (*list)[k]; }
};

// Below this many points a pass runs on the calling thread: waking a worker costs more.
constexpr std::size_t kGrain = std::size_t{1} << 14;

// Andrew's monotone chain over sorted entries with distinct coordinates: positions of the strict corners,
// counter-clockwise from the first entry.  Popping on orient2d <= 0 drops the points inside an edge; for
// collinear input it leaves the two ends, for one entry that entry.
std::vector<std::size_t> monotone_chain(const std::vector<Entry>& sorted) {
  const std::size_t n = sorted.size();
  if (n <= 2) {
    std::vector<std::size_t> all(n);
    for (std::size_t k = 0; k < n; ++k)
      all[k] = k;
    return all;
  }
  std::vector<std::size_t> hull(2 * n);
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {  // lower chain, left to right
    while (k >= 2 && orient(sorted[hull[k - 2]], sorted[hull[k - 1]], sorted[i]) <= 0)
      --k;
    hull[k++] = i;
  }
  for (std::size_t i = n - 1, lower = k + 1; i-- > 0;) {  // upper chain, right to left
    while (k >= lower && orient(sorted[hull[k - 2]], sorted[hull[k - 1]], sorted[i]) <= 0)
      --k;
    hull[k++] = i;
  }
  hull.resize(k - 1);  // the first entry closes the upper chain
  return hull;
}

// Sorts, keeps the lowest index of each set of identical coordinates, and returns the chain's corners.
std::vector<Entry> exact_hull(std::vector<Entry> entries) {
  std::sort(entries.begin(), entries.end());
  entries.erase(std::unique(entries.begin(), entries.end(),
                            [](const Entry& a, const Entry& b) { return a.x == b.x && a.y == b.y; }),
                entries.end());
  std::vector<Entry> corners;
  for (std::size_t k : monotone_chain(entries))
    corners.push_back(entries[k]);
  return corners;
}

// The input points furthest along +-u for `kAxes` directions u spread over half a turn, in plain double
// arithmetic: a rounding that picks a point a little less far only makes the inner polygon a little
// smaller, so nothing here needs to be exact.
template <std::size_t kAxes, class T, class Points>
std::vector<PointIndex> extremes(const Cloud<T>& cloud, const Points& points, unsigned workers) {
  std::array<double, kAxes> ux, uy;
  for (std::size_t a = 0; a < kAxes; ++a) {
    const double angle = std::numbers::pi * static_cast<double>(a) / kAxes;
    ux[a] = std::cos(angle);
    uy[a] = std::sin(angle);
  }
  struct Best {
    std::array<double, kAxes> low, high;
    std::array<PointIndex, kAxes> low_at, high_at;
  };
  // A chunk that does not run leaves +-infinity, which never wins over a point.
  Best none;
  none.low.fill(std::numeric_limits<double>::infinity());
  none.high.fill(-std::numeric_limits<double>::infinity());
  none.low_at.fill(points[0]);
  none.high_at.fill(points[0]);
  std::vector<Best> best(workers, none);
  parallel_chunks(
      points.size(), workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        Best b = none;
        // Block by block: the block's least and greatest value along each axis without a branch, and only
        // where one beats the best so far (rarely, after the first blocks) a scan for its point.  Which of
        // equal values wins, or whether a rounding differs between the two loops, does not matter.
        constexpr std::size_t kBlock = 128;
        double bx[kBlock], by[kBlock];
        for (std::size_t k = begin; k < end; k += kBlock) {
          const std::size_t n = std::min(kBlock, end - k);
          for (std::size_t j = 0; j < n; ++j) {
            const PointIndex i = points[k + j];
            bx[j] = cloud.x(i);
            by[j] = cloud.y(i);
          }
          // The axes inside the point loop: 2 * kAxes independent minima and maxima (one axis at a time
          // waited on the latency of each min and max).
          std::array<double, kAxes> low = b.low, high = b.high;
          for (std::size_t j = 0; j < n; ++j)
            for (std::size_t a = 0; a < kAxes; ++a) {
              const double d = ux[a] * bx[j] + uy[a] * by[j];
              low[a] = d < low[a] ? d : low[a];
              high[a] = d > high[a] ? d : high[a];
            }
          for (std::size_t a = 0; a < kAxes; ++a) {
            if (low[a] < b.low[a] || high[a] > b.high[a]) {
              for (std::size_t j = 0; j < n; ++j) {
                const double d = ux[a] * bx[j] + uy[a] * by[j];
                if (d < b.low[a]) b.low[a] = d, b.low_at[a] = points[k + j];
                if (d > b.high[a]) b.high[a] = d, b.high_at[a] = points[k + j];
              }
            }
          }
        }
        best[worker] = b;
      },
      kGrain);
  std::vector<PointIndex> found;
  for (std::size_t a = 0; a < kAxes; ++a) {
    const Best* low = &best[0];
    const Best* high = &best[0];
    for (const Best& b : best) {
      if (b.low[a] < low->low[a]) low = &b;
      if (b.high[a] > high->high[a]) high = &b;
    }
    found.push_back(low->low_at[a]);
    found.push_back(high->high_at[a]);
  }
  return found;
}

// The pseudo-angle of (dx, dy) in [0, 4): increasing counter-clockwise from +x like the angle, without a
// transcendental.  Only ever a guess (of a fan sector), so its rounding does not matter.
double pseudo_angle(double dx, double dy) {
  const double p = dx / (std::fabs(dx) + std::fabs(dy));
  // 1 - p above the x axis, 3 + p below, without a branch: half the points would mispredict it.
  const double side = std::copysign(1.0, dy);
  return (2 - side) - side * p;
}

// A convex polygon of input points (strict corners, counter-clockwise) and an exact test for "strictly
// inside" that costs a few comparisons or three orient2d per point instead of one orient2d per edge.
class InnerPolygon {
 public:
  explicit InnerPolygon(const std::vector<Entry>& corners) {
    const std::size_t m = corners.size();
    double sx = 0, sy = 0;
    for (const Entry& c : corners)
      sx += c.x, sy += c.y;
    ox_ = sx / static_cast<double>(m);
    oy_ = sy / static_cast<double>(m);
    // The fan's centre must be strictly inside, exactly; the corners' mean is, but for rounding in a
    // sliver.  Without it every test goes edge by edge.
    x_.resize(m), y_.resize(m);
    for (std::size_t k = 0; k < m; ++k)
      x_[k] = corners[k].x, y_[k] = corners[k].y;
    fan_ = inside_by_edges(ox_, oy_);
    if (!fan_) return;
    // The corners from the smallest pseudo-angle around the centre on, and per bin of pseudo-angle how many
    // lie at or below its start: the table that finds a point's sector.
    std::vector<double> angle(m);
    for (std::size_t k = 0; k < m; ++k)
      angle[k] = pseudo_angle(x_[k] - ox_, y_[k] - oy_);
    const std::size_t first =
        static_cast<std::size_t>(std::min_element(angle.begin(), angle.end()) - angle.begin());
    std::rotate(x_.begin(), x_.begin() + first, x_.end());
    std::rotate(y_.begin(), y_.begin() + first, y_.end());
    std::rotate(angle.begin(), angle.begin() + first, angle.end());
    angle_ = angle;
    below_.resize(kBins);
    for (std::size_t b = 0, below = 0; b < kBins; ++b) {
      while (below < m && angle_[below] <= 4.0 * static_cast<double>(b) / kBins)
        ++below;
      below_[b] = static_cast<std::uint32_t>(below);
    }
    make_box();
  }

  // An axis-aligned box strictly inside (empty if none was found): a uniform square's points all but fall
  // into it, a disc's two thirds.  Comparisons of coordinates are exact.
  struct Box {
    double x0 = std::numeric_limits<double>::infinity(), x1 = -std::numeric_limits<double>::infinity();
    double y0 = 0, y1 = 0;
    bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  };
  const Box& box() const { return box_; }

  // Exact: true when (x, y) is strictly inside, false when it is on the boundary or outside.
  bool strictly_inside(double x, double y) const {
    if (box_.contains(x, y)) return true;
    if (fan_) {
      // The sector of the fan from the centre o that the pseudo-angle suggests.  If p is in the closed
      // triangle (o, c_i, c_j), it is strictly inside exactly when it is strictly left of edge c_i c_j: o is
      // strictly inside, so every point of that triangle off the edge is too.
      const std::size_t m = angle_.size();
      const double a = pseudo_angle(x - ox_, y - oy_);
      // How many corners lie at or below `a`: the table's count for a's bin start, then a step or two on at
      // most (a binary search mispredicted a branch every other step, half the time of the whole test).
      const double bin = a * (kBins / 4.0);
      std::size_t below = bin >= 0 && bin < kBins ? below_[static_cast<std::size_t>(bin)] : 0;
      while (below < m && a >= angle_[below])
        ++below;
      const std::size_t i = below == 0 ? m - 1 : below - 1;  // none below: the sector that wraps around
      const std::size_t j = i + 1 == m ? 0 : i + 1;
      // Each sector spans less than half a turn (o is strictly inside), so these two tests are the cone.
      if (orient2d(ox_, oy_, x_[i], y_[i], x, y) >= 0 && orient2d(ox_, oy_, x_[j], y_[j], x, y) <= 0)
        return orient2d(x_[i], y_[i], x_[j], y_[j], x, y) > 0;
      // The guess missed (rounding near a sector's ray): edge by edge.
    }
    return inside_by_edges(x, y);
  }

 private:
  bool inside_by_edges(double x, double y) const {
    const std::size_t m = x_.size();
    for (std::size_t k = 0, j = 1; k < m; ++k, j = j + 1 == m ? 0 : j + 1)
      if (orient2d(x_[k], y_[k], x_[j], y_[j], x, y) <= 0) return false;
    return true;
  }

  // The box: its x range lies between the corners furthest down-left and up-left and those furthest
  // down-right and up-right (y alike), shrunk towards the centre until its four corners are strictly inside,
  // exactly; then the whole box is, the polygon being convex.
  void make_box() {
    const std::size_t m = x_.size();
    std::size_t sw = 0, se = 0, nw = 0, ne = 0;
    for (std::size_t k = 1; k < m; ++k) {
      if (x_[k] + y_[k] < x_[sw] + y_[sw]) sw = k;
      if (x_[k] + y_[k] > x_[ne] + y_[ne]) ne = k;
      if (x_[k] - y_[k] > x_[se] - y_[se]) se = k;
      if (y_[k] - x_[k] > y_[nw] - x_[nw]) nw = k;
    }
    const double x0 = std::max(x_[sw], x_[nw]), x1 = std::min(x_[se], x_[ne]);
    const double y0 = std::max(y_[sw], y_[se]), y1 = std::min(y_[nw], y_[ne]);
    if (!(x0 < x1 && y0 < y1)) return;
    for (double keep : {1 - 0x1p-10, 0.875, 0.5}) {
      const Box box{ox_ + (x0 - ox_) * keep, ox_ + (x1 - ox_) * keep, oy_ + (y0 - oy_) * keep,
                    oy_ + (y1 - oy_) * keep};
      if (inside_by_edges(box.x0, box.y0) && inside_by_edges(box.x1, box.y0) &&
          inside_by_edges(box.x0, box.y1) && inside_by_edges(box.x1, box.y1)) {
        box_ = box;
        return;
      }
    }
  }

  std::vector<double> x_, y_;  // the corners, counter-clockwise
  std::vector<double> angle_;  // their pseudo-angles around (ox_, oy_), ascending but for rounding
  static constexpr std::size_t kBins = 1024;
  std::vector<std::uint32_t> below_;  // per pseudo-angle bin: how many corners are at or below its start
  double ox_ = 0, oy_ = 0;
  bool fan_ = false;
  Box box_;
};

// The visited points not strictly inside `inner`, in no particular order.  Points on its boundary stay:
// a corner of the inner polygon, or a point inside one of its edges, may be a corner of the hull.
template <class T, class Points>
std::vector<PointIndex> filter(const Cloud<T>& cloud, const Points& points, const InnerPolygon& inner,
                               unsigned workers) {
  std::vector<std::vector<PointIndex>> kept(workers);
  parallel_chunks(
      points.size(), workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        std::vector<PointIndex>& out = kept[worker];
        // The box test inline, on a copy the pushes cannot alias: most points end there.
        const InnerPolygon::Box box = inner.box();
        for (std::size_t k = begin; k < end; ++k) {
          const PointIndex i = points[k];
          const double x = cloud.x(i), y = cloud.y(i);
          if (!box.contains(x, y) && !inner.strictly_inside(x, y)) out.push_back(i);
        }
      },
      kGrain);
  std::size_t total = 0;
  for (const auto& part : kept)
    total += part.size();
  std::vector<PointIndex> all;
  all.reserve(total);
  for (const auto& part : kept)
    all.insert(all.end(), part.begin(), part.end());
  return all;
}

constexpr PointIndex kNone = std::numeric_limits<PointIndex>::max();

// Any point that is not `a` (when the inner hull is one point) or off the line a b (a segment); kNone when
// there is none.  Needed because the extremes are chosen in rounded arithmetic: a point just off the line
// of all the others may be no chosen extreme.
template <class T>
PointIndex find_witness(const Cloud<T>& cloud, std::size_t count, const std::vector<Entry>& inner,
                        unsigned workers) {
  std::vector<PointIndex> found(workers, kNone);
  parallel_chunks(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        const Entry& a = inner[0];
        for (std::size_t i = begin; i < end; ++i) {
          const double x = cloud.x(i), y = cloud.y(i);
          const bool off = inner.size() == 1 ? x != a.x || y != a.y
                                             : orient2d(a.x, a.y, inner[1].x, inner[1].y, x, y) != 0;
          if (off) {
            found[worker] = static_cast<PointIndex>(i);
            return;
          }
        }
      },
      kGrain);
  for (PointIndex w : found)
    if (w != kNone) return w;
  return kNone;
}

// Collinear input: the two ends are the least and the greatest (x, y), each named by its lowest index
// (the order along any line is the (x, y) order).
template <class T>
PlanarHull segment_ends(const Cloud<T>& cloud, std::size_t count, unsigned workers) {
  struct Ends {
    Entry low, high;
  };
  std::vector<Ends> ends(workers, Ends{cloud.entry(0), cloud.entry(0)});
  parallel_chunks(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        if (begin == end) return;
        Ends e{cloud.entry(static_cast<PointIndex>(begin)), cloud.entry(static_cast<PointIndex>(begin))};
        for (std::size_t i = begin + 1; i < end; ++i) {
          const double x = cloud.x(i), y = cloud.y(i);
          // Visited in increasing index: only a strictly lower or higher point replaces one.
          if (x < e.low.x || (x == e.low.x && y < e.low.y)) e.low = {x, y, static_cast<PointIndex>(i)};
          if (x > e.high.x || (x == e.high.x && y > e.high.y)) e.high = {x, y, static_cast<PointIndex>(i)};
        }
        ends[worker] = e;
      },
      kGrain);
  Entry low = ends[0].low, high = ends[0].high;
  for (const Ends& e : ends) {
    if (e.low < low) low = e.low;
    // Greatest (x, y), then least index.
    if (e.high.x > high.x ||
        (e.high.x == high.x && (e.high.y > high.y || (e.high.y == high.y && e.high.index < high.index))))
      high = e.high;
  }
  PlanarHull result;
  result.dimension = 1;
  result.polygon = {low.index, high.index};
  return result;
}

template <class T>
std::vector<Entry> entries_of(const std::vector<PointIndex>& indices, const Cloud<T>& cloud) {
  std::vector<Entry> entries;
  entries.reserve(indices.size());
  for (PointIndex i : indices)
    entries.push_back(cloud.entry(i));
  return entries;
}

// Every kth point of `base`, at most kSample of them: what the inner polygons are chosen from.
template <class Points>
struct Sample {
  Points base;
  std::size_t stride;
  explicit Sample(Points points, std::size_t most) : base(points), stride((points.size() + most - 1) / most) {
    stride = std::max<std::size_t>(stride, 1);
  }
  std::size_t size() const { return (base.size() + stride - 1) / stride; }
  PointIndex operator[](std::size_t k) const { return base[k * stride]; }
};
constexpr std::size_t kSample = std::size_t{1} << 16;

// A second round pays only when many points are left: below this, sorting them costs less.
constexpr std::size_t kRefineAbove = std::size_t{1} << 16;

template <class T>
PlanarHull planar_hull_of(const T* xy, std::size_t count) {
  PlanarHull result;
  if (count == 0) return result;
  if (count > std::numeric_limits<PointIndex>::max())
    throw std::length_error("planar_hull: more than 2^32 - 1 points");
  const Cloud<T> cloud{xy};
  const unsigned workers = hardware_workers();

  // Round one: the polygon of a sample's extremes in 64 directions.  Any input points make an inner polygon,
  // and reading a sample instead of every point saves a pass over the input (half the time of a uniform
  // square), while 64 directions leave far fewer points than 8 (of a uniform disc 0.3% instead of 10%).
  const AllPoints all{count};
  std::vector<PointIndex> candidates = extremes<32>(cloud, Sample(all, kSample), workers);
  std::vector<Entry> inner = exact_hull(entries_of(candidates, cloud));
  if (inner.size() < 3) {
    // A degenerate sample, or input: the extremes of every point in 8 directions, and where those are still
    // a point or a segment, any point off it.
    candidates = extremes<4>(cloud, all, workers);
    inner = exact_hull(entries_of(candidates, cloud));
    while (inner.size() < 3) {
      const PointIndex witness = find_witness(cloud, count, inner, workers);
      if (witness == kNone) {
        if (inner.size() == 2) return segment_ends(cloud, count, workers);
        result.dimension = 0;  // every point is the same: the first names it
        result.polygon = {0};
        return result;
      }
      candidates.push_back(witness);
      inner = exact_hull(entries_of(candidates, cloud));
    }
  }
  std::vector<PointIndex> survivors = filter(cloud, all, InnerPolygon(inner), workers);

  // Round two, where many points are left (an unlucky sample, or points near a curve): a sample of the
  // survivors in 128 directions, with round one's corners so that the polygon only grows; filtered only
  // where it drops a quarter of that sample (a circle's points all stay).
  if (survivors.size() > kRefineAbove) {
    const SomePoints some{&survivors};
    const Sample sample(some, kSample);
    std::vector<PointIndex> more = extremes<64>(cloud, sample, workers);
    for (const Entry& c : inner)
      more.push_back(c.index);
    const InnerPolygon polygon(exact_hull(entries_of(more, cloud)));
    if (4 * filter(cloud, sample, polygon, workers).size() <= 3 * sample.size())
      survivors = filter(cloud, some, polygon, workers);
  }

  // The chain over the survivors, which hold every strict corner with all its duplicates.
  std::vector<Entry> entries = entries_of(survivors, cloud);
  parallel_sort(entries);
  entries.erase(std::unique(entries.begin(), entries.end(),
                            [](const Entry& a, const Entry& b) { return a.x == b.x && a.y == b.y; }),
                entries.end());
  const std::vector<std::size_t> corners = monotone_chain(entries);
  result.dimension = corners.size() >= 3 ? 2 : static_cast<int>(corners.size()) - 1;
  result.polygon.reserve(corners.size());
  for (std::size_t k : corners)
    result.polygon.push_back(entries[k].index);
  return result;
}

}  // namespace

PlanarHull planar_hull(const double* xy, std::size_t count) {
  return planar_hull_of(xy, count);
}

PlanarHull planar_hull(const float* xy, std::size_t count) {
  return planar_hull_of(xy, count);
}

}  // namespace cudahull
