#!/usr/bin/env python3
"""hopper-grid-analyse.py DIR [--orifice X0 X1] [--png FILE]

Analysis of a flat-bottomed hopper run on the grid solver (§4.2 of [Naderi 2024],
docs/references.md; examples/hopper-grid.yaml). Reads what `shapedem run` wrote into DIR:

- stats.csv (columns time, in_domain, discharged, discharged_mass, written by
  solver grid) -> the discharge curve: mass fraction discharged against the
  time since the outlet opened (summary.txt gives the opening time);
- the last particles_NNNNNN.vtu frame -> the residual heap: on each side of
  the orifice the free surface (the top of each column of particles one
  diameter wide, between the wall and the orifice edge) is fitted with a
  least-squares line; its inclination is the dead zone's residual angle
  ([Naderi 2024] reports 18 degrees at 6 s).

Writes into DIR: discharge.csv, discharge.png (matplotlib, Agg backend) and
dead-zones.txt, and prints a summary, including the discharge rate over
20-50 % and 50-80 % discharged and how far each is from their mean (a steady
flow keeps them within a few per cent; Beverloo). Exit status 2 on bad input
(missing files, no discharge), 0 otherwise. Only the standard library and
matplotlib (Debian: python3-matplotlib, which scripts/deps.sh installs) are used.
"""
import csv
import math
import os
import re
import struct
import sys


def fail(msg):
    print("hopper-grid-analyse: " + msg, file=sys.stderr)
    sys.exit(2)


def read_summary(path):
    out = {}
    if not os.path.exists(path):
        return out
    with open(path) as fh:
        for line in fh:
            if ":" in line and not line.startswith("#"):
                k, v = line.split(":", 1)
                out[k.strip()] = v.strip()
    return out


