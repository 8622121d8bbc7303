"""One round of an A/B of the Python module (run once per build, alternating): cudahull.ConvexHull of N
ball and cube points (float32, as `cudahull gen` makes them) from NumPy and from CuPy, the median of
--repeat calls after a warm-up, as one JSON line per input.

    PYTHONPATH=BUILD/python python3 python/bench/ab_module.py LABEL [--n 10000000] [--repeat 5]
"""

import argparse
import json

import numpy as np

import cudahull
from bench_module import timed  # median ms of repeated calls after a warm-up (python/bench)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("label")
    parser.add_argument("--n", type=int, default=10_000_000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    rng = np.random.default_rng(1)
    cube = rng.uniform(-1, 1, size=(args.n, 3)).astype(np.float32)
    ball = rng.uniform(-1, 1, size=(2 * args.n, 3)).astype(np.float32)
    ball = np.ascontiguousarray(ball[np.einsum("ij,ij->i", ball, ball) <= 1][: args.n])
    import cupy

    for name, points in (("cube", cube), ("ball", ball)):
        on_gpu = cupy.asarray(points)
        hull = cudahull.ConvexHull(points)
        row = {"build": args.label, "input": name, "n": len(points), "vertices": len(hull.vertices),
               "numpy_ms": timed(lambda: cudahull.ConvexHull(points), args.repeat)[0],
               "cupy_ms": timed(lambda: cudahull.ConvexHull(on_gpu), args.repeat)[0],
               "describe_ms": cudahull.ConvexHull(on_gpu).stats.get("describe_ms")}
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
