#!/bin/sh
# compute-sanitizer on the batch kernels (issue 27; ctest label gpu): memcheck on spheres of 700 points (the
# blocks of four an SM, then, every point a vertex, the second launch), synccheck and racecheck on 60 balls
# of 1,000 (four an SM: prefix sums over more than a block of values) and on 2,000 clouds of 6 points on
# blocks (most end in the compaction-only relaunch), memcheck and racecheck on 400 cylinders of 200 (a warp
# a cloud, small_hull(): coplanar facets, free slots reused; racecheck sees shared memory alone), synccheck
# on 40 grids of 1,000 (the blocks' leftovers retried on warps, read from global memory) and on 30 balls
# of 30,000 (the 512-thread blocks, their finish and the describe).  Each run's vertex sets are compared with Qhull's (--vs qhull: a differing cloud
# fails the test).  Exit 77 (skipped) where there is no GPU or no compute-sanitizer.
#   tests/batch_sanitizer.sh PATH/TO/cudahull
cli=$1
command -v compute-sanitizer >/dev/null 2>&1 || { echo "batch_sanitizer: no compute-sanitizer: skipped"; exit 77; }
nvidia-smi -L >/dev/null 2>&1 || { echo "batch_sanitizer: no GPU: skipped"; exit 77; }
log=$(mktemp)
trap 'rm -f "$log"' EXIT
check() {
  tool=$1
  shift
  if ! compute-sanitizer --tool "$tool" --error-exitcode 9 "$cli" bench --batch "$@" --backend cuda --repeat 1 \
    --vs qhull >"$log" 2>&1; then
    cat "$log"
    echo "batch_sanitizer: $tool on --batch $* failed"
    exit 1
  fi
  if ! grep -q "same vertices as qhull, every cloud" "$log"; then
    cat "$log"
    echo "batch_sanitizer: --batch $*: vertex sets differ from Qhull's"
    exit 1
  fi
  echo "batch_sanitizer: $tool on --batch $*: $(tail -1 "$log")"
}
check memcheck 300 --n 700 --dist sphere
check synccheck 60 --n 1000 --dist ball
check racecheck 60 --n 1000 --dist ball
export CUDAHULL_BATCH_WARP_POINTS=0  # the tiny clouds on blocks
check synccheck 2000 --n 6 --dist ball
check racecheck 2000 --n 6 --dist ball
unset CUDAHULL_BATCH_WARP_POINTS
check memcheck 400 --n 200 --dist cylinder
check racecheck 400 --n 200 --dist cylinder
check synccheck 40 --n 1000 --dist grid
check synccheck 30 --n 30000 --dist ball
