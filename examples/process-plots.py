#!/usr/bin/python3
"""process-plots.py - plots of the process examples (issue 16), from the
CSV files their analysis: sections write.

  python3 examples/process-plots.py drum    out/drum-periodic  -> drum-periodic.png
  python3 examples/process-plots.py drum2d  out/drum-2d        -> drum-2d.png
  python3 examples/process-plots.py bed     out/fixed-bed      -> fixed-bed.png
  python3 examples/process-plots.py reactor out/reactor-fill   -> reactor-fill.png
  python3 examples/process-plots.py heap    out/heap-pour      -> heap-pour.png
  python3 examples/process-plots.py packing out                -> packing-*.png

drum: coordination.csv (mean Z, with and without the drum's contacts) and
  energy.csv (mean speed) against time, and surface_angle.csv's angle; the
  bed before the drum starts (its last 0.1 s at rest) and the second half.
drum2d: velocity_field.csv averaged over its last 0.3 s (weighted by the
  particles per cell) as arrows on the drum's cross section, by speed.
bed, reactor: the last block of the radial porosity profile
  (radial_porosity.csv) against r / R.
heap: repose_angle.csv's angle and bed_height.csv's heights against time.
packing: for each out/packing-SHAPE run (examples/packing-*.yaml) the table
  row (porosity.csv's last row, coordination.csv's last row and its mean
  over the last 0.02 s, summary.txt's stop, wall time and threads), one
  picture of the bed by `shapedem render` (packing-SHAPE.png, coloured by
  contact force; the binary is $SHAPEDEM, else build/shapedem), and
  packing-settle.png: kinetic energy and mean coordination against time
  for every shape.
Each prints the numbers it plots; the PNG goes into the output directory
(and, with a third argument, into that directory too, e.g. docs/examples).
Standard library for the numbers; matplotlib for the plots.
"""
import csv
import math
import os
import shutil
import sys


def rows(out, name):
    with open(os.path.join(out, name)) as f:
        return list(csv.DictReader(f))


def last_block(rs):
    t = rs[-1]["time"]
    return [r for r in rs if r["time"] == t]


def save(fig, out, name, also):
    path = os.path.join(out, name)
    fig.savefig(path, dpi=110)
    print("wrote", path)
    if also:
        shutil.copy(path, os.path.join(also, name))
        print("copied to", os.path.join(also, name))


# examples/drum-periodic.yaml's drum: at rest until start, then its speed
# ramps to rpm over ramp (walls[0].start and .ramp, s)
DRUM_START, DRUM_RAMP = 0.5, 0.25


def drum(out, also):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    co = rows(out, "coordination.csv")
    en = rows(out, "energy.csv")
    sa = rows(out, "surface_angle.csv")
    t = [float(r["time"]) for r in co]
    z = [float(r["mean"]) for r in co]
    zw = [float(r["mean_with_walls"]) for r in co]
    te = [float(r["time"]) for r in en]
    v = [float(r["mean_speed"]) for r in en]
    ta = [float(r["time"]) for r in sa]
    ang = [float(r["angle_deg"]) for r in sa]
    # the bed before the drum turns: the last 0.1 s before its start
    pre = [i for i, x in enumerate(t) if DRUM_START - 0.1 <= x < DRUM_START]
    pre_e = [i for i, x in enumerate(te) if DRUM_START - 0.1 <= x < DRUM_START]
    if pre and pre_e:
        print("drum: settled bed before the drum starts (%.2f-%.2f s): mean Z %.3f (%.3f-%.3f), mean speed %.2g m/s"
              % (DRUM_START - 0.1, DRUM_START, sum(z[i] for i in pre) / len(pre), min(z[i] for i in pre),
                 max(z[i] for i in pre), sum(v[i] for i in pre_e) / len(pre_e)))
    late = [i for i, x in enumerate(t) if x >= t[-1] / 2]
    zm = sum(z[i] for i in late) / len(late)
    late_e = [i for i, x in enumerate(te) if x >= te[-1] / 2]
    vm = sum(v[i] for i in late_e) / len(late_e)
    late_a = [i for i, x in enumerate(ta) if x >= ta[-1] / 2 and ang[i] > 0]
    am = sum(ang[i] for i in late_a) / len(late_a) if late_a else 0.0
    print("drum: over the second half (t >= %.2f s): mean Z %.3f, mean speed %.4f m/s, surface angle %.1f deg"
          % (t[-1] / 2, zm, vm, am))
    fig, ax = plt.subplots(3, 1, figsize=(6.4, 7.2), sharex=True)
    ax[0].plot(t, z, label="particles")
    ax[0].plot(t, zw, label="with the drum")
    ax[0].set_ylabel("mean coordination Z")
    ax[0].legend()
    ax[1].plot(te, v)
    ax[1].set_ylabel("mean speed (m/s)")
    ax[2].plot(ta, ang, "o-", ms=3)
    ax[2].set_ylabel("surface angle (deg)")
    ax[2].set_xlabel("time (s)")
    for a in ax:  # the drum at rest, then its ramp to full speed
        a.axvspan(DRUM_START, DRUM_START + DRUM_RAMP, color="0.9")
    ax[1].set_yscale("log")
    ax[0].set_title("drum-periodic: Z %.2f, speed %.3f m/s, %.0f deg (second half)" % (zm, vm, am))
    fig.tight_layout()
    save(fig, out, "drum-periodic.png", also)


