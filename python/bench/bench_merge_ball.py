"""The host merge alone for the GPU row of issue 42 ("Qt" on 523,000 ball points), measured on the CPU: the
module's merged hull of the ball --repeat times, with the library's own phase times (CUDAHULL_PHASE_TIMES=1,
set here) read back from its stderr; prints the best "merge and faces" (merge_facets() and the faces'
indices, describe_merged() in api/src/describe.cpp) and the best whole call.  --input sphere takes
bench_merged.py's 1e5 sphere points instead (every point a vertex: the merge's largest case there).

    PYTHONPATH=build/python python3 python/bench/bench_merge_ball.py [--repeat 10] [--n 523000]
        [--input ball|sphere]
"""
import argparse
import os
import re
import subprocess
import sys

CHILD = r"""
import sys, time
import numpy as np
from cudahull import _cudahull
n, repeat, kind = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
if kind == "sphere":
    ball = np.random.default_rng(42).normal(size=(100_000, 3))
    ball /= np.linalg.norm(ball, axis=1, keepdims=True)
else:
    ball = np.random.default_rng(1).uniform(-1, 1, size=(2 * n, 3))
    ball = np.ascontiguousarray(ball[np.einsum("ij,ij->i", ball, ball) <= 1][:n])
for _ in range(repeat):
    t = time.perf_counter()
    hull = _cudahull.convex_hull(ball, "cpu", "auto", "auto", "qhull", 0.0, 1.0)
    print(f"call {1e3 * (time.perf_counter() - t):.3f} ms {len(hull['vertices'])} vertices", flush=True)
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=10)
    ap.add_argument("--n", type=int, default=523_000)
    ap.add_argument("--input", choices=("ball", "sphere"), default="ball")
    a = ap.parse_args()
    env = dict(os.environ, CUDAHULL_PHASE_TIMES="1")
    run = subprocess.run([sys.executable, "-c", CHILD, str(a.n), str(a.repeat), a.input], env=env, capture_output=True,
                         text=True, check=True)
    merges = [float(m) for m in re.findall(r"merge and faces ([0-9.]+) ms", run.stderr)]
    calls = [float(m) for m in re.findall(r"call ([0-9.]+) ms", run.stdout)]
    vertices = re.findall(r"(\d+) vertices", run.stdout)[-1]
    print(f"{a.input}: {vertices} merged vertices: merge and faces best {min(merges):.2f} ms "
          f"(median {sorted(merges)[len(merges) // 2]:.2f}), whole call best {min(calls):.1f} ms")


if __name__ == "__main__":
    main()
