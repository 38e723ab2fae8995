#!/usr/bin/env python3
"""Plots tests 4 to 8 of Chung & Ooi's benchmark (tests/validation/chung_ooi.c),
one row of panels a test, each computed point against the rigid-body values
(the sliding limit where the contact slides throughout, sticking below it):

  4  alumina sphere on the wall at 3.9 m/s: tangential restitution, spin and
     rebound angle against the incidence angle;
  5  steel and polyethylene on the wall, constant normal speed: the recoil
     s'/(mu v_n') and the spin r w'/(mu v_n) against psi = v_t/(mu v_n);
  6  aluminium alloy and nylon on the wall, constant normal and tangential
     speeds, varying spin: beta = -s'/s against chi = 7/2 mu (1 + e) v_n / s,
     and the tangent of the recoil against that of the incidence;
  7  two identical spheres spinning the same way: sphere 1's tangential
     velocity and spin after against the spin before;
  8  a sphere with spin on a sphere twice its size at rest: beta and the recoil.

On the walls the analytic plane's points (circles) and the mesh's (crosses)
coincide. Tests 6-8 at e = 1 and at the benchmark's e = 0.5.

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

# (test, quantity, x label, y label) a panel
panels = [
    [(4, "et", "incidence angle (deg)", "v_t' / v_t"), (4, "spin", "incidence angle (deg)", "w' R / v_t"),
     (4, "rebound", "incidence angle (deg)", "rebound angle (deg)")],
    [(5, "recoil", "psi = v_t / (mu v_n)", "s' / (mu v_n')"), (5, "spin", "psi = v_t / (mu v_n)", "r w' / (mu v_n)")],
    [(6, "beta", "chi = 7/2 mu (1 + e) v_n / s", "beta = -s' / s"),
     (6, "tan_recoil", "tan(incidence) = s / v_n", "tan(recoil) = s' / v_n'")],
    [(7, "vt", "w0 (rad/s)", "v_t' of sphere 1 (m/s)"), (7, "spin", "w0 (rad/s)", "w' of sphere 1 (rad/s)")],
    [(8, "beta", "chi = 7/2 mu (1 + e) v_c / s", "beta = -s' / s"),
     (8, "tan_recoil", "tan(incidence) = s / v_c", "tan(recoil) = s' / v_part")],
]
titles = {4: "test 4: alumina, R 2.5 mm, 3.9 m/s, mu 0.092, e 1",
          5: "test 5: R 10 mm, v_n 5 m/s, mu 0.3, e 1",
          6: "test 6: R 0.1 m, v_n = v_t = 0.2 m/s, mu 0.4",
          7: "test 7: two R 0.1 m spheres, 0.2 m/s each, mu 0.4",
          8: "test 8: R 0.1 m at 0.2 m/s on R 0.2 m at rest, mu 0.4"}
colours = ["C0", "C1", "C2", "C3"]

fig, ax = plt.subplots(len(panels), 3, figsize=(14, 3.2 * len(panels)))
for i, row in enumerate(panels):
    for j in range(3):
        a = ax[i][j]
        if j >= len(row):
            a.axis("off")
            continue
        test, q, xl, yl = row[j]
        sel = [r for r in rows if int(r["test"]) == test and r["quantity"] == q]
        mats = []
        for r in sel:
            if r["material"] not in mats:
                mats.append(r["material"])
        for k, mat in enumerate(mats):
            pts = sorted((float(r["x"]), float(r["plane"]), float(r["mesh"]), float(r["rigid"]))
                         for r in sel if r["material"] == mat)
            pts = [p for p in pts if all(math.isfinite(v) for v in (p[0], p[1], p[3]))]
            if test in (6, 8) and q == "tan_recoil":
                pts = [p for p in pts if abs(p[1]) < 12]  # the near-sticking points' recoil over a small v_n'
            c = colours[k % len(colours)]
            x = [p[0] for p in pts]
            a.plot(x, [p[1] for p in pts], "o", mfc="none", ms=4, color=c,
                   label=mat + (", plane" if test <= 6 else ""))
            mesh = [(p[0], p[2]) for p in pts if math.isfinite(p[2])]
            if mesh:
                a.plot([m[0] for m in mesh], [m[1] for m in mesh], "+", ms=5, color=c, label=mat + ", mesh")
            a.plot(x, [p[3] for p in pts], "-", lw=0.8, color=c, alpha=0.7)
        a.set_xlabel(xl, fontsize=8)
        a.set_ylabel(yl, fontsize=8)
        a.set_title(titles[test] + "  (lines: rigid body)", fontsize=8)
        a.grid(alpha=0.3)
        a.legend(fontsize=6)
fig.suptitle("Chung & Ooi tests 4-8 under Hertz-Mindlin: computed (points) against the rigid-body "
             "sliding / sticking limits (lines)", fontsize=10)
fig.tight_layout(rect=(0, 0, 1, 0.98))
out = os.path.join(os.path.dirname(os.path.abspath(path)), "chung_ooi.png")
fig.savefig(out, dpi=90)
print("wrote %s" % out)
