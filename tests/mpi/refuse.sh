#!/usr/bin/env bash
# refuse.sh — what the decomposition does not take yet is refused at
# attach, on every rank, with one clear reason and exit status 2, never a
# hang (issue 18): the grid solver (examples/hopper-grid.yaml), on 2 ranks.
#   refuse.sh MPI_SCENE_BINARY MPIEXEC SOURCE_DIR
set -euo pipefail
bin=$1
mpiexec=${2:-mpirun}
src=$3
tmp=$(mktemp -d)
# Open MPI's session directory in this test's own $tmp: jobs that other
# tests (ctest -j) start and end at the same time cannot remove it under
# this one (tests/mpi/lib.sh does the same for the CLI tests)
export OMPI_MCA_orte_tmpdir_base=$tmp
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
fail=0
check() { # scene what-the-message-names
  local scene=$1 want=$2 rc=0
  timeout 120 "$mpiexec" --oversubscribe --allow-run-as-root -np 2 "$bin" "$src/$scene" "$tmp/out.bin" \
    >"$tmp/out" 2>"$tmp/err" || rc=$?
  if [[ $rc -eq 2 ]] && grep -q "^shapedem: rank [01] of 2: attach failed (bad input): .*$want" "$tmp/err" &&
     [[ ! -e $tmp/out.bin ]]; then
    echo "ok: $scene refused (exit 2): $(grep -m1 '^shapedem: rank' "$tmp/err")"
  else
    echo "FAIL: $scene: exit $rc (want 2; 124: a hang), expected a message naming '$want':"
    cat "$tmp/err"
    fail=1
  fi
}
check examples/hopper-grid.yaml "cells solver only"
exit $fail
