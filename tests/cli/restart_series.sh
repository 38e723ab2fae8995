#!/usr/bin/env bash
# restart_series.sh — a restart continues the run's CSV series (issue 16):
# process_scenes/restart-series.yaml run straight through (A), and run to
# step 2750 then restarted from its checkpoint into the same directory (B),
# leaves stats.csv, walls.csv, coordination.csv, energy.csv and
# bed_height.csv byte for byte as A's: the rows before the restart step
# are kept, the later ones cut and written again. Step 2750 is no stats or
# analysis step (rows due at 2500 and 3000), and the first part, ended by
# --steps there, wrote closing rows at 2750 that the restart must cut.
# outlet.csv too, its mass rates included (every row rates from the
# printed values, as the restart reads them back). The frames go on as
# well: B's frames.pvd and frame files are A's, the first part's frames
# before step 2750 kept and its closing frame at 2750 (none is due there)
# gone. Then A's directory, restarted from its step-5500 checkpoint (a
# stats and coordination step), is left as it was, and its frames, with no
# frames.pvd to continue, start from 0 at the restart step.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$root/tests/cli/process_scenes/restart-series.yaml
series="stats.csv walls.csv coordination.csv energy.csv bed_height.csv"

"$bin" run "$scene" --threads 2 --quiet -o "$tmp/a" >"$tmp/a.out" 2>&1
rc=$?
cat "$tmp/a.out"
check "A, straight through: exit 0 (got $rc)" "$((rc == 0))"
"$bin" run "$scene" --threads 1 --quiet -o "$tmp/b" --steps 2750 >"$tmp/b1.out" 2>&1
rc=$?
check "B, first part to step 2750: exit 0 (got $rc)" "$((rc == 0))"
rows_b1=$(grep -c '^2750,' "$tmp/b/stats.csv")
check "B's first part closed with no stats row at 2750 (not due: got $rows_b1)" "$((rows_b1 == 0))"
last_b1=$(tail -n 1 "$tmp/b/coordination.csv" | cut -d, -f2)
check "B's first part wrote a closing coordination row at 2750 (got $last_b1)" "$([[ $last_b1 == 2750 ]] && echo 1 || echo 0)"
"$bin" run "$scene" --threads 2 --quiet -o "$tmp/b" --restart "$tmp/b/checkpoint-002750.h5" >"$tmp/b2.out" 2>&1
rc=$?
cat "$tmp/b2.out"
check "B, restarted at step 2750 in the same directory: exit 0 (got $rc)" "$((rc == 0))"
for f in $series; do
  cmp -s "$tmp/a/$f" "$tmp/b/$f"
  same=$((! $?))
  echo "     $f: A $(wc -l <"$tmp/a/$f") lines, B $(wc -l <"$tmp/b/$f") lines"
  check "$f of B is A's, byte for byte" "$same"
done
cmp -s "$tmp/a/outlet.csv" "$tmp/b/outlet.csv"
check "outlet.csv of B is A's, byte for byte, mass rates included ($(wc -l <"$tmp/a/outlet.csv") rows)" "$((! $?))"
cmp -s "$tmp/a/frames.pvd" "$tmp/b/frames.pvd"
check "frames.pvd of B is A's ($(grep -c '<DataSet' "$tmp/a/frames.pvd") data sets)" "$((! $?))"
frames_a=$(cd "$tmp/a" && ls particles_*.vtu walls_*.vtp | tr '\n' ' ')
frames_b=$(cd "$tmp/b" && ls particles_*.vtu walls_*.vtp | tr '\n' ' ')
echo "     frames: A $frames_a"
check "B holds A's frame files, no more (the first part's closing frame at 2750 gone)" \
  "$([[ -n $frames_a && $frames_a == "$frames_b" ]] && echo 1 || echo 0)"
same=1
for f in $frames_a; do
  cmp -s "$tmp/a/$f" "$tmp/b/$f" || { same=0; echo "     $f differs"; }
done
check "each frame of B is A's, byte for byte (those of the first part kept)" "$same"
removed=$(tail -n 1 "$tmp/a/outlet.csv" | cut -d, -f6)
check "the drain removed particles, so outlet.csv has rows to compare (removed $removed)" "$((removed > 0))"

mkdir "$tmp/c"
cp "$tmp/a/"*.csv "$tmp/c/"
cp "$tmp/a/.shapedem-output" "$tmp/c/"
"$bin" run "$scene" --threads 1 --quiet -o "$tmp/c" --restart "$tmp/a/checkpoint-005500.h5" >"$tmp/c.out" 2>&1
rc=$?
check "A's files restarted at step 5500: exit 0 (got $rc)" "$((rc == 0))"
for f in $series; do
  cmp -s "$tmp/a/$f" "$tmp/c/$f"
  check "$f after a restart at a step with rows is still A's" "$((! $?))"
done
first_c=$(grep -m1 -o 'timestep="[^"]*"' "$tmp/c/frames.pvd" | cut -d'"' -f2)
check "no frames.pvd to continue: C's frames start from 0 at the restart (frame 0 at t = $first_c)" \
  "$([[ -f $tmp/c/particles_000000.vtu && $first_c == 0.055* ]] && echo 1 || echo 0)"
finish
