#!/usr/bin/env bash
# grid_hopper_example.sh — the path of examples/hopper-grid.yaml, shortened to
# CI time: the same scene (pour, settle, open the outlet, discharge) cut to a
# slice of the seed's hopper (0.10 m wide, 0.0135 m deep: two rows of
# spheres, a 0.03 m slot in the middle, about 1,070 Set II spheres poured to
# 0.15 m, dt = 4e-5 s, 6 s),
# run with `shapedem run`, then examples/hopper-grid-analyse.py. Checks: the
# run writes the grid columns of stats.csv and summary.txt; the analysis
# writes discharge.csv, discharge.png and dead-zones.txt; every sphere asked
# for is poured and none is lost (in domain + discharged = poured); the
# discharge rate over 20-50 % and 50-80 % discharged are each within 10 % of
# their mean (a steady flow, seed 001 §4.2); and `shapedem check` shows the
# pour and the outlet.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene="$tmp/hopper-short.yaml"
sed -f "$root/validate/cases/hopper_dead_zone/slice.sed" "$root/examples/hopper-grid.yaml" >"$scene"
# the edits above must all have applied (the example changed otherwise)
for want in "dt: 4.0e-5" "duration: 6.0" "0.10, 0.0135, 0.25" "fill_height: 0.15" "height: 0.22" \
    "0.035, 0.0" "0.065, 0.0135" "open_at: 3.2" "every: 150000" "stats_every: 250"; do
    check "shortened scene has '$want'" "$(grep -qF "$want" "$scene" && echo 1 || echo 0)"
done

out=$("$bin" check "$scene" 2>&1)
check "check shows the pour" "$(grep -q '^pour  .*spheres of radius 0.003 m' <<<"$out" && echo 1 || echo 0)"
check "check shows the outlet" "$(grep -q '^outlet .*opens at t = 3.2 s' <<<"$out" && echo 1 || echo 0)"

"$bin" run "$scene" -o "$tmp/out" --threads 2 --quiet >"$tmp/run.log" 2>&1
rc=$?
check "run exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
[[ $rc == 0 ]] || cat "$tmp/run.log"
sum="$tmp/out/summary.txt"
poured=$(awk '/^grid_poured:/ {print $2}' "$sum")
indom=$(awk '/^grid_in_domain:/ {print $2}' "$sum")
dis=$(awk '/^grid_discharged:/ {print $2}' "$sum")
conf=$(awk '/^grid_conflicts_resolved:/ {print $2}' "$sum")
want=$(grep -o 'spheres of radius' <<<"$out" >/dev/null && awk '/^pour/ {print $2}' <<<"$out")
echo "pour: asked $want, poured $poured; in domain $indom, discharged $dis, conflicts $conf"
check "all poured ($poured of $want)" "$([[ -n "$poured" && "$poured" == "$want" ]] && echo 1 || echo 0)"
check "none lost: in domain $indom + discharged $dis = poured $poured" \
    "$([[ -n "$indom" && -n "$dis" && $((indom + dis)) == "$poured" ]] && echo 1 || echo 0)"
check "stats.csv has the grid columns" \
    "$(head -1 "$tmp/out/stats.csv" | grep -q 'poured,in_domain,discharged,discharged_mass' && echo 1 || echo 0)"

ana=$(/usr/bin/python3 "$root/examples/hopper-grid-analyse.py" "$tmp/out" 2>&1)
rc=$?
echo "$ana"
check "analysis exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
for f in discharge.csv discharge.png dead-zones.txt; do
    check "analysis wrote $f" "$([[ -s "$tmp/out/$f" ]] && echo 1 || echo 0)"
done
dev=$(sed -n 's/.*(each \([0-9.]*\) % from their mean).*/\1/p' <<<"$ana")
check "discharge rate 20-50 % and 50-80 % within 10 % of their mean (each $dev %)" \
    "$([[ -n "$dev" ]] && awk -v d="$dev" 'BEGIN {print (d <= 10.0)}' || echo 0)"
# the residual heaps beside the slot: measured on both sides, below the
# 45-degree bound any heap of these spheres stays under, and on average
# sloping down towards the slot (two rows deep, one side alone is noisy)
la=$(awk '/^left_angle_deg:/ {print $2}' "$tmp/out/dead-zones.txt" 2>/dev/null)
ra=$(awk '/^right_angle_deg:/ {print $2}' "$tmp/out/dead-zones.txt" 2>/dev/null)
for a in "left $la" "right $ra"; do
    v=${a#* }
    check "residual angle ${a% *} $v deg in (-45, 45)" \
        "$([[ -n "$v" && "$v" != nan ]] && awk -v v="$v" 'BEGIN {print (v > -45 && v < 45)}' || echo 0)"
done
check "mean residual angle > 0 (left $la, right $ra)" \
    "$([[ -n "$la" && -n "$ra" && "$la" != nan && "$ra" != nan ]] && awk -v a="$la" -v b="$ra" 'BEGIN {print (a + b > 0)}' || echo 0)"

# bad input: one clear message, exit 2 (pour without the grid solver)
sed -e 's/solver: grid/solver: cells/' "$scene" >"$tmp/bad.yaml"
msg=$("$bin" check "$tmp/bad.yaml" 2>&1)
rc=$?
check "pour with solver cells: exit 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
check "pour with solver cells: message names the key ($msg)" \
    "$(grep -q 'pour needs simulation.solver: grid' <<<"$msg" && echo 1 || echo 0)"

finish
