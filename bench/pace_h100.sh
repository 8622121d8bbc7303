#!/usr/bin/env bash
# The pace goals' table on the GPU machine in one run (docs/benchmarks.md, "Phases and their floors"):
# every row of the resident engine's goals with this build (.carry/bin/cudahull) and, where OLD names it, its
# predecessor (.carry/bin/$OLD, built here from an earlier commit), alternating for ROUNDS rounds (default
# 2), then Qhull once on the rows it finishes in reasonable time (the same points: each binary generates
# them from the same seed).
# One JSON line a run in $OUT/pace.jsonl (with the resident engine's phases and floors); a summary on stdout.
#   OLD=cudahull_cbe1aa3 ROUNDS=2 bash bench/pace_h100.sh
#   ROUNDS=1 bash bench/pace_h100.sh   (this build alone: the phases and floors of every row)
# Carried: .carry/bin, .carry/lib (libqhull_r, libgmp), .carry/models/dragon_scans.ply.  The cube-faces row
# is written here as a binary PLY (every point on a face of the unit cube, seed 7).
# SKIP="sphere 100M|..." drops rows by label; BUDGET_S stops starting rows after that many seconds.
# VARIANT=cudahull_x runs a third binary (a change under test) on the rows VARIANT_ROWS="sphere 1M|..." names.
set -u
export LD_LIBRARY_PATH=$PWD/.carry/lib
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p "$O"
start=$(date +%s)
faces_ply=/tmp/cube_faces_10m.ply
python3 - "$faces_ply" <<'PY'
import sys
import numpy as np
rng = np.random.default_rng(7)
n = 10_000_000
p = rng.uniform(-1, 1, size=(n, 3)).astype(np.float32)
axis = rng.integers(0, 3, size=n)
p[np.arange(n), axis] = np.where(rng.integers(0, 2, size=n) == 1, 1.0, -1.0).astype(np.float32)
with open(sys.argv[1], "wb") as f:
    f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % n)
    f.write(b"property float x\nproperty float y\nproperty float z\nend_header\n")
    f.write(p.tobytes())
PY
# label|arguments|runs a binary|Qhull (1: once, on the new binary)
ROWS=(
  "cube 10M|--dist cube --n 10000000|5|1"
  "ball 10M|--dist ball --n 10000000|5|1"
  "ball 1M|--dist ball --n 1000000|5|1"
  "sphere 100K|--dist sphere --n 100000|5|1"
  "sphere 1M|--dist sphere --n 1000000|3|1"
  "sphere 10M|--dist sphere --n 10000000|3|0"
  "sphere 100M|--dist sphere --n 100000000|1|0"
  "gauss 1M|--dist gauss --n 1000000|7|1"
  "dragon_scans (469K)|.carry/models/dragon_scans.ply --precision float|7|1"
  "cylinder 10M|--dist cylinder --n 10000000|3|1"
  "cube faces 10M|$faces_ply|3|1"
)
: > "$O/pace.jsonl"
run() {  # BIN LABEL REPEAT EXTRA ARGS...
  local bin=$1 label=$2 repeat=$3 extra=$4
  shift 4
  timeout 300 $B/$bin bench "$@" --engine resident --repeat "$repeat" $extra --json 2>>"$O/pace_stderr.txt" |
    python3 -c 'import json, sys; j = json.loads(sys.stdin.read()); j["label"], j["bin"] = sys.argv[1], sys.argv[2]; print(json.dumps(j))' \
      "$label" "$bin" >> "$O/pace.jsonl" || echo "$label ($bin): failed"
}
for round in $(seq "${ROUNDS:-2}"); do
  for row in "${ROWS[@]}"; do
    IFS='|' read -r label args repeat qhull <<< "$row"
    [[ "|${SKIP:-}|" == *"|$label|"* ]] && continue
    [ $(( $(date +%s) - start )) -gt "${BUDGET_S:-100000}" ] && { echo "budget: $label round $round not run"; continue; }
    bins="${OLD:-} cudahull"
    [[ -n "${VARIANT:-}" && "|${VARIANT_ROWS:-}|" == *"|$label|"* ]] && bins="$bins $VARIANT"
    for bin in $bins; do
      run $bin "$label" "$repeat" "" $args
    done
    [ "$round" = 1 ] && [ "$qhull" = 1 ] && run cudahull "$label" 1 "--vs qhull" $args
  done
done
python3 - "$O/pace.jsonl" <<'PY'
import collections, json, sys
rows = collections.defaultdict(lambda: collections.defaultdict(list))
qhull = {}
for line in open(sys.argv[1]):
    j = json.loads(line)
    if "qhull_ms" in j:
        qhull[j["label"]] = (j["qhull_ms"], j["same_vertices"])
        continue
    rows[j["label"]][j["bin"]].append(j)
for label, bins in rows.items():
    cells = []
    for bin, runs in bins.items():
        cells.append(f'{bin} ' + "/".join(f'{r["total_ms"]:.3f}' for r in runs))
    new = bins.get("cudahull", [None])[-1]
    phases = ""
    if new:
        r = new["resident"]
        phases = ", ".join(f'{p["name"]} {p["ms"]:.3f}/{p["floor_ms"]:.3f}' for p in r["phases"] if p["ms"] > 0)
        phases += f' | floor {sum(p["floor_ms"] for p in r["phases"]):.3f} | B/vertex {new.get("bytes_per_hull_vertex", 0):.0f}'
    q = qhull.get(label)
    print(f'{label}: {"; ".join(cells)}; qhull {q[0]:.1f} ms same {q[1]}' if q else f'{label}: {"; ".join(cells)}', "|", phases)
PY
