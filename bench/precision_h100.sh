#!/usr/bin/env bash
# Issue 14 on the GPU machine: the gpu label in both precisions, the models, and float/double timings with
# the float path before (84aa319) and after (docs/benchmarks.md, "Float and double").  Run by the device
# tool from the repository root, with what it carries in .carry/: bin/ (cudahull, cudahull-84aa319,
# test_cuda_backend, test_viewer_interop, built here for sm_90), lib/ (libqhull_r.so.8.0), models/ (the
# shared models), and the GL loader packages in .gl/ (the device tool's README says how).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export LD_LIBRARY_PATH=$PWD/.carry/lib CUDAHULL_MODELS_DIR=$PWD/.carry/models CUDAHULL_CLI=$PWD/.carry/bin/cudahull
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p $O
nvidia-smi -L
echo "== gpu label"
$B/test_cuda_backend 2>&1 | tee $O/test_cuda_backend.txt | grep -E "^\[  (PASSED|FAILED|SKIPPED)|FAILED|tests ran"
$B/test_viewer_interop 2>&1 | tail -3
echo "== models through cuda, --verify, auto and forced precisions"
for m in .carry/models/*.ply .carry/models/*.obj; do
  for p in auto float double; do
    $B/cudahull hull $m --backend cuda --engine stepping --verify --precision $p -q --stats - | python3 -c "import json,sys; j=json.load(sys.stdin); print('$m', '$p', j['precision'], j['hull_vertices'], j['verified'])"
  done
done
echo "== float and double, same points, Qhull in the same run"
for d in cube ball; do for p in float double float double; do
  $B/cudahull bench --dist $d --n 10000000 --repeat 3 --engine stepping --precision $p --vs qhull --json | tee -a $O/bench_precision.jsonl
done; done
echo "== float path before (84aa319) and after, alternating"
for round in 1 2; do
  for bin in cudahull-84aa319 cudahull; do
    for a in "--dist cube --n 10000000 --repeat 5" "--dist ball --n 10000000 --repeat 5" "--dist sphere --n 1000000 --repeat 1" ".carry/models/dragon_scans.ply --repeat 5"; do
      echo "{\"binary\": \"$bin\", \"round\": $round, \"result\": $($B/$bin bench $a --json)}" | tee -a $O/bench_before_after.jsonl
    done
  done
done
