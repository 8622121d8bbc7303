#!/usr/bin/env bash
# The resident engine's phases against the hardware's floor on the GPU machine: the gpu label's C++ tests,
# then `cudahull bench --json` on the rows of the pace goals (docs/benchmarks.md, "Phases and their
# floors"), one JSON line each in $OUT/phases.jsonl and a table on stdout.  Run by the device tool from the
# repository root with .carry/bin (cudahull, test_resident_cuda, test_cuda_backend, built here for sm_90),
# .carry/lib (libqhull_r, libgmp) and .carry/models (the shared models) carried.
set -u
export LD_LIBRARY_PATH=$PWD/.carry/lib CUDAHULL_MODELS_DIR=$PWD/.carry/models CUDAHULL_CLI=$PWD/.carry/bin/cudahull
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p "$O"
nvidia-smi -L
for t in test_cuda_backend test_resident_cuda; do
  timeout 300 $B/$t > "$O/$t.txt" 2>&1
  echo "$t: exit $? $(grep -hE '^\[  (PASSED|FAILED)' "$O/$t.txt" | tr '\n' ' ')"
done
: > "$O/phases.jsonl"
bench() {  # LABEL ARGS...
  local label=$1
  shift
  timeout 120 $B/cudahull bench "$@" --repeat 5 --json 2>>"$O/bench_stderr.txt" |
    python3 -c 'import json, sys; j = json.loads(sys.stdin.read()); j["label"] = sys.argv[1]; print(json.dumps(j))' \
      "$label" >> "$O/phases.jsonl" || echo "$label: failed"
}
bench "cube 10M" --dist cube --n 10000000
bench "ball 10M" --dist ball --n 10000000
bench "ball 1M" --dist ball --n 1000000
bench "sphere 100K" --dist sphere --n 100000
bench "sphere 1M" --dist sphere --n 1000000
bench "sphere 10M" --dist sphere --n 10000000
bench "gauss 1M" --dist gauss --n 1000000
bench "dragon_scans (469K)" .carry/models/dragon_scans.ply --precision float
bench "cylinder 10M" --dist cylinder --n 10000000
python3 - "$O/phases.jsonl" <<'PY'
import json, sys
for line in open(sys.argv[1]):
    j = json.loads(line)
    r = j["resident"]
    cells = ", ".join(f'{p["name"]} {p["ms"]:.3f}/{p["floor_ms"]:.3f}' for p in r["phases"] if p["ms"] > 0)
    print(f'{j["label"]}: total {j["total_ms"]:.3f} ms (last run {r["phases_total_ms"]:.3f}); {cells}; '
          f'pace {r["pace"]["bytes_per_ms"] / 1e9:.2f} TB/s, launch {r["pace"]["launch_ms"] * 1e3:.1f} us, '
          f'wait {r["pace"]["wait_ms"] * 1e3:.1f} us')
PY
