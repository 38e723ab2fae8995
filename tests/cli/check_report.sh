#!/usr/bin/env bash
# check_report.sh — what `shapedem check` estimates (issue 11, item 3):
#  - the spheres a pour will insert are counted (hopper-grid: 0 at the start);
#  - the total mass of a known scene, to the printed round-off;
#  - the output size against the bytes a short run actually writes;
#  - the run-time line from the timed trial is there and positive;
#  - a scene written in millimetres warns about radius, dt and gravity, and
#    no shipped example gets a unit warning;
#  - shapes are counted as the user wrote them: one template inserted in 4
#    size classes is "1 shape in 4 sizes", not 5 shapes (issue 31);
#  - the run time says what its trial did not time (the particles inserted
#    later, a settled bed's contacts; mesh walls timed apart), and its 10-minute warning
#    comes exactly when the printed estimate is above 10m00s (issue 31).
# No timing is asserted: only that the estimate is there and positive.
set -u
bin="$1"
root="$2"
# Absolute paths: the CLI runs in a scratch directory.
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
root=$(cd "$root" && pwd)
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_check_report.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1

# 1. the pour: hopper-grid pours 0.6 x floor x 0.36 m / sphere volume spheres
out=$("$bin" check "$root/examples/hopper-grid.yaml" --threads 1)
n=$(awk '/^pour / {print $2}' <<<"$out")
check "hopper-grid: particles line counts the $n poured spheres" \
    "$([[ -n $n && $(grep -c "and $n spheres the pour inserts: $n in all" <<<"$out") == 1 ]] && echo 1 || echo 0)"
bpp=$(sed -n 's/^memory .*(\([0-9.]*\) bytes per particle).*/\1/p' <<<"$out")
check "hopper-grid: bytes per particle > 100 with the poured spheres in (got $bpp)" \
    "$(awk -v b="$bpp" 'BEGIN {print (b > 100) ? 1 : 0}')"
m=$(awk '/^mass / {print $2}' <<<"$out")
# expected: n x 1592 kg/m^3 x 4/3 pi (0.003 m)^3
check "hopper-grid: mass $m kg = $n x 1592 x 4/3 pi 0.003^3 within 1e-5" \
    "$(awk -v m="$m" -v n="$n" 'BEGIN {e = n * 1592 * 4 / 3 * 3.14159265358979 * 0.003^3; d = (m - e) / e; print (d < 1e-5 && d > -1e-5) ? 1 : 0}')"

# 2. total mass of a known scene: a 4 x 4 x 3 lattice of glass (r 1 mm,
# 2500 kg/m^3) and three steel spheres (r 1.5 mm, 7800 kg/m^3)
cat >mass.yaml <<'EOF'
simulation: {dt: 1.0e-6, steps: 40, gravity: [0, 0, -9.81]}
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7}
  - {name: steel, density: 7800, youngs_modulus: 1.0e7}
walls:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}
particles:
  - {generator: lattice, material: glass, radius: 0.001, origin: [0.001, 0.001, 0.001], spacing: 0.0025, count: [4, 4, 3]}
  - generator: list
    material: steel
    spheres:
      - {position: [0.02, 0, 0.002], radius: 0.0015}
      - {position: [0.025, 0, 0.002], radius: 0.0015}
      - {position: [0.03, 0, 0.002], radius: 0.0015}
output: {every: 10, stats_every: 5}
EOF
out=$("$bin" check mass.yaml --threads 1)
m=$(awk '/^mass / {print $2}' <<<"$out")
check "known scene: mass $m kg = 48 x 2500 x 4/3 pi 1e-9 + 3 x 7800 x 4/3 pi 3.375e-9 within 1e-5" \
    "$(awk -v m="$m" 'BEGIN {p = 4 / 3 * 3.14159265358979; e = 48 * 2500 * p * 1e-9 + 3 * 7800 * p * 3.375e-9; d = (m - e) / e; print (d < 1e-5 && d > -1e-5) ? 1 : 0}')"

# 3. run time: present and positive
t=$(sed -n 's/^run time .*in \([0-9.e+-]*\) s, scaled.*/\1/p' <<<"$out")
check "run-time line present, trial time positive (got '$t' s)" \
    "$([[ -n $t ]] && awk -v t="$t" 'BEGIN {print (t > 0) ? 1 : 0}' || echo 0)"
check "run-time line says it is rough" "$(grep -c '^run time .*about .*rough' <<<"$out")"

