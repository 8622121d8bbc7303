"""The large host transfers (cudahull/cuda/host_transfer.hpp) under compute-sanitizer, on a GPU machine.

A host batch whose 36 MB upload and 19 MB of planes cross through the pinned staging buffers, and a
2M-point NumPy hull whose 48 MB upload does, each compared with the CPU backend's answer.  Run with the
module installed (a wheel, or PYTHONPATH pointing at one unpacked):

    compute-sanitizer --tool memcheck --error-exitcode 3 python3 tests/staged_copies_sanitizer.py
    compute-sanitizer --tool racecheck --error-exitcode 3 python3 tests/staged_copies_sanitizer.py
"""
import numpy as np

import cudahull

rng = np.random.default_rng(3)
points = rng.normal(size=(15_000 * 100, 3))
offsets = np.arange(0, len(points) + 1, 100)
got = cudahull.convex_hull_batch(points, offsets, backend="cuda")
want = cudahull.convex_hull_batch(points, offsets, backend="cpu")
assert got.backend.startswith("cuda"), got.backend
assert got.planes.nbytes > 16 << 20, got.planes.nbytes  # large enough to be staged
assert np.array_equal(got.vertices, want.vertices)
assert np.array_equal(got.face_offsets, want.face_offsets)

cloud = rng.normal(size=(2_000_000, 3))
hull = cudahull.ConvexHull(cloud)
assert np.array_equal(hull.vertices, cudahull.ConvexHull(cloud, backend="cpu").vertices)
print(f"staged copies: a batch with {got.planes.nbytes} bytes of planes and a hull of {len(hull.vertices)} "
      "vertices, equal to the CPU's")
