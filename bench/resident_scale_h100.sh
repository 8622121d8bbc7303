#!/usr/bin/env bash
# Issue 26 on the GPU machine: the resident engine at scale (no cliff: the defects the rounds leave are
# repaired where they are) and its gpu tests.  Run by the device tool from the repository root, with
# .carry/bin (cudahull, test_resident_cuda, test_cuda_backend, built here for sm_90; cudahull_base, the
# binary to compare with, optional), .carry/lib (libgmp.so.10, libqhull_r.so.8.0) and .carry/models (the
# shared models).
#   PART=tests  test_resident_cuda (the dense caps among them), test_cuda_backend, the 10,000 property
#               cases on the device path, compute-sanitizer memcheck and racecheck on the caps up to 30K
#   PART=scale  sphere 1M and 10M, ball and cube 10M from both binaries (BOTH="ARGS|ARGS"), then sphere
#               20M, 30M, 40M (SIZES="N N"), one line of `cudahull bench --json` each with the peak device
#               memory; the 400K-point cap of the issue through `cudahull hull --stats`
# The raw lines go to $OUT/scale.jsonl and the logs to $OUT.
set -u
export LD_LIBRARY_PATH=$PWD/.carry/lib CUDAHULL_MODELS_DIR=$PWD/.carry/models
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p "$O"
PART=${PART:?PART=tests or scale}
nvidia-smi -L
case $PART in
  tests)
    for t in test_resident_cuda test_cuda_backend; do
      timeout 300 $B/$t > "$O/$t.txt" 2>&1; echo "$t: exit $?"; grep -E "^\[  (PASSED|FAILED)" "$O/$t.txt"
    done
    CUDAHULL_PROPERTY_CASES=10000 timeout 200 $B/test_resident_cuda --gtest_filter='*Property*' \
      > "$O/property_10000.txt" 2>&1
    echo "property_10000: exit $?"; grep -E "^\[  (PASSED|FAILED)" "$O/property_10000.txt"
    for tool in memcheck racecheck; do
      CUDAHULL_CAP_POINTS=30000 timeout 200 compute-sanitizer --tool $tool --error-exitcode 9 \
        $B/test_resident_cuda --gtest_filter='*Defects*' > "$O/sanitizer_$tool.txt" 2>&1
      echo "$tool: exit $?"; grep -E "ERROR SUMMARY|RACECHECK SUMMARY|^\[  (PASSED|FAILED)" "$O/sanitizer_$tool.txt"
    done
    ;;
  scale)
    line() {  # BINARY LABEL ARGS...: one JSON line
      local bin=$1 label=$2
      shift 2
      echo "{\"binary\": \"$label\", \"result\": $(timeout 280 $B/$bin bench "$@" --engine resident --json)}" \
        | tee -a "$O/scale.jsonl" | python3 -c 'import json, sys
j = json.loads(sys.stdin.read()); r = j["result"]; s = r.get("resident", r)
print(j["binary"], r["input"], "total_ms", round(r["total_ms"], 1), "finish_ms", round(s["finish_ms"], 1),
      "overflows", s.get("round_overflows"), "B/vertex", round(r["device_bytes_peak"] / r["hull_vertices"]),
      "peak_GB", round(r["device_bytes_peak"] / 1e9, 2), "vertices", r["hull_vertices"], "faults",
      s["faults"], "repaired", s.get("repaired_patches"), "exact_finish", s["exact_finish"])' 2>&1 | tail -1
    }
    # The same inputs from both binaries first (peak memory and time side by side), then the sizes.
    IFS='|' read -ra both <<< "${BOTH:---dist sphere --n 1000000|--dist sphere --n 10000000|--dist ball --n 10000000|--dist cube --n 10000000}"
    for a in "${both[@]}"; do
      # shellcheck disable=SC2086
      line cudahull new $a --repeat 2
      # shellcheck disable=SC2086
      [ -x $B/cudahull_base ] && line cudahull_base base $a --repeat 2
    done
    for n in ${SIZES:-20000000 30000000 40000000}; do
      line cudahull new --dist sphere --n "$n" --repeat 2
    done
    python3 - "$O/cap.ply" <<'PY'
import sys
import numpy as np
r = np.random.default_rng(1)
n, m, angle = 400000, 2000, 0.05
u, phi = r.random(n), r.random(n) * 2 * np.pi
z = 1 - u * (1 - np.cos(angle)); s = np.sqrt(1 - z * z)
rest = r.normal(size=(m, 3)); rest /= np.linalg.norm(rest, axis=1)[:, None]
p = np.concatenate([np.stack([s * np.cos(phi), s * np.sin(phi), z], 1), rest]).astype(np.float32)
with open(sys.argv[1], "wb") as f:
    f.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {len(p)}\n"
            "property float x\nproperty float y\nproperty float z\nend_header\n".encode())
    f.write(p.tobytes())
PY
    for backend in cuda cpu; do
      $B/cudahull hull "$O/cap.ply" --engine resident --backend $backend --verify --stats - --quiet \
        > "$O/cap_$backend.json"
      echo "cap 400K $backend: exit $? $(grep -E '"(faults|repaired_patches|exact_finish|finish_ms|total_ms)"' "$O/cap_$backend.json" | tr -d ' \n')"
    done
    rm -f "$O/cap.ply"
    ;;
  *)
    echo "unknown PART=$PART"
    exit 2
    ;;
esac
