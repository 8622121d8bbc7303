// Morton (Z-order) keys for sorting points by place, for memory locality only (never a decision): the exact
// reference hull, the checker and the merge's point tree order their points with them.
#pragma once

#include <cstdint>

namespace cudahull {

// The low 21 bits of x spread to every third bit of 63, so that three coordinates' cells interleave.
inline std::uint64_t spread3(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

}  // namespace cudahull
