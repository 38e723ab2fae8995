#!/usr/bin/python3
"""dump_check.py ROOT DIR DT [PERIODIC] — trajectory.dump against the run's frames.

DIR is the output directory of a run with `output.formats: [vtk, dump]`.
trajectory.dump is read with the small parser below (the LAMMPS dump layout:
ITEM: TIMESTEP / NUMBER OF ATOMS / BOX BOUNDS / ATOMS, docs/output.md) and
held against the particle frames that frames.pvd lists, read by
scripts/frame_to_csv.py (17 digits, in id order):

- one snapshot per frame, TIMESTEP = the frame's time / DT (to 1e-9 of a step);
- the column line of docs/output.md, as many lines as NUMBER OF ATOMS, ids
  increasing and the frame's count;
- x y z, vx vy vz, omegax omegay omegaz and radius equal to the frame's
  values (the same doubles), quatw..quatk those of the frame;
- BOX BOUNDS: "pp" on the axes PERIODIC names (e.g. "y") and "ss" on the
  others, every particle inside the bounds of the ss axes.

Prints one line per check, exit 1 on any failure.
"""
import csv
import io
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

COLUMNS = ("id type x y z vx vy vz fx fy fz omegax omegay omegaz radius "
           "quatw quati quatj quatk shape").split()


def parse_dump(path):
    """[(step, bounds_kind, [(lo, hi)] * 3, [row dict])] of every snapshot."""
    lines = open(path).read().split("\n")
    snaps, i = [], 0
    while i < len(lines) and lines[i]:
        assert lines[i] == "ITEM: TIMESTEP", "line %d: %r" % (i + 1, lines[i])
        step = int(lines[i + 1])
        assert lines[i + 2] == "ITEM: NUMBER OF ATOMS", "line %d" % (i + 3)
        n = int(lines[i + 3])
        head = lines[i + 4].split()
        assert head[:3] == ["ITEM:", "BOX", "BOUNDS"] and len(head) == 6, "line %d" % (i + 5)
        bounds = [tuple(float(v) for v in lines[i + 5 + k].split()) for k in range(3)]
        cols = lines[i + 8].split()
        assert cols[:2] == ["ITEM:", "ATOMS"] and cols[2:] == COLUMNS, "line %d: %r" % (i + 9, lines[i + 8])
        rows = []
        for k in range(n):
            vals = lines[i + 9 + k].split()
            assert len(vals) == len(COLUMNS), "line %d" % (i + 10 + k)
            rows.append(dict(zip(COLUMNS, vals)))
        snaps.append((step, head[3:], bounds, rows))
        i += 9 + n
    return snaps


def main():
    root, d, dt = sys.argv[1], sys.argv[2], float(sys.argv[3])
    periodic = sys.argv[4] if len(sys.argv) > 4 else ""
    passed = failed = 0

    def check(name, ok, detail=""):
        nonlocal passed, failed
        passed += bool(ok)
        failed += not ok
        print(("PASS " if ok else "FAIL ") + name + ("" if ok or not detail else " (%s)" % detail))

    tag = os.path.basename(d.rstrip("/"))
    try:
        snaps = parse_dump(os.path.join(d, "trajectory.dump"))
        check("%s: trajectory.dump parses: %d snapshots" % (tag, len(snaps)), True)
    except (AssertionError, ValueError, IndexError, OSError) as e:
        check("%s: trajectory.dump parses" % tag, False, str(e))
        return 1
    sets = [s for s in ET.parse(os.path.join(d, "frames.pvd")).getroot().iter("DataSet") if s.get("part") == "0"]
    check("%s: one snapshot per frame (%d frames)" % (tag, len(sets)), len(sets) == len(snaps))
    bad = []
    for f, (s, snap) in enumerate(zip(sets, snaps)):
        step, kinds, bounds, rows = snap
        t = float(s.get("timestep"))
        out = subprocess.run(["/usr/bin/python3", os.path.join(root, "scripts", "frame_to_csv.py"),
                              os.path.join(d, s.get("file"))], capture_output=True, text=True)
        frame = list(csv.DictReader(line for line in io.StringIO(out.stdout) if not line.startswith("#")))
        why = []
        if out.returncode != 0:
            why.append("frame_to_csv: " + out.stderr.strip())
        if abs(step - t / dt) > 1e-9 * max(1.0, step):
            why.append("step %d, frame time %.17g" % (step, t))
        if len(frame) != len(rows):
            why.append("%d atoms, %d in the frame" % (len(rows), len(frame)))
        ids = [int(r["id"]) for r in rows]
        if ids != sorted(set(ids)):
            why.append("ids not increasing")
        want = ["pp" if a in periodic else "ss" for a in "xyz"]
        if kinds != want:
            why.append("bounds %s, want %s" % (kinds, want))
        pairs = (("x", "x"), ("y", "y"), ("z", "z"), ("vx", "vx"), ("vy", "vy"), ("vz", "vz"),
                 ("omegax", "wx"), ("omegay", "wy"), ("omegaz", "wz"))
        for r, c in zip(rows, frame):
            diff = [a for a, b in pairs if float(r[a]) != float(c[b])]
            if c["radius"] and float(r["radius"]) != float(c["radius"]):
                diff.append("radius")
            if c["qw"] and any(float(r[a]) != float(c[b]) for a, b in
                               (("quatw", "qw"), ("quati", "qx"), ("quatj", "qy"), ("quatk", "qz"))):
                diff.append("quat")
            for k, a in enumerate("xyz"):
                rad = float(r["radius"])
                if want[k] == "ss" and not bounds[k][0] <= float(r[a]) - rad <= float(r[a]) + rad <= bounds[k][1]:
                    diff.append("outside the %s bounds" % a)
            if diff:
                why.append("id %s: %s" % (r["id"], ", ".join(diff)))
                break
        if why:
            bad.append("frame %d: %s" % (f, "; ".join(why)))
    check("%s: every snapshot is its frame: step, count, ids, positions, velocities, spins, radii, "
          "orientations, bounds" % tag, not bad, "; ".join(bad)[:1500])
    print("dump_check %s: %d passed, %d failed" % (tag, passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
