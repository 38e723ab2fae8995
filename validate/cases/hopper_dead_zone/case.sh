#!/usr/bin/env bash
# hopper_dead_zone — seed 001 §4.2 ([Naderi 2024]): the flat-bottomed
# hopper of examples/hopper-grid.yaml (Set II, H 0.40 m, W 0.20 m, D
# 0.04 m, orifice 0.04 m, about 15,300 spheres) at the paper's dt 5e-6 s:
# pour, settle, open the orifice at 6.5 s, 7.5 s of discharge; the residual
# heaps beside the orifice measured by examples/hopper-grid-analyse.py
# (a least-squares line through the tops of the columns between the wall
# and the orifice's edge). Asserted: every sphere poured and none lost;
# the dead-zone angle on each side against the paper's 18 degrees within
# 3 degrees (full run); the discharge rate steady (20-50 % and 50-80 %
# within 10 % of their mean). Writes hopper_dead_zone-discharge.png and
# -dead-zones.txt. Quick form: the slice of cli.grid_hopper_example (dt
# 4e-5 s, 6 s), whose angles are only printed.
. "$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/lib.sh"
scene="$out/hopper.yaml"
if [[ $quick == 1 ]]; then
    sed -f "$root/validate/cases/hopper_dead_zone/slice.sed" "$root/examples/hopper-grid.yaml" >"$scene"
else
    cp "$root/examples/hopper-grid.yaml" "$scene"
fi
claim "the scene runs at dt $(awk '/^ *dt:/ {print $2; exit}' "$scene") s" 1
"$bin" run "$scene" -o "$out/run" --threads 2 --quiet >"$out/run.log" 2>&1
claim "the run exits 0" "$([[ $? == 0 ]] && echo 1 || echo 0)"
sum="$out/run/summary.txt"
poured=$(awk '/^grid_poured:/ {print $2}' "$sum")
indom=$(awk '/^grid_in_domain:/ {print $2}' "$sum")
dis=$(awk '/^grid_discharged:/ {print $2}' "$sum")
compare "in the domain + discharged = poured" "$((${indom:-0} + ${dis:-0}))" "${poured:-nan}" 0
ana=$(/usr/bin/python3 "$root/examples/hopper-grid-analyse.py" "$out/run" 2>&1)
claim "the analysis ran" "$([[ $? == 0 ]] && echo 1 || echo 0)"
echo "$ana"
dev=$(sed -n 's/.*(each \([0-9.]*\) % from their mean).*/\1/p' <<<"$ana")
compare "discharge rate 20-50 % and 50-80 % from their mean (%)" "${dev:-nan}" 0 10
for side in left right; do
    a=$(awk -v k="${side}_angle_deg:" '$1 == k {print $2}' "$out/run/dead-zones.txt" 2>/dev/null)
    compare "dead-zone angle, $side (deg)" "${a:-nan}" 18 3 full
done
cp "$out/run/dead-zones.txt" "$docs/hopper_dead_zone-dead-zones.txt" 2>/dev/null
cp "$out/run/discharge.png" "$docs/hopper_dead_zone-discharge.png" 2>/dev/null
finish
