#!/usr/bin/env bash
# run_profile.sh — `shapedem run --profile` prints the per-stage table of
# the step (sd_profile) and summary.txt carries the same stages: a short
# run of spheres and boxes on a floor must list rebuild, spheres, convex,
# walls, integration and output, each with its call count; without
# --profile no table is printed. Times are never compared to anything.
set -u
bin="$1"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/mix.yaml" <<'EOF'
simulation: {dt: 1.0e-5, steps: 40}
materials: [{name: glass, density: 2500, youngs_modulus: 1.0e7}]
shapes: [{name: cube, type: box, size: [0.002, 0.002, 0.002]}]
particles:
  - {generator: list, material: glass, spheres: [{position: [0, 0, 0.001], radius: 0.001},
                                                 {position: [0.00202, 0, 0.001], radius: 0.001},
                                                 {position: [0.001, 0, 0.0033], shape: cube}]}
walls: [{name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}]
output: {every: 10}
EOF
"$bin" run "$tmp/mix.yaml" -o "$tmp/out" --profile >"$tmp/run.txt" 2>&1
rc=$?
check "run --profile exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
[[ $rc == 0 ]] || cat "$tmp/run.txt"
check "the table is printed" "$(grep -q '^profile: wall time per stage' "$tmp/run.txt" && echo 1 || echo 0)"
# steps 40: the force stages run once per step and once at the prepare
for stage in rebuild:41 spheres:41 convex:41 walls:41 integration:40; do
    name=${stage%%:*}
    calls=${stage##*:}
    got=$(awk -v s="$name" '$1 == s {print $4}' "$tmp/run.txt")
    check "table row $name: calls $got, expected $calls" "$([[ "$got" == "$calls" ]] && echo 1 || echo 0)"
    sgot=$(awk -v s="profile $name:" 'index($0, s) == 1 {print $NF}' "$tmp/out/summary.txt")
    check "summary.txt profile $name: calls $sgot, expected $calls" "$([[ "$sgot" == "$calls" ]] && echo 1 || echo 0)"
done
out=$(awk '$1 == "output" {print $4}' "$tmp/run.txt")
check "table row output counted (calls $out > 0)" "$([[ -n "$out" && "$out" -gt 0 ]] && echo 1 || echo 0)"
check "no row for a kind absent from the scene (poly_volume)" \
    "$(grep -q '^  poly_volume' "$tmp/run.txt" && echo 0 || echo 1)"
check "a total row" "$(grep -q '^  total ' "$tmp/run.txt" && echo 1 || echo 0)"
"$bin" run "$tmp/mix.yaml" -o "$tmp/out2" >"$tmp/plain.txt" 2>&1
check "without --profile, no table" "$(grep -q '^profile:' "$tmp/plain.txt" && echo 0 || echo 1)"
finish
