// The resident engine's per-element operations, one file per phase of Algorithm 1 (as engine/src/phases/ is
// for the stepping engine), each with its design header:
//   star_mesh.hpp     the mesh as the operations see it, the decision entries (Fig. 7), the atomics
//   first_mesh.hpp    P, the drop filter and the first distribution (section 3.1)
//   refinement.hpp    Fig. 3a
//   swaps.hpp         swaps and removals in conflict-free rounds (Figs. 3b, 4, 5)
//   distribution.hpp  Algorithm 2: the routing through the entries, the furthest points
//   compaction.hpp    faces and points renumbered between iterations
//   finish.hpp        the defects, the result, the device side of the local repair (fault_repair.hpp)
// Each operation is a function of one face or one point, compiled for the host (HostExec, loops) and the
// device (CudaExec, one thread each); resident_driver.hpp runs them in order.
#pragma once

#include "cudahull/resident/compaction.hpp"
#include "cudahull/resident/distribution.hpp"
#include "cudahull/resident/finish.hpp"
#include "cudahull/resident/first_mesh.hpp"
#include "cudahull/resident/refinement.hpp"
#include "cudahull/resident/rounds.hpp"
#include "cudahull/resident/star_mesh.hpp"
#include "cudahull/resident/swaps.hpp"
