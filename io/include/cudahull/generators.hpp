// Synthetic point distributions for tests, benchmarks and demos.  Deterministic for a given seed on every
// platform (own generator, no std:: distributions, whose output is implementation-defined).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

enum class Distribution {
  kCube,        // uniform in [-1, 1]^3
  kBall,        // uniform in the unit ball
  kSphere,      // on the unit sphere (every point extreme, up to float rounding)
  kGauss,       // standard normal in each coordinate
  kParaboloid,  // z = x^2 + y^2 over the unit disc (every point extreme)
  kCylinder,    // rings on a cylinder surface (degenerate: many coplanar points)
  kGrid,        // integer lattice, side ceil(cbrt(N)) (degenerate)
};

// "cube", "ball", ... ; throws std::invalid_argument listing the valid names.
Distribution distribution_from_name(const std::string& name);
std::string distribution_name(Distribution dist);
std::vector<std::string> distribution_names();

std::vector<Point3> generate_points(Distribution dist, std::size_t count, std::uint64_t seed);

}  // namespace cudahull