# 4. output size against a short run of each scene (frames, stats rows,
# biaxial.csv, frames.pvd, summary.txt and the marker). Stats rows and pvd
# lines are sized from the start; their numbers change length by a few
# digits over a run: 3 % tolerance.
for scene in mass.yaml "$root/examples/settle-spheres.yaml" "$root/examples/biaxial-2d.yaml" \
    "$root/examples/polyhedra-pour.yaml"; do
    name=$(basename "$scene")
    est=$("$bin" check "$scene" --steps 400 --threads 1 | sed -n 's/^output .*(\([0-9]*\) bytes).*/\1/p')
    rm -rf run
    "$bin" run "$scene" --steps 400 --threads 1 -o run -q
    got=$(cat run/* run/.shapedem-output | wc -c)
    check "$name: output estimate $est bytes vs $got written by a 400-step run, within 3 %" \
        "$(awk -v e="$est" -v g="$got" 'BEGIN {d = (e - g) / g; print (e > 0 && d < 0.03 && d > -0.03) ? 1 : 0}')"
done

# 5. units: a scene written in millimetres (radius 1, box 12 x 12 x 50,
# gravity 9810): 1 m glass balls of 10 t each
cat >mm.yaml <<'EOF'
simulation: {dt: 1.0e-6, steps: 20, gravity: [0, 0, -9810]}
materials:
  - {name: glass, density: 2500, youngs_modulus: 6.3e10, poisson_ratio: 0.2, restitution: 0.9, friction: 0.3}
walls:
  - {name: box, type: box, min: [0, 0, 0], max: [12, 12, 50], open: [zmax], material: glass}
particles:
  - {generator: lattice, material: glass, radius: 1, origin: [2, 2, 2], spacing: 2.5, count: [4, 4, 4]}
EOF
out=$("$bin" check mm.yaml --threads 1)
check "mm scene: radius warning" "$(grep -c '^warning .*radius up to 1 m .*SI' <<<"$out")"
check "mm scene: dt warning" "$(grep -c '^warning .*dt = 1e-06 s is [0-9]* times below the shortest contact' <<<"$out")"
check "mm scene: gravity warning" "$(grep -c '^warning .*gravity 9810 m/s^2 .*mm/s^2' <<<"$out")"
for scene in "$root"/examples/*.yaml; do
    out=$("$bin" check "$scene" --threads 1 --steps 10)
    rc=$?
    check "$(basename "$scene"): check exits 0 with no unit warning" \
        "$([[ $rc == 0 && $(grep -c '^warning .*SI' <<<"$out") == 0 ]] && echo 1 || echo 0)"
done

# 6. shapes as written: one template, 4 size classes (5 templates in the world)
cat >sizes.yaml <<'EOF'
simulation: {dt: 1.0e-6, steps: 100000, gravity: [0, 0, -9.81]}
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7}
shapes:
  - {name: brick, type: box, size: [0.002, 0.003, 0.004]}
walls:
  - {name: tray, type: box, min: [0, 0, 0], max: [0.03, 0.03, 0.03], open: [zmax], material: glass}
insert:
  - name: fill
    region: box
    min: [0.002, 0.002, 0.005]
    max: [0.028, 0.028, 0.028]
    count: 20
    mix: [{material: glass, shape: brick, distribution: uniform, radius: {min: 0.0012, max: 0.0016}, size_classes: 4}]
EOF
out=$("$bin" check sizes.yaml --threads 1)
echo "     $(grep '^particles' <<<"$out" | cut -c1-90)"
check "one template in 4 size classes: 'bodies of 1 shape in 4 sizes'" \
    "$(grep -c '^particles .* bodies of 1 shape in 4 sizes, and 20 particles the insertions add' <<<"$out")"
echo "     $(grep '^untimed' <<<"$out")"
check "the trial (200 of 100000 steps) says the settled bed's contacts were not timed" \
    "$(grep -c '^untimed .*first [0-9]* steps .*not timed:.* the contacts of a settled bed: the run may take longer' <<<"$out")"

# 7. a mesh scene: the mesh-wall contacts are timed apart (cli.check_mesh_time), not named as untimed
out=$("$bin" check "$root/examples/mesh-hopper.yaml" --threads 1)
echo "     $(grep -E '^(untimed|mesh walls)' <<<"$out")"
check "mesh-hopper: a mesh walls line times the particles against its facets, the untimed line does not name them" \
    "$(grep -q '^mesh walls .* particles against the facets of 1 mesh wall' <<<"$out" &&
        ! grep -q 'mesh-wall contacts' <<<"$out" && echo 1 || echo 0)"

# 8. the 10-minute warning agrees with the printed estimate (whatever the
# load makes it): warned exactly when the estimate shows more than 10m00s
for scene in sizes.yaml "$root/examples/mesh-hopper.yaml" "$root/examples/mesh-drum.yaml"; do
    out=$("$bin" check "$scene" --threads 1)
    shown=$(sed -n 's/^run time *\(at most \)*about \([^ ]*\) on.*/\2/p' <<<"$out")
    secs=$(awk -v d="$shown" 'BEGIN { s = 0; if (d ~ /h/) { split(d, a, "h"); s = 3600 * a[1] + 60 * a[2] }
        else if (d ~ /m/) { split(d, a, "m"); s = 60 * a[1] + a[2] } else s = d + 0; print s }')
    warned=$(grep -c '^warning .*more than 10 minutes' <<<"$out")
    check "$(basename "$scene"): estimate $shown ($secs s), 10-minute warning $warned: warned iff above 600 s" \
        "$([[ -n $shown && (($secs -gt 600 && $warned == 1) || ($secs -le 600 && $warned == 0)) ]] && echo 1 || echo 0)"
done

finish check_report
