#!/usr/bin/env bash
# case1_full — seed 001 §4.1 Case I at full size (scene.yaml): the packing
# density as the paper defines it, the particles' volume over the bulk
# domain's (5 m x 5 m x 5 m), against its 30.01 % (Fig. 6, the mean of
# three realisations) within 1 point; every sphere asked for poured, none
# lost. (72,029 spheres of R 0.05 m hold 30.17 % of the cube: the paper's
# own figure is 0.16 point below what its count gives.) Quick form: the
# same cube with 5,000 spheres (4 sheets), 3 s: the pour and the count.
. "$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/lib.sh"
scene="$out/case1.yaml"
want=72029
if [[ $quick == 1 ]]; then
    want=5000
    sed -e 's/count: 72029/count: 5000/' -e 's/duration: 20.0/duration: 3.0/' "$root/validate/cases/case1_full/scene.yaml" >"$scene"
else
    cp "$root/validate/cases/case1_full/scene.yaml" "$scene"
fi
"$bin" run "$scene" -o "$out/run" --threads 2 --quiet >"$out/run.log" 2>&1
claim "the run exits 0" "$([[ $? == 0 ]] && echo 1 || echo 0)"
sum="$out/run/summary.txt"
poured=$(awk '/^grid_poured:/ {print $2}' "$sum")
indom=$(awk '/^grid_in_domain:/ {print $2}' "$sum")
conf=$(awk '/^grid_conflicts_resolved:/ {print $2}' "$sum")
compare "spheres poured" "${poured:-nan}" "$want" 0
compare "spheres in the domain at the end" "${indom:-nan}" "$want" 0
# two spheres wanting one cell are resolved by the solver (grid/); printed
echo "info case1_full: cell conflicts resolved $conf"
phi=$(awk -v n="${indom:-0}" 'BEGIN {printf "%.4f", 100 * n * 4 / 3 * 3.14159265358979 * 0.05^3 / 125}')
compare "packing density over the bulk domain (%)" "$phi" 30.01 1.0 full
cp "$sum" "$docs/case1_full-summary.txt" 2>/dev/null
finish
