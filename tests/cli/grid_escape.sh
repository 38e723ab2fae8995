#!/usr/bin/env bash
# grid_escape.sh — the grid solver counts spheres that leave through the
# outlet (discharged, discharged_mass) apart from those that leave elsewhere,
# here through the box's open top (escaped, escaped_mass); before, the
# escaped sphere's mass went into discharged_mass ("discharged 0" next to a
# non-zero "discharged_mass"). Scene without gravity: sphere A (material a,
# 1000 kg/m^3) falls at 1 m/s through the hole in the floor, sphere B
# (material b, 3000 kg/m^3, so a different mass) rises at 1 m/s out of the
# open top and leaves first, sphere C stays. Expected masses: density x 4/3 pi
# R^3. Checks stats.csv (by column name) at the row where only B has left and
# at the end, and summary.txt.
set -u
bin="$1"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/escape.yaml" <<'EOF'
simulation: {dt: 1.0e-5, duration: 0.04, gravity: [0, 0, 0], solver: grid, contact_law: linear}
materials:
  - {name: a, density: 1000, stiffness: 1.0e4}
  - {name: b, density: 3000, stiffness: 1.0e4}
walls: [{name: box, type: box, min: [0, 0, 0], max: [0.1, 0.1, 0.1], open: [zmax], material: a}]
outlet: {min: [0.04, 0.04], max: [0.06, 0.06], open_at: 0}
particles:
  - {generator: list, material: a, spheres: [{position: [0.05, 0.05, 0.02], radius: 0.003, velocity: [0, 0, -1]}]}
  - {generator: list, material: b, spheres: [{position: [0.02, 0.02, 0.09], radius: 0.003, velocity: [0, 0, 1]}]}
  - {generator: list, material: a, spheres: [{position: [0.08, 0.08, 0.05], radius: 0.003}]}
output: {every: 100000, stats_every: 100, formats: [csv]}
EOF
"$bin" run "$tmp/escape.yaml" -o "$tmp/out" --threads 1 --quiet >"$tmp/run.log" 2>&1
rc=$?
check "run exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
[[ $rc == 0 ]] || cat "$tmp/run.log"
ma=$(awk 'BEGIN {printf "%.10g", 1000 * 4 / 3 * atan2(0, -1) * 0.003 ^ 3}')
mb=$(awk 'BEGIN {printf "%.10g", 3000 * 4 / 3 * atan2(0, -1) * 0.003 ^ 3}')
csv="$tmp/out/stats.csv"
check "stats.csv has discharged, discharged_mass, escaped, escaped_mass, removed" \
    "$(head -1 "$csv" | grep -q ',discharged,discharged_mass,escaped,escaped_mass,removed,' && echo 1 || echo 0)"
check "stats.csv has the box's torque columns" \
    "$(head -1 "$csv" | grep -q ',box_fx,box_fy,box_fz,box_tx,box_ty,box_tz,' && echo 1 || echo 0)"
# columns by name: "t in_domain discharged discharged_mass escaped escaped_mass removed" per row
cols() {
    awk -F, 'NR == 1 {for (i = 1; i <= NF; ++i) c[$i] = i; next}
        {print $c["time"], $c["in_domain"], $c["discharged"], $c["discharged_mass"], $c["escaped"],
            $c["escaped_mass"], $c["removed"]}' "$csv"
}
near() { awk -v a="$1" -v b="$2" 'BEGIN {d = a - b; if (d < 0) d = -d; print (d <= 1e-9 * (b > 0 ? b : 1))}'; }
# the first row where B has left and A has not
read -r t1 in1 dis1 dm1 esc1 em1 rem1 < <(cols | awk '$5 == 1 && $3 == 0' | head -1)
echo "B gone, A not yet: t $t1 s, in domain $in1, discharged $dis1 ($dm1 kg), escaped $esc1 ($em1 kg), removed $rem1"
check "a row with only B gone exists" "$([[ -n "${t1:-}" ]] && echo 1 || echo 0)"
check "then discharged_mass $dm1 kg = 0 (B left through the top, not the outlet)" \
    "$([[ -n "${dm1:-}" ]] && near "$dm1" 0 || echo 0)"
check "then escaped_mass $em1 kg = B's mass $mb kg (1e-9)" "$([[ -n "${em1:-}" ]] && near "$em1" "$mb" || echo 0)"
check "then in domain $in1 = 2, removed $rem1 = 1" "$([[ "${in1:-}" == 2 && "${rem1:-}" == 1 ]] && echo 1 || echo 0)"
read -r t2 in2 dis2 dm2 esc2 em2 rem2 < <(cols | tail -1)
echo "end: t $t2 s, in domain $in2, discharged $dis2 ($dm2 kg, expected $ma), escaped $esc2 ($em2 kg, expected $mb), removed $rem2"
check "end: discharged 1, escaped 1, removed 2, in domain 1" \
    "$([[ "$dis2" == 1 && "$esc2" == 1 && "$rem2" == 2 && "$in2" == 1 ]] && echo 1 || echo 0)"
check "end: discharged_mass $dm2 kg = A's mass $ma kg (1e-9)" "$(near "$dm2" "$ma")"
check "end: escaped_mass $em2 kg = B's mass $mb kg (1e-9)" "$(near "$em2" "$mb")"
sum="$tmp/out/summary.txt"
sdis=$(awk '/^grid_discharged:/ {print $2}' "$sum")
sdm=$(awk '/^grid_discharged_mass_kg:/ {print $2}' "$sum")
sesc=$(awk '/^grid_escaped:/ {print $2}' "$sum")
sem=$(awk '/^grid_escaped_mass_kg:/ {print $2}' "$sum")
srem=$(awk '/^grid_removed:/ {print $2}' "$sum")
echo "summary: discharged $sdis ($sdm kg), escaped $sesc ($sem kg), removed $srem"
check "summary: grid_discharged 1, grid_escaped 1, grid_removed 2" \
    "$([[ "$sdis" == 1 && "$sesc" == 1 && "$srem" == 2 ]] && echo 1 || echo 0)"
check "summary: grid_discharged_mass_kg $sdm = $ma" "$([[ -n "$sdm" ]] && near "$sdm" "$ma" || echo 0)"
check "summary: grid_escaped_mass_kg $sem = $mb" "$([[ -n "$sem" ]] && near "$sem" "$mb" || echo 0)"

finish
