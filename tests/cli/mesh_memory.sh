#!/usr/bin/env bash
# mesh_memory.sh — what a large triangle soup costs (issue 31: a 10^6-facet
# soup of random 5 mm triangles took more than 7.8 GB in `check` before
# the facet bins were bounded). Measured with a 10^6-facet soup in a 0.5 m
# cube (docs/mesh-walls.md): `check` 541 MB peak RSS, a 20-step run 528 MB
# (586 B a facet of address space, 550 B of RSS, 486 B allocated by the
# library). Here a 10^5-facet soup of the same triangles, with 1 thread:
#  - `check` and a 20-step run (50 spheres above the soup) pass in an
#    address space of 60 MB (the program, its libraries and a 1-facet mesh
#    take 33 MB) plus 1,000 bytes a facet: 160 MB;
#  - the same with a 1-facet mesh pass in 60 MB;
#  - the 10^5-facet run fails in 60 MB (the limit bites: the soup needs
#    its 60 MB or so).
set -u
bin="$1"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
python3 - soup.stl 100000 <<'EOF'
import random, struct, sys
n = int(sys.argv[2]); random.seed(1)
pack = struct.Struct('<12fH').pack
with open(sys.argv[1], 'wb') as f:
    f.write(b'soup'.ljust(80, b' ') + struct.pack('<I', n))
    for _ in range(n):
        c = [random.random() * 0.5 for _ in range(3)]
        v = c + [c[k % 3] + random.uniform(-0.005, 0.005) for k in range(6)]
        f.write(pack(0, 0, 0, *v, 0))
EOF
printf 'solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.01 0 0\nvertex 0 0.01 0\nendloop\nendfacet\nendsolid s\n' \
    >one.stl
for m in soup one; do
    cat >"$m.yaml" <<EOF
simulation: {dt: 2.0e-6, steps: 20, seed: 3}
materials: [{name: g, density: 2500, youngs_modulus: 1.0e7}]
walls:
  - {name: soup, type: mesh, file: $m.stl, material: g}
  - {name: box, type: box, min: [0, 0, 0], max: [0.5, 0.5, 0.6], material: g}
particles: [{generator: lattice, material: g, radius: 0.001, origin: [0.1, 0.1, 0.54], spacing: 0.05, count: [5, 5, 2]}]
output: {every: 20, formats: [csv]}
EOF
done
base=60000             # kB of address space: the program, its libraries, a small world
limit=$((base + 100000)) # and 1,000 bytes a facet for 10^5 facets
limited() { # limited KB COMMAND...: the command's exit status in KB kB of address space
    (ulimit -v "$1"; shift; "$@" >/dev/null 2>"$tmp/err")
}
limited $limit "$bin" check soup.yaml --threads 1
rc=$?
check "check of the 10^5-facet soup in $limit kB: exit 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
[[ $rc == 0 ]] || cat "$tmp/err"
limited $limit "$bin" run soup.yaml -o soup --threads 1 --quiet
rc=$?
check "20 steps with the 10^5-facet soup in $limit kB: exit 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
[[ $rc == 0 ]] || cat "$tmp/err"
limited $base "$bin" check one.yaml --threads 1 && limited $base "$bin" run one.yaml -o one --threads 1 --quiet
rc=$?
check "check and run with a 1-facet mesh in $base kB: exit 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
limited $base "$bin" run soup.yaml -o soup2 --threads 1 --quiet
rc=$?
check "the 10^5-facet run in $base kB fails (got $rc): the limit bites" "$([[ $rc != 0 ]] && echo 1 || echo 0)"
finish
