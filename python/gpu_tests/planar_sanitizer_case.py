"""The 2-D filter's kernels under compute-sanitizer (bench/scipy_drop_in_h100.sh, PART=sanitizers): a few
2-D inputs in GPU memory through every branch of the device path (filtered, degenerate, a bad point,
float32 and float64), each checked against the NumPy path."""

import cupy
import numpy as np

import cudahull

rng = np.random.default_rng(5)
cases = {
    "square": rng.uniform(-1, 1, size=(100_000, 2)),
    "circle": np.column_stack([np.cos(t := rng.uniform(0, 6.3, size=2000)), np.sin(t)]),
    "collinear": np.outer(rng.integers(-99, 99, size=500), [1.0, 2.0]),
}
for name, points in cases.items():
    for dtype in (np.float32, np.float64):
        host = points.astype(dtype)
        got = cudahull.convex_hull(cupy.asarray(host))
        want = cudahull.convex_hull(host)
        assert np.array_equal(got["polygon"], want["polygon"]), (name, dtype)
bad = cases["square"].copy()
bad[123, 0] = np.nan
try:
    cudahull.convex_hull(cupy.asarray(bad))
    raise AssertionError("a NaN was taken")
except ValueError as error:
    assert str(error).startswith("point 123: x coordinate nan"), error
print("planar sanitizer cases: ok")
