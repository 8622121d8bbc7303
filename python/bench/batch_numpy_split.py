"""Where the NumPy batch's time goes (docs/benchmarks.md, "Where the NumPy batch's time goes").

100,000 clouds of 100 float32 ball points: uploaded alone (``cupy.asarray``), hulled from CuPy (results
left on the device) and from NumPy (results brought back), best and median of 4 after a warm-up; then the
host columns' sizes.  Needs CuPy and a GPU.  With ``CUDAHULL_PHASE_TIMES=1`` the batch's laps go to stderr.

    python3 python/bench/batch_numpy_split.py
"""
import time

import cupy
import numpy as np

import cudahull
from pace_rows import ball


def best(call, repeat=4):
    result = call()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = call()
        times.append((time.perf_counter() - t0) * 1e3)
    return result, min(times), sorted(times)[len(times) // 2]


def main():
    host = ball(np.random.default_rng(7), (100_000, 100, 3))

    def upload():
        array = cupy.asarray(host)
        cupy.cuda.runtime.deviceSynchronize()
        return array

    on_device, t, tm = best(upload)
    print(f"upload {host.nbytes / 1e6:.0f} MB (cupy.asarray from pageable memory): best {t:.1f} ms, median {tm:.1f}")
    result, t, tm = best(lambda: cudahull.convex_hull_batch(on_device))
    print(f"batch from CuPy (results on the device): best {t:.1f} ms, median {tm:.1f}; {result.report}")
    result, t, tm = best(lambda: cudahull.convex_hull_batch(host))
    print(f"batch from NumPy (results on the host): best {t:.1f} ms, median {tm:.1f}; {result.report}")
    sizes = {name: getattr(result, name).nbytes for name in ("vertices", "faces", "planes")}
    print("host columns, bytes:", sizes)


if __name__ == "__main__":
    main()
