#!/usr/bin/env bash
# check_packing_reload.sh — the start-overlap check measures the true
# shapes, not bounding spheres (issue 11, item 5): a packing of rounded
# boxes and cylinders, let fall into a bin until its grains touch, is
# written from its last frame (positions and orientations, read from the
# VTU) to a list generator and loaded again by `check`, which accepts it
# (its bounding spheres overlap by tens of per cent, which the old check
# refused). A real overlap is still refused, naming both particles and the
# depth. Two sharp cubes under the volume law (the exact polyhedron
# overlap): face to face, their bounding spheres overlapping, accepted; 0.5 %
# into each other accepted; 5 % refused.
set -u
bin="$1"
root="$2"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
root=$(cd "$root" && pwd)
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_check_reload.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1

head='simulation: {dt: 1.5e-6, duration: 0.1, gravity: [0, 0, -9.81], seed: 7, contact_law: linear}
materials:
  - {name: grain, density: 2500, stiffness: 2.0e4, restitution: 0.3, friction: 0.5}
shapes:
  - {name: cube, type: box, size: [0.002, 0.002, 0.002], rounding: 0.0001}
  - {name: cyl, type: cylinder, diameter: 0.002, length: 0.002, rounding: 0.0001}
walls:
  - {name: bin, type: box, min: [0, 0, 0], max: [0.012, 0.012, 0.03], open: [zmax], material: grain}'
cat >settle.yaml <<EOF
$head
particles:
  - {generator: lattice, material: grain, shape: cube, orientation: random, origin: [0.0022, 0.0022, 0.003], spacing: 0.0038, count: [3, 3, 2]}
  - {generator: lattice, material: grain, shape: cyl, orientation: random, origin: [0.0022, 0.0022, 0.011], spacing: 0.0038, count: [3, 3, 2]}
output: {every: 100000, stats_every: 10000}
EOF
"$bin" run settle.yaml -o settle -q --threads 1
check "the packing settles (exit $?)" "$([[ -f settle/particles_000001.vtu ]] && echo 1 || echo 0)"
contacts=$(tail -1 settle/stats.csv | cut -d, -f8)
check "the grains touch at the end ($contacts contacts)" "$([[ ${contacts:-0} -gt 5 ]] && echo 1 || echo 0)"

