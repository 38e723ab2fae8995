#!/usr/bin/env bash
# cli_ranks.sh — `mpirun -np N shapedem run` (issue 18; docs/mpi.md): the
# scene tests/mpi/run_scene.yaml on 1, 2, 3 and 4 ranks (oversubscribed:
# CI has two cores; Open MPI as root needs --allow-run-as-root) must write
# the same frames, frames.pvd, stats.csv and walls.csv, byte for byte;
# summary.txt names the ranks and the split; a run rebalanced every 50
# steps, and one split 2 x 2 x 1 by simulation.mpi_split, write the same
# bytes; a split whose product is not the rank count is refused (exit 2,
# nothing written); `check --ranks 4` prints the grid and each rank's box. The plain serial program gives
# the same particle bits (mpi.serial_bits) but sums stats.csv's totals over
# its particles in storage order, the ranks' view in stable-id order, so it
# is compared within a tolerance here. Then the failures: bad input on every rank,
# on some ranks only, and ranks that built different worlds end the job
# with one message and exit 2, never a hang (each run under `timeout`; a
# guard tripped on one rank inside a step: cli_fail.sh).
#   cli_ranks.sh SHAPEDEM MPIEXEC SOURCE_DIR
set -euo pipefail
bin=$1
mpiexec=${2:-mpirun}
src=$3
scene=$src/tests/mpi/run_scene.yaml
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
fail=0
source "$src/tests/mpi/lib.sh"

"$bin" run "$scene" -o "$tmp/serial" -q || bad "the serial run failed"
for np in 1 2 3 4; do
  mpi -np "$np" "$bin" run "$scene" -o "$tmp/r$np" -q || bad "$np ranks: the run failed (exit $?)"
