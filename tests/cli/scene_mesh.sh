#!/usr/bin/env bash
# scene_mesh.sh — mesh walls in a scene (walls: - type: mesh, issue 14):
# the file read relative to the scene, scaled, rotated and placed; the
# motion keys; the frames' walls_*.vtp drawing the mesh's triangles at its
# pose of that frame (translation, rotation, time table); the repairs
# stated as warnings naming the facet; and each bad file or key refused
# with exit 2 and one stderr line naming the scene, its line and the key.
#
# Usage: bash scene_mesh.sh /path/to/shapedem /path/to/repo
set -u
exe=${1:?usage: scene_mesh.sh SHAPEDEM REPO}
repo=${2:?usage: scene_mesh.sh SHAPEDEM REPO}
[[ $exe == */* ]] && exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
repo=$(cd "$repo" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_scene_mesh.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
mkdir -p meshes
pass=0
fail=0
report() { # report 1|0 name detail
    if [[ $1 == 1 ]]; then pass=$((pass + 1)); echo "PASS $2: $3"; else fail=$((fail + 1)); echo "FAIL $2: $3"; fi
}

# scene NAME WALL-KEYS [STEPS]: NAME.yaml with one mesh wall at line 4.
scene() {
    cat >"$1.yaml" <<EOF
simulation: {dt: 1.0e-5, steps: ${3:-200}}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: list, material: m, spheres: [{position: [0, 0, 0.05], radius: 0.005}]}]
walls: [{type: mesh, name: w, material: m, $2}]
output: {every: 100}
EOF
}

# refused NAME KEY TEXT...: `check NAME.yaml` exits 2 with one line holding
# NAME.yaml:4: KEY: and each TEXT.
refused() {
    local name=$1 key=$2 err rc n ok=1
    shift 2
    err=$("$exe" check "$name.yaml" 2>&1 >/dev/null)
    rc=$?
    n=$(printf '%s\n' "$err" | wc -l)
    [[ $rc == 2 && $n == 1 && $err == *"$name.yaml:4: $key: "* ]] || ok=0
    for text in "$@"; do [[ $err == *"$text"* ]] || ok=0; done
    report $ok "$name" "exit $rc, $n line(s): $err"
}

/usr/bin/python3 "$repo/scripts/make_meshes.py" box meshes/box.stl --min -0.05 -0.05 0 --max 0.05 0.05 0.1 \
    --cells 2 >/dev/null
# the VTP reader: NumberOfPoints, NumberOfPolys and the arrays of a walls frame
cat >vtp.py <<'EOF'
import re, struct, sys
def read(path):
    d = open(path, 'rb').read()
    head, data = d.split(b'<AppendedData encoding="raw">', 1)
    data = data[data.index(b'_') + 1:]
    h = head.decode()
    arrs = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)"[^>]*offset="(\d+)"', h):
        fmt = {'Int32': 'i', 'Int64': 'q', 'Float64': 'd'}[m.group(1)]
        off = int(m.group(3))
        n = struct.unpack_from('<Q', data, off)[0] // struct.calcsize(fmt)
        arrs[m.group(2)] = struct.unpack_from('<%d%s' % (n, fmt), data, off + 8)
    return int(re.search(r'NumberOfPoints="(\d+)"', h).group(1)), int(re.search(r'NumberOfPolys="(\d+)"', h).group(1)), arrs
EOF

# ---- a box mesh in mm, moved: 48 triangles in every frame, at the pose of the frame ----
cat >tr.yaml <<'EOF'
simulation: {dt: 1.0e-5, steps: 200}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: list, material: m, spheres: [{position: [0, 0, 0.05], radius: 0.005}]}]
walls:
  - {type: mesh, name: slide, material: m, file: meshes/box_mm.stl, scale: 0.001, position: [1, 0, 0],
     motion: {type: translate, velocity: [0.5, 0, 0], start: 0.0005}}
  - {type: mesh, name: turn, material: m, file: meshes/box.stl, position: [0, 0, 0], torque_point: [0, 0, 0],
     motion: {type: rotate, axis_point: [0, 0, 0], axis: [0, 0, 1], rpm: 7500}}
  - {type: mesh, name: tab, material: m, file: meshes/box.stl, position: [0, 3, 0], orientation: [0.7071067811865476, 0, 0, 0.7071067811865476],
     motion: {type: table, table: meshes/tab.csv}}
  - {type: plane, name: floor, material: m, point: [0, 0, -1], normal: [0, 0, 1]}
output: {every: 100}
EOF
/usr/bin/python3 "$repo/scripts/make_meshes.py" box meshes/box_mm.stl --min -50 -50 0 --max 50 50 100 --cells 2 >/dev/null
printf 't,dx,dy,dz,angle_deg\n# a comment\n0, 0, 0, 0, 0\n0.002, 0.004, 0, 0, 0\n' >meshes/tab.csv
out=$("$exe" run tr.yaml 2>&1)
rc=$?
report $([[ $rc == 0 ]] && echo 1 || echo 0) "run with three moving meshes" "exit $rc: $(printf '%s' "$out" | head -3)"
res=$(/usr/bin/python3 - out/tr <<'EOF'
import math, sys
sys.path.insert(0, '.')
import vtp
d = sys.argv[1]
n0, c0, a0 = vtp.read(d + '/walls_000000.vtp')
n2, c2, a2 = vtp.read(d + '/walls_000002.vtp')
ok = True
msgs = []
# three boxes of 26 welded points and 48 triangles, then the floor's quad (4 points)
ok &= n0 == 3 * 26 + 4 and c0 == 3 * 48 + 1 and n2 == n0 and c2 == c0
ok &= list(a0['offsets'][:3]) == [3, 6, 9] and a0['offsets'][-1] == 9 * 48 + 4
p0, p2 = a0['position'], a2['position']
pt = lambda p, k: p[3 * k:3 * k + 3]
# slide: from x in [0.95, 1.05] (mm file, scale and position) to 0.5 m/s x (0.002 - 0.0005) s = 0.75 mm further
dx = [pt(p2, k)[0] - pt(p0, k)[0] for k in range(26)]
ok &= all(abs(x - 0.00075) < 1e-9 for x in dx) and abs(min(pt(p0, k)[0] for k in range(26)) - 0.95) < 1e-9
msgs.append('slide dx %.3g m (0.00075)' % dx[0])
# turn: 7500 rpm for 0.002 s = 90 degrees about z through the origin
err = 0.0
for k in range(26, 52):
    x0, y0, z0 = pt(p0, k)
    x2, y2, z2 = pt(p2, k)
    err = max(err, abs(x2 + y0), abs(y2 - x0), abs(z2 - z0))
ok &= err < 1e-9
msgs.append('turn: 90 degree error %.2g m' % err)
# tab: rotated 90 degrees about z at load (orientation), then the table's 4 mm in x at 0.002 s
err = 0.0
for k in range(52, 78):
    x0, y0, z0 = pt(p0, k)
    x2, y2, z2 = pt(p2, k)
    err = max(err, abs(x2 - x0 - 0.004), abs(y2 - y0), abs(z2 - z0))
ok &= err < 1e-9 and abs(max(pt(p0, k)[1] for k in range(52, 78)) - 3.05) < 1e-9
msgs.append('table: 4 mm error %.2g m' % err)
ok &= all(w == (0 if i < 48 else 1 if i < 96 else 2 if i < 144 else 3) for i, w in enumerate(a0['wall']))
print(('1 ' if ok else '0 ') + '; '.join(msgs))
EOF
)
report "${res%% *}" "walls_*.vtp of moving meshes" "${res#* }"

# ---- repairs are warnings naming the facet (check and run) ----
cat >meshes/fix.stl <<'EOF'
solid fix
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 1 1 0
 endloop
endfacet
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 1 0
 endloop
endfacet
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 0.5 0 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 0 1
 outer loop
  vertex 1 1 0
  vertex 1 0 0
  vertex 0 0 0
 endloop
endfacet
endsolid fix
EOF
scene fix "file: meshes/fix.stl, position: [-0.5, -0.5, 0]"
out=$("$exe" check fix.yaml 2>&1)
rc=$?
want="warning      wall w: dropped 1 degenerate (zero-area) facet, the first facet 3; dropped 1 duplicated facet, the first facet 4; turned 1 facet wound against their neighbours, the first facet 2"
report $([[ $rc == 0 && $out == *"$want"* ]] && echo 1 || echo 0) "repairs stated by check" \
    "exit $rc: $(printf '%s\n' "$out" | grep 'wall w')"
err=$("$exe" run fix.yaml --steps 2 2>&1 >/dev/null)
report $([[ $err == *"shapedem: warning: wall w: dropped 1 degenerate"* ]] && echo 1 || echo 0) "repairs stated by run" "$err"

# ---- refusals: one per bad file or key ----
scene missing "file: meshes/none.stl"
refused missing "walls[0].file" "cannot open the mesh file" "meshes/none.stl"
: >meshes/empty.stl
scene empty "file: meshes/empty.stl"
refused empty "walls[0].file" "empty.stl' is empty (0 bytes)"
head -c 1000 meshes/box.stl >meshes/cut.stl
scene cut "file: meshes/cut.stl"
refused cut "walls[0].file" "truncated binary STL file: its header counts 48 facets (2484 bytes), the file has 1000 bytes, so facet 19 is cut off"
printf 'solid n\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n' >meshes/nan.stl
scene nan "file: meshes/nan.stl"
refused nan "walls[0].file" "nan.stl line 5: coordinate nan is not finite"
printf 'solid n\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 0 0 0\nendloop\nendfacet\nendsolid\n' >meshes/flat.stl
scene flat "file: meshes/flat.stl"
refused flat "walls[0].file" "no facet is left: all 1 are degenerate (zero area) or duplicates"
# a Moebius strip (OBJ): 6 quads with a half twist
/usr/bin/python3 - <<'EOF'
import math
with open('meshes/moebius.obj', 'w') as f:
    n = 6
    for i in range(n):
        u = 2 * math.pi * i / n
        for s in (-0.3, 0.3):
            f.write('v %.9f %.9f %.9f\n' % ((2 + s * math.cos(u / 2)) * math.cos(u), (2 + s * math.cos(u / 2)) * math.sin(u), s * math.sin(u / 2)))
    for i in range(n):
        a, b = 2 * i + 1, 2 * i + 2
        c, d = (2 * i + 3, 2 * i + 4) if i + 1 < n else (2, 1)
        f.write('f %d %d %d %d\n' % (a, c, d, b))
EOF
scene moebius "file: meshes/moebius.obj"
refused moebius "walls[0].file" "moebius.obj' (facets numbered as triangles in file order)" "cannot be wound consistently" "not orientable"
scene scale "file: meshes/box_mm.stl, scale: 1e308"
refused scale "walls[0].file" "vertex 1 of 'meshes/box_mm.stl' is not finite once scaled by 1e+308"
scene huge "file: meshes/box.stl, scale: 1e200"
refused huge "walls[0].file" "coordinates reach 1e+199 m" "wrong units (check scale:)"
scene random "file: meshes/box.stl, orientation: random"
refused random "walls[0].orientation" "identity or a quaternion"
scene motion "file: meshes/box.stl, motion: {type: spin}"
refused motion "walls[0].motion.type" "fixed, translate, rotate, table" "spin"
scene rpm "file: meshes/box.stl, motion: {type: rotate, axis_point: [0, 0, 0]}"
refused rpm "walls[0].motion.rpm" "missing required key"
scene axis "file: meshes/box.stl, motion: {type: rotate, axis_point: [0, 0, 0], rpm: 10, axis: [0, 0, 0]}"
refused axis "walls[0].motion.axis" "non-zero axis"
scene velkey "file: meshes/box.stl, motion: {type: rotate, axis_point: [0, 0, 0], rpm: 10, velocity: [1, 0, 0]}"
refused velkey "walls[0].motion.velocity" "rotate motion"
scene plainvel "file: meshes/box.stl, velocity: [1, 0, 0]"
refused plainvel "walls[0].velocity" "mesh wall"
printf '0,0,0,0,0\n0.001,1,0,0\n' >meshes/short.csv
scene table "file: meshes/box.stl, motion: {type: table, table: meshes/short.csv}"
refused table "walls[0].motion.table" "short.csv line 2: expected 5 finite decimal numbers t, dx, dy, dz, angle_deg, got '0.001,1,0,0'"
printf '0,0,0,0,0\n0.001,1,0,0,0\n0.001,2,0,0,0\n' >meshes/back.csv
scene back "file: meshes/box.stl, motion: {type: table, table: meshes/back.csv}"
refused back "walls[0].motion.table" "back.csv line 3: t = 0.001 s does not increase"
scene notable "file: meshes/box.stl, motion: {type: table, table: meshes/none.csv}"
refused notable "walls[0].motion.table" "cannot open the motion table" "none.csv"
scene nofile "scale: 2"
refused nofile "walls[0].file" "missing required key"
cat >grid.yaml <<'EOF'
simulation: {dt: 1.0e-5, steps: 200, solver: grid}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: list, material: m, spheres: [{position: [0, 0, 0.05], radius: 0.005}]}]
walls: [{type: mesh, name: w, material: m, file: meshes/box.stl}]
EOF
refused grid "walls[0].type" "cells solver only"

echo "$pass passed, $fail failed"
[[ $fail == 0 ]]
