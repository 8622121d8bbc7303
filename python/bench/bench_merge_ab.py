# The GPU merged path against the exact hull for several installed wheels (sites), alternating: 523,000
# ball points from NumPy, best of 9; ROUNDS rounds.  Usage: python3 python/bench/bench_merge_ab.py SITE [SITE ...]
import os, subprocess, sys
CHILD = r'''
import time, sys
import numpy as np, cudahull
rng = np.random.default_rng(5)
p = rng.normal(size=(523_000, 3))
p *= (rng.random(len(p)) ** (1 / 3) / np.linalg.norm(p, axis=1))[:, None]
def best(f, n=9):
    f(); times = []
    for _ in range(n):
        t = time.perf_counter(); out = f(); times.append(time.perf_counter() - t)
    return out, min(times)
exact, te = best(lambda: cudahull.ConvexHull(p))
m1, t1 = best(lambda: cudahull.ConvexHull(p, qhull_options="Qt"))
m2, t2 = best(lambda: cudahull.ConvexHull(p, qhull_options="QbB Pp Qt"))
exact2, te2 = best(lambda: cudahull.ConvexHull(p))
te = min(te, te2)
print(f"{sys.argv[1]}: exact {te*1e3:.2f} ms, Qt {t1*1e3:.2f} ({t1/te:.3f}x), QbB Pp Qt {t2*1e3:.2f} ({t2/te:.3f}x), V {len(m1.vertices)} max_outside {m1.max_outside:.6g}", flush=True)
'''
sites = sys.argv[1:]
for rnd in range(int(os.environ.get("ROUNDS", "3"))):
    for site in sites:
        subprocess.run([sys.executable, "-c", CHILD, site], env=dict(os.environ, PYTHONPATH=site), check=False)
