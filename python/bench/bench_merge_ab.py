# The GPU merged path against the exact hull for several installed wheels (sites), alternating: 523,000
# ball points from NumPy, best of 9; ROUNDS rounds.  Usage: python3 python/bench/bench_merge_ab.py SITE [SITE ...]
import os, subprocess, sys
CHILD = r'''
import sys
import cudahull
from timing import ball_points, warm_best
p = ball_points()
def best(f):
    return warm_best(f, 9)
exact, te = best(lambda: cudahull.ConvexHull(p))
m1, t1 = best(lambda: cudahull.ConvexHull(p, qhull_options="Qt"))
m2, t2 = best(lambda: cudahull.ConvexHull(p, qhull_options="QbB Pp Qt"))
exact2, te2 = best(lambda: cudahull.ConvexHull(p))
te = min(te, te2)
print(f"{sys.argv[1]}: exact {te*1e3:.2f} ms, Qt {t1*1e3:.2f} ({t1/te:.3f}x), QbB Pp Qt {t2*1e3:.2f} ({t2/te:.3f}x), V {len(m1.vertices)} max_outside {m1.max_outside:.6g}", flush=True)
'''
sites = sys.argv[1:]
here = os.path.dirname(os.path.abspath(__file__))  # timing.py, after the site's cudahull
for rnd in range(int(os.environ.get("ROUNDS", "3"))):
    for site in sites:
        subprocess.run([sys.executable, "-c", CHILD, site], env=dict(os.environ, PYTHONPATH=site + os.pathsep + here),
                       check=False)
