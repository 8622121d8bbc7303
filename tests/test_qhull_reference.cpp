// The Qhull reference wrapper (reference/qhull/qhull_reference.hpp) the tests compare against: vertex ids
// sorted and valid, its options passed through, and a one-line error on degenerate input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "qhull_reference.hpp"

namespace cudahull {
namespace {

// ---------------------------------------------------------------------------------------------------------
// Qhull reference

TEST(QhullReference, CubeCornersPlusInteriorPoints) {
  std::vector<Point3> points;
  for (int i = 0; i < 8; ++i)
    points.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
  std::mt19937 rng(10);
  std::uniform_real_distribution<float> inner(0.1f, 0.9f);
  for (int i = 0; i < 500; ++i)
    points.push_back({inner(rng), inner(rng), inner(rng)});
  std::shuffle(points.begin(), points.end(), rng);
  QhullResult r = run_qhull(points);
  ASSERT_EQ(r.vertex_ids.size(), 8u);
  for (PointIndex id : r.vertex_ids) {
    const Point3& p = points.at(id);
    EXPECT_TRUE((p.x == 0 || p.x == 1) && (p.y == 0 || p.y == 1) && (p.z == 0 || p.z == 1));
  }
  EXPECT_TRUE(std::is_sorted(r.vertex_ids.begin(), r.vertex_ids.end()));
  EXPECT_EQ(r.facets, 12u);  // six squares, triangulated by Qt
  EXPECT_GE(r.milliseconds, 0.0);
}

TEST(QhullReference, RandomPointsGiveValidSortedIds) {
  std::mt19937 rng(11);
  std::normal_distribution<float> gauss;
  std::vector<Point3> points;
  for (int i = 0; i < 20000; ++i)
    points.push_back({gauss(rng), gauss(rng), gauss(rng)});
  QhullResult r = run_qhull(points);
  ASSERT_GE(r.vertex_ids.size(), 4u);
  EXPECT_TRUE(std::is_sorted(r.vertex_ids.begin(), r.vertex_ids.end()));
  EXPECT_EQ(std::set<PointIndex>(r.vertex_ids.begin(), r.vertex_ids.end()).size(), r.vertex_ids.size());
  for (PointIndex id : r.vertex_ids)
    EXPECT_LT(id, points.size());
  // A closed triangulated surface: F = 2V - 4.
  EXPECT_EQ(r.facets, 2 * r.vertex_ids.size() - 4);
  // Options are passed through.
  QhullResult again = run_qhull(points, "Qt Qbb");
  EXPECT_EQ(again.vertex_ids, r.vertex_ids);
}

TEST(QhullReference, SpherePointsAreAllVertices) {
  std::mt19937 rng(12);
  std::normal_distribution<double> gauss;
  std::vector<Point3> points;
  for (int i = 0; i < 2000; ++i) {
    double x = gauss(rng), y = gauss(rng), z = gauss(rng), n = std::sqrt(x * x + y * y + z * z);
    points.push_back({float(x / n), float(y / n), float(z / n)});
  }
  EXPECT_EQ(run_qhull(points).vertex_ids.size(), points.size());
}

TEST(QhullReference, DegenerateInputThrowsWithMessage) {
  std::vector<Point3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5f, 0.5f, 0}};
  try {
    run_qhull(flat);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("QH"), std::string::npos) << what;  // Qhull's own error code
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
  }
  EXPECT_THROW(run_qhull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), std::runtime_error);
  EXPECT_THROW(run_qhull({}), std::runtime_error);
}

}  // namespace
}  // namespace cudahull
