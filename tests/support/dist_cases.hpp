// Parameterised tests over the generators' distributions: a case is a distribution at a size, named
// "<distribution>_<size>" (cube_1000) in the test's name.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "cudahull/generators.hpp"

namespace cudahull::testing {

struct DistCase {
  Distribution dist;
  std::size_t n;
};

struct DistSizes {
  Distribution dist;
  std::vector<std::size_t> sizes;
};

// Each distribution at each of its sizes, in that order.
inline std::vector<DistCase> dist_cases(const std::vector<DistSizes>& rows) {
  std::vector<DistCase> cases;
  for (const DistSizes& row : rows)
    for (std::size_t n : row.sizes)
      cases.push_back({row.dist, n});
  return cases;
}

inline std::string dist_case_name(const ::testing::TestParamInfo<DistCase>& info) {
  return distribution_name(info.param.dist) + "_" + std::to_string(info.param.n);
}

}  // namespace cudahull::testing
