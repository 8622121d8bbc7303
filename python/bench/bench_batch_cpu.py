"""Batched hulls of small clouds on the CPU, against a scipy loop (issue 42).

Times ``cudahull.convex_hull_batch(points, offsets, backend="cpu")`` on B clouds of 6 to 40 points (sizes
and points seeded; normal points, so that scipy's vertex sets are exact) against a loop of
``scipy.spatial.ConvexHull`` over the same clouds, best of ``--repeat`` each (taken in turn), and checks every cloud's
vertex set against scipy's.  The module comes from PYTHONPATH.

    PYTHONPATH=build/python python3 python/bench/bench_batch_cpu.py [--clouds 10000] [--low 6] [--high 40]
        [--repeat 3] [--threads 0]
"""
import argparse
import os

import numpy as np
import scipy.spatial

import cudahull
from timing import best_of



def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--clouds", type=int, default=10_000)
    ap.add_argument("--low", type=int, default=6)
    ap.add_argument("--high", type=int, default=40)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()

    rng = np.random.default_rng(a.seed)
    sizes = rng.integers(a.low, a.high + 1, size=a.clouds)
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    points = rng.normal(size=(int(offsets[-1]), 3))
    clouds = [points[offsets[c]:offsets[c + 1]] for c in range(a.clouds)]

    cudahull.convex_hull_batch(points[:offsets[10]], offsets[:11], backend="cpu")  # warm: the worker pool
    (hulls, loop), (t_batch, t_scipy) = best_of([
        lambda: cudahull.convex_hull_batch(points, offsets, backend="cpu", threads=a.threads),
        lambda: [scipy.spatial.ConvexHull(cloud) for cloud in clouds],
    ], a.repeat)
    wrong = sum(not np.array_equal(hulls.vertices[hulls.vertex_offsets[c]:hulls.vertex_offsets[c + 1]],
                                   np.sort(loop[c].vertices)) for c in range(a.clouds))
    print(f"cudahull from {os.path.dirname(cudahull.__file__)}; {os.cpu_count()} cores; best of {a.repeat}")
    print(f"{a.clouds} clouds of {a.low}-{a.high} points ({int(offsets[-1])} points, mean {sizes.mean():.1f})")
    print(f"  scipy loop                      {t_scipy * 1e3:9.1f} ms  {t_scipy / a.clouds * 1e6:6.1f} us a cloud")
    print(f"  cudahull.convex_hull_batch, cpu {t_batch * 1e3:9.1f} ms  {t_batch / a.clouds * 1e6:6.1f} us a cloud"
          f"  ({t_scipy / t_batch:.1f}x faster)")
    print(f"  vertex sets equal to scipy's: {a.clouds - wrong} of {a.clouds}")
    if wrong:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
