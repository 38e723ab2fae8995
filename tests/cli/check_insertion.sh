#!/usr/bin/env bash
# check_insertion.sh — `shapedem check` on a scene filled only by insertion
# (no particle at the start) estimates from the insertion's templates and
# size laws (cli/check_report.c, sd_check_insertions):
#  - the time step, the contact duration and their limit equal those of the
#    same particles placed by a list generator (linear law: they depend on
#    the masses alone): a mix of spheres of radius 1 to 1.5 mm and cubes
#    scaled to an equivalent radius of 0.8 mm (the lightest, so the cubes'
#    scaled copy sets the step);
#  - the particles line counts the 200 inserted, the mass line their mass
#    (100 spheres of the uniform law's mean r^3 and 100 cubes);
#  - the memory and output lines are there and positive;
#  - a composite template scaled to an equivalent radius (a cross3d preset,
#    whose scaled copy brings element templates named COPY.eJ) is probed
#    as the composite alone: its mass line is 100 x the sphere of that
#    radius and its contact line equals that of 100 spheres of the same
#    radius (linear law: the mass alone). Before, the elements were probed
#    as free bodies too: the mass line was the mean of composite and
#    elements (0.40 of the truth for examples/packing-crosses2d.yaml) and
#    the contact an element's.
set -u
bin="$1"
root="$2"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_check_insertion.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1

common='simulation: {dt: 5.0e-6, steps: 1000, contact_law: linear}
materials:
  - {name: glass, density: 2500, stiffness: 1.0e4, restitution: 0.5, friction: 0.5}
walls:
  - {name: box, type: box, min: [0, 0, 0], max: [0.04, 0.04, 0.1], open: [zmax], material: glass}'
# a cube of the volume of a sphere of radius 0.8 mm
edge=$(awk 'BEGIN { printf "%.15g", (4 / 3 * 3.14159265358979 * 0.0008^3)^(1 / 3) }')
cat >insert.yaml <<EOF
$common
shapes:
  - {name: cube, type: box, size: [0.001, 0.001, 0.001]}
insert:
  - name: fill
    region: box
    min: [0.002, 0.002, 0.002]
    max: [0.038, 0.038, 0.06]
    count: 200
    velocity: [0, 0, -1]
    mix:
      - {material: glass, radius: {min: 0.001, max: 0.0015}, fraction: 0.5}
      - {material: glass, shape: cube, radius: 0.0008, fraction: 0.5}
EOF
cat >placed.yaml <<EOF
$common
shapes:
  - {name: cube, type: box, size: [$edge, $edge, $edge]}
particles:
  - generator: list
    material: glass
    spheres:
      - {position: [0.01, 0.01, 0.01], radius: 0.001}
      - {position: [0.02, 0.01, 0.01], radius: 0.0015}
      - {position: [0.03, 0.01, 0.01], shape: cube}
      - {position: [0.01, 0.02, 0.01], shape: cube}
EOF
ins=$("$bin" check insert.yaml --threads 1)
rc_i=$?
placed=$("$bin" check placed.yaml --threads 1)
rc_p=$?
check "check exits 0 on both scenes (got $rc_i, $rc_p)" "$((rc_i == 0 && rc_p == 0))"
for key in "time step  " "contact    " "dt limit  "; do
    a=$(grep "^$key " <<<"$ins")
    b=$(grep "^$key " <<<"$placed")
    echo "     inserted: $a"
    echo "     placed:   $b"
    check "${key%%  *}: the insertion's estimate equals the placed particles'" \
        "$([[ -n $a && $a == "$b" && $a != *inf* ]] && echo 1 || echo 0)"
done
grep "^particles " <<<"$ins"
check "particles: the 200 inserted are counted" \
    "$(grep -c "and 200 particles the insertions add: 200 in all" <<<"$ins")"
m=$(awk '/^mass / {print $2}' <<<"$ins")
# 100 spheres of E[r^3] = (b^4 - a^4) / (4 (b - a)) and 100 cubes of r_eq 0.8 mm
check "mass: $m kg = 100 spheres (uniform 1-1.5 mm) + 100 cubes (r_eq 0.8 mm), 2500 kg/m^3, within 1e-5" \
    "$(awk -v m="$m" 'BEGIN { a = 0.001; b = 0.0015; pi = 3.14159265358979
        e = 2500 * 4 / 3 * pi * (100 * (b^4 - a^4) / (4 * (b - a)) + 100 * 0.0008^3); d = (m - e) / e
        print (d < 1e-5 && d > -1e-5) ? 1 : 0 }')"
bpp=$(sed -n 's/^memory .*(\([0-9.]*\) bytes per particle).*every inserted particle in.*/\1/p' <<<"$ins")
check "memory: per particle with every inserted one in, > 100 bytes (got $bpp)" \
    "$(awk -v b="$bpp" 'BEGIN { print (b > 100) ? 1 : 0 }')"
ob=$(sed -n 's/^output .*(\([0-9]*\) bytes).*/\1/p' <<<"$ins")
check "output: an estimate for the inserted particles (got $ob bytes)" "$([[ -n $ob && $ob -gt 10000 ]] && echo 1 || echo 0)"

for kind in composite spheres; do
    if [[ $kind == composite ]]; then
        shapes='shapes:
  - {name: cross, type: composite, preset: cross3d, diameter: 0.0025, length: 0.008}'
        entry='{material: glass, shape: cross, radius: 0.0015}'
    else
        shapes=''
        entry='{material: glass, radius: 0.0015}'
    fi
    cat >"$kind.yaml" <<EOF
$common
$shapes
insert:
  - {name: fill, region: box, min: [0.002, 0.002, 0.002], max: [0.038, 0.038, 0.09], count: 100, mix: [$entry]}
EOF
done
comp=$("$bin" check composite.yaml --threads 1)
rc_c=$?
sph=$("$bin" check spheres.yaml --threads 1)
rc_s=$?
check "check exits 0 on the composite and sphere insertions (got $rc_c, $rc_s)" "$((rc_c == 0 && rc_s == 0))"
m=$(awk '/^mass / {print $2}' <<<"$comp")
check "mass: $m kg = 100 cross3d of r_eq 1.5 mm, 2500 kg/m^3, within 1e-5" \
    "$(awk -v m="$m" 'BEGIN { e = 100 * 2500 * 4 / 3 * 3.14159265358979 * 0.0015^3; d = (m - e) / e
        print (d < 1e-5 && d > -1e-5) ? 1 : 0 }')"
a=$(grep "^contact  " <<<"$comp")
b=$(grep "^contact  " <<<"$sph")
echo "     composite: $a"
echo "     spheres:   $b"
check "contact: the scaled composite's estimate equals the spheres' of its equivalent radius" \
    "$([[ -n $a && $a == "$b" ]] && echo 1 || echo 0)"

finish
