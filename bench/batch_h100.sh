#!/usr/bin/env bash
# Batched hulls on the GPU machine (issue 27), in one run: the gpu tests that cover the batch kernel (and
# the device allocator every CUDA path shares), compute-sanitizer on a batch, `cudahull bench --batch` at the
# issue's sizes against a loop of Qhull, then the Python module built there, its gpu tests, and
# python/bench/bench_batch.py from PyTorch tensors against loops of scipy and of single calls.
# Carried: .carry/bin.tar.xz (cudahull, test_resident_cuda, test_cuda_backend, test_convex_hull_batch, built
# here for sm_90, unpacked into .carry/bin), .carry/lib (Qhull's and GMP's shared libraries), .carry/models, and .carry-py as
# python/gpu_tests/run_on_gpu_machine.sh says.
#   PART=tests|bench|python|all bash bench/batch_h100.sh
#   PART=profile bash bench/batch_h100.sh  (ncu on a batch kernel; PROFILE_INPUTS="REGEX B N DIST|...")
#   PART=variants bash bench/batch_h100.sh  (builds or settings side by side; VARIANTS="LABEL:ENV=VALUE:BIN|...")
#   PART=ab bash bench/batch_h100.sh  (this build against cudahull_base; AB_INPUTS="B N DIST|...", ROUNDS)
set -uo pipefail
O=${OUT:-/tmp/out}
PART=${PART:-all}
mkdir -p $O .carry/bin
tar -xJf .carry/bin.tar.xz -C .carry/bin
export LD_LIBRARY_PATH=$PWD/.carry/lib CUDAHULL_MODELS_DIR=$PWD/.carry/models CUDAHULL_CLI=$PWD/.carry/bin/cudahull
B=.carry/bin
failed=0
nvidia-smi -L

if [ "$PART" = all ] || [ "$PART" = tests ]; then
  for t in test_resident_cuda test_cuda_backend test_convex_hull_batch; do
    timeout 300 $B/$t ${FILTER:+--gtest_filter=$FILTER} >$O/$t.txt 2>&1
    echo "$t exit $?"; grep -E "^\[  (PASSED|FAILED)|Failure|SKIPPED" $O/$t.txt | head -8
  done
  timeout 200 compute-sanitizer --tool memcheck --error-exitcode 9 $B/cudahull bench --batch 300 --n 700 \
    --dist sphere --backend cuda --repeat 1 >$O/memcheck.txt 2>&1
  echo "memcheck exit $?"; tail -3 $O/memcheck.txt
  timeout 200 compute-sanitizer --tool racecheck --error-exitcode 9 $B/cudahull bench --batch 40 --n 3000 \
    --dist ball --backend cuda --repeat 1 >$O/racecheck.txt 2>&1
  echo "racecheck exit $?"; tail -3 $O/racecheck.txt
fi

if [ "$PART" = all ] || [ "$PART" = bench ]; then
  : >$O/batch_cli.jsonl
  for args in "10000 1000 ball" "100000 100 ball" "100 100000 ball" "10000 1000 sphere" "1000 5000 cube"; do
    set -- $args
    timeout 240 $B/cudahull bench --batch $1 --n $2 --dist $3 --backend cuda --repeat 5 --vs qhull --json \
      >>$O/batch_cli.jsonl 2>$O/batch_cli_err.txt || { echo "bench $args failed"; cat $O/batch_cli_err.txt; }
  done
  python3 - <<PY
import json
for l in open('$O/batch_cli.jsonl'):
    j = json.loads(l)
    print(j['input'], 'total', round(j['total_ms'], 2), 'ms; qhull loop', round(j.get('versus_ms', 0)), 'ms;',
          'batched', j['clouds_batched'], 'launches', j['batch_launches'], 'peak MB',
          round(j['device_bytes_peak'] / 2**20), 'differ', j.get('clouds_with_different_vertices'),
          'device', round(j['device_ms'], 1), 'kernel', round(j['kernel_ms'], 1), 'describe', round(j['describe_ms'], 1))
PY
fi

if [ "$PART" = ncu ]; then  # issue 26: every kernel's time (NCU_INPUTS="ARGS|ARGS"), this build and OLD's
  IFS='|' read -ra ncu_inputs <<< "${NCU_INPUTS:-.carry/models/dragon_scans.ply|--dist ball --n 1000000}"
  for bin in ${OLD:-cudahull_base} cudahull; do
    for args in "${ncu_inputs[@]}"; do
      timeout 120 ncu --metrics gpu__time_duration.sum --csv $B/$bin bench $args --engine resident --repeat 1 \
        >$O/ncu_${bin}_$(echo $args | tr -c 'a-z0-9' _).csv 2>/dev/null
      python3 - $O/ncu_${bin}_$(echo $args | tr -c 'a-z0-9' _).csv "$bin $args" <<'PY'
