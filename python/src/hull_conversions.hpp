// Between the package's words and the library's structs: its options as ConvexHullOptions, a ConvexHull
// as its dict (hull_conversions.cpp).
#pragma once

#include <string>

#include "cudahull/convex_hull.hpp"
#include "numpy_arrays.hpp"

namespace cudahull::python {

// A hull's result as the package's dict: its measures, its arrays as NumPy (moved, not copied), and the
// resident engine's stats where it ran.
nb::dict hull_to_dict(ConvexHull&& hull);

// How a hull is merged, from the package's words: "exact", "qhull" or "relative" with its tolerance.
struct Merge {
  std::string mode = "exact";
  double tolerance = 0;
  double angle_cosine = 1;  // Qhull's An (1: none)
};

ConvexHullOptions options_from(const std::string& backend, const std::string& precision,
                               const std::string& engine, const Merge& merge);

}  // namespace cudahull::python
