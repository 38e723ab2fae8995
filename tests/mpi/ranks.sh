#!/usr/bin/env bash
# ranks.sh — the same bits on any rank count (issue 18): tests/mpi/spheres.c
# on 1, 2, 3 and 4 ranks (oversubscribed: CI has two cores; Open MPI as
# root needs --allow-run-as-root) must write the same gathered states, byte
# for byte, split along x; and so must the same runs split otherwise (slabs
# along y and z, grids 2 x 2 x 1 and 1 x 2 x 2, auto; periodic in x and y
# across a grid), where particles cross the boxes' faces, edges and
# corners. The serial world (no decomposition) must give 1 rank's bits too:
# every run sums in the canonical order (issue 29; docs/architecture.md,
# "MPI decomposition").
#   ranks.sh MPI_SPHERES_BINARY MPIEXEC
set -euo pipefail
bin=$1
mpiexec=${2:-mpirun}
tmp=$(mktemp -d)
# Open MPI's session directory in this test's own $tmp: jobs that other
# tests (ctest -j) start and end at the same time cannot remove it under
# this one (tests/mpi/lib.sh does the same for the CLI tests)
export OMPI_MCA_orte_tmpdir_base=$tmp
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
run() { # ranks out [args]
  local np=$1
  shift
  timeout 300 "$mpiexec" --oversubscribe --allow-run-as-root -np "$np" "$bin" "$@"
}
fail=0
for mode in box periodic; do
  args=()
  [[ $mode == periodic ]] && args=(--periodic)
  for np in 1 2 3 4; do
    run "$np" "$tmp/$mode$np.bin" "${args[@]}" || { echo "FAIL: $mode, $np ranks: the run failed"; fail=1; continue; }
  done
  run 1 "$tmp/${mode}serial.bin" --serial "${args[@]}" || { echo "FAIL: $mode: the serial run failed"; fail=1; }
  for np in 2 3 4; do
    if [[ -f $tmp/$mode$np.bin ]] && cmp -s "$tmp/${mode}1.bin" "$tmp/$mode$np.bin"; then
      echo "ok: $mode, $np ranks: the same $(stat -c %s "$tmp/$mode$np.bin") bytes of state as 1 rank"
    else
      echo "FAIL: $mode, $np ranks: state differs from 1 rank's"
      fail=1
    fi
  done
  # the serial world against 1 rank: the same bits
  /usr/bin/python3 "$(dirname "$0")/serial_vs_rank.py" "$tmp/${mode}serial.bin" "$tmp/${mode}1.bin" "$mode" 600 || fail=1
done
# the split does not change the bits: other grids against 1 rank's state
# (itself the same bytes as the x split's on 2, 3 and 4 ranks, above)
for s in box:2:y box:3:z box:4:2x2x1 box:4:1x2x2 box:4:auto periodic:4:2x2x1 periodic:3:y; do
  IFS=: read -r mode np spec <<<"$s"
  args=()
  [[ $mode == periodic ]] && args=(--periodic)
  out=$tmp/$mode-$spec-$np.bin
  if run "$np" "$out" "${args[@]}" --split "$spec" && cmp -s "$tmp/${mode}1.bin" "$out"; then
    echo "ok: $mode, $np ranks split $spec: the same $(stat -c %s "$out") bytes of state as 1 rank"
  else
    echo "FAIL: $mode, $np ranks split $spec: the run failed or its state differs from 1 rank's"
    fail=1
  fi
done
# simulation.mpi_rebalance_every under a grid: re-cut every 50 steps, the
# same grid shape at the end, the same bytes
if run 4 "$tmp/rebalanced.bin" --split 1x2x2 --rebalance 50 >"$tmp/rebalanced.out" &&
  grep -q 'split 1 x 2 x 2 after [1-9][0-9]* re-cuts' "$tmp/rebalanced.out" &&
  cmp -s "$tmp/box1.bin" "$tmp/rebalanced.bin"; then
  echo "ok: box, 4 ranks split 1x2x2 rebalanced every 50 steps: $(grep -o 'split 1 x 2 x 2 after [0-9]* re-cuts' "$tmp/rebalanced.out"), the same bytes of state as 1 rank"
else
  echo "FAIL: box, 4 ranks split 1x2x2 rebalanced: the run failed, the grid changed or the state differs:"
  cat "$tmp/rebalanced.out"
  fail=1
fi
# a rank that fails alone (a bad material on rank 1 of 3) ends the job:
# a non-zero status well before the timeout, one message naming the rank
set +e
run 3 "$tmp/fail.bin" --fail-rank 1 >"$tmp/fail.out" 2>"$tmp/fail.err"
rc=$?
set -e
msgs=$(grep -c '^shapedem: rank' "$tmp/fail.err" || true)
if [[ $rc -ne 0 && $rc -ne 124 && $msgs -eq 1 ]] && grep -q '^shapedem: rank 1 of 3: scene failed (bad input)' "$tmp/fail.err"; then
  echo "ok: a failing rank ends the job (exit $rc): $(grep '^shapedem: rank' "$tmp/fail.err")"
else
  echo "FAIL: a failing rank: exit $rc (124: a hang), $msgs messages from shapedem:"
  cat "$tmp/fail.err"
  fail=1
fi
exit $fail
