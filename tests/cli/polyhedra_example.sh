#!/usr/bin/env bash
# polyhedra_example.sh — examples/polyhedra-pour.yaml (sharp polyhedra under
# the overlap-volume law) is accepted by `shapedem check` without warnings,
# and a short run of it (2,000 steps, 1 and 2 threads) writes its summary
# with polyhedron-polyhedron narrow-phase counts, no NaN, and the same
# energies with 1 and 2 threads (60 bodies stay below the parallel
# threshold, so this checks the option path; tests/validation/
# poly_determinism.c checks 1200 bodies on 2 threads bit for bit).
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene="$root/examples/polyhedra-pour.yaml"
out=$("$bin" check "$scene" 2>&1)
rc=$?
check "check exits 0" "$((rc == 0))"
check "check: contact law volume" "$([[ "$out" == *"contact law  volume"* ]] && echo 1 || echo 0)"
check "check: no warnings" "$([[ "$out" != *warning* ]] && echo 1 || echo 0)"
for t in 1 2; do
    "$bin" run "$scene" --steps 2000 --threads "$t" -o "$tmp/out$t" --quiet >/dev/null 2>"$tmp/err$t"
    rc=$?
    check "run with $t thread(s) exits 0" "$((rc == 0))"
    check "run $t: summary written" "$([[ -f "$tmp/out$t/summary.txt" ]] && echo 1 || echo 0)"
done
check "narrow-phase counts for polyhedron pairs" \
    "$(grep -q '^narrow_phase polyhedron-polyhedron: evaluations [1-9]' "$tmp/out1/summary.txt" && echo 1 || echo 0)"
check "no NaN in the summary" "$(! grep -qi 'nan' "$tmp/out1/summary.txt" && echo 1 || echo 0)"
e1=$(grep -E '^(kinetic|potential|total)' "$tmp/out1/summary.txt")
e2=$(grep -E '^(kinetic|potential|total)' "$tmp/out2/summary.txt")
check "1 and 2 threads: same energies" "$([[ -n "$e1" && "$e1" == "$e2" ]] && echo 1 || echo 0)"
finish
