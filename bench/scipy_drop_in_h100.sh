#!/usr/bin/env bash
# The scipy drop-in (issue 25) on the GPU machine, in one device call: the Python module built there against
# .carry-py (python/gpu_tests/run_on_gpu_machine.sh says what it holds; here also deps/lib/libgmp.a and
# deps/include/gmp.h, and trimesh's wheel in wheels/), then
#   python/gpu_tests                      CuPy and PyTorch inputs, 2-D ones filtered on the device included
#   python/tests                          the cpu suite, less test_scipy_suite.py (its counts are scipy
#                                         1.17.1's, which CI pins; the GPU machine has its own scipy)
#   python/bench/bench_planar.py          2-D, N points, from NumPy and from CuPy, against scipy; 3-D through
#                                         the drop-in, exact and merged
#   python/bench/bench_module.py          3-D, N cube and ball points: the module against `cudahull bench`
#   PART=sanitizers                       compute-sanitizer memcheck and racecheck on the 2-D filter's kernels
# Logs and JSON go to $OUT.  PART=all|tests|bench|sanitizers (all: tests and bench).
set -uo pipefail
cd "$(dirname "$0")/.."
source python/gpu_tests/build_module.sh
nvidia-smi -L
python3 -c "import numpy, scipy, cupy, torch; print('numpy', numpy.__version__, 'scipy', scipy.__version__, 'cupy', cupy.__version__, 'torch', torch.__version__)"

rm -rf /tmp/build-py
build_module || { tail -20 "$OUT/build.log"; exit 1; }
echo "module built in $build_seconds s"
export PYTHONPATH=/tmp/build-py/python:/tmp/site LD_LIBRARY_PATH="$PWD/$CARRY/deps/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

failed=0
if [ "$PART" = all ] || [ "$PART" = tests ]; then
  python3 -m pytest -q -p no:cacheprovider -rs python/gpu_tests 2>&1 | tee "$OUT/pytest_gpu.txt" | tail -15
  [ "${PIPESTATUS[0]}" = 0 ] || failed=1
  ignore=(--ignore=python/tests/test_scipy_suite.py)
  python3 -c "import dask, distributed" 2>/dev/null || ignore+=(--ignore=python/tests/test_dask.py)
  python3 -m pytest -q -p no:cacheprovider -rs python/tests "${ignore[@]}" 2>&1 | tee "$OUT/pytest_cpu.txt" | tail -8
  [ "${PIPESTATUS[0]}" = 0 ] || failed=1
fi
if [ "$PART" = sanitizers ]; then
  # The 2-D filter's kernels: memcheck and racecheck over python/gpu_tests/planar_sanitizer_case.py.
  for tool in memcheck racecheck; do
    compute-sanitizer --tool $tool --error-exitcode 9 python3 python/gpu_tests/planar_sanitizer_case.py \
      > "$OUT/sanitizer_$tool.txt" 2>&1
    status=$?
    echo "sanitizer $tool: exit $status $(grep -hE 'ERROR SUMMARY|RACECHECK SUMMARY|cases: ok' "$OUT/sanitizer_$tool.txt" | tr '\n' ' ')"
    [ $status = 0 ] || failed=1
  done
fi
if [ "$PART" = all ] || [ "$PART" = bench ]; then
  python3 python/bench/bench_planar.py --n "$N" --repeat 5 --json "$OUT/bench_planar.jsonl" 2>&1 |
    tee "$OUT/bench_planar.txt" | tail -12
  [ "${PIPESTATUS[0]}" = 0 ] || failed=1
  export LD_LIBRARY_PATH="$PWD/$CARRY/bin/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  for dist in cube ball; do
    "$CARRY/bin/cudahull" gen "$dist" "$N" -o "/tmp/$dist.ply" >/dev/null || failed=1
    python3 python/bench/bench_module.py "$CARRY/bin/cudahull" "/tmp/$dist.ply" --repeat 5 \
      --json "$OUT/bench_module_$dist.jsonl" 2>&1 | tee "$OUT/bench_module_$dist.txt" | tail -9
    [ "${PIPESTATUS[0]}" = 0 ] || failed=1
  done
fi
exit $failed
