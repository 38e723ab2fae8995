#!/usr/bin/env bash
# csv_packing_reload.sh — a packing written from a frame loads again
# (issue 11, item 5, last bullet), through the CSV generator: rounded boxes
# and cylinders (and a few spheres) settle in a bin; the last frame is
# converted by scripts/frame_to_csv.py (positions, orientations, velocities,
# shape and material names); generator: csv loads it, `check` accepts it and
# a run from it starts with a max_overlap_ratio as small as the settled
# run's. The reloaded run's first frame gives the same CSV back. The script
# refuses a file that is not a particle frame with one line, exit 2.
set -u
bin="$1"
root="$2"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
root=$(cd "$root" && pwd)
py=/usr/bin/python3
conv=$root/scripts/frame_to_csv.py
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_csv_reload.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1

# two materials, so the material column is exercised
head='simulation: {dt: 1.5e-6, duration: 0.1, gravity: [0, 0, -9.81], seed: 7, contact_law: linear}
materials:
  - {name: grain, density: 2500, stiffness: 2.0e4, restitution: 0.3, friction: 0.5}
  - {name: light grain, density: 1200, stiffness: 2.0e4, restitution: 0.3, friction: 0.5}
shapes:
  - {name: cube, type: box, size: [0.002, 0.002, 0.002], rounding: 0.0001}
  - {name: cyl, type: cylinder, diameter: 0.002, length: 0.002, rounding: 0.0001}
walls:
  - {name: bin, type: box, min: [0, 0, 0], max: [0.012, 0.012, 0.03], open: [zmax], material: grain}'
cat >settle.yaml <<EOF
$head
particles:
  - {generator: lattice, material: grain, shape: cube, orientation: random, origin: [0.0022, 0.0022, 0.003], spacing: 0.0038, count: [3, 3, 2]}
  - {generator: lattice, material: light grain, shape: cyl, orientation: random, origin: [0.0022, 0.0022, 0.011], spacing: 0.0038, count: [3, 3, 2]}
  - {generator: lattice, material: grain, radius: 0.0009, origin: [0.0030, 0.0030, 0.019], spacing: 0.0050, count: [2, 2, 1]}
output: {every: 66000, stats_every: 6000}
EOF
# 66000 steps: the last frame and the last stats row are of the same step,
# so that row's max_overlap_ratio is the frame's
"$bin" run settle.yaml -o settle -q --threads 1 --steps 66000
check "the packing settles (exit $?)" "$([[ -f settle/particles_000001.vtu ]] && echo 1 || echo 0)"
contacts=$(tail -1 settle/stats.csv | cut -d, -f8)
check "the grains touch at the end ($contacts contacts)" "$([[ ${contacts:-0} -gt 5 ]] && echo 1 || echo 0)"
col=$(head -1 settle/stats.csv | tr ',' '\n' | grep -n '^max_overlap_ratio$' | cut -d: -f1)
expected=$(tail -1 settle/stats.csv | cut -d, -f"${col:-10}")

$py "$conv" settle/particles_000001.vtu >packing.csv
check "frame_to_csv.py converts the frame (exit $?)" "$([[ -s packing.csv ]] && echo 1 || echo 0)"
ncube=$(grep -c ',cube,' packing.csv)
ncyl=$(grep -c ',cyl,' packing.csv)
nsph=$(grep -c '^[^#x].*,0.00089999999999999998,,' packing.csv)
nlight=$(grep -c ',light grain$' packing.csv)
check "40 rows: 18 cubes, 18 cylinders, 4 spheres (got $ncube, $ncyl, $nsph); 18 of light grain (got $nlight)" \
    "$([[ $ncube == 18 && $ncyl == 18 && $nsph == 4 && $nlight == 18 ]] && echo 1 || echo 0)"

cat >reload.yaml <<EOF
$head
particles:
  - {generator: csv, material: grain, file: packing.csv}
output: {every: 100000, stats_every: 10000}
EOF
out=$("$bin" check reload.yaml --threads 1 2>&1)
rc=$?
check "check loads the CSV packing (exit $rc: $(tail -1 <<<"$out" | head -c 200))" \
    "$([[ $rc == 0 ]] && echo 1 || echo 0)"
