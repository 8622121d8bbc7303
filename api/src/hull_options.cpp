// hull_options.hpp: the choices' names, and what this process offers.
#include "cudahull/hull_options.hpp"

#include <stdexcept>
#include <string>

#include "cudahull/convex_hull.hpp"
#include "cudahull/cuda/device_info.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/device_points.hpp"

namespace cudahull {

CudaStatus cuda_presence() {
  CudaStatus status;
  status.usable = cuda_device_present(&status.reason);
  return status;
}

CudaStatus cuda_status() {
  const CudaDeviceInfo device = query_cuda_device();
  return {device.usable, device.name, device.reason};
}

void release_device_memory() {
  release_device_memory_now();  // no device, or none cudahull allocated on: nothing
}

namespace {

template <class Choice>
struct Named {
  const char* name;
  Choice choice;
};

// The choice called `name` among three; else std::invalid_argument "WHAT must be a, b or c, not 'NAME'".
template <class Choice>
Choice from_name(const std::string& name, const char* what, const Named<Choice> (&choices)[3]) {
  for (const Named<Choice>& c : choices)
    if (name == c.name) return c.choice;
  throw std::invalid_argument(std::string(what) + " must be " + choices[0].name + ", " + choices[1].name +
                              " or " + choices[2].name + ", not '" + name + "'");
}

}  // namespace

BackendChoice backend_from_name(const std::string& name) {
  return from_name<BackendChoice>(
      name, "backend",
      {{"auto", BackendChoice::kAuto}, {"cpu", BackendChoice::kCpu}, {"cuda", BackendChoice::kCuda}});
}

EngineChoice engine_from_name(const std::string& name) {
  return from_name<EngineChoice>(name, "engine",
                                 {{"auto", EngineChoice::kAuto},
                                  {"stepping", EngineChoice::kStepping},
                                  {"resident", EngineChoice::kResident}});
}

const char* choice_name(BackendChoice choice) {
  return choice == BackendChoice::kCpu ? "cpu" : choice == BackendChoice::kCuda ? "cuda" : "auto";
}

const char* choice_name(EngineChoice choice) {
  return choice == EngineChoice::kStepping   ? "stepping"
         : choice == EngineChoice::kResident ? "resident"
                                             : "auto";
}

MergeMode merge_from_name(const std::string& name) {
  return from_name<MergeMode>(
      name, "merge",
      {{"exact", MergeMode::kExact}, {"qhull", MergeMode::kQhull}, {"relative", MergeMode::kRelative}});
}

Precision precision_from_name_strict(const std::string& name) {
  if (name == "auto" || name == "float" || name == "double") return precision_from_name(name);
  throw std::invalid_argument("precision must be auto, float or double, not '" + name + "'");
}

}  // namespace cudahull
