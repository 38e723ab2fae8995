#!/usr/bin/env python3
"""Plots test 4 of Chung & Ooi's benchmark (tests/validation/chung_ooi.c):
oblique impacts of an alumina sphere on a wall at 3.9 m/s, against the
incidence angle, on the analytic plane and on a mesh of it, with the
rigid-body sliding limit.

Usage:  SD_CHUNG_OOI_CSV=docs/validation/chung_ooi.csv build/tests/validation_chung_ooi
        /usr/bin/python3 docs/validation/chung_ooi.py docs/validation/chung_ooi.csv
Writes chung_ooi.png next to the CSV (needs matplotlib: Debian's python3-matplotlib).
"""
import csv
import math
import os
import sys

try:
    import matplotlib
except ImportError:  # one line, not a traceback
    sys.exit("%s: needs the Python module matplotlib: install the Debian package "
             "python3-matplotlib (apt-get install python3-matplotlib, or make deps)" % sys.argv[0])

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

path = sys.argv[1] if len(sys.argv) > 1 else "docs/validation/chung_ooi.csv"
rows = list(csv.DictReader(open(path)))
th = [float(r["theta_deg"]) for r in rows]
col = lambda k: [float(r[k]) for r in rows]  # noqa: E731
# the sliding limit holds where the sphere slides throughout: tan theta > 7/2 mu (1 + e)
slide = math.degrees(math.atan(3.5 * 0.092 * 2))
lim = [(t, r) for t, r in zip(th, rows) if t >= slide]
fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
panels = [("et", "tangential restitution v_t' / v_t"), ("spin", "spin w' R / v_t"),
          ("rebound", "rebound angle (degrees)")]
for a, (key, title) in zip(ax, panels):
    p = "rebound_plane_deg" if key == "rebound" else key + "_plane"
    m = "rebound_mesh_deg" if key == "rebound" else key + "_mesh"
    a.plot(th, col(p), "o", mfc="none", ms=5, label="analytic plane")
    a.plot(th, col(m), "+", ms=6, label="mesh (2 triangles)")
    if key == "et":
        a.plot([t for t, _ in lim], [float(r["et_sliding"]) for _, r in lim], "k-", lw=1, label="sliding limit")
    elif key == "spin":
        a.plot([t for t, _ in lim], [float(r["spin_sliding"]) for _, r in lim], "k-", lw=1, label="sliding limit")
    else:
        a.plot(th, th, "k:", lw=1, label="incidence angle")
    a.axvline(slide, color="grey", lw=0.5)
    a.set_xlabel("incidence angle from the normal (degrees)")
    a.set_title(title, fontsize=10)
    a.grid(alpha=0.3)
    a.legend(fontsize=8)
fig.suptitle("Chung & Ooi test 4: alumina sphere, R 2.5 mm, 3.9 m/s, mu 0.092, e = 1, Hertz-Mindlin", fontsize=10)
fig.tight_layout()
out = os.path.join(os.path.dirname(os.path.abspath(path)), "chung_ooi.png")
fig.savefig(out, dpi=110)
print("wrote %s" % out)
