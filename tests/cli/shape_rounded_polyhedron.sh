#!/usr/bin/env bash
# shape_rounded_polyhedron.sh — a polyhedron typed with rounded coordinates
# and a margin is accepted (the probe's F4, issue 11 §2): the icosahedron of
# examples/mixed-shapes.yaml (phi to 6 decimals) at margins 0 to 0.1 gives
# the hull of an icosahedron in `shape info` (12 vertices, 20 faces), and
# both shipped scenes that use it pass `check`. tests/unit/shape_weld.c
# sweeps more solids, orientations and round-off levels.
set -u
bin="$1"
root="$2"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
root=$(cd "$root" && pwd)
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_shape_rounded.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

for m in 0 0.01 0.05 0.08 0.1; do
    cat >"$tmp/d20.yaml" <<EOF
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
shapes:
  - {name: d20, type: polyhedron, scale: 0.00063, margin: $m, vertices: [[0, 1, 1.618034], [0, 1, -1.618034], [0, -1, 1.618034], [0, -1, -1.618034], [1, 1.618034, 0], [1, -1.618034, 0], [-1, 1.618034, 0], [-1, -1.618034, 0], [1.618034, 0, 1], [1.618034, 0, -1], [-1.618034, 0, 1], [-1.618034, 0, -1]]}
particles: [{generator: list, material: m, spheres: [{position: [0, 0, 0], shape: d20}]}]
EOF
    out=$("$bin" shape info "$tmp/d20.yaml" 2>&1)
    rc=$?
    nv=$(awk '/^hull vertices/ {print $3}' <<<"$out")
    nf=$(awk '/^welded faces/ {print $3}' <<<"$out")
    check "icosahedron, phi to 6 decimals, margin $m: exit 0 (got $rc), 12 hull vertices (got $nv), 20 faces (got $nf)" \
        "$([[ $rc == 0 && $nv == 12 && $nf == 20 ]] && echo 1 || echo 0)"
    out=$(cd "$tmp" && "$bin" check d20.yaml 2>&1)
    rc=$?
    check "icosahedron, margin $m: check exit 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
done

for scene in examples/mixed-shapes.yaml bench/scenes/convex-settle.yaml; do
    out=$(cd "$tmp" && "$bin" check "$root/$scene" 2>&1)
    rc=$?
    check "$scene: check exit 0 (got $rc)" "$([[ $rc == 0 ]] && grep -c '^check: ok' <<<"$out" || echo 0)"
    [[ $rc == 0 ]] || echo "$out" | tail -1
done

# far too rounded to weld (phi as 1.6): a convex solid all the same, whose
# shrunk core has 36 corners (the five planes at each corner no longer meet
# in one point); its template has room for them
cat >"$tmp/rough.yaml" <<'EOF'
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
shapes:
  - {name: d20, type: polyhedron, scale: 0.00063, margin: 0.08, vertices: [[0, 1, 1.6], [0, 1, -1.6], [0, -1, 1.6], [0, -1, -1.6], [1, 1.6, 0], [1, -1.6, 0], [-1, 1.6, 0], [-1, -1.6, 0], [1.6, 0, 1], [1.6, 0, -1], [-1.6, 0, 1], [-1.6, 0, -1]]}
particles: [{generator: list, material: m, spheres: [{position: [0, 0, 0], shape: d20}]}]
EOF
out=$(cd "$tmp" && "$bin" check rough.yaml 2>&1)
rc=$?
check "a coarsely rounded icosahedron (phi = 1.6) with a margin: a convex body, check exit 0 (got $rc)" \
    "$([[ $rc == 0 ]] && echo 1 || echo 0)"
finish
