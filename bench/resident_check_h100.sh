#!/usr/bin/env bash
# Issue 15's checks of one commit on the GPU machine in one short call: test_resident_cuda (the models in
# .carry/models), the 10,000 property cases, a few bench rows against Qhull, then compute-sanitizer
# (memcheck on the seeded sets, 100 property cases, the models and the stepped records; racecheck and
# synccheck on the dragon and, racecheck, 30 property cases).  For the full table: resident_h100.sh.
#   bash bench/resident_check_h100.sh
set -u
export LD_LIBRARY_PATH=$PWD/.carry/lib CUDAHULL_MODELS_DIR=$PWD/.carry/models CUDAHULL_CLI=$PWD/.carry/bin/cudahull
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p $O
nvidia-smi -L
timeout 60 $B/test_resident_cuda > $O/t_full.txt 2>&1; echo "test_resident_cuda exit $?"
grep -E "^\[  (PASSED|FAILED)|Failure|OK \]" $O/t_full.txt | head -8
CUDAHULL_PROPERTY_CASES=10000 timeout 90 $B/test_resident_cuda --gtest_filter='*Property*' > $O/property_10000.txt 2>&1
echo "property 10000 exit $?"; grep -E "^\[  (PASSED|FAILED)|OK \]" $O/property_10000.txt
: > $O/bench.jsonl
bench() {
  local result
  result=$($B/cudahull bench $2 --engine resident --vs qhull --json) || result=null
  echo "{\"round\": $1, \"args\": \"$2\", \"result\": $result}" >> $O/bench.jsonl
}
for r in 1 2 3; do
  bench $r ".carry/models/dragon_scans.ply --repeat 9"; bench $r "--dist gauss --n 1000000 --repeat 9"
done
for a in "--dist cube --n 10000000 --repeat 5" "--dist ball --n 1000000 --repeat 5" "--dist sphere --n 100000 --repeat 5"; do bench 1 "$a"; done
python3 - "$O/bench.jsonl" <<'PY'
import json, sys
for l in open(sys.argv[1]):
    j = json.loads(l); r = j['result']
    if r is None:
        print(j['args'], 'FAILED'); continue
    print(r['input'][-22:], round(r['total_ms'], 3), round(r['qhull_ms'], 1), r['same_vertices'], r.get('host_syncs'), r.get('bytes_from_device'))
PY
export CUDAHULL_PROPERTY_CASES=100
timeout 80 compute-sanitizer --tool memcheck --error-exitcode 9 $B/test_resident_cuda \
  --gtest_filter='*Seeded*:*Property*:*SharedModels*:*SteppedRecords*' > $O/memcheck.txt 2>&1
echo "memcheck exit $?"; grep -E "ERROR SUMMARY|^\[  (PASSED|FAILED)" $O/memcheck.txt
for tool in racecheck synccheck; do
  timeout 50 compute-sanitizer --tool $tool --error-exitcode 9 $B/cudahull bench .carry/models/dragon_scans.ply \
    --engine resident --repeat 1 > $O/${tool}_dragon.txt 2>&1
  echo "$tool dragon exit $?"; grep -E "SUMMARY" $O/${tool}_dragon.txt
done
CUDAHULL_PROPERTY_CASES=30 timeout 60 compute-sanitizer --tool racecheck --error-exitcode 9 $B/test_resident_cuda \
  --gtest_filter='*Property*' > $O/racecheck_property.txt 2>&1
echo "racecheck property (30) exit $?"; grep -E "RACECHECK SUMMARY|^\[  (PASSED|FAILED)" $O/racecheck_property.txt
