#!/usr/bin/python3
"""vtk_readers.py DIR[:PERIOD,...] ... — a run's files opened with VTK's own readers.

Each DIR is the output directory of a finished `shapedem run` whose scene
wrote a checkpoint at its last step. frames.pvd is parsed (a VTK Collection;
VTK itself has no reader for it outside ParaView) and every file it lists is
opened with vtkXMLUnstructuredGridReader (.vtu) or vtkXMLPolyDataReader
(.vtp), with every message of VTK captured (a vtkStringOutputWindow and
observers of the readers' error and warning events): any message fails.
Then the data are held against the run:

- frames.pvd: as many frames as summary.txt's `frames`, parts 0, 1 (and 2
  with shapes) of each, times increasing, the last the checkpoint's time;
- particles: points = VERTEX cells = the frame's particles, the arrays and
  components of docs/output.md, ids distinct; the last frame's ids,
  positions, velocities, radii, materials and shapes equal the
  checkpoint's, bit for bit (positions up to a period of the box on its
  periodic axes, PERIOD values in metres; frames wrap the images);
  field data shape_names and material_names as the checkpoint's scene;
- walls: cells with the cell arrays wall, kind and force, every wall of
  summary.txt present, kinds 0 to 3;
- shapes: cells carrying the particle arrays, the ids of the cells those
  of the particle frame with the same shape index each.

A frame damaged on purpose (its point count raised) must be reported by the
capture, so the check can fail. Prints one line per check, exit 1 on any
failure.
"""
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np
from vtkmodules.vtkCommonCore import vtkCommand, vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy

POINT_ARRAYS = {"id": 1, "radius": 1, "velocity": 3, "angular_velocity": 3, "force": 3,
                "material": 1, "orientation": 4, "axis": 3, "shape": 1}
WALL_ARRAYS = {"wall": 1, "kind": 1, "force": 3}
VTK_VERTEX = 1

failed = 0
passed = 0


def check(name, ok, detail=""):
    global failed, passed
    if ok:
        passed += 1
        print("PASS " + name)
    else:
        failed += 1
        print("FAIL " + name + (" (%s)" % detail if detail else ""))


def read(path):
    """The dataset and the messages VTK gave while reading it."""
    reader = vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtkXMLPolyDataReader()
    events = []
    for ev in (vtkCommand.ErrorEvent, vtkCommand.WarningEvent):
        reader.AddObserver(ev, lambda obj, e, events=events: events.append(e))
    window = vtkStringOutputWindow()  # a fresh one per file: its text is this file's
    vtkOutputWindow.SetInstance(window)
    reader.SetFileName(path)
    reader.Update()
    text = window.GetOutput().strip()
    msgs = events + ([text] if text else [])
    if reader.GetErrorCode():
        msgs.append("error code %d" % reader.GetErrorCode())
    return reader.GetOutput(), msgs


def arrays(data):
    return {data.GetArrayName(i): data.GetArray(i) for i in range(data.GetNumberOfArrays())}


def strings(field, name):
    a = field.GetAbstractArray(name)
    return None if a is None else [a.GetValue(i) for i in range(a.GetNumberOfValues())]


def summary(d):
    out = {}
    for line in open(os.path.join(d, "summary.txt")):
        k, sep, v = line.partition(":")
        if sep:
            out[k.strip()] = v.strip()
    return out


def names(ds):
    return [bytes(r).rstrip(b"\0").decode() for r in ds[()]]


