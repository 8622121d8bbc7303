#!/usr/bin/env bash
# The whole `gpu` label on the GPU machine (it has no Debian packages, so ctest cannot run there), in parts
# that each fit one device call of 10 minutes.  Run by the device tool from the repository root, with
# .carry/bin (cudahull, test_resident_cuda, test_cuda_backend, test_viewer_interop, built here for sm_90),
# .carry/lib (libqhull_r and the GL loaders the interop test needs: libEGL, libOpenGL, libGLdispatch,
# libtinyobjloader), .carry/models (the shared models) and, for PART=python, .carry-py (see
# python/gpu_tests/run_on_gpu_machine.sh).
#   PART=tests       test_cuda_backend, test_viewer_interop (CUDA-GL interop through headless EGL),
#                    test_resident_cuda, and the 10,000 property cases on the resident engine's device path
#   PART=python      the Python module built there, its cpu tests and its gpu tests (CuPy, PyTorch)
#   PART=sanitizers  compute-sanitizer memcheck, synccheck and initcheck on test_resident_cuda (seeded,
#                    generated, model, 100 property and stepped-record cases), racecheck on the seeded sets,
#                    the property cases and the stepped records
#   PART=racecheck-models  racecheck on the six shared models (the slowest: one call of its own)
# Each part prints one line per test program with its exit status; the logs go to $OUT.
set -u
export LD_LIBRARY_PATH=$PWD/.carry/lib CUDAHULL_MODELS_DIR=$PWD/.carry/models CUDAHULL_CLI=$PWD/.carry/bin/cudahull
export __EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json}
B=.carry/bin; O=${OUT:-/tmp/out}; mkdir -p "$O"
PART=${PART:?PART=tests, python, sanitizers or racecheck-models}
nvidia-smi -L
failed=0
run() {  # NAME TIMEOUT COMMAND...: the command's log to $O/NAME.txt, a summary line here
  local name=$1 limit=$2 start=$SECONDS status
  shift 2
  timeout "$limit" "$@" > "$O/$name.txt" 2>&1
  status=$?
  echo "$name: exit $status ($((SECONDS - start)) s) $(grep -hE '^\[  (PASSED|FAILED)|ERROR SUMMARY|RACECHECK SUMMARY' "$O/$name.txt" | tr '\n' ' ')"
  [ $status = 0 ] || failed=1
}
case $PART in
  tests)
    run test_cuda_backend 300 $B/test_cuda_backend
    run test_viewer_interop 120 $B/test_viewer_interop
    run test_resident_cuda 300 $B/test_resident_cuda
    CUDAHULL_PROPERTY_CASES=10000 run property_10000 300 $B/test_resident_cuda --gtest_filter='*Property*'
    ;;
  python)
    PART=tests OUT=$O python/gpu_tests/run_on_gpu_machine.sh > "$O/python.txt" 2>&1
    status=$?
    grep -E "passed|failed|skipped|exit|build failed" "$O/python.txt"
    echo "python: exit $status"
    [ $status = 0 ] || failed=1
    ;;
  sanitizers)
    export CUDAHULL_PROPERTY_CASES=100
    all='*Seeded*:*SharedModels*:*Property*:*Generated*:*SteppedRecords*'
    for tool in memcheck synccheck initcheck; do
      run sanitizer_$tool 200 compute-sanitizer --tool $tool --error-exitcode 9 $B/test_resident_cuda --gtest_filter="$all"
    done
    run sanitizer_racecheck 280 compute-sanitizer --tool racecheck --error-exitcode 9 $B/test_resident_cuda \
      --gtest_filter='*Seeded*:*Property*:*SteppedRecords*'
    ;;
  racecheck-models)
    run sanitizer_racecheck_models 560 compute-sanitizer --tool racecheck --error-exitcode 9 $B/test_resident_cuda \
      --gtest_filter='*SharedModels*'
    ;;
  *)
    echo "unknown PART=$PART"
    exit 2
    ;;
esac
exit $failed
