#!/usr/bin/env python3
"""biaxial-2d.py — §3.2 of [Huang 2021] (docs/references.md): random
packing and biaxial compression of 500 planar particles (circles, ellipses,
polygons, polybéziers and Fourier-series shapes), and the plot of its
stress–strain curves.

    biaxial-2d.py scene > examples/biaxial-2d.yaml
        writes the scene (deterministic: the same file every time)
    biaxial-2d.py plot out/biaxial-2d/biaxial.csv docs/validation/biaxial-2d.png
        plots axial and lateral stress (Fig. 7a) and the deviatoric stress
        ratio q/p and volumetric strain against axial strain (Fig. 7b)

Shapes: 25 templates, five equivalent diameters (the diameter of the circle
of the same area: 0.040, 0.045, 0.050, 0.055, 0.060 m, as in the paper) for
each of the five kinds; every template is scaled to its exact area so the
equivalent size is exact. Fourier shapes (eq. 2) satisfy the sufficient
convexity condition of eq. 7. Particles sit on a 13 x 39 lattice filling the
1.0 m x 3.0 m box, each of a random template and orientation.
"""
import math
import random
import sys

KINDS = ("circle", "ellipse", "polygon", "polybezier", "fourier")
SIZES = (0.040, 0.045, 0.050, 0.055, 0.060)


def shoelace(pts):
    a = 0.0
    for i in range(len(pts)):
        x0, y0 = pts[i]
        x1, y1 = pts[(i + 1) % len(pts)]
        a += x0 * y1 - x1 * y0
    return 0.5 * a


def bezier_area(ctrl):
    """Area inside a closed chain of cubic segments (sampled finely)."""
    m = len(ctrl) // 3
    pts = []
    for k in range(m):
        p = [ctrl[(3 * k + i) % len(ctrl)] for i in range(4)]
        for s in range(64):
            t = s / 64.0
            u = 1 - t
            b = (u ** 3, 3 * u * u * t, 3 * u * t * t, t ** 3)
            pts.append((sum(b[i] * p[i][0] for i in range(4)), sum(b[i] * p[i][1] for i in range(4))))
    return shoelace(pts)


def template(kind, d, rng):
    """Keys of one shape entry with equivalent diameter d."""
    r = 0.5 * d
    area = math.pi * r * r
    if kind == "circle":
        return {"radius": r}
    if kind == "ellipse":
        ar = rng.uniform(1.2, 1.6)
        return {"axes": [r * math.sqrt(ar), r / math.sqrt(ar)]}
    if kind == "polygon":
        n = rng.choice((5, 6, 7, 8))
        pts = []
        for k in range(n):
            t = 2 * math.pi * k / n + rng.uniform(-0.25, 0.25) * math.pi / n
            rho = r * rng.uniform(0.95, 1.05)
            pts.append((rho * math.cos(t), rho * math.sin(t)))
        c = math.sqrt(area / shoelace(pts))
        return {"points": [[c * x, c * y] for x, y in pts]}
    if kind == "polybezier":
        ar = rng.uniform(1.1, 1.4)
        kap = rng.uniform(0.55, 0.7)  # 0.5523: an ellipse; larger: squarer, still convex
        a, b = math.sqrt(ar), 1 / math.sqrt(ar)
        ctrl = [(a, 0), (a, kap * b), (kap * a, b), (0, b), (-kap * a, b), (-a, kap * b),
                (-a, 0), (-a, -kap * b), (-kap * a, -b), (0, -b), (kap * a, -b), (a, -kap * b)]
        c = math.sqrt(area / bezier_area(ctrl))
        return {"points": [[c * x, c * y] for x, y in ctrl]}
    # fourier, order 8: p = a0/2 + sum a_k cos k t + b_k sin k t (eq. 2)
    n = 8
    a = [2.0] + [0.0] * n
    b = [0.0] * n
    for k in range(2, n + 1):
        amp = 0.18 / (k * k) * rng.uniform(0.3, 1.0)
        ph = rng.uniform(0, 2 * math.pi)
        a[k] = amp * math.cos(ph)
        b[k - 1] = amp * math.sin(ph)
    # eq. 7: a0/2 - sum (k^2 - 1) |c_k| >= 0, with a margin: shrink the harmonics if needed
    s = sum((k * k - 1) * math.hypot(a[k], b[k - 1]) for k in range(2, n + 1))
    if s > 0.8 * a[0] / 2:
        f = 0.8 * a[0] / 2 / s
        a = [a[0]] + [f * x for x in a[1:]]
        b = [f * x for x in b]
    # area = pi a0^2 / 4 - pi/2 sum (k^2 - 1)(a_k^2 + b_k^2)
    ar = math.pi * a[0] ** 2 / 4 - 0.5 * math.pi * sum((k * k - 1) * (a[k] ** 2 + b[k - 1] ** 2)
                                                       for k in range(1, n + 1))
    c = math.sqrt(area / ar)
    return {"fourier_a": [c * x for x in a], "fourier_b": [c * x for x in b]}


