// A bounding-box tree for the merge's all-pairs searches (the certificate's dropped points, the coplanar
// points' nearest triangles).
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "cudahull/morton.hpp"
#include "geometry.hpp"

namespace cudahull::merge {

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

}  // namespace cudahull::merge
