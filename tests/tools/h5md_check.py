#!/usr/bin/python3
"""h5md_check.py ROOT DIR DT [PERIODIC] — trajectory.h5md against the standard and the run's frames.
   h5md_check.py --same A B — two trajectory.h5md files hold the same groups, attributes and values.

DIR is the output directory of a run with `output.formats: [vtk, h5md]`.
trajectory.h5md is read with h5py (python3-h5py) and held to what H5MD 1.1
requires (docs/output.md): /h5md with version [1, 1] and the groups author
(name) and creator (name, version); /particles/all/box with the attributes
dimension and boundary ("periodic" on the axes PERIODIC names, e.g. "y",
"none" elsewhere; edges and offset where any is periodic); every element a
group of step, time and value, all sharing one step and one time dataset.
Then against the particle frames that frames.pvd lists, read by
scripts/frame_to_csv.py (17 digits, in id order): one frame each, the step
= the frame's time / DT, the time the frame's exactly; the first n rows
(n the frame's particles) have increasing ids and the frame's positions,
velocities and radii (the same doubles; D = dimension components), the
rows after them id -1 and NaN positions.

With --same (restarts, MPI ranks): every dataset of A is in B with the same
shape, type and values (NaN where the other has NaN) and every attribute
equal, and B has nothing more.

Prints one line per check, exit 1 on any failure.
"""
import csv
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

ELEMENTS = {"position": "D", "velocity": "D", "force": "D", "species": 1, "id": 1,
            "orientation": 4, "angular_velocity": 3, "radius": 1, "shape": 1}


def same(a, b):
    """The paths where the files a and b differ (empty: none)."""
    fa, fb = h5py.File(a, "r"), h5py.File(b, "r")
    names = []
    fa.visit(names.append)
    other = []
    fb.visit(other.append)
    diff = sorted(set(names) ^ set(other))
    for n in names:
        oa, ob = fa.get(n), fb.get(n)
        if ob is None:
            continue
        if {k: np.asarray(v).tolist() for k, v in oa.attrs.items()} != \
                {k: np.asarray(v).tolist() for k, v in ob.attrs.items()}:
            diff.append(n + " (attributes)")
        if isinstance(oa, h5py.Dataset):
            va, vb = oa[()], ob[()]
            if va.shape != vb.shape or va.dtype != vb.dtype or not np.array_equal(va, vb, equal_nan=va.dtype.kind == "f"):
                diff.append(n)
    return diff


def main():
    if sys.argv[1] == "--same":
        diff = same(sys.argv[2], sys.argv[3])
        print(("PASS" if not diff else "FAIL") + " the same groups, attributes and values"
              + ("" if not diff else " (%s)" % ", ".join(diff[:10])))
        return 1 if diff else 0
    root, d, dt = sys.argv[1], sys.argv[2], float(sys.argv[3])
    periodic = sys.argv[4] if len(sys.argv) > 4 else ""
    passed = failed = 0
    tag = os.path.basename(d.rstrip("/"))

    def check(name, ok, detail=""):
        nonlocal passed, failed
        passed += bool(ok)
        failed += not ok
        print(("PASS " if ok else "FAIL ") + "%s: %s" % (tag, name) + ("" if ok or not detail else " (%s)" % detail))

    try:
        f = h5py.File(os.path.join(d, "trajectory.h5md"), "r")
    except OSError as e:
        check("trajectory.h5md opens in h5py", False, str(e))
        return 1
    h = f.get("h5md")
    ok = (h is not None and list(h.attrs.get("version", [])) == [1, 1] and "name" in h["author"].attrs
          and h["creator"].attrs.get("name") == b"shapedem" and "version" in h["creator"].attrs)
    check("/h5md: version [1, 1], author name, creator name and version", ok)
    box = f["particles/all/box"]
    dim = int(box.attrs["dimension"])
    want = [b"periodic" if a in periodic else b"none" for a in "xyz"[:dim]]
    ok = list(box.attrs["boundary"]) == want and (not periodic or ("edges" in box and box["edges"].shape == (dim,)))
    check("box: dimension %d, boundary %s%s" % (dim, [b.decode() for b in want], ", edges" if periodic else ""), ok)
    all_ = f["particles/all"]
    step, time = all_["position/step"], all_["position/time"]
    shapes = {}
    ok = True
    for name, c in ELEMENTS.items():
        g = all_.get(name)
        c = dim if c == "D" else c
        if g is None or not {"step", "time", "value"} <= set(g):
            ok = False
            continue
        v = g["value"]
        shapes[name] = v.shape
        ok = ok and g["step"].id == step.id and g["time"].id == time.id and v.shape[0] == step.shape[0]
        ok = ok and (v.ndim == 2 if c == 1 else v.ndim == 3 and v.shape[2] == c)
    check("%d elements, each of step, time and value, one step and time shared: %s" % (len(ELEMENTS), shapes), ok)

    sets = [s for s in ET.parse(os.path.join(d, "frames.pvd")).getroot().iter("DataSet") if s.get("part") == "0"]
    steps, times = step[()], time[()]
    check("one frame per particle frame (%d)" % len(sets), len(sets) == len(steps))
    x, vel, rad, ids = all_["position/value"], all_["velocity/value"], all_["radius/value"], all_["id/value"]
    bad = []
    for k, s in enumerate(sets[:len(steps)]):
        t = float(s.get("timestep"))
        out = subprocess.run(["/usr/bin/python3", os.path.join(root, "scripts", "frame_to_csv.py"),
                              os.path.join(d, s.get("file"))], capture_output=True, text=True)
        frame = list(csv.DictReader(line for line in out.stdout.splitlines() if not line.startswith("#")))
        n = len(frame)
        why = []
        if times[k] != t or abs(steps[k] - t / dt) > 1e-9 * max(1.0, steps[k]):
            why.append("step %d time %.17g, frame time %.17g" % (steps[k], times[k], t))
        fid = ids[k]
        if n > len(fid) or list(fid[:n]) != sorted(set(fid[:n].tolist())) or np.any(fid[n:] != -1):
            why.append("ids %s" % fid.tolist())
        fx, fv, fr = x[k], vel[k], rad[k]
        for i, row in enumerate(frame):
            want_x = [float(row[a]) for a in "xyz"[:dim]]
            want_v = [float(row[a]) for a in ("vx", "vy", "vz")[:dim]]
            if list(fx[i]) != want_x or list(fv[i]) != want_v or (row["radius"] and fr[i] != float(row["radius"])):
                why.append("row %d (id %d): %s against %s" % (i, fid[i], fx[i].tolist(), want_x))
                break
        if n < fx.shape[0] and not np.all(np.isnan(fx[n:])):
            why.append("rows past %d not NaN" % n)
        if why:
            bad.append("frame %d: %s" % (k, "; ".join(why)))
    check("every frame is its particle frame: step, time, ids, positions, velocities, radii, fill past the count",
          not bad, "; ".join(bad)[:1500])
    print("h5md_check %s: %d passed, %d failed" % (tag, passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
