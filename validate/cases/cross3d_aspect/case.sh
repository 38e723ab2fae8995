#!/usr/bin/env bash
# cross3d_aspect — the sensitivity of the 3D-cross packing's porosity to
# the beam aspect ratio L/D = 3, 4, 5, 6 (issue 34: seed 004 gives its
# crosses no dimensions, docs/shapes.md says which we chose). The protocol
# of packing_six (validate/packing.py: 1,000 crosses of the volume of a
# 2 mm sphere, one at a time, bi-periodic, the embedding box at two voxel
# sizes). Asserted: the voxel count has converged (0.005, as packing_six)
# and, full run only, the porosity rises with L/D (longer, thinner beams
# entangle and hold more void; the known trend for rods and crosses).
# Writes cross3d_aspect.csv and cross3d_aspect.png. Quick form: 60 crosses.
. "$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/lib.sh"
n=1000
[[ $quick == 1 ]] && n=60
echo "aspect,particles,top_m,porosity_coarse,porosity_fine,voxels_coarse,voxels_fine,simulated_s,wall_s,settled" >"$docs/cross3d_aspect.csv"
prev=""
for a in 3 4 5 6; do
    line=$(/usr/bin/python3 "$root/validate/packing.py" "$bin" "$out/ld$a" cross3d "$n" --aspect "$a" | grep '^result ')
    if [[ -z "$line" ]]; then
        claim "L/D $a: the packing ran and was measured" 0
        continue
    fi
    echo "$line"
    read -r _ _ _ top ec ef vc vf sim wall settled <<<"$line"
    echo "$a,$n,$top,$ec,$ef,$vc,$vf,$sim,$wall,$settled" >>"$docs/cross3d_aspect.csv"
    claim "L/D $a: settled (kinetic energy below 1e-9 J a particle) after $sim s" "$settled" full
    compare "L/D $a: porosity at h/16 against h/8 (voxels $vf, $vc)" "$ef" "$ec" 0.005
    if [[ -n "$prev" ]]; then
        claim "porosity rises with L/D: $prev_a $prev < $a $ef" "$(awk -v p="$prev" -v e="$ef" 'BEGIN {print (p < e) ? 1 : 0}')" full
    fi
    prev=$ef
    prev_a=$a
done
/usr/bin/python3 - "$docs/cross3d_aspect.csv" "$docs/cross3d_aspect.png" <<'PY' || claim "plot written" 0
import csv, sys
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
rows = list(csv.DictReader(open(sys.argv[1])))
fig, ax = plt.subplots(figsize=(5, 3.5))
ax.plot([float(r['aspect']) for r in rows], [float(r['porosity_fine']) for r in rows], 'o-')
ax.set_xlabel('beam length / diameter')
ax.set_ylabel('porosity of the embedding box')
ax.set_title('3D crosses, %s particles, bi-periodic' % rows[0]['particles'])
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
PY
finish