n=$(sed -n 's/^particles *\([0-9]*\):.*/\1/p' <<<"$out")
check "check counts 40 particles (got $n)" "$([[ $n == 40 ]] && echo 1 || echo 0)"
ratio=$("$bin" run reload.yaml -o reload --steps 0 -q --threads 1 && tail -1 reload/stats.csv | cut -d, -f"${col:-10}")
echo "max_overlap_ratio at the start of the reloaded run: computed $ratio, expected <= $expected (the settled run's last)"
check "the reloaded packing starts with max_overlap_ratio $ratio <= $expected (+1e-9)" \
    "$(awk -v r="${ratio:-1}" -v e="${expected:-0}" 'BEGIN {print (r != "" && e > 0 && r <= e + 1e-9) ? 1 : 0}')"

# the reloaded run's first frame, converted again: the same packing
$py "$conv" reload/particles_000000.vtu >again.csv
same=$($py - packing.csv again.csv <<'PY'
import sys
def rows(p):
    return [l.rstrip('\n').split(',') for l in open(p) if not l.startswith('#')]
a, b = rows(sys.argv[1]), rows(sys.argv[2])
worst = 0.0
ok = len(a) == len(b) and a[0] == b[0]
for ra, rb in zip(a[1:], b[1:]):
    for ca, cb in zip(ra, rb):
        try:
            worst = max(worst, abs(float(ca) - float(cb)))
        except ValueError:
            ok = ok and ca == cb
print('%d %.3g' % (ok and worst < 1e-15, worst))
PY
)
check "the reloaded run's first frame gives the same rows back (largest difference ${same#* })" \
    "$([[ ${same%% *} == 1 ]] && echo 1 || echo 0)"

# columns in any order; a quaternion of norm 2 is normalised on read; an
# empty shape cell takes the generator's shape, an empty material the
# generator's material
printf 'qx,x,y,z,qw,shape,qy,qz,material,radius\n0,0.003,0.003,0.004,2,cube,0,0,light grain,\n0,0.008,0.003,0.004,0,,0,-3,,\n,0.003,0.008,0.004,,,,,,0.0009\n' >order.csv
cat >order.yaml <<EOF
$head
particles:
  - {generator: csv, material: grain, shape: cyl, orientation: identity, file: order.csv}
EOF
"$bin" run order.yaml -o order --steps 0 -q --threads 1
$py "$conv" order/particles_000000.vtu >order_out.csv
got=$(grep -v '^#' order_out.csv | tail -3 | cut -d, -f4-9,16 | tr '\n' ' ')
check "columns in any order, quaternions normalised, defaults from the generator (got $got)" \
    "$([[ $got == ',cube,1,0,0,0,light grain ,cyl,0,0,0,-1,grain 0.00089999999999999998,,,,,,grain ' ]] && echo 1 || echo 0)"

# not a frame: one line, exit 2
$py "$conv" settle/walls_000001.vtp >/dev/null 2>err.txt
rc=$?
check "a wall file is refused with exit 2 and one line (got $rc, $(wc -l <err.txt) lines: $(head -c 200 err.txt))" \
    "$([[ $rc == 2 && $(wc -l <err.txt) == 1 ]] && grep -q 'walls_000001.vtp: not a shapedem particle frame' err.txt && echo 1 || echo 0)"
$py "$conv" settle.yaml >/dev/null 2>err.txt
rc=$?
check "a scene file is refused with exit 2 and one line (got $rc)" \
    "$([[ $rc == 2 && $(wc -l <err.txt) == 1 ]] && echo 1 || echo 0)"
head -c 3000 settle/particles_000001.vtu >cut.vtu
$py "$conv" cut.vtu >/dev/null 2>err.txt
rc=$?
check "a truncated frame is refused with exit 2 and one line (got $rc: $(head -c 200 err.txt))" \
    "$([[ $rc == 2 && $(wc -l <err.txt) == 1 ]] && echo 1 || echo 0)"

finish csv_packing_reload
