#!/usr/bin/env python3
"""Plots the mesh-resolution test of seed 000 §3.2, Table 2 (tests/validation/mesh_resolution.c).

Usage:  SD_MESH_RESOLUTION_CSV=docs/validation/mesh_resolution.csv build/tests/validation_mesh_resolution
        python3 docs/validation/mesh_resolution.py docs/validation/mesh_resolution.csv
Writes mesh_resolution.png next to the CSV (needs matplotlib: Debian's python3-matplotlib).
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

path = sys.argv[1] if len(sys.argv) > 1 else "docs/validation/mesh_resolution.csv"
rows = list(csv.DictReader(open(path)))
kappa = [float(r["kappa"]) for r in rows]
lams = [k[len("fn_l"):] for k in rows[0].keys() if k.startswith("fn_l")]
fig, ax = plt.subplots(1, 2, figsize=(10, 4))
marks = "os^vDx"
for i, lam in enumerate(lams):
    ax[0].plot(kappa, [float(r["fn_l" + lam]) for r in rows], marks[i % 6] + "-", mfc="none", ms=4,
               label="lambda = %s" % lam)
    ax[1].plot(kappa, [float(r["ft_l" + lam]) for r in rows], marks[i % 6] + "-", mfc="none", ms=4,
               label="lambda = %s" % lam)
ax[0].plot(kappa, [float(r["plane_fn"]) for r in rows], "k--", label="analytic plane (no rim)")
ax[0].set_ylabel("normal force F_n / m g")
ax[1].set_ylabel("tangential force F_t / m g")
for a in ax:
    a.set_xlabel("kappa = dx / L_c")
    a.legend(fontsize=7)
fig.suptitle("cuboid pushed across a flat mesh wall at six resolutions (seed 000 §3.2, Table 2)")
fig.tight_layout()
out = os.path.join(os.path.dirname(path) or ".", "mesh_resolution.png")
fig.savefig(out, dpi=100)
print(out)
