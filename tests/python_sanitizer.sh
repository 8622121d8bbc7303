#!/usr/bin/env bash
# The Python module under AddressSanitizer and UBSan: the extension (python/src/, nanobind's
# array import and the library under it) built with -fsanitize=address,undefined into the sanitizer build
# (-DCUDAHULL_PYTHON=ON, cmake/Python.cmake), loaded into build-venv's Python with the ASan runtime
# preloaded, running the Python tests that cross its array boundary: DLPack tensors and
# __cuda_array_interface__ pointers said to be in CUDA memory (shapes, strides, dtypes refused or accepted,
# nothing read; python/tests/test_binding_arrays.py), host arrays of every layout, the hull, 2-D, batch,
# stepping-engine and merged (qhull_options) paths and their errors.  Any sanitizer report aborts the run.
#
#   tests/python_sanitizer.sh [BUILD_DIR]
#
# BUILD_DIR: a sanitizer build already configured (scripts/test passes build-asan, whose libraries the
# extension then shares), or by default a build of its own, build-asan-python (the library and the
# extension only, -O1 as scripts/test's).  A sanitizer build registers no Python test with ctest
# (tests/CMakeLists.txt): they run here.  Exit 77 (skipped) where the compiler has no ASan runtime.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-asan-python}
python=${CUDAHULL_SANITIZER_PYTHON:-$PWD/build-venv/bin/python}
export PATH="$PATH:/usr/local/cuda/bin"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -G Ninja -DCUDAHULL_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCUDAHULL_PYTHON=ON -DPython_EXECUTABLE="$python" \
    -DCUDAHULL_BUILD_TESTS=OFF -DCUDAHULL_BUILD_VIEWER=OFF >/dev/null
fi
grep -q '^CUDAHULL_SANITIZE:BOOL=ON' "$build/CMakeCache.txt" ||
  { echo "python_sanitizer: $build is not a sanitizer build (-DCUDAHULL_SANITIZE=ON)"; exit 1; }
build=$(cd "$build" && pwd)
cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")
asan=$("$cxx" -print-file-name=libasan.so)
if [ ! -e "$asan" ]; then
  echo "python_sanitizer: $cxx has no ASan runtime (libasan.so): skipped"
  exit 77
fi
# libstdc++ preloaded with it: Python itself does not link it, and without it at start ASan's __cxa_throw
# interceptor finds no real __cxa_throw ("CHECK failed: asan_interceptors.cpp:320") at the first C++ throw.
runtime="$asan $("$cxx" -print-file-name=libstdc++.so)"
cmake --build "$build" --target _cudahull
module=$(ls "$build"/python/cudahull/_cudahull*.so)
nm -D --undefined-only "$module" | grep __asan_report >/dev/null ||
  { echo "python_sanitizer: $module is not instrumented"; exit 1; }
# detect_leaks=0: CPython keeps its interned objects to the end.  protect_shadow_gap=0: the CUDA runtime
# (linked into the extension) maps memory there.  PYTHONMALLOC=malloc: Python's own buffers (ctypes memory,
# bytes) through malloc, where ASan sees their bounds.
export ASAN_OPTIONS=detect_leaks=0:protect_shadow_gap=0:abort_on_error=1:halt_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export PYTHONMALLOC=malloc PYTHONDONTWRITEBYTECODE=1 PYTHONPATH="$build/python"
LD_PRELOAD="$runtime" "$python" -c 'import cudahull._cudahull as m, sys; sys.exit(0 if m.__file__.startswith(sys.argv[1]) else 1)' \
  "$build/python/" || { echo "python_sanitizer: the sanitized extension is not the one imported"; exit 1; }
# --capture=sys: pytest leaves file descriptor 2 alone, so that a sanitizer's report reaches the log.
# test_batch.py without its six large batches (2.5 of the 3 minutes under the sanitizers on 2 cores): the
# batch binding's paths are the small tests' too.
large="test_padded_and_packed_agree or test_each_cloud_is_its_own_hull or test_thread_count_changes_nothing or"
large="$large test_sizes_and_kinds_span_the_range or test_measures_of_a_hull_of_many_chunks or"
large="$large test_vertices_are_scipys_where_qhull_is_exact"
LD_PRELOAD="$runtime" "$python" -m pytest -q -p no:cacheprovider --capture=sys -k "not ($large)" \
  python/tests/test_binding_arrays.py python/tests/test_device_input.py python/tests/test_convex_hull.py \
  python/tests/test_engine.py python/tests/test_batch.py \
  "python/tests/test_scipy_drop_in.py::test_merged_hull_matches_qhull_on_rotated_chamfered_boxes" \
  "python/tests/test_scipy_drop_in.py::test_qhull_option_words_follow_qhulls_groups"