import csv, sys, collections
rows = [r for r in csv.reader(open(sys.argv[1])) if len(r) > 10]
head, body = rows[0], rows[1:]
k, v = head.index('Kernel Name'), head.index('Metric Value')
t = collections.Counter(); n = collections.Counter()
for r in body:
    name = r[k].split('(')[0].split('<')[0][-40:]
    t[name] += float(r[v].replace(',', '')); n[name] += 1
print(sys.argv[2], 'kernels', sum(n.values()), 'gpu us', round(sum(t.values()) / 1000, 1))
for name, ns in t.most_common(8): print('   ', name, n[name], round(ns / 1000, 1))
PY
    done
  done
fi

# ncu's full set on one batch kernel (PROFILE_INPUTS="KERNEL_REGEX B N DIST|..."): the details page, and the
# per-instruction page (SASS addresses, samples, instructions) that nvdisasm -g maps to source lines on the
# build machine, where the sources and the cubin are.
if [ "$PART" = profile ]; then
  IFS='|' read -ra profile_inputs <<< "${PROFILE_INPUTS:-batch_warp_kernel 100000 100 ball|batch_kernel 10000 1000 ball}"
  for args in "${profile_inputs[@]}"; do
    set -- $args
    name=$(echo "$1_$2x$3_$4" | tr -c 'A-Za-z0-9_\n' _)
    timeout 300 ncu --set full -k regex:"^$1" -c 1 -o $O/$name $B/cudahull bench --batch $2 --n $3 --dist $4 \
      --backend cuda --repeat 1 >$O/$name.log 2>&1 || { echo "ncu $args failed"; tail -5 $O/$name.log; }
    ncu -i $O/$name.ncu-rep --page details >$O/$name.details.txt 2>&1
    ncu -i $O/$name.ncu-rep --page source --csv --print-source sass >$O/$name.sass.csv 2>&1
    xz -9 $O/$name.sass.csv
    echo "$args: $(grep -E "Duration|Registers Per|Achieved Occupancy|Issued Ipc Active|Executed Instructions  " $O/$name.details.txt | tr -s ' ' | head -6 | tr '\n' ';')"
  done
fi

# Builds or settings side by side, ROUNDS rounds: VARIANTS="LABEL:ENV=VALUE:BIN|..." (PART=ab: this build
# against cudahull_base, built from another commit).
if [ "$PART" = variants ] || [ "$PART" = ab ]; then
  : >$O/batch_variants.jsonl
  IFS='|' read -ra variants <<< "${VARIANTS:-base::cudahull_base|new::cudahull}"
  IFS='|' read -ra ab_inputs <<< "${AB_INPUTS:-10000 1000 ball|100000 100 ball|100 100000 ball|20000 128 sphere}"
  for round in $(seq ${ROUNDS:-2}); do
    for variant in "${variants[@]}"; do
      IFS=':' read -r label setting bin <<< "$variant"
      for args in "${ab_inputs[@]}"; do
        set -- $args
        result=$(env $setting timeout 120 $B/$bin bench --batch $1 --n $2 --dist $3 --backend cuda --repeat 5 \
          ${4:+--precision $4} --json) || result=null
        echo "{\"variant\": \"$label\", \"round\": $round, \"input\": \"$args\", \"result\": $result}" \
          >>$O/batch_variants.jsonl
      done
    done
  done
  python3 - $O/batch_variants.jsonl <<'PY'
import json, sys
for l in open(sys.argv[1]):
    j = json.loads(l); r = j['result'] or {}
    print(f"{j['input']:24s} {j['variant']:14s} round {j['round']}: total {r.get('total_ms', 0):7.2f} device "
          f"{r.get('device_ms', 0):7.2f} kernel {r.get('kernel_ms', 0):7.2f} describe {r.get('describe_ms', 0):5.2f} ms")
PY
fi

if [ "$PART" = all ] || [ "$PART" = python ]; then
  PART=none python/gpu_tests/run_on_gpu_machine.sh >$O/py_build.txt 2>&1 || { echo "module build failed"; tail $O/py_build.txt; }
  export PYTHONPATH=/tmp/build-py/python:/tmp/site
  timeout 300 python3 -m pytest -q -p no:cacheprovider -rs python/gpu_tests 2>&1 | tee $O/pytest_gpu.txt | tail -6
  : >$O/batch_py.jsonl
  for args in "10000 1000" "100000 100" "100 100000"; do
    set -- $args
    timeout 200 python3 python/bench/bench_batch.py --batch $1 --n $2 --json $O/batch_py.jsonl || failed=1
  done
fi
exit $failed
