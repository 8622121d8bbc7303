// From a plan to what runs it (issue 44): the command line and the viewer build their engines here, from one
// HullPlan (plan_hull(), hull_plan.hpp), and include no header of cuda/.
//
// design:
//   planned_backend   the stepping engine's backend on the plan's backend: the CPU's threads or the GPU
//   run_resident      the resident engine's whole run on the plan's backend (every phase where the points
//                     are; on the GPU with the plan's ResidentTuning), with its counters, the hardware's
//                     floor for each phase (fill_floors(), measured after the run's clock) and the upload's
//                     and the run's times
//   resident_stepper  the resident engine an iteration a step, with records (the viewer's and --trace's),
//                     on the plan's backend (on the GPU with the plan's ResidentTuning)
// convex_hull() (convex_hull.hpp) runs the same engines for a one-call result.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cudahull/backend.hpp"
#include "cudahull/engine.hpp"
#include "cudahull/hull_plan.hpp"
#include "cudahull/resident.hpp"

namespace cudahull {

// The stepping engine's backend that `plan` chose (BackendChoice::kCuda: the GPU's; else the CPU's).
template <class Point>
std::unique_ptr<BasicBackend<Point>> planned_backend(const HullPlan& plan);

template <class Point>
struct ResidentRun {
  BasicHullMesh<Point> hull;
  ResidentStats stats;               // with each phase's floor
  std::string backend_name;          // "cuda-resident" or "cpu-resident"
  double upload_ms = 0, run_ms = 0;  // host clock; no upload on the CPU
};

// The resident engine's run of `points` on the plan's backend.
template <class Point>
ResidentRun<Point> run_resident(const std::vector<Point>& points, const HullPlan& plan);

// The resident engine one iteration a step on the plan's backend; it borrows `points`.
template <class Point>
std::unique_ptr<SteppingEngine> resident_stepper(const std::vector<Point>& points, const HullPlan& plan);

}  // namespace cudahull
