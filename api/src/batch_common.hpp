// What the batch's host and device paths share (batch_common.cpp): the offsets' check, a cloud's error
// named by its cloud, the backends' names, the batch's plan, and the single-cloud path cloud by cloud.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cudahull/convex_hull.hpp"
#include "cudahull/convex_hull_batch.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/hull_plan.hpp"

namespace cudahull::batch {

// Throws std::invalid_argument unless `offsets` are B + 1 cloud boundaries: from 0, never decreasing, to
// `count`.
void check_offsets(std::size_t count, const std::size_t* offsets, std::size_t clouds);

// convex_hull()'s InputError for a point of cloud `cloud`, whose first point is row `first_row` of the
// packed points: "cloud C: point I: ... (row R of the packed points)".
InputError in_cloud(const InputError& error, std::size_t cloud, std::size_t first_row);

// `name` joined to the report's backends unless it is there ("+" between them, in the order first met).
void add_backend(ConvexHullBatchReport& report, const std::string& name);

// The plan for the whole batch: where it runs (backend and precision resolved once), from all its points.
HullPlan batch_plan(std::size_t count, Precision own, bool on_device, const ConvexHullOptions& options);

// The clouds in turn through the single-cloud path, `hull_of(c)`, but those `skip` marks (when given), each
// hull handed to `keep(c, hull)`; the first failing cloud's exception is thrown (an InputError named by its
// cloud), and no cloud after it starts.
template <class HullOf, class Keep>
void run_each_on_device(const std::size_t* offsets, std::size_t clouds, HullOf hull_of, Keep keep,
                        const std::vector<std::uint8_t>* skip = nullptr) {
  for (std::size_t c = 0; c < clouds; ++c) {
    if (skip && (*skip)[c]) continue;
    try {
      keep(c, hull_of(c));
    } catch (const InputError& error) {
      throw in_cloud(error, c, offsets[c]);
    }
  }
}

}  // namespace cudahull::batch
