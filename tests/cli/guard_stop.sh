#!/usr/bin/env bash
# guard_stop.sh — the overlap guard of the cells solver from the command
# line (issue 17): simulation.max_overlap sets it (default 0.5, 0 = off).
# A soft sphere (linear law, k = 10 N/m) is shot at 0.8 m/s into a floor
# without gravity: its deepest overlap is about 61 % of its radius. With
# the default guard the run stops with exit 1 and one stderr line that
# names the particle, the wall, the step and the limit, and says where
# the state was written (OUT/failed-STEP.h5, a checkpoint that `shapedem
# info` reads, of that step); max_overlap 0.3 stops it earlier, at 30 %;
# 0.95 and 0 let it bounce off (exit 0, no failed-*.h5); a negative value
# is refused at load (exit 2, simulation.max_overlap).
set -u
exe=${1:?usage: guard_stop.sh SHAPEDEM REPO}
[[ $exe == */* ]] && exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_guard_stop.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
scene() { # $1: extra simulation keys
    cat <<EOF
simulation: {dt: 1.0e-5, steps: 1500, gravity: [0, 0, 0], contact_law: linear$1}
materials:
  - {name: soft, density: 2500, stiffness: 10, restitution: 0.5}
particles:
  - generator: list
    material: soft
    spheres:
      - {position: [0, 0, 0.0015], radius: 0.001, velocity: [0, 0, -0.8]}
walls:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: soft}
output: {every: 500, stats_every: 10}
EOF
}
run() { # run NAME EXTRA: sets rc, err
    scene "$2" >"$tmp/$1.yaml"
    (cd "$tmp" && "$exe" run "$1.yaml" -o "out-$1" --threads 1 >"$tmp/$1.out" 2>"$tmp/$1.err")
    rc=$?
    err=$(cat "$tmp/$1.err")
    echo "  $1: exit $rc: $err"
}
stopped() { # stopped NAME LIMIT%
    local f step
    check "$1: exit 1 (got $rc)" "$([[ $rc == 1 ]] && echo 1 || echo 0)"
    # the pattern in a variable first (cli.deps_complete reads a '(' inside
    # a quoted pattern within $(...) as a substitution)
    local want="particle id 0 overlaps wall 'floor' by .* at step [0-9]*, [0-9]* % of its radius .the guard's limit is $2 %, simulation.max_overlap.: "
    local said=0
    [[ $(wc -l <"$tmp/$1.err") == 1 ]] && grep -q "$want" "$tmp/$1.err" && said=1
    check "$1: one stderr line naming particle id 0, wall 'floor' and the limit $2 %" "$said"
    f=$(sed -n "s/.*the state is in \(out-$1\/failed-[0-9]*\.h5\) for inspection.*/\1/p" "$tmp/$1.err")
    check "$1: it says where the state is ($f)" "$([[ -n $f && -s $tmp/$f ]] && echo 1 || echo 0)"
    step=$(sed -n 's/.*at step \([0-9]*\), [0-9]* % of its radius.*/\1/p' "$tmp/$1.err")
    (cd "$tmp" && "$exe" info "$f" >"$tmp/$1.info" 2>&1)
    check "$1: shapedem info reads it: step $step" \
        "$([[ $? == 0 ]] && grep -q "^run .*step $step, " "$tmp/$1.info" && echo 1 || echo 0)"
    stop_step=$step
}
run default ""
stopped default 50
s50=$stop_step
run tight ", max_overlap: 0.3"
stopped tight 30
check "0.3 stops before 0.5 (step $stop_step < $s50)" "$([[ -n $stop_step && -n $s50 && $stop_step -lt $s50 ]] && echo 1 || echo 0)"
for v in 0.95 0; do
    run "loose$v" ", max_overlap: $v"
    check "max_overlap $v: exit 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
    check "max_overlap $v: no failed-*.h5" "$(ls "$tmp/out-loose$v" | grep -q '^failed-' && echo 0 || echo 1)"
done
# the overlap the guard let through, from stats.csv's max_overlap_ratio column
peak=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "max_overlap_ratio") c = i }
    NR > 1 && c && $c > m { m = $c } END { print m + 0 }' "$tmp/out-loose0/stats.csv")
echo "  the deepest overlap with the guard off: $peak of the radius (expected about 0.6)"
check "the deepest overlap lies between 0.5 and 0.95 ($peak)" \
    "$(awk -v p="$peak" 'BEGIN { print (p > 0.5 && p < 0.95) ? 1 : 0 }')"
run negative ", max_overlap: -1"
check "max_overlap -1: exit 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
check "max_overlap -1: names negative.yaml:1: simulation.max_overlap" \
    "$(grep -q 'negative.yaml:1: simulation.max_overlap: ' "$tmp/negative.err" && echo 1 || echo 0)"
check "max_overlap -1: no output directory" "$([[ ! -e $tmp/out-negative ]] && echo 1 || echo 0)"

finish
