// The module's parts: each adds its functions (and classes) to the module; module.cpp calls them in order.
#pragma once

#include "numpy_arrays.hpp"

namespace cudahull::python {

void bind_host_hulls(nb::module_& m);    // host_hulls.cpp: NumPy points, 3-D and 2-D, and their helpers
void bind_device_hulls(nb::module_& m);  // device_hulls.cpp: points in CUDA memory
void bind_batch_hulls(nb::module_& m);   // batch_hulls.cpp: many clouds in one call (issue 27)
void bind_step_engine(nb::module_& m);   // step_engine.cpp: the stepping engine for notebooks

}  // namespace cudahull::python
