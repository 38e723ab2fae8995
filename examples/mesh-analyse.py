#!/usr/bin/python3
"""mesh-analyse.py - the series of the mesh-wall examples, from their output.

  python3 examples/mesh-analyse.py drum   out/mesh-drum    -> torque.csv, torque.png
  python3 examples/mesh-analyse.py hopper out/mesh-hopper  -> discharge.csv, discharge.png
  python3 examples/mesh-analyse.py silo   out/mesh-silo    -> silo.csv, silo.png

drum: the torque the charge exerts on the drum about its axis (y), from the
  drum_ty column of walls.csv (the drum's torque_point is on the axis), and
  its mean once the drum turns steadily.
hopper: the particles that have passed below the floor (z < 0, through the
  orifice) in each frame, and the discharge rate (particles/s and kg/s from
  the mean particle mass) by a straight fit over the middle of the flow.
silo: the vertical force of the grains on the silo (silo_fz: floor and the
  friction on the corrugated wall), which at rest is their weight.
Standard library for the numbers; matplotlib (when installed) for the plots.
"""
import csv
import math
import os
import re
import struct
import sys


def stats(out, name="stats.csv"):
    with open(os.path.join(out, name)) as f:
        rows = list(csv.DictReader(f))
    return rows


def frames(out):
    """(time, path) of each particle frame, from frames.pvd."""
    text = open(os.path.join(out, "frames.pvd")).read()
    res = []
    for m in re.finditer(r'timestep="([^"]+)"[^>]*part="0"[^>]*file="([^"]+)"', text):
        res.append((float(m.group(1)), os.path.join(out, m.group(2))))
    return res


def vtu_arrays(path, names):
    d = open(path, "rb").read()
    head, data = d.split(b'<AppendedData encoding="raw">', 1)
    data = data[data.index(b"_") + 1:]
    res = {}
    for m in re.finditer(rb'<DataArray type="(\w+)" Name="(\w+)"[^>]*offset="(\d+)"', head):
        name = m.group(2).decode()
        if name not in names:
            continue
        fmt = {b"Int32": "i", b"Int64": "q", b"UInt64": "Q", b"Float64": "d"}[m.group(1)]
        off = int(m.group(3))
        n = struct.unpack_from("<Q", data, off)[0] // struct.calcsize(fmt)
        res[name] = struct.unpack_from("<%d%s" % (n, fmt), data, off + 8)
    return res


def plot(path, xs, ys, xlabel, ylabel, title, extra=None):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not installed: no %s" % path)
        return
    fig, ax = plt.subplots(figsize=(6, 3.6))
    ax.plot(xs, ys, lw=1.2)
    if extra:
        extra(ax)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print("wrote %s" % path)


def fit(ts, ys):
    n = len(ts)
    mt, my = sum(ts) / n, sum(ys) / n
    sxx = sum((t - mt) ** 2 for t in ts)
    return sum((t - mt) * (y - my) for t, y in zip(ts, ys)) / sxx if sxx > 0 else 0.0


def drum(out, start=0.5):
    rows = stats(out, "walls.csv")
    t = [float(r["time"]) for r in rows]
    ty = [float(r["drum_ty"]) for r in rows]
    with open(os.path.join(out, "torque.csv"), "w") as f:
        f.write("time_s,torque_y_N_m\n")
        for a, b in zip(t, ty):
            f.write("%.6g,%.6g\n" % (a, b))
    steady = [b for a, b in zip(t, ty) if a >= start + 0.2]
    mean = sum(steady) / len(steady) if steady else float("nan")
    print("drum: mean torque about the axis from t = %.2f s: %.4g N m (%d rows)" % (start + 0.2, mean, len(steady)))
    plot(os.path.join(out, "torque.png"), t, ty, "time (s)", "torque on the drum about y (N m)",
         "mesh-drum: torque on the drum, mean %.3g N m turning" % mean,
         lambda ax: ax.axvline(0.3, color="grey", ls=":", lw=1))


def hopper(out):
    fr = frames(out)
    ts, below, mass = [], [], None
    for t, p in fr:
        a = vtu_arrays(p, ("position", "radius"))
        z = a["position"][2::3]
        ts.append(t)
        below.append(sum(1 for v in z if v < 0.0))
        if mass is None and a.get("radius"):
            # the example's glass spheres: 2500 kg/m^3
            mass = 2500.0 * sum(4.0 / 3.0 * math.pi * r ** 3 for r in a["radius"]) / len(a["radius"])
    n_total = len(vtu_arrays(fr[0][1], ("position",))["position"]) // 3 if fr else 0
    with open(os.path.join(out, "discharge.csv"), "w") as f:
        f.write("time_s,discharged\n")
        for a, b in zip(ts, below):
            f.write("%.6g,%d\n" % (a, b))
    # the middle of the flow: between 20 % and 80 % of what left
    last = below[-1] if below else 0
    mid = [(a, b) for a, b in zip(ts, below) if 0.2 * last <= b <= 0.8 * last]
    rate = fit([a for a, _ in mid], [b for _, b in mid]) if len(mid) >= 2 else float("nan")
    msg = "hopper: %d of %d particles discharged; rate %.4g particles/s over the middle of the flow" % (
        last, n_total, rate)
    if mass:
        msg += " (%.4g kg/s)" % (rate * mass)
    print(msg)
    plot(os.path.join(out, "discharge.png"), ts, below, "time (s)", "particles below the floor",
         "mesh-hopper: discharge, %.3g particles/s" % rate)


def silo(out):
    rows = stats(out)
    t = [float(r["time"]) for r in rows]
    fz = [float(r["silo_fz"]) for r in rows]
    ke = [float(r["kinetic_translational"]) for r in rows]
    with open(os.path.join(out, "silo.csv"), "w") as f:
        f.write("time_s,vertical_force_N,kinetic_J\n")
        for a, b, c in zip(t, fz, ke):
            f.write("%.6g,%.6g,%.6g\n" % (a, b, c))
    # at rest the silo (floor and wall) carries the whole weight of the grains
    print("silo: vertical force on the silo %.4g N at t = %.3g s (peak %.4g N during the pour), kinetic energy %.3g J"
          % (fz[-1], t[-1], min(fz), ke[-1]))
    plot(os.path.join(out, "silo.png"), t, fz, "time (s)", "vertical force on the silo (N)",
         "mesh-silo: grains poured into a corrugated silo",
         lambda ax: ax.axhline(fz[-1], color="grey", ls=":", lw=1))


def main(argv):
    if len(argv) != 2 or argv[0] not in ("drum", "hopper", "silo"):
        print(__doc__)
        return 2
    {"drum": drum, "hopper": hopper, "silo": silo}[argv[0]](argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
