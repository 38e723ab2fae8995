#!/usr/bin/env bash
# cli_restart.sh — checkpoints under mpirun (issue 18; docs/mpi.md): a
# checkpoint written by 2 ranks, restarted on 3, continues with the bits of
# the uninterrupted 3-rank run (the last frame, the stats and walls rows,
# every dataset of the last checkpoint), in a box and periodic along x and
# y; the serial program continues the same checkpoint within a tolerance;
# checkpoint_minutes and a bad checkpoint are refused (exit 2, one message).
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
for mode in box periodic; do
  scene=$tmp/$mode.yaml
  d=$tmp/$mode
  mpi -np 3 "$bin" run "$scene" -o "$d.whole" -q || bad "$mode: the uninterrupted 3-rank run failed"
  mpi -np 2 "$bin" run "$scene" --steps 200 -o "$d.first" -q || bad "$mode: the 2-rank run to step 200 failed"
  ck=$d.first/checkpoint-000200.h5
  [[ -f $ck ]] || bad "$mode: 2 ranks wrote no checkpoint at step 200"
  mpi -np 3 "$bin" run "$scene" --restart "$ck" -o "$d.rest" -q || bad "$mode: the 3-rank restart failed"
  same=1
  cmp -s "$d.whole/particles_000004.vtu" "$d.rest/particles_000002.vtu" || { bad "$mode: the frame at step 400 differs"; same=0; }
  for f in stats.csv walls.csv; do
    [[ $(tail -n 5 "$d.whole/$f") == "$(tail -n 5 "$d.rest/$f")" ]] || { bad "$mode: $f rows 200..400 differ"; same=0; }
  done
  "$ckdiff" "$d.whole/checkpoint-000400.h5" "$d.rest/checkpoint-000400.h5" >"$tmp/diff.out" 2>&1 || { bad "$mode: checkpoints at 400 differ:"; cat "$tmp/diff.out"; same=0; }
  [[ $same -eq 1 ]] && ok "$mode: written on 2 ranks at step 200, restarted on 3: the frame, stats and walls rows at 200..400 the same bytes as the uninterrupted 3-rank run; $(tail -n 1 "$tmp/diff.out")"
  # the serial program continues the same checkpoint (it rebuilds at its first step)
  "$bin" run "$scene" --restart "$ck" -o "$d.serial" -q || bad "$mode: the serial restart failed"
  /usr/bin/python3 - "$src/scripts/frame_to_csv.py" "$d.whole/particles_000004.vtu" "$d.serial/particles_000002.vtu" "$mode" <<'PY' || fail=1
import csv, io, subprocess, sys
conv, a, b, mode = sys.argv[1:]
def rows(f):
    out = subprocess.run([sys.executable, conv, f], capture_output=True, text=True, check=True).stdout
    return [r for r in csv.reader(io.StringIO(out)) if r and not r[0].startswith('#') and r[0] != 'x']
ra, rb = rows(a), rows(b)
dx = max(abs(float(p[c]) - float(q[c])) for p, q in zip(ra, rb) for c in range(3))
print(f"{mode}: the serial program from the 2-rank checkpoint vs 3 ranks at step 400: {len(rb)} particles, "
      f"max |dx| = {dx:.3e} m (tolerance 1e-9 m)")
sys.exit(0 if len(ra) == len(rb) == 720 and dx <= 1e-9 else 1)
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
