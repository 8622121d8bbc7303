#!/usr/bin/env bash
# Issue 15 on the GPU machine: the resident engine's gpu tests, the property cases in full on the device
# path, compute-sanitizer, and the speed table (docs/benchmarks.md, "The resident engine"): the resident
# engine and the stepping engine on the same points, Qhull in the same run.  Run by the device tool from the
# repository root, with what it carries in .carry/: bin/ (cudahull, test_resident_cuda, test_cuda_backend,
# built here for sm_90), lib/ (libqhull_r.so.8.0), models/ (the shared models).
#   PART=tests   the gpu tests, the 10,000 property cases, compute-sanitizer
#   PART=bench   the speed table
#   (unset)      both
#   RACE2=1 with PART=bench: racecheck on the models and the stepped records first; SKIP_STEPPING=1: the
#   speed table without the stepping engine's column
set -u
export LD_LIBRARY_PATH=$PWD/.carry/lib CUDAHULL_MODELS_DIR=$PWD/.carry/models
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p $O
PART=${PART:-all}
nvidia-smi -L
if [ "$PART" != bench ]; then
  echo "== gpu tests (the resident engine; the stepping engine's CUDA backend)"
  for t in test_resident_cuda test_cuda_backend; do
    timeout 300 $B/$t > $O/$t.txt 2>&1; echo "$t: exit $?"; grep -E "^\[  (PASSED|FAILED)" $O/$t.txt
  done
  echo "== the property cases, all 10,000 in float and in double, device == host executor == exact_hull"
  CUDAHULL_PROPERTY_CASES=10000 timeout 300 $B/test_resident_cuda --gtest_filter='*Property*' \
    > $O/property_10000.txt 2>&1
  echo "exit $?"; grep -E "^\[  (PASSED|FAILED)" $O/property_10000.txt
  # The first 100 property cases, the seeded sets and the models under each tool (racecheck, the
  # slowest, without the generated sets).
  export CUDAHULL_PROPERTY_CASES=100
  # racecheck, the slowest, in two runs (the seeded sets alone take about 190 s under it).
  for tool in memcheck synccheck initcheck racecheck racecheck2; do
    echo "== compute-sanitizer --tool ${tool%2}"
    filter='*Seeded*:*SharedModels*:*Property*:*Generated*:*SteppedRecords*'
    [ $tool = racecheck ] && filter='*Seeded*:*Property*'
    [ $tool = racecheck2 ] && filter='*SharedModels*:*SteppedRecords*'
    timeout 280 compute-sanitizer --tool ${tool%2} --error-exitcode 9 $B/test_resident_cuda --gtest_filter="$filter" \
      > $O/sanitizer_$tool.txt 2>&1
    echo "exit $?"; grep -E "ERROR SUMMARY|RACECHECK SUMMARY|^\[  (PASSED|FAILED)" $O/sanitizer_$tool.txt | head -3
  done
  unset CUDAHULL_PROPERTY_CASES
fi
if [ "$PART" = bench ] && [ -n "${RACE2:-}" ]; then
  echo "== compute-sanitizer --tool racecheck (the stepped records)"
  CUDAHULL_PROPERTY_CASES=100 timeout 280 compute-sanitizer --tool racecheck --error-exitcode 9 $B/test_resident_cuda \
    --gtest_filter='*SteppedRecords*' > $O/sanitizer_racecheck2.txt 2>&1
  echo "exit $?"; grep -E "RACECHECK SUMMARY|^\[  (PASSED|FAILED)" $O/sanitizer_racecheck2.txt | head -3
fi
if [ "$PART" != tests ]; then
  echo "== speed: resident (Qhull in the same run), then stepping"
  run() { echo "{\"engine\": \"$1\", \"result\": $($B/cudahull bench "${@:2}" --engine $1 --json)}" | tee -a $O/bench_resident.jsonl; }
  for a in "--dist sphere --n 100000 --repeat 5" "--dist sphere --n 1000000 --repeat 3" "--dist ball --n 1000000 --repeat 5" \
           "--dist ball --n 10000000 --repeat 3" "--dist cube --n 10000000 --repeat 5" "--dist gauss --n 1000000 --repeat 7" \
           ".carry/models/dragon_scans.ply --repeat 7"; do
    run resident $a --vs qhull
    [ -z "${SKIP_STEPPING:-}" ] && run stepping $a
  done
  echo "== double (the same points), resident"
  run resident --dist ball --n 10000000 --repeat 3 --precision double
  run resident --dist sphere --n 1000000 --repeat 3 --precision double
  echo "== sphere 10M (a 20M-face hull), resident only"
  run resident --dist sphere --n 10000000 --repeat 3
  echo "== records on (--table: a step at a time, each step's records read back), sphere 1M"
  $B/cudahull gen sphere 1000000 -o /tmp/sphere_1m.xyz 2>/dev/null
  for engine in resident stepping; do
    /usr/bin/time -f "$engine --table: %e s wall" $B/cudahull hull /tmp/sphere_1m.xyz --engine $engine --backend cuda \
      --table --quiet > $O/table_$engine.txt
    tail -3 $O/table_$engine.txt
  done
  echo "== the viewer at 20M points, CUDA-GL interop, 1920x1080: resident and stepping engines"
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  for dist in cube ball; do
    for engine in resident stepping; do
      echo "{\"engine\": \"$engine\", \"dist\": \"$dist\", \"result\": $($B/cudahull-viewer --gen $dist 20000000 \
        --headless --width 1920 --height 1080 --steps 2 --bench-frames 200 --engine $engine --quiet)}" \
        | tee -a $O/viewer_resident.jsonl
    done
  done
fi
