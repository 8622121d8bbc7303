"""Timing and inputs shared by the benchmark scripts beside it (they import it from their own folder; so does
tests/wheel/run_on_gpu_machine.sh)."""
import time

import numpy as np


def best_of(fns, repeat):
    """Each function's result and best time over `repeat` rounds, the functions taken in turn within a round
    (a busy machine slows them alike, not whichever ran during the busy spell)."""
    results, times = [None] * len(fns), [float("inf")] * len(fns)
    for _ in range(repeat):
        for k, fn in enumerate(fns):
            t0 = time.perf_counter()
            results[k] = fn()
            times[k] = min(times[k], time.perf_counter() - t0)
    return results, times


def warm_best(f, n):
    """f's last result and its best time over n calls, after one call to warm up."""
    f()
    times = []
    for _ in range(n):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return out, min(times)


def ball_points(n=523_000, seed=5):
    """n points uniform in the unit ball, as issue 42's GPU rows take them."""
    rng = np.random.default_rng(seed)
    p = rng.normal(size=(n, 3))
    p *= (rng.random(len(p)) ** (1 / 3) / np.linalg.norm(p, axis=1))[:, None]
    return p