done
files=$(cd "$tmp/r1" && ls particles_*.vtu walls_*.vtp frames.pvd stats.csv walls.csv)
[[ $(echo "$files" | grep -c particles_) -eq 5 ]] || bad "1 rank: $(echo "$files" | grep -c particles_) particle frames, not 5"
for np in 2 3 4; do
  same=1
  for f in $files; do
    cmp -s "$tmp/r1/$f" "$tmp/r$np/$f" || { bad "$np ranks: $f differs from 1 rank's"; same=0; }
  done
  [[ $same -eq 1 ]] && ok "$np ranks: $(echo "$files" | wc -w) files the same bytes as 1 rank's ($(cat "$tmp/r$np"/* | wc -c) bytes)"
  # summary.txt: the ranks, the split and every particle on some rank
  s=$tmp/r$np/summary.txt
  per=$(sed -n 's/^mpi_particles_per_rank: //p' "$s")
  if grep -q "^mpi_ranks: $np$" "$s" && [[ $(echo "$per" | wc -w) -eq $np ]] &&
    [[ $((${per// /+})) -eq 720 ]] && grep -q "^mpi_split: $np x 1 x 1 boxes" "$s" &&
    [[ $(sed -n 's/^mpi_migrations: //p' "$s") -gt 0 ]]; then
    ok "$np ranks: summary.txt: $(grep '^mpi_' "$s" | tr '\n' ';')"
  else
    bad "$np ranks: summary.txt lacks the ranks' lines:"; grep '^mpi_' "$s" || true
  fi
done
# The scene with one line added to simulation (LINE) run on NP ranks into
# $tmp/DIR (the scene: $tmp/DIR.yaml): every file the same bytes as 1
# rank's, else same=0.
variant() { # NAME LINE NP DIR
  sed "s/^  threads: 1\$/  threads: 1\n  $2/" "$scene" >"$tmp/$4.yaml"
  mpi -np "$3" "$bin" run "$tmp/$4.yaml" -o "$tmp/$4" -q || bad "$1: the run failed"
  same=1
  for f in $files; do
    cmp -s "$tmp/r1/$f" "$tmp/$4/$f" || { bad "$1: $f differs from 1 rank's"; same=0; }
  done
}
# simulation.mpi_rebalance_every: the split cut again every 50 steps (at
# the next rebuild) changes no byte of the output, and evens the counts
variant "3 ranks, rebalanced" "mpi_rebalance_every: 50" 3 b3
spread() { sed -n 's/^mpi_particles_per_rank: //p' "$1" | tr ' ' '\n' | sort -n | sed -n '1p;$p' | paste -sd' ' | awk '{print $2 - $1}'; }
cuts=$(sed -n 's/^mpi_rebalances: //p' "$tmp/b3/summary.txt")
if [[ $same -eq 1 && ${cuts:-0} -gt 0 && $(spread "$tmp/b3/summary.txt") -le $(spread "$tmp/r3/summary.txt") ]]; then
  ok "3 ranks, rebalanced $cuts times: the same bytes as 1 rank's; particles per rank at the end spread by" \
    "$(spread "$tmp/b3/summary.txt") (without: $(spread "$tmp/r3/summary.txt"))"
else
  bad "3 ranks, rebalanced: $cuts re-cuts, spread $(spread "$tmp/b3/summary.txt") vs $(spread "$tmp/r3/summary.txt")"
fi

# simulation.mpi_split: [2, 2, 1] on 4 ranks writes the same bytes (and
# summary.txt says so); on 3 ranks it is refused before anything is written
variant "4 ranks, split [2, 2, 1]" "mpi_split: [2, 2, 1]" 4 g4
if [[ $same -eq 1 ]] && grep -q '^mpi_split: 2 x 2 x 1 boxes' "$tmp/g4/summary.txt"; then
  ok "4 ranks split [2, 2, 1]: the same bytes as 1 rank's; $(grep -E '^mpi_(split|particles_per_rank|migrations)' "$tmp/g4/summary.txt" | tr '\n' ';')"
else
  bad "4 ranks split [2, 2, 1]: summary.txt: $(grep '^mpi_split' "$tmp/g4/summary.txt" || true)"
fi
set +e
mpi -np 3 "$bin" run "$tmp/g4.yaml" -o "$tmp/f4" >/dev/null 2>"$tmp/f4.err"
check_fail "split [2, 2, 1] on 3 ranks" $? "$tmp/f4.err" "^shapedem: $tmp/g4.yaml:[0-9]*: simulation.mpi_split: \[2, 2, 1\] makes 4 boxes, but the run has 3 MPI ranks"
set -e
[[ -e $tmp/f4 ]] && bad "split [2, 2, 1] on 3 ranks: the output directory was created"
# the serial program ignores the key (the results are the same)
"$bin" run "$tmp/g4.yaml" -o "$tmp/gs" -q --steps 10 || bad "the serial program refused simulation.mpi_split"
# check --ranks: the grid, each rank's box and its particles (720 in all)
"$bin" check "$tmp/g4.yaml" --ranks 4 >"$tmp/check.txt" || bad "check --ranks 4 failed"
boxes=$(grep -c '^  rank [0-3] .* m: [0-9]* particles$' "$tmp/check.txt" || true)
total=$(sed -n 's/^  rank .* m: \([0-9]*\) particles$/\1/p' "$tmp/check.txt" | paste -sd+)
total=$((${total:-0}))
if grep -q '^ranks        4: 2 x 2 x 1 boxes along x, y, z (as simulation.mpi_split asks)' "$tmp/check.txt" &&
  [[ $boxes -eq 4 && $total -eq 720 ]]; then
  ok "check --ranks 4: $(grep -A4 '^ranks ' "$tmp/check.txt" | tr -s ' ' | tr '\n' ';')"
else
  bad "check --ranks 4: $boxes boxes, $total particles:"; grep -A4 '^ranks ' "$tmp/check.txt" || true
fi
"$bin" check "$tmp/g4.yaml" --ranks 3 >"$tmp/check3.txt" || true
grep -q '^warning      3 MPI ranks: .*simulation.mpi_split: \[2, 2, 1\] makes 4 boxes' "$tmp/check3.txt" ||
  bad "check --ranks 3 with a split for 4: no warning"

# the serial program against 1 rank, particle by particle in id order
/usr/bin/python3 - "$src/scripts/frame_to_csv.py" "$tmp/serial" "$tmp/r1" <<'PY' || fail=1
import csv, io, subprocess, sys
conv, a, b = sys.argv[1:]
def rows(d, f):
    out = subprocess.run([sys.executable, conv, f"{d}/{f}"], capture_output=True, text=True, check=True).stdout
    return [r for r in csv.reader(io.StringIO(out)) if r and not r[0].startswith('#') and r[0] != 'x']
dx = 0.0
for f in ("particles_000000.vtu", "particles_000004.vtu"):
    ra, rb = rows(a, f), rows(b, f)
    assert len(ra) == len(rb) == 720, (len(ra), len(rb))
    dx = max(dx, max(abs(float(p[c]) - float(q[c])) for p, q in zip(ra, rb) for c in range(3)))
def stats(d):
    return list(csv.DictReader(open(f"{d}/stats.csv")))
sa, sb = stats(a), stats(b)
de = max(abs(float(p["total_energy"]) - float(q["total_energy"])) / abs(float(p["total_energy"])) for p, q in zip(sa, sb))
same_counts = all(p["contacts"] == q["contacts"] and p["wall_contacts"] == q["wall_contacts"] for p, q in zip(sa, sb))
print(f"serial vs 1 rank: max |dx| = {dx:.3e} m (tolerance 1e-9 m), max relative total-energy difference "
      f"{de:.3e} (tolerance 1e-9), contact counts equal: {same_counts}")
sys.exit(0 if dx <= 1e-9 and de <= 1e-9 and same_counts and len(sa) == len(sb) == 9 else 1)
PY

# failures: one message, exit 2, no hang, nothing written
printf 'simulation:\n  dt: 1.0e-5\n  steps: 10\nmaterials:\n  - name: a\n    densty: 2500\n' >"$tmp/bad.yaml"
set +e
mpi -np 3 "$bin" run "$tmp/bad.yaml" -o "$tmp/f1" >/dev/null 2>"$tmp/f1.err"
check_fail "bad input on every rank" $? "$tmp/f1.err" "^shapedem: $tmp/bad.yaml:6: materials\[0\].densty"
# MPMD: ranks 1 and 2 read the bad scene, rank 0 the good one
mpi -np 1 "$bin" run "$scene" -o "$tmp/f2" : -np 2 "$bin" run "$tmp/bad.yaml" -o "$tmp/f2" >/dev/null 2>"$tmp/f2.err"
check_fail "bad input on ranks 1 and 2 only" $? "$tmp/f2.err" "^shapedem: rank 1 of 3: $tmp/bad.yaml:6"
sed 's/count: \[40, 6, 3\]/count: [40, 6, 2]/' "$scene" >"$tmp/other.yaml"
mpi -np 1 "$bin" run "$scene" -o "$tmp/f3" : -np 1 "$bin" run "$tmp/other.yaml" -o "$tmp/f3" >/dev/null 2>"$tmp/f3.err"
check_fail "ranks that built different worlds" $? "$tmp/f3.err" "rank 1 of 2: its scene differs from rank 0's (the start particles differ"
set -e
for d in f1 f2 f3; do
  [[ -e $tmp/$d ]] && bad "$d: the output directory was created by a run that failed on its input"
done
exit $fail
