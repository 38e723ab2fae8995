#!/usr/bin/env bash
# kinds.sh — the same bits on any rank count for every particle kind (issue
# 18): tests/mpi/scene.c runs SCENE on 1, 2, 3 and 4 ranks (oversubscribed:
# CI has two cores; Open MPI as root needs --allow-run-as-root); the
# gathered states must be the same bytes. Each run checks the particle
# count and id set at every step and, on more than one rank, that particles
# migrated carrying history (--hints: volume-law overlap hints among it,
# --walls: wall pairs' springs).
# The serial world (no decomposition) is compared with 1 rank within a
# tolerance only: it sums in the search's order (docs/architecture.md,
# "MPI decomposition").
# --splits "NP:SPEC ...": instead of 2, 3 and 4 ranks with the scene's
# split, NP ranks split as SPEC (mpi_scene --split: x, y, z, auto or
# PxPyPz such as 2x2x1), each against 1 rank's state: the bits do not
# depend on the split either (the serial world is left to the test
# without --splits).
# --cuda N (BINARY built against the emulated CUDA backend,
# mpi_scene_cuda): the ranks run on backend cuda with N emulated devices
# per node (rank r must take device r mod N: scene.c checks it), and 1
# rank's state must also equal the CPU backend's byte for byte (issue 18:
# one rank per GPU).
#   kinds.sh MPI_SCENE_BINARY MPIEXEC SCENE [--splits "NP:SPEC ..."] [--cuda N] [--hints | --walls]
set -euo pipefail
bin=$1
mpiexec=${2:-mpirun}
scene=$3
shift 3
runs=("2:" "3:" "4:") # NP:SPEC, SPEC empty: the scene's own split
serial=1 cuda=0
while [[ ${1:-} == --splits || ${1:-} == --cuda ]]; do
  if [[ $1 == --splits ]]; then
    read -r -a runs <<<"$2"
    serial=0
  else
    cuda=1
    export SD_CUDA_EMULATE_DEVICES=$2
  fi
  shift 2
done
backend=()
[[ $cuda == 1 ]] && backend=(--backend cuda)
tmp=$(mktemp -d)
# Open MPI's session directory in this test's own $tmp: jobs that other
# tests (ctest -j) start and end at the same time cannot remove it under
# this one (tests/mpi/lib.sh does the same for the CLI tests)
export OMPI_MCA_orte_tmpdir_base=$tmp
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
name=$(basename "$scene" .yaml)
run() { # ranks out [args]
  local np=$1 out=$2
  shift 2
  timeout 300 "$mpiexec" --oversubscribe --allow-run-as-root -np "$np" "$bin" "$scene" "$out" "$@"
}
fail=0
keys=(1) labels=("1 rank")
run 1 "$tmp/1.bin" "$@" ${backend[@]+"${backend[@]}"} >"$tmp/1.out" || { echo "FAIL: $name, 1 rank: the run failed"; fail=1; }
cat "$tmp/1.out"
for r in "${runs[@]}"; do
  np=${r%%:*} spec=${r#*:} key=${r/:/-}
  split=()
  [[ -n $spec ]] && split=(--split "$spec")
  keys+=("$key")
  labels+=("$np ranks${spec:+, split $spec}")
  run "$np" "$tmp/$key.bin" "$@" ${split[@]+"${split[@]}"} ${backend[@]+"${backend[@]}"} >"$tmp/$key.out" ||
    { echo "FAIL: $name, $np ranks${spec:+, split $spec}: the run failed"; fail=1; }
  cat "$tmp/$key.out"
done
if [[ $serial -eq 1 ]]; then
  run 1 "$tmp/serial.bin" --serial --backend cpu || { echo "FAIL: $name: the serial run failed"; fail=1; }
fi
if [[ $cuda == 1 ]]; then
  # the CPU backend's decomposed run: the device's bits to the last one
  run 1 "$tmp/cpu.bin" "$@" --backend cpu >"$tmp/cpu.out" || { echo "FAIL: $name: the CPU backend's run failed"; fail=1; }
  if [[ -f $tmp/cpu.bin && -f $tmp/1.bin ]] && cmp -s "$tmp/cpu.bin" "$tmp/1.bin" &&
     [[ $(grep "^walls:" "$tmp/cpu.out") == $(grep "^walls:" "$tmp/1.out") ]]; then
    echo "ok: $name, backend cuda on 1 rank: the same $(stat -c %s "$tmp/1.bin") bytes of state and the same walls as the CPU backend"
  else
    echo "FAIL: $name, backend cuda on 1 rank: state or walls differ from the CPU backend's"
    fail=1
  fi
fi
for i in "${!keys[@]}"; do
  [[ $i -eq 0 ]] && continue
  k=${keys[$i]} what_run=${labels[$i]}
  # the walls where they ended, and the accounts of insertions and outlets
  # (counts, masses): to the bit
  for what in walls accounts; do
    if [[ -f $tmp/$k.out ]] && [[ $(grep "^$what:" "$tmp/1.out") != $(grep "^$what:" "$tmp/$k.out") ]]; then
      echo "FAIL: $name, $what_run: the $what line differs from 1 rank's"
      fail=1
    fi
  done
  if [[ -f $tmp/$k.bin && -f $tmp/1.bin ]] && cmp -s "$tmp/1.bin" "$tmp/$k.bin"; then
    echo "ok: $name, $what_run: the same $(stat -c %s "$tmp/$k.bin") bytes of state as 1 rank"
  else
    echo "FAIL: $name, $what_run: state differs from 1 rank's"
    fail=1
  fi
done
# the serial world against 1 rank: a sanity check of the physics (the
# same particles, positions within 1e-6 m)
if [[ -f $tmp/serial.bin && -f $tmp/1.bin ]]; then
  /usr/bin/python3 "$(dirname "$0")/serial_vs_rank.py" "$tmp/serial.bin" "$tmp/1.bin" "$name" || fail=1
fi
exit $fail
