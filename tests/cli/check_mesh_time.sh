#!/usr/bin/env bash
# check_mesh_time.sh — `shapedem check` times the mesh walls' part of a run
# (issue 31: the estimate named mesh-wall contacts as not timed, and was 2x
# low for a filled hopper): 1,000 spheres of r = 1 mm in a 20 mm box whose
# floor is a 2-facet mesh of 0.02 x 0.02 m:
#  - a "mesh walls" line: 100 particles against the facets (their 0.0004
#    m^2 over (2 r)^2), the seconds a mesh adds to a particle-step and the
#    spheres timed resting on the facets against the same spheres alone;
#    the run time line says they were timed apart;
#  - the "untimed" line no longer lists mesh-wall contacts;
#  - the same scene with a plane floor has no such line.
# No time is asserted. The binary of ade592f has no mesh walls line.
set -u
bin="$1"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
printf 'v 0 0 0\nv 0.02 0 0\nv 0.02 0.02 0\nv 0 0.02 0\nf 1 2 3\nf 1 3 4\n' >floor.obj
for floor in mesh plane; do
    if [[ $floor == mesh ]]; then
        wall='{name: floor, type: mesh, file: floor.obj, material: g}'
    else
        wall='{name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: g}'
    fi
    cat >"$floor.yaml" <<EOF
simulation: {dt: 2.0e-6, steps: 100000, seed: 3}
materials: [{name: g, density: 2500, youngs_modulus: 1.0e7}]
walls:
  - $wall
  - {name: box, type: box, min: [0, 0, -0.001], max: [0.02, 0.02, 0.05], open: [zmin, zmax], material: g}
particles: [{generator: lattice, material: g, radius: 0.001, origin: [0.001, 0.001, 0.0011], spacing: 0.002, count: [10, 10, 10]}]
EOF
done
"$bin" check mesh.yaml --threads 1 >mesh.out 2>&1
rc=$?
grep -E "^(run time|mesh walls|untimed)" mesh.out
check "check of the mesh-floored box: exit 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
check "a mesh walls line: 100 particles against the facets of 1 mesh wall (0.0004 m^2), timed on resting spheres" \
    "$(grep -Eq "^mesh walls .* of it: 100 particles against the facets of 1 mesh wall \(their 0.0004 m\^2 .*, [0-9.e+-]+ s a particle-step more, timed on [0-9]+ spheres resting on the facets against the same spheres alone for [0-9]+ steps$" mesh.out && echo 1 || echo 0)"
check "the run time line says the particles against mesh walls were timed apart" \
    "$(grep -q "^run time .*the particles against mesh walls timed apart" mesh.out && echo 1 || echo 0)"
check "no 'not timed ... mesh-wall contacts'" "$(grep -q "mesh-wall contacts" mesh.out && echo 0 || echo 1)"
"$bin" check plane.yaml --threads 1 >plane.out 2>&1
rc=$?
check "the plane-floored box: exit 0 [rc $rc], no mesh walls line" \
    "$([[ $rc == 0 ]] && ! grep -q "^mesh walls" plane.out && echo 1 || echo 0)"
finish