def drum2d(out, also):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    allr = rows(out, "velocity_field.csv")
    t_end = float(allr[-1]["time"])
    cells = {}
    for r in allr:  # count-weighted mean over the outputs of the last 0.3 s
        if float(r["time"]) < t_end - 0.3 - 1e-9 or int(r["count"]) == 0:
            continue
        c = cells.setdefault((r["i"], r["j"]), [float(r["u"]), float(r["v"]), 0, 0.0, 0.0])
        n = int(r["count"])
        c[2] += n
        c[3] += n * float(r["vx"])
        c[4] += n * float(r["vz"])
    pts = list(cells.values())
    u = [c[0] for c in pts]
    w = [c[1] for c in pts]
    vx = [c[3] / c[2] for c in pts]
    vz = [c[4] / c[2] for c in pts]
    sp = [math.hypot(a, b) for a, b in zip(vx, vz)]
    vf = [{"time": "%g" % t_end}]
    print("drum2d: %.2f-%.2f s, %d cells with particles, fastest cell %.3f m/s, slowest %.3f m/s"
          % (t_end - 0.3, t_end, len(pts), max(sp), min(sp)))
    fig, ax = plt.subplots(figsize=(6.0, 6.0))
    q = ax.quiver(u, w, vx, vz, sp, cmap="viridis")
    fig.colorbar(q, ax=ax, label="speed (m/s)")
    R = 0.15
    th = [2 * math.pi * k / 200 for k in range(201)]
    ax.plot([R * math.cos(a) for a in th], [R * math.sin(a) for a in th], "k-", lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title("drum-2d: mean velocity, %.2f-%.2f s" % (t_end - 0.3, t_end))
    fig.tight_layout()
    save(fig, out, "drum-2d.png", also)


def profile(out, also, name):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rp = last_block(rows(out, "radial_porosity.csv"))
    R = float(rp[-1]["r_outer"])
    r = [0.5 * (float(x["r_inner"]) + float(x["r_outer"])) / R for x in rp]
    e = [float(x["porosity"]) for x in rp]
    vox = sum(int(x["voxels"]) for x in rp)
    solid = sum(int(x["solid_voxels"]) for x in rp)
    print("%s: t = %s s, mean porosity %.4f over %d voxels; by annulus: %s"
          % (name, rp[0]["time"], 1 - solid / vox, vox, ", ".join("%.3f" % x for x in e)))
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.plot(r, e, "o-")
    ax.set_xlabel("r / R")
    ax.set_ylabel("porosity")
    ax.set_ylim(0, 1)
    ax.set_title("%s: radial porosity, mean %.3f" % (name, 1 - solid / vox))
    fig.tight_layout()
    save(fig, out, name + ".png", also)


def heap(out, also):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ra = rows(out, "repose_angle.csv")
    bh = rows(out, "bed_height.csv")
    t = [float(r["time"]) for r in ra]
    a = [float(r["angle_deg"]) for r in ra]
    tb = [float(r["time"]) for r in bh]
    top = [1e3 * float(r["top"]) for r in bh]
    fh = [1e3 * float(r["fraction_height"]) for r in bh]
    print("heap: angle of repose at %.2f s: %.1f deg (rms %s m over %s columns); top %.1f mm, 95 %% height %.1f mm"
          % (t[-1], a[-1], ra[-1]["rms"], ra[-1]["columns"], top[-1], fh[-1]))
    fig, ax = plt.subplots(2, 1, figsize=(6.4, 5.6), sharex=True)
    ax[0].plot(t, a, "o-", ms=3)
    ax[0].set_ylabel("angle of repose (deg)")
    ax[1].plot(tb, top, label="highest point")
    ax[1].plot(tb, fh, label="95 % of the mass below")
    ax[1].set_ylabel("height (mm)")
    ax[1].set_xlabel("time (s)")
    ax[1].legend()
    ax[0].set_title("heap-pour: angle of repose %.1f deg at %.2f s" % (a[-1], t[-1]))
    fig.tight_layout()
    save(fig, out, "heap-pour.png", also)


PACKINGS = ["spheres", "cylinders", "cubes", "tetrahedra", "crosses2d", "crosses3d"]


def summary(path):
    out = {}
    with open(path) as f:
        for line in f:
            if ":" in line and not line.startswith("#"):
                k, v = line.split(":", 1)
                out[k.strip()] = v.strip()
    return out


def packing(top, also):
    import subprocess
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    exe = os.environ.get("SHAPEDEM", os.path.join("build", "shapedem"))
    fig, ax = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True)
    print("| shape | stopped at | porosity | coordination at the stop | mean coordination, last 0.02 s "
          "| wall time | threads |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for s in PACKINGS:
        out = os.path.join(top, "packing-" + s)
        if not os.path.exists(os.path.join(out, "summary.txt")):
            print("| %s | not run | | | | | |" % s)
            continue
        sm = summary(os.path.join(out, "summary.txt"))
        por = rows(out, "porosity.csv")[-1]
        co = rows(out, "coordination.csv")
        t_end = float(co[-1]["time"])
        late = [float(r["mean"]) for r in co if float(r["time"]) >= t_end - 0.02 - 1e-9]
        st = rows(out, "stats.csv")
        print("| %s | %.3f s | %.3f | %.2f | %.2f (%.2f-%.2f) | %.0f s | %s |"
              % (s, float(sm["simulated_time_s"]), float(por["porosity"]), float(co[-1]["mean"]),
                 sum(late) / len(late), min(late), max(late), float(sm["wall_seconds"]), sm["threads"]))
        ke = [(float(r["time"]), float(r["kinetic_translational"]) + float(r["kinetic_rotational"])) for r in st]
        ke = [x for x in ke if x[1] > 0]  # step 0 is before the insertion
        ax[0].semilogy([x[0] for x in ke], [x[1] for x in ke], label=s)
        ax[1].plot([float(r["time"]) for r in co], [float(r["mean"]) for r in co], label=s)
        name = "packing-%s.png" % s
        subprocess.run([exe, "render", os.path.join(out, "frames.pvd"), "-o", os.path.join(out, name),
                        "--field", "force", "--size", "400x300"], check=True)
        print("wrote", os.path.join(out, name))
        if also:
            shutil.copy(os.path.join(out, name), os.path.join(also, name))
    ax[0].axhline(1e-6, color="k", lw=0.6, ls="--")
    ax[0].set_ylabel("kinetic energy (J)")
    ax[0].legend(fontsize=8)
    ax[1].set_ylabel("mean coordination")
    ax[1].set_xlabel("time (s)")
    ax[0].set_title("packings: settling until kinetic energy < 1e-6 J (dashed)")
    fig.tight_layout()
    save(fig, top, "packing-settle.png", also)


def main(argv):
    if len(argv) < 2 or argv[0] not in ("drum", "drum2d", "bed", "reactor", "heap", "packing"):
        print(__doc__)
        return 2
    out, also = argv[1], argv[2] if len(argv) > 2 else None
    if argv[0] == "drum":
        drum(out, also)
    elif argv[0] == "drum2d":
        drum2d(out, also)
    elif argv[0] == "heap":
        heap(out, also)
    elif argv[0] == "packing":
        packing(out, also)
    else:
        profile(out, also, {"bed": "fixed-bed", "reactor": "reactor-fill"}[argv[0]])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
