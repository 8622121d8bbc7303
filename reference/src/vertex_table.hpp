// A hash table from vertex coordinates to vertex index, for the lowest-index rule.  Internal to reference/.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "checker.hpp"
#include "cudahull/types.hpp"

namespace cudahull::checking {

// Coordinates as a hash key; +0 and -0 are the same coordinate.
inline std::uint32_t bits(float f) {
  if (f == 0) f = 0;
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}
inline std::uint64_t bits(double f) {
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

}  // namespace cudahull::checking
