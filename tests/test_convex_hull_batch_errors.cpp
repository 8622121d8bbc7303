// What convex_hull_batch() refuses (issue 27): a point that is not finite (or not a float where float is
// asked for) named by its cloud, its index in the cloud and its row of the packed points, whichever cloud
// finishes first; offsets that do not partition the points.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/errors.hpp"
#include "support/batch_clouds.hpp"

namespace cudahull {
namespace {

std::string input_error(const std::function<void()>& call) {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

TEST(ConvexHullBatch, BadPointsAreNamedByCloudAndPoint) {
  std::vector<Point3d> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1},  // cloud 0
                                 {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},             // cloud 2
                                 {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};            // cloud 3
  const std::vector<std::size_t> offsets{0, 5, 5, 9, 13};
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  points[7].y = nan;
  points[11].z = inf;
  for (unsigned threads : {1u, 4u}) {
    // The first bad point in packed order, whichever cloud finishes first.
    EXPECT_EQ(input_error([&] { convex_hull_batch(points, offsets, on_cpu(threads)); }),
              "cloud 2: point 2: y coordinate nan is not finite (row 7 of the packed points)");
  }
  points[7].y = 1;
  EXPECT_EQ(input_error([&] { convex_hull_batch(points, offsets, on_cpu()); }),
            "cloud 3: point 2: z coordinate inf is not finite (row 11 of the packed points)");
  points[11].z = 1e39;  // finite: taken in double, beyond float's range in float
  EXPECT_EQ(convex_hull_batch(points, offsets, on_cpu()).dimensions[3], 3);
  EXPECT_EQ(input_error([&] { convex_hull_batch(points, offsets, on_cpu(0, Precision::kFloat)); }),
            "cloud 3: point 2: z coordinate 1e+39 does not fit in float (row 11 of the packed points)");
  std::vector<Point3> floats(6, Point3{1, 2, 3});
  floats[0].x = -std::numeric_limits<float>::infinity();
  EXPECT_EQ(input_error([&] {
              convex_hull_batch(floats, {0, 6}, on_cpu());
            }),
            "cloud 0: point 0: x coordinate -inf is not finite (row 0 of the packed points)");
}

TEST(ConvexHullBatch, BadOffsetsAreRefused) {
  const std::vector<Point3> points(10, Point3{1, 2, 3});
  auto refused = [&](const std::vector<std::size_t>& offsets, const std::string& words) {
    try {
      convex_hull_batch(points, offsets, on_cpu());
      ADD_FAILURE() << "offsets taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused({}, "no offsets");
  refused({1, 10}, "offsets[0] is 1, not 0");
  refused({0, 6, 4, 10}, "offsets decrease at cloud 1 (6 then 4)");
  refused({0, 5}, "the last offset is 5, not the point count 10");
  refused({0, 5, 11}, "the last offset is 11");
}

}  // namespace
}  // namespace cudahull
