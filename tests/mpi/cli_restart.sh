#!/usr/bin/env bash
# cli_restart.sh — checkpoints under mpirun (issue 18; docs/mpi.md): a
# checkpoint written by 2 ranks, restarted on 3, continues with the bits of
# the uninterrupted 3-rank run (the last frames, the stats and walls rows,
# every dataset of the last checkpoint), in a box, periodic along x and y,
# with moving walls, in a turning mesh drum and with an insertion (spheres
# and bricks into a bed of spheres) and an outlet; the serial program
# continues the same checkpoint within a tolerance; checkpoint_minutes
# and a bad checkpoint are refused (exit 2, one message).
#   cli_restart.sh SHAPEDEM MPIEXEC SOURCE_DIR CKPT_DIFF
set -euo pipefail
bin=$1
mpiexec=${2:-mpirun}
src=$3
ckdiff=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
fail=0
source "$src/tests/mpi/lib.sh"

sed 's/^  stats_every: 50$/  stats_every: 50\n  checkpoint_every: 200/' "$src/tests/mpi/run_scene.yaml" >"$tmp/box.yaml"
cp "$src/tests/mpi/run_periodic.yaml" "$tmp/periodic.yaml"
# moving walls (a piston plane and a lid), a turning mesh drum, a feed and
# an outlet: the scenes of mpi.kinds.walls, .mesh and .process, with output
for mode in walls mesh process; do
  sed "s|file: .*/meshes/|file: $src/examples/meshes/|" "$src/tests/mpi/scenes/$mode.yaml" >"$tmp/$mode.yaml"
  printf 'output:\n  every: 100\n  stats_every: 50\n  checkpoint_every: 200\n  formats: [vtk, csv]\n' >>"$tmp/$mode.yaml"
done
last() { ls "$1" | grep "^$2" | sort | tail -n 1; } # the last frame file of a kind
after200() { awk -F, 'NR == 1 || $1 >= 200' "$1"; } # the header and the rows from step 200 on
for mode in box periodic walls mesh process; do
  scene=$tmp/$mode.yaml
  d=$tmp/$mode
  mpi -np 3 "$bin" run "$scene" -o "$d.whole" -q || bad "$mode: the uninterrupted 3-rank run failed"
  mpi -np 2 "$bin" run "$scene" --steps 200 -o "$d.first" -q || bad "$mode: the 2-rank run to step 200 failed"
  ck=$d.first/checkpoint-000200.h5
  [[ -f $ck ]] || bad "$mode: 2 ranks wrote no checkpoint at step 200"
  mpi -np 3 "$bin" run "$scene" --restart "$ck" -o "$d.rest" -q || bad "$mode: the 3-rank restart failed"
  same=1
  for kind in particles_ walls_; do
    cmp -s "$d.whole/$(last "$d.whole" $kind)" "$d.rest/$(last "$d.rest" $kind)" || { bad "$mode: the last $kind frame differs"; same=0; }
  done
  for f in stats.csv walls.csv; do
    [[ $(after200 "$d.whole/$f") == "$(after200 "$d.rest/$f")" ]] || { bad "$mode: $f rows from step 200 differ"; same=0; }
  done
  ckl=$(last "$d.whole" checkpoint-)
  "$ckdiff" "$d.whole/$ckl" "$d.rest/$ckl" >"$tmp/diff.out" 2>&1 || { bad "$mode: $ckl differs:"; cat "$tmp/diff.out"; same=0; }
  [[ $same -eq 1 ]] && ok "$mode: written on 2 ranks at step 200, restarted on 3: the last frames and the stats and walls rows from step 200 the same bytes as the uninterrupted 3-rank run; $ckl: $(tail -n 1 "$tmp/diff.out")"
  # the serial program continues the same checkpoint (it rebuilds at its first step)
  "$bin" run "$scene" --restart "$ck" -o "$d.serial" -q || bad "$mode: the serial restart failed"
  /usr/bin/python3 - "$src/scripts/frame_to_csv.py" "$d.whole/$(last "$d.whole" particles_)" "$d.serial/$(last "$d.serial" particles_)" "$mode" <<'PY' || fail=1
import csv, io, subprocess, sys
conv, a, b, mode = sys.argv[1:]
def rows(f):
    out = subprocess.run([sys.executable, conv, f], capture_output=True, text=True, check=True).stdout
    return [r for r in csv.reader(io.StringIO(out)) if r and not r[0].startswith('#') and r[0] != 'x']
ra, rb = rows(a), rows(b)
dx = max(abs(float(p[c]) - float(q[c])) for p, q in zip(ra, rb) for c in range(3))
print(f"{mode}: the serial program from the 2-rank checkpoint vs 3 ranks at the end: {len(rb)} particles, "
      f"max |dx| = {dx:.3e} m (tolerance 1e-9 m)")
sys.exit(0 if len(ra) == len(rb) > 0 and dx <= 1e-9 else 1)
PY
done

set +e
sed 's/checkpoint_every: 200/checkpoint_minutes: 5/' "$tmp/periodic.yaml" >"$tmp/minutes.yaml"
mpi -np 2 "$bin" run "$tmp/minutes.yaml" -o "$tmp/f1" >/dev/null 2>"$tmp/f1.err"
check_fail "checkpoint_minutes under mpirun" $? "$tmp/f1.err" "checkpoint_minutes"
head -c 1000 "$tmp/box.first/checkpoint-000200.h5" >"$tmp/cut.h5"
mpi -np 2 "$bin" run "$tmp/box.yaml" --restart "$tmp/cut.h5" -o "$tmp/f2" >/dev/null 2>"$tmp/f2.err"
check_fail "a damaged checkpoint under mpirun" $? "$tmp/f2.err" "cut.h5"
set -e
for d in f1 f2; do
  [[ -e $tmp/$d ]] && bad "$d: the output directory was created by a run refused on its input"
done
exit $fail
