#!/usr/bin/env bash
# kinds.sh DIR — writes one tiny scene per particle kind into DIR (for
# tests/cli/render.sh): sphere, convex (ellipsoid), polyhedron
# (icosahedron), planar (2D ellipses and a polygon), composite (cross3d).
set -eu
d="$1"
mat="materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}"
out="output: {every: 1, formats: [vtk, shapes]}"
cat >"$d/sphere.yaml" <<YAML
simulation: {dt: 1.0e-6, steps: 1}
$mat
particles:
  - {generator: lattice, material: m, radius: 0.001, origin: [0, 0, 0], spacing: 0.003, count: [3, 2, 2]}
$out
YAML
cat >"$d/convex.yaml" <<YAML
simulation: {dt: 1.0e-6, steps: 1}
$mat
shapes:
  - {name: egg, type: ellipsoid, semi_axes: [0.002, 0.001, 0.0008]}
particles:
  - {generator: lattice, material: m, shape: egg, orientation: random, origin: [0, 0, 0], spacing: 0.005, count: [3, 2, 1]}
$out
YAML
cat >"$d/polyhedron.yaml" <<YAML
simulation: {dt: 1.0e-6, steps: 1}
$mat
shapes:
  - {name: d20, type: polyhedron, preset: icosahedron, size: 0.003}
particles:
  - {generator: lattice, material: m, shape: d20, orientation: random, origin: [0, 0, 0], spacing: 0.005, count: [3, 2, 1]}
$out
YAML
cat >"$d/planar.yaml" <<YAML
simulation: {dimension: 2, dt: 1.0e-6, steps: 1, contact_law: linear, gravity: [0, -9.81, 0]}
materials:
  - {name: m, density: 2700, stiffness: 1.0e7, restitution: 0.5, friction: 0.2}
shapes:
  - {name: oval, type: ellipse, axes: [0.002, 0.001]}
  - {name: tri, type: polygon, points: [[0, 0], [0.003, 0], [0.001, 0.002]]}
particles:
  - {generator: lattice, material: m, shape: oval, orientation: random, origin: [0, 0, 0], spacing: 0.005, count: [3, 2, 1]}
  - {generator: lattice, material: m, shape: tri, orientation: random, origin: [0, 0.012, 0], spacing: 0.005, count: [3, 1, 1]}
$out
YAML
cat >"$d/composite.yaml" <<YAML
simulation: {dt: 1.0e-6, steps: 1}
$mat
shapes:
  - {name: jack, type: composite, preset: cross3d, diameter: 0.001, length: 0.004}
particles:
  - {generator: lattice, material: m, shape: jack, orientation: random, origin: [0, 0, 0], spacing: 0.006, count: [2, 2, 1]}
$out
YAML
