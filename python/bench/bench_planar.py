"""The scipy drop-in's speed (issue 25): 2-D hulls of N points from NumPy and from CuPy against
scipy.spatial.ConvexHull on the same points, and the 3-D drop-in (exact and merged) against scipy.

    python3 python/bench/bench_planar.py [--n 10000000] [--repeat 5] [--json OUT.jsonl]

Each time is the median of --repeat calls after one warm-up, wall clock around the call (results as NumPy
arrays included; for CuPy input the points are already on the GPU).  Every cudahull result is checked
against scipy's vertex set where scipy is exact (uniform doubles in general position).
"""

import argparse
import json

import numpy as np
import scipy.spatial

import cudahull
from bench_module import timed  # median ms of repeated calls after a warm-up (python/bench)


def planar_inputs(n, rng):
    square = rng.uniform(-1, 1, size=(n, 2))
    radius = np.sqrt(rng.uniform(0, 1, size=n))
    angle = rng.uniform(0, 2 * np.pi, size=n)
    disc = np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])
    gauss = rng.normal(size=(n, 2))
    return {"square": square, "disc": disc, "gauss": gauss}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, default=10_000_000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json")
    args = parser.parse_args()
    rng = np.random.default_rng(25)
    try:
        import cupy
    except ImportError:
        cupy = None
    rows = []

    def record(**row):
        rows.append(row)
        print(json.dumps(row), flush=True)

    for name, points in planar_inputs(args.n, rng).items():
        scipy_ms, _, reference = timed(lambda: scipy.spatial.ConvexHull(points), max(1, args.repeat // 2))
        numpy_ms, _, hull = timed(lambda: cudahull.ConvexHull(points), args.repeat)
        assert sorted(hull.vertices.tolist()) == sorted(reference.vertices.tolist()), name
        record(input=f"2-D {name}", n=args.n, source="numpy", ms=numpy_ms, scipy_ms=scipy_ms,
               speedup=scipy_ms / numpy_ms, vertices=len(hull.vertices), backend=hull.backend)
        if cupy is not None:
            on_gpu = cupy.asarray(points)
            cupy_ms, _, hull = timed(lambda: cudahull.ConvexHull(on_gpu), args.repeat)
            assert sorted(hull.vertices.tolist()) == sorted(reference.vertices.tolist()), name
            record(input=f"2-D {name}", n=args.n, source="cupy", ms=cupy_ms, scipy_ms=scipy_ms,
                   speedup=scipy_ms / cupy_ms, vertices=len(hull.vertices), backend=hull.backend)

    # 3-D through the drop-in: exact and merged (tolerance "qhull", as with qhull_options), against scipy.
    n3 = min(args.n, 1_000_000)
    ball = rng.uniform(-1, 1, size=(n3, 3))
    ball = ball[np.einsum("ij,ij->i", ball, ball) <= 1]
    scipy_ms, _, reference = timed(lambda: scipy.spatial.ConvexHull(ball), max(1, args.repeat // 2))
    for label, kwargs in (("exact", {}), ("qhull_options='Qt'", {"qhull_options": "Qt"})):
        ms, _, hull = timed(lambda: cudahull.ConvexHull(ball, **kwargs), args.repeat)
        record(input=f"3-D ball {label}", n=len(ball), source="numpy", ms=ms, scipy_ms=scipy_ms,
               speedup=scipy_ms / ms, vertices=len(hull.vertices), backend=hull.backend,
               same_vertices_as_scipy=sorted(hull.vertices.tolist()) == sorted(reference.vertices.tolist()))

    print(f"\n{'input':32} {'from':6} {'n':>9} {'ms':>9} {'scipy ms':>9} {'x scipy':>8}")
    for r in rows:
        print(f"{r['input']:32} {r['source']:6} {r['n']:9} {r['ms']:9.2f} {r['scipy_ms']:9.1f} {r['speedup']:8.1f}")
    if args.json:
        with open(args.json, "w") as out:
            for r in rows:
                out.write(json.dumps(r) + "\n")


if __name__ == "__main__":
    main()