def read_vtu_points(path):
    """Points, radius and id arrays of a particles_NNNNNN.vtu frame
    (docs/output.md: appended raw binary, UInt64 headers, little-endian)."""
    with open(path, "rb") as fh:
        data = fh.read()
    marker = data.find(b'<AppendedData encoding="raw">')
    if marker < 0:
        fail("%s: no appended data (not a shapedem frame?)" % path)
    start = data.find(b"_", marker) + 1
    head = data[:marker].decode("utf-8", "replace")
    npts = int(re.search(r'NumberOfPoints="(\d+)"', head).group(1))
    arrays = {}
    for m in re.finditer(r"<DataArray([^>]*)>", head):
        attrs = m.group(1)
        name = re.search(r'Name="([^"]*)"', attrs)
        off = re.search(r'offset="(\d+)"', attrs)
        typ = re.search(r'type="([^"]*)"', attrs)
        ncomp = re.search(r'NumberOfComponents="(\d+)"', attrs)
        if not (name and off and typ):
            continue
        arrays[name.group(1)] = (int(off.group(1)), typ.group(1), int(ncomp.group(1)) if ncomp else 1)

    def get(name):
        off, typ, nc = arrays[name]
        at = start + off
        (nbytes,) = struct.unpack_from("<Q", data, at)
        fmt = {"Float64": "d", "UInt64": "Q", "Int32": "i"}[typ]
        vals = struct.unpack_from("<%d%s" % (nbytes // struct.calcsize(fmt), fmt), data, at + 8)
        return [vals[i * nc:(i + 1) * nc] for i in range(len(vals) // nc)] if nc > 1 else list(vals)

    # the points array is the one without a Name in <Points>, or "Points"
    pts_name = "Points" if "Points" in arrays else None
    if pts_name is None:
        m = re.search(r"<Points>\s*<DataArray([^>]*)>", head)
        off = int(re.search(r'offset="(\d+)"', m.group(1)).group(1))
        arrays["Points"] = (off, "Float64", 3)
    pts = get("Points")
    radius = get("radius") if "radius" in arrays else [0.0] * npts
    if len(pts) != npts:
        fail("%s: expected %d points, read %d" % (path, npts, len(pts)))
    return pts, radius


def dead_zone_angles(pts, radius, width, x0, x1):
    """Least-squares slope of the heap's top on each side of [x0, x1]."""
    if not pts:
        return None, None, [], []
    d = 2 * max(radius)
    nb = max(1, int(width / d))
    top = [None] * nb
    for (x, _, z), r in zip(pts, radius):
        b = int(x / width * nb)
        if 0 <= b < nb and (top[b] is None or z + r > top[b]):
            top[b] = z + r
    sides = []
    for side in (0, 1):
        xs, zs = [], []
        for b in range(nb):
            xc = (b + 0.5) * width / nb
            if top[b] is None:
                continue
            # the columns between the wall and the orifice edge, leaving out
            # the one against the wall and the one over the edge
            if side == 0 and d <= xc <= x0 - d:
                xs.append(x0 - xc)
            elif side == 1 and x1 + d <= xc <= width - d:
                xs.append(xc - x1)
            else:
                continue
            zs.append(top[b])
        if len(xs) < 2:
            sides.append((None, xs, zs))
            continue
        mx, mz = sum(xs) / len(xs), sum(zs) / len(zs)
        sxx = sum((a - mx) ** 2 for a in xs)
        sxz = sum((a - mx) * (b - mz) for a, b in zip(xs, zs))
        slope = sxz / sxx if sxx > 0 else 0.0
        sides.append((math.degrees(math.atan(slope)), xs, zs))
    return sides[0], sides[1], top, nb


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if args else 2)
    out = args[0]
    orifice = None
    png = os.path.join(out, "discharge.png")
    k = 1
    while k < len(args):
        if args[k] == "--orifice" and k + 2 < len(args):
            orifice = (float(args[k + 1]), float(args[k + 2]))
            k += 3
        elif args[k] == "--png" and k + 1 < len(args):
            png = args[k + 1]
            k += 2
        else:
            fail("unknown option %s" % args[k])
    stats = os.path.join(out, "stats.csv")
    if not os.path.exists(stats):
        fail("%s: no stats.csv (run shapedem run SCENE -o %s first)" % (out, out))
    summary = read_summary(os.path.join(out, "summary.txt"))
    t_open = float(summary.get("grid_outlet_time_s", "nan"))

    rows = []
    with open(stats) as fh:
        reader = csv.DictReader(fh)
        need = {"time", "in_domain", "discharged", "discharged_mass"}
        if not need <= set(reader.fieldnames or []):
            fail("%s: columns %s missing (a solver grid run writes them)" %
                 (stats, ", ".join(sorted(need - set(reader.fieldnames or [])))))
        for r in reader:
            rows.append((float(r["time"]), int(r["in_domain"]), int(r["discharged"]), float(r["discharged_mass"])))
    if not rows:
        fail("%s: no rows" % stats)
    if math.isnan(t_open):
        # before the first discharge: the last row with nothing discharged
        first = next((i for i, r in enumerate(rows) if r[2] > 0), None)
        t_open = rows[first - 1][0] if first else rows[0][0]
    before = [r for r in rows if r[0] <= t_open + 1e-12]
    at_open = before[-1] if before else rows[0]
    last = rows[-1]
    if last[2] == 0:
        fail("%s: nothing was discharged (did the outlet open before the run ended?)" % stats)
    m_particle = last[3] / last[2]
    m0 = (at_open[1] + at_open[2]) * m_particle  # in the hopper when the outlet opened
    curve = [(r[0] - t_open, r[3] / m0) for r in rows if r[0] >= at_open[0]]
    with open(os.path.join(out, "discharge.csv"), "w") as fh:
        fh.write("time_since_open_s,mass_fraction_discharged\n")
        for t, f in curve:
            fh.write("%.6f,%.6f\n" % (t, f))

    def time_at(frac):
        for (ta, fa), (tb, fb) in zip(curve, curve[1:]):
            if fb >= frac:
                return ta + (frac - fa) / (fb - fa) * (tb - ta) if fb > fa else tb
        return None

    t20, t50, t80 = time_at(0.2), time_at(0.5), time_at(0.8)
    lines = ["hopper: %d particles when the outlet opened at t = %.4g s (%.4g kg); %.1f %% discharged after %.3g s" %
             (at_open[1] + at_open[2], t_open, m0, 100 * curve[-1][1], curve[-1][0])]
    if t80 is not None:
        r1, r2 = 0.3 / (t50 - t20), 0.3 / (t80 - t50)
        mean = 0.5 * (r1 + r2)
        lines.append("discharge rate: 20-50 %% %.4f /s, 50-80 %% %.4f /s (each %.1f %% from their mean); %.4g kg/s" %
                     (r1, r2, 100 * abs(r1 - mean) / mean, 0.6 * m0 / (t80 - t20)))
    elif t50 is not None:
        lines.append("discharge rate: 20-50 %% %.4f /s (80 %% not reached)" % (0.3 / (t50 - t20)))

    # residual heap from the last frame
    frames = sorted(f for f in os.listdir(out) if re.fullmatch(r"particles_\d{6}\.vtu", f))
    angles = None
    if frames:
        pts, radius = read_vtu_points(os.path.join(out, frames[-1]))
        xlo = float(summary.get("grid_domain_min_m", "nan nan nan").split()[0])
        xhi = float(summary.get("grid_domain_max_m", "nan nan nan").split()[0])
        if math.isnan(xlo) or math.isnan(xhi):
            fail("%s: summary.txt lacks grid_domain_min_m / grid_domain_max_m (a solver grid run writes them)" % out)
        if orifice is None:
            orifice = tuple(float(v) for v in summary.get("grid_outlet_x_m", "nan nan").split()[:2])
        if not any(math.isnan(v) for v in orifice) and pts:
            # x measured from the box's xmin wall
            shifted = [(p[0] - xlo, p[1], p[2]) for p in pts]
            left, right, _, _ = dead_zone_angles(shifted, radius, xhi - xlo, orifice[0] - xlo, orifice[1] - xlo)
            angles = (left[0], right[0])
            with open(os.path.join(out, "dead-zones.txt"), "w") as fh:
                fh.write("# residual free surface beside the orifice, frame %s (%d particles)\n" % (frames[-1], len(pts)))
                fh.write("# least-squares line through the top of each column one diameter wide\n")
                for name, side in (("left", left), ("right", right)):
                    fh.write("%s_angle_deg: %s\n" % (name, "nan" if side[0] is None else "%.2f" % side[0]))
                    fh.write("%s_columns: %d\n" % (name, len(side[1])))
            lines.append("dead zones (%s): residual angle left %s deg, right %s deg ([Naderi 2024]: 18 deg)" %
                         (frames[-1], "n/a" if angles[0] is None else "%.1f" % angles[0],
                          "n/a" if angles[1] is None else "%.1f" % angles[1]))

    try:
        import matplotlib
    except ImportError:  # one line, not a traceback
        sys.exit("%s: needs the Python module matplotlib: install the Debian package "
                 "python3-matplotlib (apt-get install python3-matplotlib, or make deps)" % sys.argv[0])

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 3.6))
    ax.plot([c[0] for c in curve], [c[1] for c in curve], lw=1.8, label="shapedem, solver grid")
    ax.set_xlabel("time since the orifice opened (s)")
    ax.set_ylabel("mass fraction discharged")
    ax.set_ylim(0, 1)
    ax.grid(alpha=0.3)
    ax.set_title("Flat-bottomed hopper, Set II (§4.2 of [Naderi 2024])")
    ax.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    lines.append("wrote %s, %s%s" % (os.path.join(out, "discharge.csv"), png,
                                     ", " + os.path.join(out, "dead-zones.txt") if angles else ""))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
