#!/usr/bin/env bash
# output_safety.sh — what a command writes never destroys what it should not
# (issue 31, probe 3 findings 1, 4, 9 and a low one):
#  - `render -o PATH` refuses a FIFO, a device node, a link, and any file it
#    is drawn from (the frame, its walls/shapes siblings, frames.pvd): exit 2,
#    one line, the entry as it was (before: each replaced by a PNG, exit 0);
#  - an analysis file: named like any file of the run (frames.pvd, a frame, a
#    checkpoint, the .shapedem-output marker, a temporary) is refused with
#    the scene's file, line and key, exit 2; so is an outlet name that would
#    split outlet.csv's header (a comma, a line break);
#  - a checkpoint temporary left by a kill during its write
#    (.checkpoint-NNNNNN.h5.tmp) is removed by the next run into the
#    directory; another dot file ending in .tmp is not;
#  - a checkpoint write that fails for want of space (here: a file size limit,
#    which fails the write as a full disk does) ends the run with exit 1 and
#    one message, no crash at exit (before: segfault in HDF5's exit handler,
#    exit 139), no temporary left, summary.txt written.
set -u
bin="$1"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
{ sed 's/steps: 200/steps: 100/' "$(dirname "${BASH_SOURCE[0]}")/output_scenes/box27.yaml"
    echo "output: {every: 50, checkpoint_every: 50}"; } >"$tmp/s.yaml"

# ---- render -o onto what it must not replace
"$bin" run "$tmp/s.yaml" -o "$tmp/r" --quiet >/dev/null 2>&1
frame="$tmp/r/particles_000000.vtu"
"$bin" render "$frame" -o "$tmp/ok.png" >/dev/null 2>"$tmp/ok.err"
if grep -q "built without rendering" "$tmp/ok.err"; then
    echo "  (this build has no renderer: render -o is not tested)"
else
    check "render -o a new file: exit 0, a PNG" "$(yes01 test -s "$tmp/ok.png")"
    mkfifo "$tmp/fifo"
    ln -s "$tmp/ok.png" "$tmp/link.png"
    mknod "$tmp/null" c 1 3 2>/dev/null || echo "  (mknod not permitted: no device node case)"
    targets=("$tmp/fifo" "$tmp/link.png" "$frame" "$tmp/r/walls_000000.vtp" "$tmp/r/frames.pvd")
    [[ -e $tmp/null ]] && targets+=("$tmp/null")
    for t in "${targets[@]}"; do
        before=$(stat -c '%F %s %i' "$t") # (a FIFO is never read: cksum only of a plain file)
        [[ -f $t && ! -L $t ]] && before="$before $(cksum <"$t")"
        for in in "$frame" "$tmp/r/frames.pvd"; do
            timeout 60 "$bin" render "$in" -o "$t" >/dev/null 2>"$tmp/r.err"
            rc=$?
            after=$(stat -c '%F %s %i' "$t")
            [[ -f $t && ! -L $t ]] && after="$after $(cksum <"$t")"
            check "render $(basename "$in") -o $(basename "$t") ($(stat -c %F "$t")): exit 2 (got $rc), one line, \
untouched" "$([[ $rc == 2 && $(wc -l <"$tmp/r.err") == 1 && $before == "$after" ]] && echo 1 || echo 0)"
        done
    done
    cat "$tmp/r.err"
    "$bin" render "$tmp/r/frames.pvd" --movie -o "$tmp/r/particles.png" >/dev/null 2>&1
    check "render --movie of the run still writes beside the frames" "$(yes01 test -s "$tmp/r/particles_000000.png")"
fi

# ---- analysis files under the run's own names; outlet names that break the CSV
n=0
for name in frames.pvd particles_000000.vtu walls_000002.vtp checkpoint-000100.h5 failed-000050.h5 \
    .shapedem-output .stats.csv.tmp .checkpoint-000050.h5.tmp outlet.csv stats.csv; do
    n=$((n + 1))
    { cat "$tmp/s.yaml"; echo "analysis:"; echo "  - type: energy"; echo "    file: $name"; } >"$tmp/a$n.yaml"
    "$bin" run "$tmp/a$n.yaml" -o "$tmp/a$n" --quiet >/dev/null 2>"$tmp/a.err"
    rc=$?
    line=$(grep -n "file: " "$tmp/a$n.yaml" | cut -d: -f1)
    check "analysis file: $name: exit 2 (got $rc), the file: key's line, nothing made" \
        "$([[ $rc == 2 && ! -e $tmp/a$n ]] && grep -q "a$n.yaml:$line: analysis\[0\].file: .*run's own output" \
            "$tmp/a.err" && echo 1 || echo 0)"
