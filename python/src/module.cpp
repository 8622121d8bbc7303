// cudahull._cudahull: the nanobind extension under the Python package (python/cudahull/__init__.py), which
// gives it scipy's ConvexHull interface (and convex_hull_batch, issue 27).  It takes C-contiguous (n, 3)
// float32 or float64 NumPy arrays, as the package hands them over, or such arrays in CUDA memory (DLPack:
// CuPy, PyTorch; or a raw pointer from
// __cuda_array_interface__), and returns plain dicts of NumPy arrays (a batch on the device: of PyTorch
// tensors or CuPy arrays that share the result's device memory).
//
// This file makes the module from its parts (bindings.hpp): hulls of NumPy points (host_hulls.cpp), of points
// in CUDA memory (device_hulls.cpp), batches (batch_hulls.cpp) and the stepping engine (step_engine.cpp).
#include <nanobind/nanobind.h>

#include "bindings.hpp"
#include "cudahull/convex_hull.hpp"
#include "cudahull/errors.hpp"

NB_MODULE(_cudahull, m) {
  using namespace cudahull;
  using namespace cudahull::python;
  m.doc() = "cudahull's C++ core; use the cudahull package (ConvexHull, Engine) rather than this module.";
  // The C++ errors keep their messages; bad input is a ValueError, as scipy raises for it.
  nb::exception<InputError>(m, "InputError", PyExc_ValueError);
  nb::exception<DeviceError>(m, "DeviceError", PyExc_RuntimeError);

  bind_host_hulls(m);
  bind_device_hulls(m);
  bind_batch_hulls(m);
  m.def("release_device_memory", []() {
    nb::gil_scoped_release unlocked;
    release_device_memory();
  });
  // Whether a CUDA array can be taken here at all: (usable, why not), before its data is touched.
  m.def("cuda_device", []() {
    const CudaStatus cuda = cuda_status();
    return nb::make_tuple(cuda.usable, cuda.usable ? cuda.device : cuda.reason);
  });

  bind_step_engine(m);
}
