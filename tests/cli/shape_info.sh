#!/usr/bin/env bash
# shape_info.sh — `shapedem shape info` prints a shape's mass properties:
# a box's volume and principal moments against closed forms, a scene's
# shapes, exit status 2 for an unknown kind, and composites (exact or lattice).
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
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
# a mesh file given directly, with the options of a polyhedron from a file:
# the unit octahedron |x| + |y| + |z| <= 1 (OBJ) and a unit cube (ASCII STL),
# volumes 4/3 and 1 before scale
cat >"$tmp/octa.obj" <<'EOF'
v 1 0 0
v -1 0 0
v 0 1 0
v 0 -1 0
v 0 0 1
v 0 0 -1
f 1 3 5
f 3 2 5
f 2 4 5
f 4 1 5
f 3 1 6
f 2 3 6
f 4 2 6
f 1 4 6
EOF
out=$("$bin" shape info "$tmp/octa.obj" --scale 0.001 --density 2500 2>&1)
rc=$?
vol=$(awk '/^volume/ {print $2}' <<<"$out")
check "mesh file octa.obj --scale 0.001: exit 0 (got $rc), volume 1.333333e-09 m^3 (got $vol)" \
    "$([[ $rc == 0 ]] && awk -v v="$vol" 'BEGIN {print (v > 1.3333332e-9 && v < 1.3333334e-9)}' || echo 0)"
check "mesh file octa.obj: 6 hull vertices, 8 welded faces" \
    "$([[ $(grep -c 'hull vertices *6$' <<<"$out") == 1 && $(grep -c 'welded faces *8 ' <<<"$out") == 1 ]] && echo 1 || echo 0)"
{
    echo "solid cube"
    for f in "0 0 0 1 1 0 1 0 0" "0 0 0 0 1 0 1 1 0" "0 0 1 1 0 1 1 1 1" "0 0 1 1 1 1 0 1 1" \
        "0 0 0 1 0 0 1 0 1" "0 0 0 1 0 1 0 0 1" "0 1 0 0 1 1 1 1 1" "0 1 0 1 1 1 1 1 0" \
        "0 0 0 0 0 1 0 1 1" "0 0 0 0 1 1 0 1 0" "1 0 0 1 1 0 1 1 1" "1 0 0 1 1 1 1 0 1"; do
        read -r a b c d e g h i j <<<"$f"
        printf ' facet normal 0 0 0\n  outer loop\n   vertex %s %s %s\n   vertex %s %s %s\n   vertex %s %s %s\n  endloop\n endfacet\n' \
            "$a" "$b" "$c" "$d" "$e" "$g" "$h" "$i" "$j"
    done
    echo "endsolid cube"
} >"$tmp/cube.STL"
out=$("$bin" shape info "$tmp/cube.STL" --scale 0.002 --margin 0.1 2>&1)
rc=$?
vol=$(awk '/^volume/ {print $2}' <<<"$out")
# margin 0.1 x 0.002: the outer size kept, edges rounded: V = 0.8^3 + 6 (0.8^2)(0.1)
# + 3 pi (0.8)(0.1^2) + 4/3 pi 0.1^3, times 0.002^3
exp_vol=$(awk 'BEGIN {pi = atan2(0, -1); printf "%.10g", (0.512 + 6 * 0.64 * 0.1 + 3 * pi * 0.8 * 0.01 + 4 / 3 * pi * 0.001) * 8e-9}')
check "mesh file cube.STL --scale 0.002 --margin 0.1: exit 0 (got $rc), volume $exp_vol m^3 (got $vol)" \
    "$([[ $rc == 0 ]] && awk -v v="$vol" -v e="$exp_vol" 'BEGIN {print (v > e * (1 - 1e-9) && v < e * (1 + 1e-9))}' || echo 0)"
out=$("$bin" shape info "$tmp/nonconvex-mesh.obj" --scale 0.001 2>&1)
rc=$?
check "non-convex mesh file without --nonconvex hull: exit 2 (got $rc), says --nonconvex hull" \
    "$([[ $rc == 2 && $(wc -l <<<"$out") == 1 ]] && grep -c 'not convex.*--nonconvex hull' <<<"$out" || echo 0)"
out=$("$bin" shape info "$tmp/nonconvex-mesh.obj" --scale 0.001 --nonconvex hull 2>&1)
rc=$?
check "non-convex mesh file with --nonconvex hull: exit 0 (got $rc), with a warning" \
    "$([[ $rc == 0 ]] && grep -c '^warning .*not convex' <<<"$out" || echo 0)"
out=$("$bin" shape info "$tmp/missing.obj" 2>&1)
rc=$?
check "missing mesh file: exit 2 (got $rc), one line naming it" \
    "$([[ $rc == 2 && $(wc -l <<<"$out") == 1 ]] && grep -c "missing.obj" <<<"$out" || echo 0)"
"$bin" shape info "$tmp/octa.obj" --sides 5 >/dev/null 2>&1
rc=$?
check "mesh file with an option it does not take: exit 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
# a scene that loads but does not build (a body behind the floor): exit 2,
# one line, and (under the sanitizer build) the loaded scene freed
cat >"$tmp/crossing.yaml" <<'EOF'
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
shapes: [{name: b, type: box, size: [0.01, 0.01, 0.01]}]
walls: [{name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}]
particles: [{generator: list, material: m, spheres: [{position: [0, 0, -0.02], shape: b}]}]
EOF
out=$("$bin" shape info "$tmp/crossing.yaml" 2>&1)
rc=$?
check "scene that fails to build: exit 2 (got $rc), one line" "$([[ $rc == 2 && $(wc -l <<<"$out") == 1 ]] && echo 1 || echo 0)"
# composites (seed 004): a flush tile spacer is exact, the 3D cross of three
# cylinders (R = 0.5 mm, L = 4 mm) goes through the lattice; its volume is
# 3 pi R^2 L - 3 (16/3) R^3 + 8 (2 - sqrt 2) R^3 = 8.01056e-9 m^3
cat >"$tmp/comp.yaml" <<'EOF'
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
shapes:
  - {name: spacer, type: composite, preset: cross2d, length: 0.004, width: 0.001, thickness: 0.0005}
  - {name: c3, type: composite, preset: cross3d, length: 0.004, diameter: 0.001}
particles: [{generator: list, material: m, shape: c3, spheres: [{position: [0, 0, 0]}]}]
EOF
out=$("$bin" shape info "$tmp/comp.yaml")
sp=$(awk '/^shape .*spacer \(composite\)/ {f = 1} f && /^volume/ {print $2; exit}' <<<"$out")
check "tile spacer: volume 3.5e-09 m^3 (got $sp)" "$(awk -v v="$sp" 'BEGIN {print (v > 3.4999999e-9 && v < 3.5000001e-9)}')"
n_exact=$(grep -c 'mass properties *exact (no two elements' <<<"$out")
n_elem=$(grep -c 'elements *5 convex' <<<"$out")
check "tile spacer: exact mass properties, 5 elements" \
    "$([[ $n_exact == 1 && $n_elem == 1 ]] && echo 1 || echo 0)"
c3=$(awk '/^shape .*c3 \(composite\)/ {f = 1} f && /^volume/ {print $2; exit}' <<<"$out")
check "3D cross: volume 8.01056e-9 m^3 within 0.2 % (got $c3)" "$(awk -v v="$c3" 'BEGIN {print (v > 7.9945e-9 && v < 8.0266e-9)}')"
check "3D cross: lattice of 200 points per direction reported" "$(grep -c 'voxel lattice of 200 points' <<<"$out")"
rm -rf "$tmp"
finish
