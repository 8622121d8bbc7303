"""The merged path (trimesh's options) against Qhull on the CPU, per call from NumPy.

Times ``scipy.spatial.ConvexHull(points, qhull_options=OPTIONS)``, ``cudahull.ConvexHull`` with the same
options (the merged path), the merged path's C++ call alone (``_cudahull.convex_hull``: what the Python layer
adds is the difference) and ``cudahull.ConvexHull(points)`` (the exact path), best of ``--repeat`` calls
each (the four taken in turn within each round), on the rows of issue 42's table, and prints each hull's vertex count and the merged hull's certificate
(``max_outside``).  The module comes from PYTHONPATH; the backend is the CPU's.

    PYTHONPATH=build/python python3 python/bench/bench_merged.py [--repeat 5] [--options "QbB Pp Qt"]
        [--rows small,normal,bunny,sphere]
"""
import argparse
import os

import numpy as np
import scipy.spatial

import cudahull
from timing import best_of

ASSETS = os.path.join(os.path.dirname(__file__), "..", "..", "assets")


def bunny():
    """The Stanford bunny's scan points (assets/bun_zipper.ply, ASCII: x y z confidence intensity)."""
    path = os.path.join(ASSETS, "bun_zipper.ply")
    with open(path) as f:
        count = 0
        for line in f:
            if line.startswith("element vertex"):
                count = int(line.split()[2])
            if line.strip() == "end_header":
                break
        return np.loadtxt(f, max_rows=count)[:, :3].copy()


def rows():
    rng = np.random.default_rng(42)
    sphere = rng.normal(size=(100_000, 3))
    sphere /= np.linalg.norm(sphere, axis=1, keepdims=True)
    return {
        "small": ("100 normal points", rng.normal(size=(100, 3))),
        "normal": ("2,000 normal points", rng.normal(size=(2000, 3))),
        "bunny": ("bunny (bun_zipper.ply)", bunny()),
        "sphere": ("1e5 sphere points", sphere),
    }



def shown(seconds):
    return f"{seconds * 1e6:.0f} us" if seconds < 1e-3 else f"{seconds * 1e3:.2f} ms" if seconds < 1 else \
        f"{seconds:.2f} s"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--options", default="QbB Pp Qt")
    ap.add_argument("--rows", default="small,normal,bunny,sphere")
    a = ap.parse_args()

    table = rows()
    print(f"cudahull from {os.path.dirname(cudahull.__file__)}; options {a.options!r}; best of {a.repeat} "
          f"({20 * a.repeat} up to 10,000 points)")
    print(f"{'input':<28}{'points':>9}{'Qhull':>11}{'merged':>11}{'C++ alone':>11}{'exact':>11}{'merged/Qhull':>14}"
          f"{'V qhull':>9}{'V merged':>9}{'V exact':>9}  max_outside")
    for key in a.rows.split(","):
        name, points = table[key]
        repeat = a.repeat * (20 if len(points) <= 10_000 else 1)  # a call of microseconds: more tries
        # One untimed call each first: imports, the worker pool, the allocator.
        scipy.spatial.ConvexHull(points, qhull_options=a.options)
        cudahull.ConvexHull(points, qhull_options=a.options, backend="cpu")
        (qhull, merged, _, exact), (t_qhull, t_merged, t_module, t_exact) = best_of([
            lambda: scipy.spatial.ConvexHull(points, qhull_options=a.options),
            lambda: cudahull.ConvexHull(points, qhull_options=a.options, backend="cpu"),
            lambda: cudahull._cudahull.convex_hull(points, "cpu", "auto", "auto", "qhull", 0.0, 1.0),
            lambda: cudahull.ConvexHull(points, backend="cpu"),
        ], repeat)
        print(f"{name:<28}{len(points):>9}{shown(t_qhull):>11}{shown(t_merged):>11}{shown(t_module):>11}"
              f"{shown(t_exact):>11}"
              f"{t_merged / t_qhull:>13.2f}x{len(qhull.vertices):>9}{len(merged.vertices):>9}"
              f"{len(exact.vertices):>9}  {merged.max_outside:.3g}")


if __name__ == "__main__":
    main()