def fmt(v):
    if isinstance(v, list):
        return "[" + ", ".join(fmt(x) for x in v) + "]"
    return "%.9g" % v


def scene(out):
    rng = random.Random(20020302)
    w = out.write
    w("# Section 3.2 of [Huang 2021] (S. Huang, L. Huang, Z. Lai, \"An extension of the\n"
      "# Fourier series-based particle model to the GJK-based contact detection and\n"
      "# resolution framework for DEM\", Computational Particle Mechanics, 2021;\n"
      "# docs/references.md): random packing and biaxial compression of 500 planar\n"
      "# particles (circles, ellipses, polygons, polybeziers, Fourier shapes), equivalent\n"
      "# sizes 0.04-0.06 m, in a 1.0 m x 3.0 m box. Written by\n"
      "#   docs/validation/biaxial-2d.py scene > examples/biaxial-2d.yaml\n"
      "# Stages (80,000 steps, as in the paper): settling under gravity; the top wall\n"
      "# comes down under servo control from 1.5 s; consolidation at 100 kPa on the\n"
      "# top and side walls from 5 s; compression at 0.1 m/s from 6 s to 8 s with\n"
      "# the side walls servo-controlled at 100 kPa. The run writes biaxial.csv;\n"
      "#   docs/validation/biaxial-2d.py plot out/biaxial-2d/biaxial.csv out.png\n"
      "# plots it. Linear law of eqs. 8-10 (restitution 1: no dashpot; k_t = k_n),\n"
      "# local damping 0.7.\n"
      "#\n"
      "# Time step: dt = 1e-4 s is the paper's own. `shapedem check` warns that it is\n"
      "# above the recommended 2.6e-5 s (1/50 of the shortest contact, 1.29e-3 s for\n"
      "# the two smallest grains; with the linear law that duration does not depend\n"
      "# on speed or load): each contact is resolved in 12.9 steps. That is well\n"
      "# inside the stability limit (5 steps, dt 2.6e-4 s): for the undamped spring\n"
      "# velocity Verlet needs omega dt < 2, here omega dt = pi / 12.9 = 0.24.\n"
      "# Measured: the whole run at 1e-4 s against the same scene at 2.5e-5 s (rows\n"
      "# every 0.01 s in both). While settling (0-1.5 s, walls fixed) the total energy\n"
      "# never rises in either run and ends at 0.517 and 0.516 of its start; at 6 s\n"
      "# the consolidated sample is 1.2301 m x 0.9714 m against 1.2251 m x 0.9734 m\n"
      "# (0.4 % and 0.2 % apart), with 976 and 973 contacts. In the compression q/p\n"
      "# peaks at 0.400 against 0.399, averages 0.358 against 0.340 over 7-8 s, the\n"
      "# volumetric strain ends at 2.1 % against 2.5 %, the side walls hold 100 kPa\n"
      "# within 0.94 % against 0.11 %, and the largest overlap is 23 % against 22 %\n"
      "# of the smaller radius: differences within the curve's own swings (after\n"
      "# 6.3 s q/p moves between 0.28 and 0.40 at 1e-4 s, 0.23 and 0.40 at 2.5e-5 s).\n")
    w("simulation:\n  dimension: 2\n  dt: 1.0e-4\n  duration: 8.0\n  gravity: [0, -9.8, 0]\n"
      "  contact_law: linear\n  local_damping: 0.7\n  seed: 2\n")
    w("materials:\n  - name: grain\n    density: 2700\n    stiffness: 1.0e7\n"
      "    tangential_stiffness_ratio: 1.0\n    restitution: 1.0\n    friction: 0.2\n")
    w("shapes:\n")
    names = []
    for kind in KINDS:
        for d in SIZES:
            name = "%s_%d" % (kind, round(d * 1000))
            names.append(name)
            w("  - name: %s\n    type: %s\n" % (name, kind))
            for k, v in template(kind, d, rng).items():
                w("    %s: %s\n" % (k, fmt(v)))
    w("particles:\n  - generator: list\n    material: grain\n    orientation: random\n    spheres:\n")
    nx, ny = 13, 39
    sx, sy = 1.0 / nx, 3.0 / ny
    for k in range(500):
        i, j = k % nx, k // nx
        w("      - {position: [%s, %s, 0], shape: %s}\n" %
          (fmt((i + 0.5) * sx), fmt((j + 0.5) * sy), rng.choice(names)))
    w("walls:\n"
      "  - {name: left, type: plane, material: grain, point: [0, 0, 0], normal: [1, 0, 0],\n"
      "     servo_stress: 1.0e5, servo_start: 5.0, servo_max_speed: 0.5}\n"
      "  - {name: right, type: plane, material: grain, point: [1, 0, 0], normal: [-1, 0, 0],\n"
      "     servo_stress: 1.0e5, servo_start: 5.0, servo_max_speed: 0.5}\n"
      "  - {name: bottom, type: plane, material: grain, point: [0, 0, 0], normal: [0, 1, 0]}\n"
      "  - {name: top, type: plane, material: grain, point: [0, 3, 0], normal: [0, -1, 0],\n"
      "     servo_stress: 1.0e5, servo_start: 1.5, servo_end: 6.0, servo_max_speed: 0.5,\n"
      "     velocity: [0, -0.1, 0], move_start: 6.0, move_end: 8.0}\n")
    w("output:\n  every: 2000\n  stats_every: 100\n")


