#!/usr/bin/env bash
# cli_scene.sh — ranks that read different scenes are refused before
# anything runs (issue 31, probe 3 finding 7: gravity or density differing
# on rank 1 ran to exit 0; a different dt gave an out-of-memory message).
# Rank 0 reads run_scene.yaml, rank 1 (of 2) or rank 2 (of 3) an edited
# copy: exit 2, one message "rank K of N: its scene differs from rank 0's
# (... differ ...)" naming the part, and no output directory.
#   cli_scene.sh SHAPEDEM MPIEXEC SOURCE_DIR
set -uo pipefail
bin=$1
mpiexec=${2:-mpirun}
src=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
fail=0
source "$src/tests/mpi/lib.sh"
scene=$src/tests/mpi/run_scene.yaml

n=0
# differ NP PART SED-SCRIPT: the last rank reads the edited scene
differ() {
  local np=$1 part=$2 edit=$3
  n=$((n + 1))
  sed "$edit" "$scene" >"$tmp/e$n.yaml"
  if cmp -s "$scene" "$tmp/e$n.yaml"; then
    bad "edit $n ($edit) does not change the scene"
    return
  fi
  mpi -np $((np - 1)) "$bin" run "$scene" -o "$tmp/o$n" : -np 1 "$bin" run "$tmp/e$n.yaml" -o "$tmp/o$n" \
    >/dev/null 2>"$tmp/e$n.err"
  check_fail "$edit on rank $((np - 1)) of $np" $? "$tmp/e$n.err" \
    "^shapedem: rank $((np - 1)) of $np: its scene differs from rank 0's (.*$part.* differ"
  [[ -e $tmp/o$n ]] && bad "$edit: the output directory was created"
}
set +e
differ 2 "the simulation settings" 's/gravity: \[0, 0, -9.81\]/gravity: [0, 0, 9.81]/'
differ 2 "the materials" 's/density: 2500/density: 2600/'
differ 2 "the simulation settings" 's/dt: 1.0e-5/dt: 0.9e-5/'
differ 3 "the walls" 's/max: \[0.1, 0.0135, 0.2\]/max: [0.1, 0.0135, 0.21]/'
differ 2 "the start particles" 's/origin: \[0.0012, 0.0012, 0.0012\]/origin: [0.0012, 0.0012, 0.0013]/'
exit $fail
