#!/usr/bin/env bash
# Tests a wheel as it ships (scripts/test runs it on scripts/wheel --quick's wheel):
#  1. `auditwheel show` grants the platform tag the wheel's name carries;
#  2. the wheel goes into a fresh virtual environment, with nothing else of the project's: the environment
#     emptied (env -i), no CUDA directory on PATH or LD_LIBRARY_PATH, no compiler (CC, CXX and CUDACXX
#     are /bin/false and pip takes binary packages only), and every ELF file in it finds its libraries;
#  3. there it imports, passes python/tests (the CPU suite) and a drop-in smoke test against scipy;
#  4. the console commands run: `cudahull` checks the bunny's hull, `cudahull-viewer` with no arguments
#     renders the bundled bunny's stepping sequence headless, and under Xvfb opens a window and closes it.
# On the GPU machine (PYTHON=python3.12, GPU_TESTS=1) it runs python/gpu_tests as well.
#   tests/wheel/check_installed_wheel.sh WHEEL
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
wheel=$(realpath "${1:?usage: check_installed_wheel.sh WHEEL}")
python=${PYTHON:-$("$root/build-venv/bin/python" -c 'import sys; print(sys._base_executable)')}
work=$(mktemp -d /tmp/cudahull-wheel.XXXXXX)
trap 'rm -rf "$work"' EXIT
say() { printf 'check-wheel: %s\n' "$*" >&2; }
fail() { say "FAILED: $*"; exit 1; }

# 1. The tag.
name=$(basename "$wheel" .whl)
platform=${name##*-}
if [ -x "$root/build-wheel/venv-tools/bin/auditwheel" ]; then
  show=$(PATH="$root/build-wheel/venv-tools/bin:$PATH" "$root/build-wheel/venv-tools/bin/auditwheel" show "$wheel")
  echo "$show" | tr '\n' ' ' | grep -q "\"$platform\"" ||
    fail "auditwheel show does not grant the wheel's tag $platform: $show"
  say "auditwheel grants $platform"
else
  fail "no auditwheel (build-wheel/venv-tools, made by scripts/wheel)"
fi

# 2. A clean environment: only the venv, /usr/bin and /bin on PATH.
clean=(env -i HOME="$HOME" LANG=C.UTF-8 TMPDIR=/tmp PATH="$work/venv/bin:/usr/bin:/bin" CC=/bin/false
       CXX=/bin/false CUDACXX=/bin/false PYTHONDONTWRITEBYTECODE=1 PIP_DISABLE_PIP_VERSION_CHECK=1)
"$python" -m venv "$work/venv"
"${clean[@]}" pip install -q --only-binary :all: "$wheel" -r "$root/python/requirements-test.txt" ||
  fail "pip could not install the wheel with binary packages only"
"${clean[@]}" sh -c 'command -v nvcc' >/dev/null && fail "nvcc is on the clean PATH"
package=$("${clean[@]}" python -c 'import cudahull, os; print(os.path.dirname(cudahull.__file__))')
case "$package" in "$work"/venv/*) ;; *) fail "cudahull imported from $package, not the venv" ;; esac
say "installed in $package"
while IFS= read -r -d '' file; do
  if head -c 4 "$file" | grep -q "ELF"; then
    missing=$("${clean[@]}" ldd "$file" 2>&1 | grep -E "not found|libcudart" || true)
    [ -z "$missing" ] || fail "$file: $missing"
  fi
done < <(find "$package" "$work"/venv/lib/python*/site-packages/cudahull.libs -type f -print0 2>/dev/null)
say "every ELF file finds its libraries, none the CUDA toolkit's runtime"

# 3. The module: the CPU suite and the drop-in smoke test, from outside the source tree.
cd "$work"
"${clean[@]}" python "$root/tests/wheel/drop_in_smoke.py"
"${clean[@]}" python -m pytest -q -p no:cacheprovider "$root/python/tests" || fail "python/tests"
if [ "${GPU_TESTS:-0}" = 1 ]; then
  "${clean[@]}" python -m pytest -q -p no:cacheprovider -rs "$root/python/gpu_tests" || fail "python/gpu_tests"
fi

# 4. The commands.
"${clean[@]}" cudahull hull "$root/assets/bun_zipper.ply" --verify -q --vertices-out "$work/vertices.txt" ||
  fail "cudahull hull --verify on the bunny"
[ "$(wc -l <"$work/vertices.txt")" = 1564 ] || fail "cudahull found $(wc -l <"$work/vertices.txt") bunny vertices, not 1564"
"${clean[@]}" cudahull-viewer -q || fail "cudahull-viewer, headless"
frames=$(ls "$work"/out/bunny/step_*.png 2>/dev/null | wc -l)
[ "$frames" -ge 2 ] || fail "cudahull-viewer wrote $frames pictures of the bunny's steps"
say "cudahull-viewer rendered $frames steps of the bundled bunny headless"
if command -v xvfb-run >/dev/null; then
  "${clean[@]}" xvfb-run -a -s "-screen 0 1280x1024x24" cudahull-viewer --frames 3 -q ||
    fail "cudahull-viewer in a window (Xvfb)"
  say "cudahull-viewer opened and closed a window under Xvfb"
else
  fail "no xvfb-run (scripts/setup installs xvfb) for the windowed check"
fi
say "the wheel passed"
