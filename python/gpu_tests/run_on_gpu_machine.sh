#!/usr/bin/env bash
# On the GPU machine (nvcc, CMake, ninja, Python 3.12 with NumPy, SciPy, pytest, CuPy and PyTorch, but none
# of the Debian packages the whole project needs): builds the Python module against what the development
# container built and carried in CARRY, then runs the Python tests (cpu and gpu) and the module's
# benchmark (python/bench/bench_module.py).  Logs and the benchmark's JSON go to $OUT.
#
# CARRY (default .carry-py) holds: prefix/ (`cmake --install BUILD --component library` of a build with
# -DCMAKE_POSITION_INDEPENDENT_CODE=ON), deps/ (nlohmann_json's headers and CMake files, which the package's
# config asks for), wheels/ (nanobind, pinned as in python/requirements-test.txt), bin/cudahull (the
# command line, for the comparison) and bin/lib/ (its shared libraries missing there: Qhull's).
#   PART=all|tests|bench python/gpu_tests/run_on_gpu_machine.sh
set -uo pipefail
cd "$(dirname "$0")/../.."
source python/gpu_tests/build_module.sh

echo "== machine"
nvidia-smi -L
nvcc --version | tail -1
python3 - <<'EOF'
import importlib, sys
print("python", sys.version.split()[0], sys.executable)
for name in ("numpy", "scipy", "pytest", "cupy", "torch", "nanobind", "dask", "distributed"):
    try:
        print(name, importlib.import_module(name).__version__)
    except Exception as e:
        print(name, "missing:", type(e).__name__)
EOF

echo "== build the module"
build_module
status=$?
tail -5 "$OUT/build.log"
[ $status = 0 ] || { echo "build failed"; exit 1; }
export PYTHONPATH=/tmp/build-py/python:/tmp/site

failed=0
if [ "$PART" = all ] || [ "$PART" = tests ]; then
  echo "== python/tests (the cpu suite; test_dask where dask is installed)"
  ignore=()
  python3 -c "import dask, distributed" 2>/dev/null || ignore=(--ignore=python/tests/test_dask.py)
  # python/tests/conftest.py fails any skip it does not allow: name what this Python lacks of
  # python/requirements-test.txt, so that its importorskip skips are allowed (and reported).
  without=()
  for module in trimesh mypy nanobind; do python3 -c "import $module" 2>/dev/null || without+=("$module"); done
  CUDAHULL_TESTS_WITHOUT=$(IFS=,; echo "${without[*]}")
  export CUDAHULL_TESTS_WITHOUT
  echo "python/tests without: ${CUDAHULL_TESTS_WITHOUT:-nothing}"
  python3 -m pytest -q -p no:cacheprovider -rs python/tests "${ignore[@]}" 2>&1 | tee "$OUT/pytest_cpu.txt" | tail -15
  [ "${PIPESTATUS[0]}" = 0 ] || failed=1
  echo "== python/gpu_tests"
  python3 -m pytest -q -p no:cacheprovider -rs python/gpu_tests 2>&1 | tee "$OUT/pytest_gpu.txt" | tail -25
  gpu_status=${PIPESTATUS[0]}
  echo "gpu tests exit $gpu_status (77: all skipped)"
  [ "$gpu_status" = 0 ] || failed=1
fi

if [ "$PART" = all ] || [ "$PART" = bench ]; then
  echo "== benchmark: $N points"
  export LD_LIBRARY_PATH="$PWD/$CARRY/bin/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  cli="$PWD/$CARRY/bin/cudahull"
  for dist in cube ball; do
    "$cli" gen "$dist" "$N" -o "/tmp/$dist.ply" >/dev/null || failed=1
    python3 python/bench/bench_module.py "$cli" "/tmp/$dist.ply" --repeat 5 --json "$OUT/bench_$dist.jsonl" 2>&1 |
      tee "$OUT/bench_$dist.txt" | tail -9
    [ "${PIPESTATUS[0]}" = 0 ] || failed=1
  done
fi
exit $failed
