// A map from input point index to a small value that is zero for every point not yet stored, sized by the
// points that ever become mesh vertices rather than by the input.  A per-point array of 20M entries would
// cost a page fault (and, with transparent huge pages, a 2 MB clear) for almost every hull vertex touched,
// which was most of the host time on a 10M-point cube (docs/benchmarks.md).
//
// Open addressing with linear probing; keys are never erased (a value is reset to zero instead).
#pragma once

#include <cstdint>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

template <class V>
class PointMap {
 public:
  PointMap() { rehash(64); }

  // The value stored for `key`, or zero.
  V get(PointIndex key) const {
    const std::size_t i = probe(key);
    return keys_[i] == key ? values_[i] : V{};
  }
  // A reference to the value for `key`, inserting a zero first if absent.  Valid until the next insert.
  V& operator[](PointIndex key) {
    for (std::size_t i = slot(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) return values_[i];
      if (keys_[i] == kEmpty) {
        if (2 * (size_ + 1) > keys_.size()) {
          rehash(2 * keys_.size());
          return (*this)[key];
        }
        ++size_;
        keys_[i] = key;
        return values_[i];
      }
    }
  }
  // The value stored for `key` if it is present, else null.  Several threads may look up and write the
  // values of different present keys at once, as long as none inserts.
  V* find(PointIndex key) {
    const std::size_t i = probe(key);
    return keys_[i] == key ? &values_[i] : nullptr;
  }
  // Empties the map, back to 64 slots.  (It was rehash(64), which kept every entry: a restarted engine then
  // saw the last run's vertex flags.)
  void clear() {
    keys_.assign(64, kEmpty);
    values_.assign(64, V{});
    mask_ = 63;
    size_ = 0;
  }
  // Room for `count` keys without growing.
  void reserve(std::size_t count) {
    std::size_t capacity = keys_.size();
    while (capacity < 2 * count + 2)
      capacity *= 2;
    if (capacity != keys_.size()) rehash(capacity);
  }
  // Calls visit(key, value&) for every stored key, in no particular order.
  template <class Visit>
  void for_each(Visit&& visit) {
    for_each_in(0, keys_.size(), visit);
  }
  // The same over slots [begin, end) of slot_count(): disjoint ranges may run on different threads.
  std::size_t slot_count() const { return keys_.size(); }
  template <class Visit>
  void for_each_in(std::size_t begin, std::size_t end, Visit&& visit) {
    for (std::size_t i = begin; i < end; ++i) {
      if (keys_[i] != kEmpty) visit(keys_[i], values_[i]);
    }
  }
  template <class Visit>
  void for_each(Visit&& visit) const {
    for (std::size_t i = 0; i < keys_.size(); ++i) {
      if (keys_[i] != kEmpty) visit(keys_[i], values_[i]);
    }
  }

 private:
  static constexpr PointIndex kEmpty = 0xffffffffu;  // never a point index (at most 2^32 - 2 points)
  // The slot that holds `key`, or the empty slot where it would go.
  std::size_t probe(PointIndex key) const {
    std::size_t i = slot(key);
    while (keys_[i] != key && keys_[i] != kEmpty)
      i = (i + 1) & mask_;
    return i;
  }
  std::size_t slot(PointIndex key) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ull) >> 32) & mask_;
  }
  void rehash(std::size_t capacity) {
    std::vector<PointIndex> old_keys = std::move(keys_);
    std::vector<V> old_values = std::move(values_);
    keys_.assign(capacity, kEmpty);
    values_.assign(capacity, V{});
    mask_ = capacity - 1;
    size_ = 0;
    for (std::size_t i = 0; i < old_keys.size(); ++i) {
      if (old_keys[i] != kEmpty) (*this)[old_keys[i]] = old_values[i];
    }
  }

  std::vector<PointIndex> keys_;
  std::vector<V> values_;
  std::size_t mask_ = 0, size_ = 0;
};

}  // namespace cudahull
