#!/usr/bin/env bash
# grid_failed_step.sh — a grid run stopped by the eq. 11 guard (one cell per
# step) ends cleanly (probe F3: writing summary.txt segfaulted, exit 139,
# and left .summary.txt.tmp). The probe's reproducers: its 6-line pour at
# vertical_speed 1e4 m/s (spheres carried out of the grid) and 1000 m/s
# (they stay in it), and examples/hopper-grid.yaml with pour.vertical_speed
# 3000. Each must exit 1 with the eq. 11 message, write a complete
# summary.txt that names the failed step, leave no .tmp file, and report
# the same particle count in summary.txt and on stdout (the pour starts
# from none: stdout said "0 particles" next to the poured spheres' energy).
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

probe() { # $1 = vertical speed
    cat <<EOF
simulation: {dt: 2.0e-5, steps: 20, solver: grid, contact_law: linear}
materials: [{name: m, density: 1592, stiffness: 1.0e4}]
pour: {material: m, radius: 0.003, count: 50, height: 0.1, vertical_speed: $1}
walls: [{name: box, type: box, min: [0, 0, 0], max: [0.1, 0.04, 0.2], open: [zmax], material: m}]
EOF
}
probe 1.0e4 >"$tmp/fast.yaml"
probe 1000 >"$tmp/slower.yaml"
sed -e 's/vertical_speed: 0.5 /vertical_speed: 3000 /' "$root/examples/hopper-grid.yaml" >"$tmp/hopper.yaml"
check "hopper scene has vertical_speed 3000" "$(grep -q 'vertical_speed: 3000 ' "$tmp/hopper.yaml" && echo 1 || echo 0)"

for case in fast slower hopper; do
    out="$tmp/out-$case"
    "$bin" run "$tmp/$case.yaml" -o "$out" --threads 1 >"$tmp/$case.stdout" 2>"$tmp/$case.stderr"
    rc=$?
    err=$(cat "$tmp/$case.stderr")
    echo "$case: exit $rc; stderr: $err"
    check "$case: exit 1 (got $rc)" "$([[ $rc == 1 ]] && echo 1 || echo 0)"
    check "$case: one stderr line with the eq. 11 message" \
        "$([[ $(wc -l <"$tmp/$case.stderr") == 1 ]] && grep -q 'run stopped at step 0: .*eq\. 11.* violated at step 1: ' \
            "$tmp/$case.stderr" && echo 1 || echo 0)"
    sum="$out/summary.txt"
    check "$case: summary.txt written" "$([[ -s "$sum" ]] && echo 1 || echo 0)"
    # complete: the wall lines and the last section (the profile) are there,
    # and the failure is named
    check "$case: summary.txt names the failed step" "$(grep -qx 'grid_failed_at_step: 1' "$sum" && echo 1 || echo 0)"
    check "$case: summary.txt is complete (the wall lines, then the profile to the end)" \
        "$(grep -q '^wall 0 ([a-z]*) torque_N_m: ' "$sum" && tail -1 "$sum" | grep -q '^profile [a-z_0-9]*: seconds ' &&
            echo 1 || echo 0)"
    left=$(find "$out" -name '*.tmp' | wc -l)
    check "$case: no .tmp left ($left)" "$([[ $left == 0 ]] && echo 1 || echo 0)"
    np=$(awk '/^particles:/ {print $2}' "$sum")
    poured=$(awk '/^grid_poured:/ {print $2}' "$sum")
    indom=$(awk '/^grid_in_domain:/ {print $2}' "$sum")
    said=$(sed -n 's/^shapedem: \([0-9]*\) particles,.*/\1/p' "$tmp/$case.stdout")
    echo "$case: summary particles $np, poured $poured, in domain $indom; stdout says $said particles"
    check "$case: particles = poured = in domain = stdout's count" \
        "$([[ -n "$np" && "$np" != 0 && "$np" == "$poured" && "$np" == "$indom" && "$np" == "$said" ]] && echo 1 || echo 0)"
    rows=$(($(wc -l <"$out/stats.csv") - 1))
    check "$case: stats.csv has its one row (step 0), got $rows" "$([[ $rows == 1 ]] && echo 1 || echo 0)"
done

finish
