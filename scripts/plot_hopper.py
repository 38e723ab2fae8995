#!/usr/bin/env python3
"""plot_hopper.py CSV PNG — draws the discharge curve of the grid solver's
hopper ([Naderi 2024] §4.2, docs/references.md; tests/validation/grid_hopper.c, long mode): mass
fraction discharged against time since the orifice opened. Needs matplotlib
(Debian: apt-get install python3-matplotlib)."""
import csv
import sys

try:
    import matplotlib
except ImportError:  # one line, not a traceback
    sys.exit("%s: needs the Python module matplotlib: install the Debian package "
             "python3-matplotlib (apt-get install python3-matplotlib, or make deps)" % sys.argv[0])

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_hopper.py CSV PNG")
    t, f = [], []
    with open(sys.argv[1]) as fh:
        for row in csv.DictReader(fh):
            t.append(float(row["time_s"]))
            f.append(float(row["mass_fraction_discharged"]))
    fig, ax = plt.subplots(figsize=(5, 3.6))
    ax.plot(t, f, lw=1.8, label="shapedem, solver grid")
    ax.set_xlabel("time since the orifice opened (s)")
    ax.set_ylabel("mass fraction discharged")
    ax.set_ylim(0, 1)
    ax.grid(alpha=0.3)
    ax.set_title("Flat-bottomed hopper, Set II ([Naderi 2024] §4.2)")
    ax.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
