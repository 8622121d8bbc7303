"""Timing shared by the benchmark scripts beside it (they import it from their own folder)."""
import time


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
