#!/usr/bin/env python3
"""Discharge curves of the hopper of [Naderi 2024] §4.2 (examples/hopper-grid.yaml)
run with three time steps: grid-hopper-discharge.csv (dt = 1e-5 s),
grid-hopper-discharge-dt2e-5.csv and grid-hopper-discharge-dt4e-5.csv.
Writes grid-hopper-discharge.png next to this script.

    python3 docs/validation/grid-hopper-dt.py
"""
import csv
import sys
import os

try:
    import matplotlib
except ImportError:  # one line, not a traceback
    sys.exit("%s: needs the Python module matplotlib: install the Debian package "
             "python3-matplotlib (apt-get install python3-matplotlib, or make deps)" % sys.argv[0])

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
runs = [("grid-hopper-discharge-dt4e-5.csv", "dt = 4e-5 s (t_c / 8)", ":"),
        ("grid-hopper-discharge-dt2e-5.csv", "dt = 2e-5 s (t_c / 16)", "--"),
        ("grid-hopper-discharge.csv", "dt = 1e-5 s (t_c / 33)", "-")]
fig, ax = plt.subplots(figsize=(6, 4))
for name, label, style in runs:
    with open(os.path.join(here, name)) as fh:
        rows = [(float(r["time_since_open_s"]), float(r["mass_fraction_discharged"])) for r in csv.DictReader(fh)]
    ax.plot([t for t, _ in rows], [f for _, f in rows], style, label=label)
ax.set_xlim(0, 7.5)
ax.set_ylim(0, 1)
ax.set_xlabel("time since the orifice opened (s)")
ax.set_ylabel("mass fraction discharged")
ax.set_title("Flat-bottomed hopper, Set II ([Naderi 2024] §4.2), solver grid")
ax.grid(alpha=0.3)
ax.legend(loc="lower right")
fig.tight_layout()
fig.savefig(os.path.join(here, "grid-hopper-discharge.png"), dpi=100)
