#!/usr/bin/env bash
# An A/B of the resident engine in one run on the GPU machine (its host's times vary by up to 2x between runs):
# .carry/bin/cudahull_OLD, built here from an earlier commit (e.g. cudahull_3ebe518), against .carry/bin/cudahull,
# first the gpu tests most affected, then three alternating rounds of each input, Qhull beside the new one.
#   OLD=cudahull_3ebe518 bash bench/resident_ab_h100.sh
# INPUTS="ARGS|ARGS|..." and ROUNDS=N change the inputs and the rounds.
# OLD=env:NAME=VALUE is the new binary with that tuning variable set (e.g. env:CUDAHULL_LOOP_POINTS=32768).
export LD_LIBRARY_PATH=$PWD/.carry/lib
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p $O
timeout 200 $B/test_resident_cuda --gtest_filter='*SteppedRecords*:*Generated*:*Seeded*' > $O/t.txt 2>&1; echo "test exit $?"; grep -E "^\[  (PASSED|FAILED)|Failure" $O/t.txt | head -5
INPUTS=${INPUTS:-"--dist sphere --n 100000 --repeat 5|--dist sphere --n 1000000 --repeat 3|--dist gauss --n 1000000 --repeat 9|.carry/models/dragon_scans.ply --repeat 9|--dist cube --n 10000000 --repeat 7|--dist ball --n 10000000 --repeat 3"}
IFS='|' read -ra args <<< "$INPUTS"
: > $O/ab2.jsonl
for round in $(seq ${ROUNDS:-3}); do
  for a in "${args[@]}"; do
    for bin in ${OLD:?name the old binary} cudahull; do
      vs=""; [ $bin = cudahull ] && vs="--vs qhull"
      exe=$bin; env=""
      if [[ $bin == env:* ]]; then exe=cudahull; env=${bin#env:}; fi
      result=$(env $env $B/$exe bench $a --engine resident $vs --json) || result=null
      echo "{\"bin\": \"$bin\", \"round\": $round, \"args\": \"$a\", \"result\": $result}" >> $O/ab2.jsonl
    done
  done
done
python3 - <<PY
import json, collections
d = collections.defaultdict(list)
for l in open('$O/ab2.jsonl'):
    j = json.loads(l); r = j['result']
    d[(j['args'][-28:], j['bin'])].append((round(r['total_ms'], 3), r.get('same_vertices'), round(r.get('qhull_ms', 0))) if r else 'FAILED')
for k in sorted(d): print(k[0], k[1], d[k])
PY
