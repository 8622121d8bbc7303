// What a caller asks of a hull (ConvexHullOptions: backend, engine, precision, merging), the choices' names,
// and what this process offers (cuda_status()).  plan_hull() (hull_plan.hpp) turns a request into a plan;
// convex_hull() (convex_hull.hpp) runs it.
#pragma once

#include <string>

#include "cudahull/types.hpp"

namespace cudahull {

// kAuto: the CUDA backend when a usable device is present, else the CPU (as `cudahull --backend auto`).
// plan_hull() (hull_plan.hpp) resolves kAuto, and the engine's and the precision's, for every caller.
enum class BackendChoice { kAuto, kCpu, kCuda };
// kAuto: kResident where the hull runs on a GPU, kStepping on the CPU (as `cudahull --engine auto`, the
// command line's default); kStepping: Algorithm 1 an iteration at a time, the host editing the mesh on all
// cores; kResident: every phase where the points are (issue 15, `cudahull --engine resident`).
enum class EngineChoice { kAuto, kStepping, kResident };
enum class MergeMode { kExact, kQhull, kRelative };

struct ConvexHullOptions {
  BackendChoice backend = BackendChoice::kAuto;
  EngineChoice engine = EngineChoice::kAuto;
  // The coordinates the hull is computed in.  kAuto: the input's own type (float stays float, double is
  // exact in double); kFloat rounds double input to float once; kDouble widens float input exactly.
  Precision precision = Precision::kAuto;
  // Facet merging (scipy's drop-in, issue 25).  kExact: the exact hull, every strictly extreme point a
  // vertex.  kQhull: merged as Qhull's default roundoff-based merging would (its tolerance from the input's
  // magnitudes, qhull_default_tolerance()).  kRelative: merged within `tolerance` times the bounding box's
  // largest side.  A merged hull is checked, not guessed: ConvexHull::max_outside bounds every input point.
  MergeMode merge = MergeMode::kExact;
  double tolerance = 0;  // kRelative only
  // With kQhull or kRelative: Qhull's An, merging facets whose normals' angle has a cosine above this too
  // (1: no angle).  A vertex is then dropped within the tolerance plus sqrt(1 - cos^2) times half its
  // distance to its farthest neighbour (facet_merge.cpp).
  double angle_cosine = 1;
  // Also Qhull's QbB volume and area of a 3-D hull (ConvexHull::box_volume, box_area), from the hull's own
  // copy of its vertices: what the drop-in reports under qhull_options "QbB".
  bool box_measures = false;
};

// Whether this process has a usable CUDA device (what backend auto looks for): its name, or why not.
struct CudaStatus {
  bool usable = false;
  std::string device;  // e.g. "NVIDIA H100 80GB HBM3"
  std::string reason;  // e.g. "no CUDA-capable device is detected"
};
CudaStatus cuda_status();
// The same without the device's name, cheaply (cuda_status() reads every property of the device, which costs
// more than a small hull): what convex_hull() and convex_hull_batch() plan with.
CudaStatus cuda_presence();

// "auto", "cpu", "cuda" and back; throws std::invalid_argument for another name.
BackendChoice backend_from_name(const std::string& name);
EngineChoice engine_from_name(const std::string& name);  // "auto", "stepping" or "resident"
// The names back, for messages and --stats: "auto", "cpu", "cuda"; "auto", "stepping", "resident".
const char* choice_name(BackendChoice choice);
const char* choice_name(EngineChoice choice);
// "auto", "float", "double"; unlike precision_from_name() (types.hpp), a bad name throws.
Precision precision_from_name_strict(const std::string& name);
// "exact", "qhull" or "relative"; throws std::invalid_argument for another name.
MergeMode merge_from_name(const std::string& name);

}  // namespace cudahull
