#!/usr/bin/env bash
# example_meshes.sh — the committed meshes of the mesh-wall examples
# (examples/meshes/*.obj) are exactly what scripts/make_meshes.py writes,
# so the script stays the source of every mesh file, and each reads and is
# prepared by `shapedem check` of its example scene (exit 0, no repairs).
# The conical hopper with an outlet and the chute (issue 30), each written
# with its defaults: every facet's normal points into it, `check` loads it
# without repairs, and a sphere too large for the outlet rests in the cone
# and one rests on the chute laid flat (the mesh's z force is its weight).
#
# Usage: bash example_meshes.sh /path/to/shapedem /path/to/repo
set -u
exe=${1:?usage: example_meshes.sh SHAPEDEM REPO}
repo=${2:?usage: example_meshes.sh SHAPEDEM REPO}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_example_meshes.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
report() { # report 1|0 name detail
    if [[ $1 == 1 ]]; then pass=$((pass + 1)); echo "PASS $2: $3"; else fail=$((fail + 1)); echo "FAIL $2: $3"; fi
}
/usr/bin/python3 "$repo/scripts/make_meshes.py" examples "$tmp" >/dev/null
for f in "$tmp"/*.obj; do
    name=$(basename "$f")
    same=$(cmp -s "$f" "$repo/examples/meshes/$name" && echo 1 || echo 0)
    report "$same" "examples/meshes/$name" "the output of scripts/make_meshes.py examples ($(wc -c <"$f") bytes)"
done
for scene in "$repo"/examples/mesh-*.yaml; do
    out=$("$exe" check "$scene" --threads 1 2>&1)
    rc=$?
    ok=$([[ $rc == 0 && $out != *"warning      wall"* ]] && echo 1 || echo 0)
    report "$ok" "check $(basename "$scene")" "exit $rc, $(printf '%s\n' "$out" | grep -c 'warning      wall') wall warnings"
done
/usr/bin/python3 "$repo/scripts/make_meshes.py" cone "$tmp/cone.stl" >/dev/null
/usr/bin/python3 "$repo/scripts/make_meshes.py" chute "$tmp/chute.stl" >/dev/null
/usr/bin/python3 "$repo/scripts/make_meshes.py" chute "$tmp/flat.stl" --angle 0 >/dev/null
# the normals: into the cone (towards the axis), up off the chute's floor,
# towards its centre line on the sides (the tilt keeps y)
# the benchmark's hopper (bench/scenes/meshes/cone-hopper.obj) is the cone's default
/usr/bin/python3 "$repo/scripts/make_meshes.py" cone "$tmp/cone-hopper.obj" >/dev/null
report "$(cmp -s "$tmp/cone-hopper.obj" "$repo/bench/scenes/meshes/cone-hopper.obj" && echo 1 || echo 0)" \
    "bench/scenes/meshes/cone-hopper.obj" "the output of scripts/make_meshes.py cone"
normals=$(/usr/bin/python3 - "$tmp/cone.stl" "$tmp/chute.stl" <<'PY'
import math, struct, sys
def facets(p):
    d = open(p, "rb").read()
    n = struct.unpack_from("<I", d, 80)[0]
    return [struct.unpack_from("<12f", d, 84 + 50 * k)[3:] for k in range(n)]
def normal(f):
    a, b, c = f[0:3], f[3:6], f[6:9]
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    return n, [(a[i] + b[i] + c[i]) / 3 for i in range(3)]
cone = facets(sys.argv[1])
bad = 0
for f in cone:
    n, m = normal(f)
    bad += n[0] * m[0] + n[1] * m[1] >= 0
chute = facets(sys.argv[2])
a = math.radians(30.0)
up = (math.sin(a), 0.0, math.cos(a))  # the floor's normal after the tilt
for f in chute:
    n, m = normal(f)
    if abs(m[1]) < 0.0249:  # the floor: its centroids lie strictly inside |y| < w/2
        bad += sum(n[i] * up[i] for i in range(3)) <= 0
    else:
        bad += n[1] * m[1] >= 0
print(len(cone), len(chute), bad)
PY
)
read -r ncone nchute bad <<<"$normals"
report "$([[ $ncone == 384 && $nchute == 60 && $bad == 0 ]] && echo 1 || echo 0)" "make_meshes.py cone, chute" \
    "$ncone and $nchute facets (expected 384 and 60), $bad facets facing away from the particles"
# a sphere of radius 12 mm rests on the 9 mm outlet's cone, one of 1.5 mm
# on the flat chute's floor: the last stats row's mesh force along z is
# -m g within 1 % (a mesh facing the wrong way lets it fall through)
for m in cone flat; do
    r=0.012 z=0.03 x=0
    [[ $m == flat ]] && r=0.0015 z=0.002 x=0.1
    cat >"$tmp/$m.yaml" <<EOF
simulation: {dt: 2.0e-5, duration: 0.3, gravity: [0, 0, -9.81]}
materials:
  - {name: grain, density: 2500, youngs_modulus: 5.0e6, poisson_ratio: 0.3, restitution: 0.3, friction: 0.5}
particles:
  - {generator: list, material: grain, spheres: [{position: [$x, 0, $z], radius: $r}]}
walls:
  - {type: mesh, name: $m, file: $m.stl, material: grain}
output: {every: 100000, stats_every: 500}
EOF
    out=$("$exe" check "$tmp/$m.yaml" --threads 1 2>&1)
    rc=$?
    report "$([[ $rc == 0 && $out != *"warning      wall"* ]] && echo 1 || echo 0)" "check $m mesh" "exit $rc"
    "$exe" run "$tmp/$m.yaml" -o "$tmp/out-$m" --threads 1 --quiet >/dev/null 2>&1
    res=$(awk -F, -v r="$r" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i ~ /_fz$/) c = i }
        END { m = 2500 * 4 / 3 * 3.14159265358979 * r * r * r; w = -m * 9.81
              e = ($c - w) / w; printf "%.6g %.6g %d", $c, w, (e < 0.01 && e > -0.01) }' "$tmp/out-$m/stats.csv" 2>/dev/null)
    read -r fz w ok <<<"$res"
    report "${ok:-0}" "a sphere rests on the $m mesh" "mesh z force ${fz:-none} N, expected $w N (1 %)"
done
echo "$pass passed, $fail failed"
[[ $fail == 0 ]]