# the last frame's ids, positions and orientations, as a list generator
# (ids 0-17 are the cubes, 18-35 the cylinders: generation order)
python3 - settle/particles_000001.vtu "$head" >reload.yaml <<'PY'
import re, struct, sys
data = open(sys.argv[1], 'rb').read()
cut = data.index(b'<AppendedData encoding="raw">')
start = data.index(b'_', cut) + 1
arrays = {}
for m in re.finditer(rb'<DataArray type="(\w+)" Name="(\w+)"(?: NumberOfComponents="(\d+)")? format="appended" offset="(\d+)"', data[:cut]):
    kind, name, comps, off = m.group(1).decode(), m.group(2).decode(), int(m.group(3) or 1), int(m.group(4))
    size = struct.unpack_from('<Q', data, start + off)[0]
    fmt = {'Float64': 'd', 'UInt64': 'Q', 'Int64': 'q', 'Int32': 'i', 'UInt8': 'B'}[kind]
    vals = struct.unpack_from('<%d%s' % (size // struct.calcsize(fmt), fmt), data, start + off + 8)
    arrays[name] = [vals[i:i + comps] for i in range(0, len(vals), comps)]
print(sys.argv[2])
print('particles:\n  - generator: list\n    material: grain\n    spheres:')
for pid, x, q in sorted(zip(arrays['id'], arrays['position'], arrays['orientation'])):
    print('      - {position: [%.17g, %.17g, %.17g], orientation: [%.17g, %.17g, %.17g, %.17g], shape: %s}'
          % (x + q + ('cube' if pid[0] < 18 else 'cyl',)))
PY
n=$(grep -c 'shape: c' reload.yaml)
check "36 grains written from the frame (got $n)" "$([[ $n == 36 ]] && echo 1 || echo 0)"
out=$("$bin" check reload.yaml --threads 1 2>&1)
rc=$?
check "check loads the settled packing again (exit $rc: $(tail -1 <<<"$out" | head -c 200))" \
    "$([[ $rc == 0 ]] && echo 1 || echo 0)"
ratio=$("$bin" run reload.yaml -o reload --steps 0 -q --threads 1 && tail -1 reload/stats.csv | cut -d, -f10)
check "the reloaded packing's largest overlap is a contact's (max_overlap_ratio $ratio < 0.01)" \
    "$(awk -v r="${ratio:-1}" 'BEGIN {print (r < 0.01) ? 1 : 0}')"

# a real overlap: grain 1 moved onto grain 0 (0.4 mm apart)
python3 - reload.yaml >overlap.yaml <<'PY'
import re, sys
lines = open(sys.argv[1]).read().split('\n')
rows = [i for i, l in enumerate(lines) if l.startswith('      - {position')]
p0 = [float(v) for v in re.search(r'position: \[([^\]]*)\]', lines[rows[0]]).group(1).split(',')]
lines[rows[1]] = re.sub(r'position: \[[^\]]*\]', 'position: [%.17g, %.17g, %.17g]' % (p0[0] + 4e-4, p0[1], p0[2]), lines[rows[1]])
print('\n'.join(lines))
PY
line=$(grep -n 'position' overlap.yaml | sed -n 2p | cut -d: -f1)
"$bin" check overlap.yaml >/dev/null 2>err.txt
rc=$?
check "a real overlap is refused with exit 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
check "the message names both grains, the line and the depth ($(head -c 300 err.txt))" \
    "$(grep -q "overlap.yaml:$line: particles\[0\].spheres\[1\]: particles overlap at the start by [0-9.e-]* m .*body 1 of shape .*body 0 of shape" err.txt && echo 1 || echo 0)"

# sharp cubes (edge 2 mm, by their vertices, so the principal frame is the
# given one) under the volume law: the exact overlap
cubes() { # cubes X2: the second cube's centre at x = X2 (the first at 0)
    cat <<EOF
simulation: {dt: 1.0e-8, steps: 10, gravity: [0, 0, 0], contact_law: volume}
materials: [{name: stone, density: 2600, youngs_modulus: 2.0e5, poisson_ratio: 0.3}]
shapes:
  - {name: cube, type: polyhedron, vertices: [[-0.001, -0.001, -0.001], [0.001, -0.001, -0.001], [-0.001, 0.001, -0.001],
     [0.001, 0.001, -0.001], [-0.001, -0.001, 0.001], [0.001, -0.001, 0.001], [-0.001, 0.001, 0.001], [0.001, 0.001, 0.001]]}
particles:
  - generator: list
    material: stone
    shape: cube
    orientation: identity
    spheres:
      - {position: [0, 0, 0.01]}
      - {position: [$1, 0, 0.01]}
EOF
}
cubes 0.002001 >face.yaml
"$bin" check face.yaml >/dev/null 2>&1
check "sharp cubes face to face, 1 um apart (bounding spheres 73 % into each other): accepted" \
    "$([[ $? == 0 ]] && echo 1 || echo 0)"
cubes 0.001995 >touch.yaml
"$bin" check touch.yaml >/dev/null 2>&1
check "sharp cubes 5 um (0.5 % of the half edge) into each other: accepted" "$([[ $? == 0 ]] && echo 1 || echo 0)"
cubes 0.00195 >deep.yaml
"$bin" check deep.yaml >/dev/null 2>err.txt
rc=$?
check "sharp cubes 50 um (5 %) into each other: refused with exit 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
depth=$(sed -n 's/.*overlap at the start by \([0-9.e-]*\) m.*/\1/p' err.txt)
check "the depth is the true one: $depth m against 5e-05 m within 1e-9" \
    "$(awk -v d="${depth:-0}" 'BEGIN {print (d > 5e-5 - 1e-9 && d < 5e-5 + 1e-9) ? 1 : 0}')"

finish check_packing_reload
