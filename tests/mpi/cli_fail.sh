#!/usr/bin/env bash
# cli_fail.sh — a guard that trips on one rank inside a step under mpirun
# (issue 18; docs/mpi.md, "Failures"): the run ends as a serial run stopped
# by the guard does, never a hang: exit 1, one message naming the rank, the
# particle and the step (the serial run's words), the whole world written
# to failed-<step>.h5 (a checkpoint `shapedem info` reads, every particle)
# and summary.txt; when guards trip on several ranks at once, the lowest
# rank's message.
#   cli_fail.sh SHAPEDEM MPIEXEC SOURCE_DIR
set -uo pipefail
bin=$1
mpiexec=${2:-mpirun}
src=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
fail=0
source "$src/tests/mpi/lib.sh"

# a soft sphere shot into the floor at x = 0.05 (rank 1's) trips the
# overlap guard at step 150 while the one at x = -0.05 (rank 0's) rests;
# with both shot (both.yaml) each rank trips at step 150
guard() { # file vz0
  cat >"$1" <<YAML
simulation: {dt: 1.0e-5, steps: 1500, gravity: [0, 0, 0], contact_law: linear}
materials:
  - {name: soft, density: 2500, stiffness: 10, restitution: 0.5}
particles:
  - generator: list
    material: soft
    spheres:
      - {position: [-0.05, 0, 0.0015], radius: 0.001, velocity: [0, 0, $2]}
      - {position: [0.05, 0, 0.0015], radius: 0.001, velocity: [0, 0, -0.8]}
walls:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: soft}
output: {every: 500, stats_every: 10}
YAML
}
guard "$tmp/one.yaml" 0
guard "$tmp/both.yaml" -0.8
# what the serial run says (the guard's words, before the file's path)
declare -A serial
for scene in one both; do
  "$bin" run "$tmp/$scene.yaml" -o "$tmp/serial-$scene" >/dev/null 2>"$tmp/serial.err"
  rc=$?
  serial[$scene]=$(sed -n 's/^shapedem: run stopped at step 150: \(.*\); the state is in .*/\1/p' "$tmp/serial.err")
  [[ $rc -eq 1 && -n ${serial[$scene]} ]] || { bad "$scene.yaml serially: exit $rc, not the guard's message:"; cat "$tmp/serial.err"; }
done

for case in one:2:1 one:3:2 both:2:0; do
  IFS=: read -r scene np rank <<<"$case"
  out=$tmp/$scene$np
  mpi -np "$np" "$bin" run "$tmp/$scene.yaml" -o "$out" >/dev/null 2>"$tmp/$scene$np.err"
  rc=$?
  msgs=$(grep -c '^shapedem:' "$tmp/$scene$np.err" || true)
  line=$(grep '^shapedem:' "$tmp/$scene$np.err" | head -n 1)
  want="shapedem: run stopped at step 150: rank $rank of $np: ${serial[$scene]}; the state is in $out/failed-000150.h5 for inspection"
  name="$scene.yaml on $np ranks (the guard on rank $rank)"
  if [[ $rc -eq 1 && $msgs -eq 1 && $line == "$want" ]]; then
    ok "$name: exit 1, one message, the serial run's words with the rank: $line"
  else
    bad "$name: exit $rc (124: a hang), $msgs messages from shapedem, wanted: $want"
    cat "$tmp/$scene$np.err"
  fi
  info=$("$bin" info "$out/failed-000150.h5" 2>&1)
  if grep -q 'verified' <<<"$info" && grep -q 'step 150,' <<<"$info" && grep -q '^particles *2$' <<<"$info"; then
    ok "$name: failed-000150.h5 holds the whole world at step 150 ($(grep '^particles' <<<"$info" | tr -s ' '))"
  else
    bad "$name: no readable failed-000150.h5 with both particles at step 150:"
    echo "$info" | head -n 8
  fi
  if grep -q "^mpi_ranks: $np$" "$out/summary.txt" 2>/dev/null && grep -q '^step: 150$' "$out/summary.txt"; then
    ok "$name: summary.txt written (step: 150, mpi_ranks: $np)"
  else
    bad "$name: no summary.txt with step: 150 and mpi_ranks: $np:"
    cat "$out/summary.txt" 2>/dev/null | head -n 5
  fi
done
exit $fail
