#!/usr/bin/env bash
# On the GPU machine (Python 3.12 with NumPy, SciPy, pytest, CuPy and PyTorch; none of our Debian packages):
# the full wheel as a user installs it.  Installs the wheel carried in WHEEL_DIR (the cp312-abi3 wheel of
# scripts/wheel) into that Python with no CUDA Toolkit directory on PATH or LD_LIBRARY_PATH, then runs
# python/gpu_tests, the drop-in smoke test, the command line on the GPU, and the merged path's benchmark
# (python/bench/bench_merged.py: against Qhull on the CPU; merged against exact on the GPU).
# Logs go to $OUT.
#   WHEEL_DIR=.carry-wheel tests/wheel/run_on_gpu_machine.sh
set -uo pipefail
cd "$(dirname "$0")/../.."
OUT=${OUT:-/tmp/cudahull-out}
mkdir -p "$OUT"
export PYTHONUNBUFFERED=1 PYTHONDONTWRITEBYTECODE=1
PATH=$(printf '%s' "$PATH" | tr ':' '\n' | grep -vi cuda | paste -sd: -)
unset LD_LIBRARY_PATH CUDA_HOME CUDA_PATH
if command -v nvcc; then echo "nvcc is still on PATH"; exit 1; fi
nvidia-smi -L

site=/tmp/cudahull-site
rm -rf "$site"
python3 -m pip install -q --no-index --no-deps --target "$site" "${WHEEL_DIR:-.carry-wheel}"/cudahull-*-cp312-abi3-*.whl ||
  { echo "pip could not install the wheel"; exit 1; }
export PYTHONPATH=$site PATH=$site/bin:$PATH
python3 -c 'import cudahull, sys; print("cudahull from", cudahull.__file__, "on Python", sys.version.split()[0])'
ldd "$site"/cudahull/*.so "$site"/cudahull/_bin/cudahull | grep -E "not found|libcudart" && { echo "unresolved"; exit 1; }
# The viewer needs the system's OpenGL and EGL (glvnd), which this machine may not have installed.
ldd "$site"/cudahull/_bin/cudahull-viewer | grep "not found" | sed 's/^/viewer (the system GL libraries): /'

failed=0
echo "== python/gpu_tests"
python3 -m pytest -q -p no:cacheprovider -rs python/gpu_tests 2>&1 | tee "$OUT/gpu_tests.txt" | tail -25
[ "${PIPESTATUS[0]}" = 0 ] || failed=1
echo "== drop-in smoke"
python3 tests/wheel/drop_in_smoke.py || failed=1
echo "== the command line"
cudahull hull assets/bun_zipper.ply --verify -q --stats "$OUT/bunny_stats.json" || failed=1
python3 -c "import json; s = json.load(open('$OUT/bunny_stats.json')); print(s.get('plan'))"
echo "== merged path"
python3 python/bench/bench_merged.py --repeat 5 2>&1 | tee "$OUT/bench_merged_cpu.txt" || failed=1
PYTHONPATH=$site:python/bench python3 - <<'PY' 2>&1 | tee "$OUT/bench_merged_gpu.txt" || failed=1
# The merged path on the GPU against the exact hull on the GPU (and Qhull), 523,000 points in a ball.
import scipy.spatial, cudahull
from timing import ball_points, warm_best
p = ball_points()
def best(f, n=7):
    return warm_best(f, n)
exact, te = best(lambda: cudahull.ConvexHull(p))
print("plan:", exact.plan)
q, tq = best(lambda: scipy.spatial.ConvexHull(p, qhull_options="Qt"), 3)
for opts in ("Qt", "QbB Pp Qt"):
    merged, tm = best(lambda: cudahull.ConvexHull(p, qhull_options=opts))
    print(f"{opts!r}: exact {te*1e3:.2f} ms ({len(exact.vertices)} V), merged {tm*1e3:.2f} ms "
          f"({len(merged.vertices)} V, max_outside {merged.max_outside:.3g}), merged/exact {tm/te:.2f}, "
          f"Qhull 'Qt' {tq*1e3:.1f} ms ({len(q.vertices)} V)")
PY
exit $failed
