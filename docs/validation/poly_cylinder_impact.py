#!/usr/bin/env python3
"""Plots the polyhedral cylinder-wall impact under the volume law
(tests/validation/poly_cylinder_impact.c; [Xu n.d.] §3.1, Table 1, eqs. 27-28).

Usage:  SD_VALIDATION_OUT=docs/validation build/tests/validation_poly_cylinder_impact
        python3 docs/validation/poly_cylinder_impact.py docs/validation/poly_cylinder_impact.csv
Writes poly_cylinder_impact.png next to the CSV (needs matplotlib: Debian's python3-matplotlib).
"""
import csv
import os
import sys

try:
    import matplotlib
except ImportError:  # one line, not a traceback
    sys.exit("%s: needs the Python module matplotlib: install the Debian package "
             "python3-matplotlib (apt-get install python3-matplotlib, or make deps)" % sys.argv[0])

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

path = sys.argv[1] if len(sys.argv) > 1 else "docs/validation/poly_cylinder_impact.csv"
rows = list(csv.DictReader(open(path)))
th = [float(r["theta_deg"]) for r in rows]
label = "shapedem, 42-vertex polyhedron, volume law"
fig, ax = plt.subplots(1, 2, figsize=(10, 4))
ax[0].plot(th, [float(r["vz_analytic"]) for r in rows], "k-", label="analytic (eq. 28 of [Xu n.d.])")
ax[0].plot(th, [float(r["vz_computed"]) for r in rows], "o", mfc="none", label=label)
ax[0].set_xlabel("impact angle theta (deg)")
ax[0].set_ylabel("post-impact V_z (m/s)")
ax[1].plot(th, [float(r["wy_analytic"]) for r in rows], "k-", label="analytic (eq. 27 of [Xu n.d.])")
ax[1].plot(th, [float(r["wy_computed"]) for r in rows], "o", mfc="none", label=label)
ax[1].set_xlabel("impact angle theta (deg)")
ax[1].set_ylabel("post-impact omega_y (rad/s)")
for a in ax:
    a.axvspan(10, 80, color="0.93", zorder=0)
    a.grid(alpha=0.3)
    a.legend(fontsize=8)
fig.suptitle("Polyhedral cylinder-wall impact ([Xu n.d.] Table 1): E = 1.15 GPa, e = 0.85, V = 1 m/s "
             "(asserted range shaded)", fontsize=10)
fig.tight_layout()
out = os.path.join(os.path.dirname(path) or ".", "poly_cylinder_impact.png")
fig.savefig(out, dpi=120)
print("wrote", out)
