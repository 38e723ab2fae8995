#!/usr/bin/env bash
# grid-pour.sh SOLVER N FILE — writes the grid-pour benchmark scene for
# solver SOLVER (grid or cells) with about N spheres to FILE and prints the
# exact particle count.
#
# The scene is the state the grid solver spends its time in when pouring
# (seed 001 §4.1, Set I: R = 0.05 m, rho = 2700 kg/m^3, k = 50,000 N/m,
# eta = 0.5 N s/m, mu = 0.5, dt = 1e-3 s): a dense bed, 10 layers of
# touching spheres (simple cubic lattice of spacing 2R, velocities jittered
# by 0.05 m/s) in a box open at the top, settling under gravity. The bed
# starts as a lattice rather than from the grid solver's pour: section so
# that the two solvers run the identical scene (bench/README.md).
set -eu
solver=$1 n=$2 file=$3
case "$solver" in grid | cells) ;; *) echo "grid-pour.sh: solver must be grid or cells" >&2; exit 2 ;; esac
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "grid-pour.sh: N must be a positive integer" >&2; exit 2; }
nz=10
side=$(awk -v n="$n" -v nz="$nz" 'BEGIN { s = int(sqrt(n / nz) + 0.5); if (s < 2) s = 2; print s }')
count=$((side * side * nz))
len=$(awk -v s="$side" 'BEGIN { printf "%.4f", s * 0.1 }')
cat >"$file" <<YAML
# grid-pour benchmark: $count Set I spheres (seed 001 Table 1) in a dense
# bed of $side x $side x $nz, solver $solver (written by bench/grid-pour.sh).
simulation:
  dt: 1.0e-3
  steps: 1000
  gravity: [0, 0, -9.8]
  seed: 42
  contact_law: linear
  solver: $solver
materials:
  - {name: set1, density: 2700, stiffness: 50000, damping: 0.5, tangential_stiffness_ratio: 1, friction: 0.5}
particles:
  - generator: lattice
    material: set1
    radius: 0.05
    origin: [0.05, 0.05, 0.05]
    spacing: 0.1
    count: [$side, $side, $nz]
    velocity_jitter: 0.05
walls:
  - {type: box, min: [0, 0, 0], max: [$len, $len, 1.5], open: [zmax], material: set1}
output:
  every: 100000000
  formats: []
YAML
echo "$count"
