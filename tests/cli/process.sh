#!/usr/bin/env bash
# process.sh — insertion and outlets through the CLI (issue 16):
#  - feed-drain.yaml: the run exits 0, warns on stderr about the outlet no
#    particle can reach (file:line: outlets[1]: ..., and so does check),
#    writes outlet.csv whose every row keeps
#    particles + removed = initial + inserted, and summary.txt says how many
#    were asked for and inserted (all 300);
#  - full-box.yaml: fewer fit than asked: summary.txt and one stderr line
#    say how many went in and why;
#  - graded-drum.yaml: log-normal cubes (scaled copies of a template) and
#    spheres inserted into an analytic drum (walls: type: drum): all go in,
#    and the walls VTK file draws the drum (48 mantle quads and 2 caps).
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes=$root/tests/cli/process_scenes

"$bin" run "$scenes/feed-drain.yaml" --threads 2 --quiet -o "$tmp/feed" >"$tmp/feed.out" 2>"$tmp/feed.err"
rc=$?
check "feed-drain: exit 0 (got $rc)" "$((rc == 0))"
cat "$tmp/feed.err"
grep -q "warning: .*feed-drain.yaml:38: outlets\[1\]: outlet 'lost' lies above every particle" "$tmp/feed.err"
check "feed-drain: stderr warns about the outlet no particle can reach, at its file, line and key" "$((! $?))"
"$bin" check "$scenes/feed-drain.yaml" --threads 1 >"$tmp/feed-check.out" 2>&1
rc=$?
grep -q "^warning .*feed-drain.yaml:38: outlets\[1\]: outlet 'lost' lies above every particle" "$tmp/feed-check.out"
check "feed-drain: check exits 0 (got $rc) and warns about that outlet at its file, line and key" "$((! $? && rc == 0))"
rows=$(awk -F, 'NR > 1 { n++; if ($3 + $6 != $4 + $5) bad++ } END { print n + 0, bad + 0 }' "$tmp/feed/outlet.csv")
echo "     outlet.csv rows, rows off the accounting: $rows"
check "feed-drain: outlet.csv keeps particles + removed = initial + inserted in every row" \
    "$([[ ${rows% *} -ge 10 && ${rows#* } == 0 ]] && echo 1 || echo 0)"
last=$(tail -1 "$tmp/feed/outlet.csv")
echo "     last row: $last"
check "feed-drain: particles left through the drain" "$(awk -F, '{ print ($9 > 0) }' <<<"$last")"
grep -q "^insert feed: asked 300, inserted 300," "$tmp/feed/summary.txt"
check "feed-drain: summary.txt: asked 300, inserted 300" "$((! $?))"

"$bin" run "$scenes/full-box.yaml" --quiet -o "$tmp/full" >"$tmp/full.out" 2>"$tmp/full.err"
rc=$?
check "full-box: exit 0 (got $rc)" "$((rc == 0))"
cat "$tmp/full.err"
grep -q "^shapedem: insert crowd: inserted [0-9]* of the 100 asked for: .*no free spot" "$tmp/full.err"
check "full-box: one stderr line says how many went in and why" "$((! $? && $(wc -l <"$tmp/full.err") == 1))"
grep -q "^insert crowd: asked 100, inserted [0-9]*, mass_kg [0-9.e-]*, why: " "$tmp/full/summary.txt"
check "full-box: summary.txt says asked, inserted and why" "$((! $?))"

"$bin" run "$scenes/graded-drum.yaml" --quiet -o "$tmp/drum" >"$tmp/drum.out" 2>"$tmp/drum.err"
rc=$?
check "graded-drum: exit 0 (got $rc)" "$((rc == 0))"
grep -q "^insert charge: asked 300, inserted 300," "$tmp/drum/summary.txt"
check "graded-drum: summary.txt: 300 graded cubes and spheres asked for and inserted" "$((! $?))"
polys=$(grep -ao 'NumberOfPolys="[0-9]*"' "$tmp/drum/walls_000000.vtp")
echo "     walls_000000.vtp: $polys"
check "graded-drum: the drum drawn in the walls file (48 mantle quads, 2 caps)" \
    "$([[ $polys == 'NumberOfPolys="50"' ]] && echo 1 || echo 0)"

finish
