#!/usr/bin/env bash
# Issue 15 on the GPU machine: the resident engine's gpu test, compute-sanitizer on it, and the speed table
# (docs/benchmarks.md, "The resident engine"): the resident engine and the stepping engine on the same
# points, Qhull in the same run.  Run by the device tool from the repository root, with what it carries in
# .carry/: bin/ (cudahull, test_resident_cuda, test_cuda_backend, built here for sm_90), lib/ (libqhull_r.so.8.0), models/
# (the shared models).
set -u
export LD_LIBRARY_PATH=$PWD/.carry/lib CUDAHULL_MODELS_DIR=$PWD/.carry/models
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p $O
nvidia-smi -L
echo "== gpu tests (the resident engine; the stepping engine's CUDA backend)"
$B/test_resident_cuda 2>&1 | tee $O/test_resident_cuda.txt | grep -E "^\[  (PASSED|FAILED|SKIPPED)|FAILED|tests ran"
$B/test_cuda_backend 2>&1 | tee $O/test_cuda_backend.txt | grep -E "^\[  (PASSED|FAILED|SKIPPED)|FAILED|tests ran"
if [ "${SANITIZE:-1}" = 1 ]; then
  # The property cases: the first 100 (float and double) under each tool.
  export CUDAHULL_PROPERTY_CASES=100
  for tool in memcheck racecheck synccheck initcheck; do
    echo "== compute-sanitizer --tool $tool"
    compute-sanitizer --tool $tool --error-exitcode 9 $B/test_resident_cuda \
      --gtest_filter='*Seeded*:*SharedModels*:*Property*' > $O/sanitizer_$tool.txt 2>&1
    echo "exit $?"; grep -E "ERROR SUMMARY|PASSED|FAILED" $O/sanitizer_$tool.txt | head -3
  done
fi
echo "== speed: resident (Qhull in the same run), then stepping"
run() { echo "{\"engine\": \"$1\", \"result\": $($B/cudahull bench "${@:2}" --engine $1 --json)}" | tee -a $O/bench_resident.jsonl; }
for a in "--dist sphere --n 100000 --repeat 5" "--dist sphere --n 1000000 --repeat 3" "--dist ball --n 1000000 --repeat 5" \
         "--dist ball --n 10000000 --repeat 3" "--dist cube --n 10000000 --repeat 3" "--dist gauss --n 1000000 --repeat 5" \
         ".carry/models/dragon_scans.ply --repeat 5"; do
  run resident $a --vs qhull
  run stepping $a
done
echo "== double (the same points), resident"
run resident --dist ball --n 10000000 --repeat 3 --precision double
run resident --dist sphere --n 1000000 --repeat 3 --precision double
echo "== sphere 10M (a 20M-face hull), resident only"
run resident --dist sphere --n 10000000 --repeat 3
