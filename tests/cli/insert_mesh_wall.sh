#!/usr/bin/env bash
# insert_mesh_wall.sh — insertion regions and mesh walls (issue 31: the
# placement checked plane, box and drum walls only, and `check` said
# nothing of a region across a mesh). A closed box mesh 'tank' (12 facets,
# an OBJ) holds the particles:
#  - a region across its xmin face: `check` warns that the region crosses
#    mesh wall 'tank'; the run places particles only inside the tank, clear
#    of the face (x - r >= 0 for every particle of the step-1 checkpoint);
#  - a region beside the tank, touching no facet: no particle is placed
#    (the tank's inside is tested by its winding number), and the run says
#    why;
#  - a region well inside: no warning.
# The binary of ade592f: no warning, particles at x < 0 (the overlap guard
# stops the run at step 1), and 20 particles outside the tank.
set -u
bin="$1"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
{
    for z in 0 0.05; do for y in 0 0.02; do for x in 0 0.02; do echo "v $x $y $z"; done; done; done
    printf 'f %s\n' "1 3 2" "2 3 4" "5 6 7" "6 8 7" "1 2 5" "2 6 5" "3 7 4" "4 7 8" "1 5 3" "3 5 7" "2 4 6" "4 8 6"
} >tank.obj
scene() { # scene NAME MIN MAX COUNT
    cat >"$1.yaml" <<EOF
simulation: {dt: 2.0e-6, steps: 1, seed: 3}
materials: [{name: g, density: 2500, youngs_modulus: 1.0e7}]
walls: [{name: tank, type: mesh, file: tank.obj, material: g}]
insert: [{name: f, region: box, min: $2, max: $3, count: $4, mix: [{material: g, radius: 0.001}]}]
output: {every: 1, checkpoint_every: 1}
EOF
}
scene across "[-0.01, 0.003, 0.02]" "[0.01, 0.017, 0.04]" 60
scene beside "[0.03, 0.003, 0.02]" "[0.05, 0.017, 0.04]" 20
scene within "[0.003, 0.003, 0.01]" "[0.017, 0.017, 0.04]" 60

"$bin" check across.yaml --threads 1 >check.out 2>&1
grep "insertion f" check.out
check "check: the region across the tank's face is reported" \
    "$(grep -q "warning .*insertion f: its region crosses mesh wall 'tank'" check.out && echo 1 || echo 0)"
"$bin" check within.yaml --threads 1 >check2.out 2>&1
check "check: a region inside the tank is not" "$(grep -q "insertion f" check2.out && echo 0 || echo 1)"

"$bin" run across.yaml -o across --quiet --threads 1 2>across.err
rc=$?
"$bin" info across/checkpoint-000001.h5 --csv >across.csv 2>/dev/null
read -r n least < <(awk -F, 'NR > 1 { n++; d = $2 - $15; if (n == 1 || d < m) m = d }
    END { printf "%d %.6g\n", n, n ? m : -1 }' across.csv)
check "run across the face: exit 0 (got $rc), $n particles, the least x - r $least m >= 0" \
    "$([[ $rc == 0 && $n -gt 10 ]] && awk -v m="$least" 'BEGIN { exit !(m >= 0) }' && echo 1 || echo 0)"

"$bin" run beside.yaml -o beside --quiet --threads 1 2>beside.err
rc=$?
cat beside.err
n=$("$bin" info beside/checkpoint-000001.h5 --csv 2>/dev/null | awk 'NR > 1' | wc -l)
check "run beside the tank: exit 0 (got $rc), no particle ($n), 'inserted 0 of the 20'" \
    "$([[ $rc == 0 && $n == 0 ]] && grep -q "inserted 0 of the 20" beside.err && echo 1 || echo 0)"
finish
