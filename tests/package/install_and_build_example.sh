#!/usr/bin/env bash
# The installed C++ package as a user gets it: `cmake --install` of BUILD_DIR into a temporary prefix, then
# examples/consumer and examples/batch configured against that prefix alone (find_package(cudahull)), built
# and run.  The consumer's hull is a unit cube's: its output must name the 8 corners (input indices
# 1000-1007), volume 1 and area 6 exactly (every term of the sums is exact for these coordinates).  The batch
# example hulls 10,000 clouds in one call: its cloud 0, a cube's corners and centre, must have volume 1, area
# 6 and 8 vertices, and its first 100 clouds the hulls convex_hull() gives each alone.
set -euo pipefail
build_dir=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" --component library >/dev/null
cmake -S "$source_dir/examples/consumer" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >/dev/null
cmake --build "$work/build" >/dev/null
output=$("$work/build/cube_hull")
echo "$output"
expected="dimension 3, 8 vertices, 12 faces, volume 1, area 6
vertices: 1000 1001 1002 1003 1004 1005 1006 1007
engine: "
if [[ "$output" != "$expected"* ]] || ! grep -q "^engine: [0-9]* iterations, 8 vertices$" <<<"$output"; then
  echo "install test: unexpected output from the example (expected the unit cube's 8 corners, volume 1, area 6)" >&2
  exit 1
fi

cmake -S "$source_dir/examples/batch" -B "$work/build-batch" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >/dev/null
cmake --build "$work/build-batch" >/dev/null
output=$("$work/build-batch/batch_volumes")
echo "$output"
if ! grep -q "^10000 clouds, their volumes in one call: " <<<"$output" ||
   ! grep -qx "cloud 0 (a unit cube): volume 1, area 6, 8 vertices" <<<"$output" ||
   ! grep -qx "clouds 0 to 99: 100 of 100 the same as convex_hull() on the cloud alone" <<<"$output"; then
  echo "install test: unexpected output from examples/batch (expected 10,000 clouds, the cube's volume 1," \
       "area 6 and 8 vertices, and 100 of 100 clouds as convex_hull() gives them)" >&2
  exit 1
fi
echo "install test: the installed package builds and runs both examples"
