// hull_options.hpp: the choices' names, and what this process offers.
#include "cudahull/hull_options.hpp"

#include <stdexcept>

#include "cudahull/convex_hull.hpp"
#include "device_info.hpp"
#include "device_memory.hpp"
#include "device_points.hpp"

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

BackendChoice backend_from_name(const std::string& name) {
  if (name == "auto") return BackendChoice::kAuto;
  if (name == "cpu") return BackendChoice::kCpu;
  if (name == "cuda") return BackendChoice::kCuda;
  throw std::invalid_argument("backend must be auto, cpu or cuda, not '" + name + "'");
}

EngineChoice engine_from_name(const std::string& name) {
  if (name == "auto") return EngineChoice::kAuto;
  if (name == "stepping") return EngineChoice::kStepping;
  if (name == "resident") return EngineChoice::kResident;
  throw std::invalid_argument("engine must be auto, stepping or resident, not '" + name + "'");
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
  if (name == "exact") return MergeMode::kExact;
  if (name == "qhull") return MergeMode::kQhull;
  if (name == "relative") return MergeMode::kRelative;
  throw std::invalid_argument("merge must be exact, qhull or relative, not '" + name + "'");
}

Precision precision_from_name_strict(const std::string& name) {
  if (name == "auto" || name == "float" || name == "double") return precision_from_name(name);
  throw std::invalid_argument("precision must be auto, float or double, not '" + name + "'");
}

}  // namespace cudahull
