# Sourced, from the repository root, by the scripts that build the Python module on the GPU machine against
# what the development container carried in CARRY (python/gpu_tests/run_on_gpu_machine.sh says what it
# holds): their settings, with their defaults, and build_module.
CARRY=${CARRY:-.carry-py}
OUT=${OUT:-/tmp/cudahull-out}
PART=${PART:-all}
N=${N:-10000000}
mkdir -p "$OUT"
export PYTHONUNBUFFERED=1 PYTHONDONTWRITEBYTECODE=1

# CARRY's wheels into /tmp/site (PYTHONPATH; the script exits when pip fails), then the module into
# /tmp/build-py, logged to $OUT/build.log.  Returns the build's status; build_seconds is what the build took.
build_module() {
  python3 -m pip install -q --no-index --no-deps --no-compile --target /tmp/site "$CARRY"/wheels/*.whl || exit 1
  export PYTHONPATH=/tmp/site
  local start=$SECONDS status
  cmake -S python/standalone -B /tmp/build-py -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$PWD/$CARRY/prefix;$PWD/$CARRY/deps" -DPython_EXECUTABLE="$(command -v python3)" \
    >"$OUT/build.log" 2>&1 && cmake --build /tmp/build-py >>"$OUT/build.log" 2>&1
  status=$?
  build_seconds=$((SECONDS - start))
  return $status
}
