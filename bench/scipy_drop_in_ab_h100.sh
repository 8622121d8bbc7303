#!/usr/bin/env bash
# "3-D no slower than now" (issue 25): an A/B in one device call of the Python module as it is against the
# module at a6c3d86 (before the drop-in), alternating rounds of python/bench/ab_module.py (ConvexHull of
# 10M cube and ball points from NumPy and from CuPy).  .carry-py as for bench/scipy_drop_in_h100.sh, plus
# prefix-old/ (`cmake --install` of a6c3d86's library, built with -DCMAKE_POSITION_INDEPENDENT_CODE=ON) and
# old/python/ (a6c3d86's python/ folder).  ROUNDS (default 3) rounds; one JSON line per build, input, round.
set -uo pipefail
cd "$(dirname "$0")/.."
CARRY=${CARRY:-.carry-py}
OUT=${OUT:-/tmp/cudahull-out}
ROUNDS=${ROUNDS:-3}
mkdir -p "$OUT"
export PYTHONUNBUFFERED=1 PYTHONDONTWRITEBYTECODE=1
nvidia-smi -L
python3 -m pip install -q --no-index --no-deps --no-compile --upgrade --target /tmp/site "$CARRY"/wheels/*.whl 2>/dev/null
export PYTHONPATH=/tmp/site LD_LIBRARY_PATH="$PWD/$CARRY/deps/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
rm -rf /tmp/build-new /tmp/build-old
cmake -S python/standalone -B /tmp/build-new -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PWD/$CARRY/prefix;$PWD/$CARRY/deps" -DPython_EXECUTABLE="$(command -v python3)" \
  >"$OUT/build_new.log" 2>&1 && cmake --build /tmp/build-new >>"$OUT/build_new.log" 2>&1 || { tail "$OUT/build_new.log"; exit 1; }
cmake -S "$CARRY/old/python/standalone" -B /tmp/build-old -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PWD/$CARRY/prefix-old;$PWD/$CARRY/deps" -DPython_EXECUTABLE="$(command -v python3)" \
  >"$OUT/build_old.log" 2>&1 && cmake --build /tmp/build-old >>"$OUT/build_old.log" 2>&1 || { tail "$OUT/build_old.log"; exit 1; }
for round in $(seq "$ROUNDS"); do
  for build in old new; do
    PYTHONPATH=/tmp/build-$build/python:/tmp/site python3 python/bench/ab_module.py "$build" | tee -a "$OUT/ab.jsonl"
  done
done
