// hull_runner.hpp: the engines a plan names, built in one place.
#include "cudahull/hull_runner.hpp"

#include "cudahull/cpu_backend.hpp"
#include "cudahull/cuda/cuda_backend.hpp"
#include "cudahull/cuda/resident_cuda.hpp"
#include "cudahull/phase_times.hpp"

namespace cudahull {

template <class Point>
std::unique_ptr<BasicBackend<Point>> planned_backend(const HullPlan& plan) {
  if (plan.backend == BackendChoice::kCuda) return make_cuda_backend<Point>();
  return make_cpu_backend<Point>();
}

template <class Point>
ResidentRun<Point> run_resident(const std::vector<Point>& points, const HullPlan& plan) {
  ResidentRun<Point> r;
  if (plan.backend == BackendChoice::kCuda) {
    r.backend_name = "cuda-resident";
    ResidentCudaHull<Point> resident(plan.resident_tuning);
    const auto t_upload = Clock::now();
    resident.upload(points);
    r.upload_ms = ms_since(t_upload);
    const auto t_run = Clock::now();
    r.hull = resident.run(&r.stats);
    r.run_ms = ms_since(t_run);
    fill_floors(r.stats, device_pace());  // after the clock: no run pays for measuring the hardware
  } else {
    r.backend_name = "cpu-resident";
    const auto t_run = Clock::now();
    r.hull = resident_hull_host(points, &r.stats);
    r.run_ms = ms_since(t_run);
    fill_floors(r.stats, host_pace());
  }
  return r;
}

template <class Point>
std::unique_ptr<SteppingEngine> resident_stepper(const std::vector<Point>& points, const HullPlan& plan) {
  if (plan.backend == BackendChoice::kCuda)
    return make_resident_cuda_stepping_engine(points, plan.resident_tuning);
  return make_resident_stepping_engine(points);
}

template std::unique_ptr<BasicBackend<Point3>> planned_backend(const HullPlan&);
template std::unique_ptr<BasicBackend<Point3d>> planned_backend(const HullPlan&);
template ResidentRun<Point3> run_resident(const std::vector<Point3>&, const HullPlan&);
template ResidentRun<Point3d> run_resident(const std::vector<Point3d>&, const HullPlan&);
template std::unique_ptr<SteppingEngine> resident_stepper(const std::vector<Point3>&, const HullPlan&);
template std::unique_ptr<SteppingEngine> resident_stepper(const std::vector<Point3d>&, const HullPlan&);

}  // namespace cudahull