done
cat "$tmp/a.err"
{ cat "$tmp/s.yaml"; echo "analysis: [{type: energy, name: stats}]"; } >"$tmp/an.yaml"
"$bin" check "$tmp/an.yaml" >/dev/null 2>"$tmp/an.err"
check "an analysis named stats (its file stats.csv): exit 2 (got $?)" \
    "$(yes01 grep -q "stats.csv is a file of the run's own output" "$tmp/an.err")"
{ cat "$tmp/s.yaml"; echo "analysis: [{type: energy, file: energy.csv}]"; } >"$tmp/good.yaml"
"$bin" run "$tmp/good.yaml" -o "$tmp/good" --quiet >/dev/null 2>&1
check "an analysis file of its own name still runs" "$(yes01 test -s "$tmp/good/energy.csv")"
for bad in '"a,b\nc"' '"a\"b"' '"tab\there"'; do
    { cat "$tmp/s.yaml"; echo "outlets: [{name: $bad, region: box, min: [-1, -1, -1], max: [1, 1, -0.5]}]"; } \
        >"$tmp/o.yaml"
    "$bin" run "$tmp/o.yaml" -o "$tmp/o" --quiet >/dev/null 2>"$tmp/o.err"
    rc=$?
    line=$(grep -n "^outlets:" "$tmp/o.yaml" | cut -d: -f1)
    check "outlet name $bad: exit 2 (got $rc), the name's line, nothing made" \
        "$([[ $rc == 2 && ! -e $tmp/o ]] && grep -q "o.yaml:$line: outlets\[0\].name: .*comma" "$tmp/o.err" &&
            echo 1 || echo 0)"
done
cat "$tmp/o.err"

# ---- a checkpoint's temporary left by a kill goes with the next run; a foreign one stays
head -c 5000 "$tmp/r/checkpoint-000050.h5" >"$tmp/r/.checkpoint-000050.h5.tmp"
echo notes >"$tmp/r/.notes.tmp"
"$bin" run "$tmp/s.yaml" -o "$tmp/r" --quiet --steps 10 >/dev/null 2>&1
check "the next run into the directory removes .checkpoint-000050.h5.tmp, keeps .notes.tmp and the checkpoints" \
    "$([[ ! -e $tmp/r/.checkpoint-000050.h5.tmp && -f $tmp/r/.notes.tmp && -f $tmp/r/checkpoint-000100.h5 ]] &&
        echo 1 || echo 0)"

# ---- no room for a checkpoint: exit 1, one message, no crash
cat >"$tmp/big.yaml" <<'EOF'
simulation: {dt: 1.0e-5, steps: 20, seed: 3}
materials: [{name: g, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: lattice, material: g, radius: 0.001, origin: [0.002, 0.002, 0.002], spacing: 0.0025, count: [16, 16, 16]}]
walls: [{name: box, type: box, min: [0, 0, 0], max: [0.05, 0.05, 0.05], material: g}]
output: {every: 10, formats: [csv], checkpoint_every: 10}
EOF
# a limit of 256 KiB per file: the CSV files fit, the checkpoint (about 1 MB) does not
(trap - EXIT; trap '' XFSZ; ulimit -f 256; exec "$bin" run "$tmp/big.yaml" -o "$tmp/full" --quiet >/dev/null \
    2>"$tmp/full.err")
rc=$?
check "a checkpoint that cannot be written: exit 1 (got $rc; 139 was the crash at exit), one message" \
    "$([[ $rc == 1 && $(wc -l <"$tmp/full.err") == 1 ]] && grep -q "could not write the checkpoint" "$tmp/full.err" &&
        echo 1 || echo 0)"
cat "$tmp/full.err"
check "no temporary left, summary.txt written" \
    "$([[ -z $(ls -A "$tmp/full" | grep '\.tmp$') && -s $tmp/full/summary.txt ]] && echo 1 || echo 0)"

finish output_safety