def run_dir(spec):
    d, _, per = spec.partition(":")
    periods = [float(p) for p in per.split(",") if p]
    tag = os.path.basename(d.rstrip("/"))
    summ = summary(d)
    root = ET.parse(os.path.join(d, "frames.pvd")).getroot()
    sets = root.findall("./Collection/DataSet")
    check("%s: frames.pvd is a VTK Collection of %d datasets" % (tag, len(sets)),
          root.tag == "VTKFile" and root.get("type") == "Collection" and len(sets) > 0)
    parts = sorted({int(s.get("part")) for s in sets})
    frames = len(sets) // len(parts)
    check("%s: %d frames of parts %s, as summary.txt's frames: %s" % (tag, frames, parts, summ.get("frames")),
          frames == int(summ["frames"]) and len(sets) == frames * len(parts) and parts[:2] == [0, 1])
    times = [float(s.get("timestep")) for s in sets if s.get("part") == "0"]
    check("%s: frame times increase" % tag, all(a < b for a, b in zip(times, times[1:])))
    ck_name = "checkpoint-%06d.h5" % int(summ["step"])
    ck = h5py.File(os.path.join(d, ck_name), "r")
    check("%s: the last frame's time %.17g is the checkpoint's %.17g" % (tag, times[-1], ck.attrs["time"]),
          times[-1] == float(ck.attrs["time"]))
    msgs_all = []
    by_frame = {}
    for s in sets:
        path = os.path.join(d, s.get("file"))
        data, msgs = read(path)
        msgs_all += ["%s: %s" % (s.get("file"), m) for m in msgs]
        by_frame.setdefault(times.index(float(s.get("timestep"))), {})[int(s.get("part"))] = data
    check("%s: VTK read all %d files without a message" % (tag, len(sets)), not msgs_all,
          "; ".join(msgs_all)[:2000])

    nwalls = int(summ["walls"])
    shape_names = names(ck["scene/shape_names"]) if "scene/shape_names" in ck else []
    mat_names = names(ck["scene/material_names"]) if "scene/material_names" in ck else None
    bad = {"particles": [], "walls": [], "shapes": []}
    for f in sorted(by_frame):
        p = by_frame[f][0]
        n = p.GetNumberOfPoints()
        pa = arrays(p.GetPointData())
        ok = (p.GetNumberOfCells() == n and set(pa) == set(POINT_ARRAYS)
              and all(pa[k].GetNumberOfComponents() == c and pa[k].GetNumberOfTuples() == n
                      for k, c in POINT_ARRAYS.items())
              and all(p.GetCellType(i) == VTK_VERTEX for i in range(n)))
        ids = vtk_to_numpy(pa["id"]) if "id" in pa else np.zeros(0)
        ok = ok and len(set(ids.tolist())) == n
        fd = p.GetFieldData()
        ok = ok and strings(fd, "shape_names") == shape_names
        if mat_names is not None:
            ok = ok and strings(fd, "material_names") == mat_names
        if not ok:
            bad["particles"].append(f)
        w = by_frame[f][1]
        wa = arrays(w.GetCellData())
        kinds = set(vtk_to_numpy(wa["kind"]).tolist()) if "kind" in wa else set()
        ok = (set(wa) == set(WALL_ARRAYS) and w.GetNumberOfCells() > 0
              and all(wa[k].GetNumberOfComponents() == c and wa[k].GetNumberOfTuples() == w.GetNumberOfCells()
                      for k, c in WALL_ARRAYS.items())
              and set(vtk_to_numpy(wa["wall"]).tolist()) == set(range(nwalls)) and kinds <= {0, 1, 2, 3})
        if not ok:
            bad["walls"].append(f)
        if 2 in by_frame[f]:
            sh = by_frame[f][2]
            sa = arrays(sh.GetCellData())
            ok = set(sa) == set(POINT_ARRAYS) and sh.GetNumberOfCells() > 0 and sh.GetNumberOfPoints() > 0
            if ok:
                cid = vtk_to_numpy(sa["id"]).tolist()
                cshape = vtk_to_numpy(sa["shape"]).tolist()
                pshape = dict(zip(ids.tolist(), vtk_to_numpy(pa["shape"]).tolist()))
                ok = set(cid) == set(ids.tolist()) and all(pshape[i] == s for i, s in zip(cid, cshape))
            if not ok:
                bad["shapes"].append(f)
    check("%s: particle frames: points, vertex cells, the %d arrays, distinct ids, shape and material names"
          % (tag, len(POINT_ARRAYS)), not bad["particles"], "frames %s" % bad["particles"])
    check("%s: wall frames: cells with wall, kind, force; all %d walls" % (tag, nwalls), not bad["walls"],
          "frames %s" % bad["walls"])
    if 2 in parts:
        check("%s: shape frames: cells with the particle arrays, every particle's id and shape" % tag,
              not bad["shapes"], "frames %s" % bad["shapes"])

    # the last frame against the checkpoint of the same step
    p = by_frame[frames - 1][0]
    pa = arrays(p.GetPointData())
    own = int(ck["particles/n"][()]) if "particles/n" in ck else len(ck["particles/id"])
    cid = ck["particles/id"][:own]
    order = np.argsort(cid)
    vid = vtk_to_numpy(pa["id"])
    vorder = np.argsort(vid)
    x = vtk_to_numpy(p.GetPoints().GetData())[vorder]
    cx = ck["particles/x"][:own][order]
    dx = np.abs(x - cx)
    wrapped = np.zeros(dx.shape, dtype=bool)
    for L in periods:
        wrapped |= np.abs(dx - L) <= 1e-12 * max(L, 1.0)
    same = {
        "ids": np.array_equal(vid[vorder], cid[order]),
        "positions": bool(np.all((dx == 0) | wrapped)),
        "velocities": np.array_equal(vtk_to_numpy(pa["velocity"])[vorder], ck["particles/v"][:own][order]),
        "radii": np.array_equal(vtk_to_numpy(pa["radius"])[vorder], ck["particles/radius"][:own][order]),
        "materials": np.array_equal(vtk_to_numpy(pa["material"])[vorder], ck["particles/material"][:own][order]),
        "shapes": np.array_equal(vtk_to_numpy(pa["shape"])[vorder], ck["particles/shape"][:own][order]),
    }
    check("%s: last frame (%d particles) equals %s: %s" % (tag, own, ck_name, ", ".join(sorted(same))),
          len(vid) == own and all(same.values()), ", ".join(k for k, v in same.items() if not v))
    return os.path.join(d, sets[0].get("file"))


def damaged(path, tmp):
    """A copy of a particle frame whose header claims one point more."""
    raw = open(path, "rb").read()
    head, sep, rest = raw.partition(b'NumberOfPoints="')
    n, q, rest = rest.partition(b'"')
    out = os.path.join(tmp, "damaged.vtu")
    open(out, "wb").write(head + sep + str(int(n) + 1).encode() + q + rest)
    _, msgs = read(out)
    check("a frame damaged on purpose (NumberOfPoints %d -> %d) is reported by the capture: %s"
          % (int(n), int(n) + 1, (msgs[0] if msgs else "nothing").splitlines()[0][:120]), bool(msgs))


def main():
    first = None
    for spec in sys.argv[1:]:
        f = run_dir(spec)
        first = first or f
    if first:
        damaged(first, os.environ.get("TMPDIR", "/tmp"))
    print("vtk_readers: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
