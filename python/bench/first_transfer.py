# What the pinned staging (cuda/host_transfer.cpp) costs a process once: its first large host transfer (after
# its CUDA context exists) against the next ones, 2M float32 standard normal points (24 MB up) from NumPy.
# Usage: python3 python/bench/first_transfer.py LABEL
import sys, time
import numpy as np
import cudahull
rng = np.random.default_rng(1)
small = rng.normal(size=(1000, 3)).astype(np.float32)
cudahull.ConvexHull(small)  # context, module, pools
times = []
for k in range(4):
    p = rng.normal(size=(2_000_000, 3)).astype(np.float32)
    t0 = time.perf_counter(); h = cudahull.ConvexHull(p); times.append((time.perf_counter() - t0) * 1e3)
print(sys.argv[1], "2M float32 normal points from NumPy, calls 1-4 (ms):", " ".join(f"{t:.2f}" for t in times), flush=True)
