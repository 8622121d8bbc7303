#!/usr/bin/env bash
# A tuning variable of the resident engine swept in one run on the GPU machine (its host's times vary by up
# to 2x between runs): ROUNDS alternating rounds of every value on each input, `cudahull bench ARGS
# --engine resident --json`, with .carry/bin/cudahull built here for sm_90.
#   VAR=CUDAHULL_SLOT_LANES VALUES="1 2 4 8" bash bench/tuning_sweep_h100.sh
export LD_LIBRARY_PATH=$PWD/.carry/lib
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p $O
: "${VAR:?name the variable}" "${VALUES:?list its values}"
INPUTS=${INPUTS:-".carry/models/dragon_scans.ply --repeat 9|--dist gauss --n 1000000 --repeat 9|--dist cube --n 10000000 --repeat 5|--dist ball --n 1000000 --repeat 5|--dist sphere --n 100000 --repeat 5|--dist sphere --n 1000000 --repeat 3"}
IFS='|' read -ra args <<< "$INPUTS"
: > $O/sweep.jsonl
for round in $(seq ${ROUNDS:-3}); do
  for a in "${args[@]}"; do
    for v in $VALUES; do
      result=$(env $VAR=$v $B/cudahull bench $a --engine resident --json) || result=null
      echo "{\"$VAR\": \"$v\", \"round\": $round, \"args\": \"$a\", \"result\": $result}" >> $O/sweep.jsonl
    done
  done
done
python3 - "$O/sweep.jsonl" "$VAR" <<'PY'
import json, collections, sys
d = collections.defaultdict(list)
for l in open(sys.argv[1]):
    j = json.loads(l); r = j['result']
    d[(j['args'][-28:], j[sys.argv[2]])].append(round(r['total_ms'], 3) if r else float('nan'))
for k in sorted(d): print(f'{k[0]:28s} {sys.argv[2]}={k[1]:>6s}', d[k], 'median', sorted(d[k])[len(d[k]) // 2])
PY
