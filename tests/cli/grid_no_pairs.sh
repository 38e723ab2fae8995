#!/usr/bin/env bash
# grid_no_pairs.sh — worlds without a single particle pair (one sphere over
# a plane, solver cells; one sphere in a box, solver grid) run and check
# cleanly. Probe F14: the pair-list build called memcpy from a NULL pair
# array with 0 bytes on every world without pairs, which UBSan reports;
# run under the sanitizer build (SHAPEDEM_SANITIZE) this test fails on any
# sanitizer report (halt_on_error), in any build it checks the exit status.
set -u
bin="$1"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export ASAN_OPTIONS=detect_leaks=1
cat >"$tmp/cells.yaml" <<'EOF'
simulation: {dt: 1.0e-6, steps: 20}
materials: [{name: glass, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: list, material: glass, spheres: [{position: [0, 0, 0.01], radius: 0.001}]}]
walls: [{name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}]
EOF
cat >"$tmp/grid.yaml" <<'EOF'
simulation: {dt: 1.0e-5, steps: 20, solver: grid, contact_law: linear}
materials: [{name: m, density: 2500, stiffness: 1.0e4}]
particles: [{generator: list, material: m, spheres: [{position: [0.05, 0.05, 0.05], radius: 0.003}]}]
walls: [{name: box, type: box, min: [0, 0, 0], max: [0.1, 0.1, 0.1], material: m}]
EOF
for s in cells grid; do
    "$bin" check "$tmp/$s.yaml" >"$tmp/$s.check" 2>&1
    rc=$?
    check "$s: check exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
    "$bin" run "$tmp/$s.yaml" -o "$tmp/out-$s" --quiet >"$tmp/$s.run" 2>&1
    rc=$?
    check "$s: run exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
    n=$(grep -c 'runtime error\|Sanitizer' "$tmp/$s.check" "$tmp/$s.run" | awk -F: '{s += $2} END {print s}')
    check "$s: no sanitizer report ($n)" "$([[ $n == 0 ]] && echo 1 || echo 0)"
    [[ $n == 0 ]] || cat "$tmp/$s.check" "$tmp/$s.run"
    check "$s: summary says 1 particle, 0 contacts" \
        "$(grep -qx 'particles: 1' "$tmp/out-$s/summary.txt" && grep -qx 'contacts: 0' "$tmp/out-$s/summary.txt" \
            && echo 1 || echo 0)"
done
finish
