// The input checks every hull path shares (convex_hull.cpp, convex_hull_2d.cpp): finite coordinates, a
// value beyond float's range where float is asked for, the point count, each named in one InputError line;
// and what points in GPU memory need before they are read.  Internal to api/.
#pragma once

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/types.hpp"

namespace cudahull::detail {

inline const char* axis_name(int axis) {
  return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

inline std::string shortest(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

[[noreturn]] inline void bad_coordinate(std::size_t point, int axis, double value, const std::string& why) {
  throw InputError("point " + std::to_string(point) + ": " + axis_name(axis) + " coordinate " +
                   shortest(value) + " " + why);
}

// Why the exact hull in Point cannot take a point whose coordinates, widened to double, are `widened`
// (the axis in `axis`), or nullptr, with the point in Point in `out`.  Every coordinate's finiteness is
// asked before any range, so that a message names a NaN before a huge neighbour.
template <class Point>
const char* rejection(const double (&widened)[3], int& axis, Point& out) {
  for (axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(widened[axis])) return "is not finite";
  }
  if constexpr (std::is_same_v<Point, Point3d>) {
    // Every finite double: outside the engines' range (in_fast_exact_range) the hull takes the wide path.
    out = Point3d{widened[0], widened[1], widened[2]};
  } else {
    // Rounded once to float (a float input is unchanged); a double beyond float's range cannot be.
    const float rounded[3] = {static_cast<float>(widened[0]), static_cast<float>(widened[1]),
                              static_cast<float>(widened[2])};
    for (axis = 0; axis < 3; ++axis) {
      if (!std::isfinite(rounded[axis])) return "does not fit in float";
    }
    out = Point3{rounded[0], rounded[1], rounded[2]};
  }
  return nullptr;
}

// Throws the InputError (one line naming the point) for point `i`, if rejection() has one.  The device
// path names its first bad point with it too.
template <class Point>
void throw_if_rejected(std::size_t i, const double (&widened)[3]) {
  int axis = 0;
  Point unused;
  if (const char* why = rejection(widened, axis, unused)) bad_coordinate(i, axis, widened[axis], why);
}

inline void check_count(std::size_t count) {
  // PointIndex is 32 bits and the engine keeps 0xffffffff as "no point".
  if (count >= 0xffffffffu)
    throw InputError("too many points: " + std::to_string(count) + " (at most 2^32 - 2)");
}

// Copies `count` points into Point (float or double), refusing what the exact hull cannot take;
// `coordinate(i, axis)` reads the input.  On all host cores: for 10M points the copy is otherwise most of
// a resident hull's time.  Each chunk stops at its first bad point; the lowest is the one named, as a
// scan in order would.
template <class Point, class Coordinate>
std::vector<Point> copy_checked(std::size_t count, Coordinate coordinate) {
  check_count(count);
  std::vector<Point> points(count);
  const unsigned workers = hardware_workers();
  std::vector<std::size_t> first_bad(workers, count);
  parallel_chunks(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned worker) {
        for (std::size_t i = begin; i < end; ++i) {
          const double widened[3] = {coordinate(i, 0), coordinate(i, 1), coordinate(i, 2)};
          int axis = 0;
          if (rejection(widened, axis, points[i])) {
            first_bad[worker] = i;
            return;
          }
        }
      },
      std::size_t{1} << 16);
  const std::size_t bad = *std::min_element(first_bad.begin(), first_bad.end());
  if (bad != count) {
    const double widened[3] = {coordinate(bad, 0), coordinate(bad, 1), coordinate(bad, 2)};
    throw_if_rejected<Point>(bad, widened);
  }
  return points;
}

template <class Scalar>
auto array_coordinate(const Scalar* xyz) {
  return [xyz](std::size_t i, int axis) -> double { return xyz[3 * i + axis]; };
}

// The plan for `count` points of `dimension` in GPU memory, whose own precision is `own`.
HullPlan device_plan(std::size_t count, int dimension, Precision own, const ConvexHullOptions& options);

// What points in GPU memory need before they are read: a CUDA backend, a device (plan_hull() says which is
// missing), and memory of the current device.  Throws as convex_hull_device() documents.
void require_device_points(const void* device_points, std::size_t count, const HullPlan& plan);

}  // namespace cudahull::detail
