#!/usr/bin/env bash
# shape_info.sh — `shapedem shape info` prints a shape's mass properties:
# a box's volume and principal moments against closed forms, a scene's
# shapes, and exit status 2 for an unknown kind.
set -u
bin="$1"
root="$2"
pass=0
fail=0
check() {
    if [[ "$2" == 1 ]]; then pass=$((pass + 1)); echo "PASS $1"; else fail=$((fail + 1)); echo "FAIL $1"; fi
}
out=$("$bin" shape info box --size 0.01,0.02,0.03 --density 2500)
vol=$(awk '/^volume/ {print $2}' <<<"$out")
mom=$(awk '/^principal moments/ {print $3}' <<<"$out" | tr -d '(,')
check "box volume 6e-06 m^3 (got $vol)" "$(awk -v v="$vol" 'BEGIN {print (v > 5.999999e-6 && v < 6.000001e-6)}')"
# I_x / rho = V (b^2 + c^2) / 12 = 6.5e-10 m^5
check "box moment about x 6.5e-10 m^5 (got $mom)" "$(awk -v v="$mom" 'BEGIN {print (v > 6.499999e-10 && v < 6.500001e-10)}')"
out=$("$bin" shape info "$root/tests/validation/scenes/mixed-packing.yaml")
check "scene shapes listed (5)" "$([[ $(grep -c '^shape ' <<<"$out") == 5 ]] && echo 1 || echo 0)"
"$bin" shape info blob --size 1 >/dev/null 2>&1
rc=$?
check "unknown kind exits 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
# built-in polyhedra: welded faces, and the seed 000 §3.1 cylinder against
# its Table 1 moments (I_xx = 2.047e-9, I_zz = 2.567e-9 kg m^2 at 1245 kg/m^3)
out=$("$bin" shape info dodecahedron --edge 0.01)
check "dodecahedron: 12 welded faces, 20 vertices" \
    "$([[ $(grep -c 'welded faces *12 ' <<<"$out") == 1 && $(grep -c 'hull vertices *20$' <<<"$out") == 1 ]] && echo 1 || echo 0)"
out=$("$bin" shape info polycylinder --size 8e-3,0,5.3e-3 --sides 20 --density 1245)
ixx=$(awk '/at 1245/ {print $8}' <<<"$out" | tr -d '(,')
izz=$(awk '/at 1245/ {print $10}' <<<"$out" | tr -d ')')
check "seed 000 cylinder: 22 welded faces" "$(grep -c 'welded faces *22 ' <<<"$out")"
check "seed 000 cylinder I_xx 2.047e-9 (got $ixx)" "$(awk -v v="$ixx" 'BEGIN {print (v > 2.0465e-9 && v < 2.0475e-9)}')"
check "seed 000 cylinder I_zz 2.567e-9 (got $izz)" "$(awk -v v="$izz" 'BEGIN {print (v > 2.5665e-9 && v < 2.5675e-9)}')"
"$bin" shape info prism --size 1 --sides 2 >/dev/null 2>&1
rc=$?
check "prism with 2 sides exits 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
# a non-convex mesh taken as its hull (nonconvex: hull): accepted, with a warning
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_shape_info.XXXXXX")
cp "$root/tests/cli/bad/nonconvex-mesh.obj" "$tmp/"
sed -e 's/    scale: 0.001/    scale: 0.001\n    nonconvex: hull/' "$root/tests/cli/bad/nonconvex-mesh.yaml" >"$tmp/hull.yaml"
out=$("$bin" shape info "$tmp/hull.yaml" 2>&1)
rc=$?
vol=$(awk '/^volume/ {print $2}' <<<"$out")
check "non-convex mesh with nonconvex: hull: exit 0 (got $rc), hull volume 1e-9 m^3 (got $vol)" \
    "$([[ $rc == 0 ]] && awk -v v="$vol" 'BEGIN {print (v > 0.999999e-9 && v < 1.000001e-9)}' || echo 0)"
check "non-convex mesh with nonconvex: hull: a warning" "$(grep -c '^warning .*not convex' <<<"$out")"
rm -rf "$tmp"
echo "$pass passed, $fail failed"
[[ $fail == 0 ]]
