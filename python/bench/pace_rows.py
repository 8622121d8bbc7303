"""The Python rows of the pace goals (docs/benchmarks.md, "Phases and their floors") on the GPU machine.

``cudahull.ConvexHull`` of a 10M-point ball (float32) read in place from CuPy and from NumPy, and
``cudahull.convex_hull_batch`` of PyTorch tensors already on the GPU and of a NumPy array: the median of
``--repeat`` calls after one warm-up, wall clock around the call, with the single hull's own split (engine
and describe, from ``hull.stats``) and the batch's (device, kernel, describe).  One JSON line a row.

    python3 python/bench/pace_rows.py [--repeat 5] [--json OUT.jsonl]
"""
import argparse
import json
import statistics
import time

import numpy as np

import cudahull


def timed(call, repeat):
    result = call()  # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = call()
        times.append((time.perf_counter() - t0) * 1e3)
    return result, statistics.median(times), min(times)


def ball(rng, shape):
    d = rng.normal(size=shape)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    return (d * rng.uniform(size=shape[:-1] + (1,)) ** (1 / 3)).astype(np.float32)


def sphere(rng, shape):
    d = rng.normal(size=shape)
    return (d / np.linalg.norm(d, axis=-1, keepdims=True)).astype(np.float32)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--json")
    ap.add_argument("--scale", type=int, default=1, help="divide every size by this (a quick check)")
    args = ap.parse_args()
    rng = np.random.default_rng(7)
    rows = []

    points = ball(rng, (10_000_000 // args.scale, 3))
    single = [("NumPy array, ball 10M", lambda: points)]
    try:
        import cupy

        on_device = cupy.asarray(points)
        single.insert(0, ("CuPy array in place, ball 10M", lambda: on_device))
    except ImportError:
        pass
    for label, source in single:
        hull, median, best = timed(lambda: cudahull.ConvexHull(source()), args.repeat)
        stats = hull.stats or {}
        rows.append({"row": label, "median_ms": median, "best_ms": best, "vertices": len(hull.vertices),
                     "engine_ms": stats.get("engine_ms"), "describe_ms": stats.get("describe_ms"),
                     "plan": hull.plan})

    batches = [("balls", 10_000 // args.scale, 1_000), ("balls", 100_000 // args.scale, 100),
               ("spheres", 10_000 // args.scale, 1_000)]
    try:
        import torch

        for dist, b, m in batches:
            clouds = torch.from_numpy((ball if dist == "balls" else sphere)(rng, (b, m, 3))).cuda()
            result, median, best = timed(lambda: cudahull.convex_hull_batch(clouds), args.repeat)
            rows.append({"row": f"batch, PyTorch, {dist} {b:,} x {m:,}", "median_ms": median, "best_ms": best,
                         "report": result.report})
    except ImportError:
        pass
    host = ball(rng, (100_000 // args.scale, 100, 3))
    result, median, best = timed(lambda: cudahull.convex_hull_batch(host), args.repeat)
    rows.append({"row": "batch from a NumPy array, balls 100,000 x 100 (float32)", "median_ms": median,
                 "best_ms": best, "report": result.report})

    for row in rows:
        print(json.dumps(row, default=str))
    if args.json:
        with open(args.json, "w") as f:
            for row in rows:
                f.write(json.dumps(row, default=str) + "\n")


if __name__ == "__main__":
    main()
