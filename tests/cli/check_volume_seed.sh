#!/usr/bin/env bash
# check_volume_seed.sh — `shapedem check` on seed 000's Table 2 parameters
# (a 25 mm cuboid, rho 1500, E = 1 MPa, nu 0.1, mu 0.8, e 0.1, dt = 1e-5 s)
# resting on a plane under the volume law (docs/physics.md, "Volume laws":
# time step and the face regularisation):
#  - with materials[].volume_face_omega_dt: 0.5 the scene is accepted, the
#    recommended step is within a factor 10 of the table's dt (it was 1e-11 s
#    at E = 5e7 Pa) and check names the limit that set it (the tangential
#    spring), the regularised range and the resting-face limit;
#  - without it check names the resting-face limit as the one that set the
#    recommended step and warns, naming the key.
set -u
bin="$1"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene() { # $1: extra material line
    cat <<YAML
simulation:
  dt: 1.0e-5
  duration: 0.01
  gravity: [0, 0, -9.81]
  contact_law: volume
materials:
  - name: grain
    density: 1500
    youngs_modulus: 1.0e6
    poisson_ratio: 0.1
    restitution: 0.1
    friction: 0.8
$1
shapes:
  - name: cuboid
    type: polyhedron
    scale: 0.025
    vertices: [[-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [-0.5, 0.5, -0.5], [0.5, 0.5, -0.5],
               [-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [-0.5, 0.5, 0.5], [0.5, 0.5, 0.5]]
particles:
  - generator: lattice
    material: grain
    shape: cuboid
    count: [1, 1, 1]
    spacing: 0.05
    origin: [0, 0, 0.0126]
walls:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: grain}
YAML
}
scene "    volume_face_omega_dt: 0.5" > "$tmp/reg.yaml"
scene "" > "$tmp/seed.yaml"
out=$("$bin" check "$tmp/reg.yaml" 2>&1)
rc=$?
echo "$out" | grep -E "time step|dt limit|volume law|resting face|face landing"
check "regularised: check exits 0" "$((rc == 0))"
rec=$(echo "$out" | sed -n 's/^time step *\([0-9.e+-]*\) s recommended.*/\1/p')
ratio_ok=$(awk -v r="$rec" 'BEGIN { x = r / 1e-5; print (x > 0.1 && x < 10) ? 1 : 0 }')
echo "recommended $rec s against the table's 1e-5 s (within a factor 10)"
check "regularised: recommended step within 10x of the table's dt" "$ratio_ok"
check "regularised: names the tangential spring" \
    "$([[ "$out" == *"set by: volume law: tangential spring"* ]] && echo 1 || echo 0)"
check "regularised: prints the regularised range" "$([[ "$out" == *"regularised below V0"* ]] && echo 1 || echo 0)"
check "regularised: names the resting-face limit" "$([[ "$out" == *"resting-face limit"* ]] && echo 1 || echo 0)"
check "regularised: no resting-face warning" "$([[ "$out" != *"above the resting-face limit"* ]] && echo 1 || echo 0)"
out=$("$bin" check "$tmp/seed.yaml" 2>&1)
echo "$out" | grep -E "time step|dt limit|resting"
check "seed's law: the resting-face limit set the step" \
    "$([[ "$out" == *"set by: volume law: the resting-face limit"* ]] && echo 1 || echo 0)"
check "seed's law: warns and names the key" \
    "$([[ "$out" == *"above the resting-face limit"*"volume_face_omega_dt"* ]] && echo 1 || echo 0)"
finish