def plot(csv, png):
    try:
        import matplotlib
    except ImportError:  # one line, not a traceback
        sys.exit("%s: needs the Python module matplotlib: install the Debian package "
                 "python3-matplotlib (apt-get install python3-matplotlib, or make deps)" % sys.argv[0])
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = []
    with open(csv) as f:
        head = f.readline().strip().split(",")
        for line in f:
            rows.append(dict(zip(head, map(float, line.split(",")))))
    t = [r["time"] for r in rows]
    load = [r for r in rows if r["strain_axial"] > 0 or r is rows[-1]]
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    ax[0].plot(t, [r["sigma_yy"] / 1e3 for r in rows], label="axial (top/bottom)")
    ax[0].plot(t, [r["sigma_xx"] / 1e3 for r in rows], label="lateral (sides)")
    ax[0].axhline(100, color="grey", lw=0.6, ls="--")
    ax[0].set_xlabel("time (s)")
    ax[0].set_ylabel("stress (kPa, compression +)")
    ax[0].set_title("a  wall stresses ([Huang 2021] Fig. 7a)")
    ax[0].legend()
    e = [100 * r["strain_axial"] for r in load]
    ax[1].plot(e, [r["stress_ratio"] for r in load], label="q/p = (s_a - s_l)/(s_a + s_l)")
    ax[1].set_xlabel("axial strain (%)")
    ax[1].set_ylabel("deviatoric stress ratio q/p")
    ax2 = ax[1].twinx()
    ax2.plot(e, [100 * r["strain_volumetric"] for r in load], color="C3", label="volumetric strain")
    ax2.set_ylabel("volumetric strain (%, compression +)")
    ax[1].set_title("b  stress ratio and volumetric strain (Fig. 7b)")
    h1, l1 = ax[1].get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax[1].legend(h1 + h2, l1 + l2, loc="lower right")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] == "scene":
        scene(sys.stdout)
    elif len(sys.argv) == 4 and sys.argv[1] == "plot":
        plot(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
