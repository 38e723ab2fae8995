#!/usr/bin/python3
"""make_meshes.py - the triangle meshes of the mesh-wall examples and the
benchmark, written as binary STL (in metres), so that no large mesh file is
committed.

Every mesh is wound so that the right-hand normals of its facets point to
the side the particles are on (inside a drum, a box, a hopper or a silo;
above a plane). shapedem re-orients inconsistent windings anyway (with a
warning), and a closed mesh is taken as holding particles inside unless the
wall says side: outside.

Usage:
  scripts/make_meshes.py drum OUT.stl [--radius R --length L --segments N]
  scripts/make_meshes.py hopper OUT.stl [--radius R --height H --orifice D --segments N --rings K --layers M]
  scripts/make_meshes.py cone OUT.stl [--outlet R0 --radius R --cone-height HC --height H
                                       --segments N --rings K --layers M]
  scripts/make_meshes.py chute OUT.stl [--length L --width W --height H --angle DEG --cells N]
  scripts/make_meshes.py silo OUT.stl [--radius R --height H --corrugations C --amplitude A
                                       --segments N --layers K]
  scripts/make_meshes.py plane OUT.stl [--size LX LY --cells NX NY --random SEED]
  scripts/make_meshes.py box OUT.stl [--min X Y Z --max X Y Z --cells N]
  scripts/make_meshes.py examples DIR    (the meshes the examples/mesh-*.yaml scenes read, as OBJ)
An OUT ending in .obj writes an indexed OBJ instead of binary STL.
Each prints the facet count. Standard library only.
"""
import argparse
import math
import os
import random
import struct
import sys


def write_obj(path, tris, title):
    """An indexed OBJ (vertices shared, coordinates to 9 digits): compact
    enough to commit the examples' meshes."""
    index, verts, faces = {}, [], []
    for t in tris:
        face = []
        for p in t:
            key = tuple("%.9g" % (x + 0.0) for x in p)
            if key not in index:
                index[key] = len(verts) + 1
                verts.append(key)
            face.append(index[key])
        faces.append(face)
    with open(path, "w") as f:
        f.write("# shapedem scripts/make_meshes.py %s: %d facets, metres\n" % (title, len(faces)))
        for v in verts:
            f.write("v %s %s %s\n" % v)
        for a, b, c in faces:
            f.write("f %d %d %d\n" % (a, b, c))
    print("%s: %d facets" % (path, len(tris)))


def write_stl(path, tris, title):
    """tris: list of ((x, y, z), (x, y, z), (x, y, z)); binary STL, normals
    computed (an OUT ending in .obj writes an OBJ instead)."""
    if path.endswith(".obj"):
        return write_obj(path, tris, title)
    with open(path, "wb") as f:
        head = ("shapedem make_meshes.py " + title).encode("ascii")[:80]
        f.write(head + b" " * (80 - len(head)))
        f.write(struct.pack("<I", len(tris)))
        for a, b, c in tris:
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            ln = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write(struct.pack("<3f", *(x / ln for x in n)))
            for p in (a, b, c):
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")
    print("%s: %d facets" % (path, len(tris)))


def quad(tris, a, b, c, d):
    """a b c d counter-clockwise seen from the particle side."""
    tris.append((a, b, c))
    tris.append((a, c, d))


def drum(radius, length, segments):
    """A closed cylinder about the y axis, y in [-length/2, length/2]: the
    rotating drum. Normals inward."""
    tris = []
    h = 0.5 * length
    ring = [(radius * math.cos(2 * math.pi * k / segments), radius * math.sin(2 * math.pi * k / segments))
            for k in range(segments)]
    for k in range(segments):
        (x0, z0), (x1, z1) = ring[k], ring[(k + 1) % segments]
        quad(tris, (x0, -h, z0), (x0, h, z0), (x1, h, z1), (x1, -h, z1))  # the mantle
        tris.append(((0.0, -h, 0.0), (x1, -h, z1), (x0, -h, z0)))  # the caps, fans from the centre
        tris.append(((0.0, h, 0.0), (x0, h, z0), (x1, h, z1)))
    # convex: inward is towards the centre for every facet
    return fix_winding(tris, lambda m, n: -(n[0] * m[0] + n[1] * m[1] + n[2] * m[2]) > 0)


def fix_winding(tris, inside):
    """Turns each facet whose normal points away from inside(p, n) == True."""
    out = []
    for a, b, c in tris:
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        m = tuple((a[i] + b[i] + c[i]) / 3.0 for i in range(3))
        out.append((a, b, c) if inside(m, n) else (a, c, b))
    return out


def hopper(radius, height, orifice, segments, rings, layers=4):
    """A flat-bottomed cylindrical bin (axis z, floor at z = 0, open top)
    with a circular orifice of diameter `orifice` in the middle of the
    floor. Normals into the bin (up on the floor, towards the axis on the
    wall)."""
    tris = []
    r0 = 0.5 * orifice
    radii = [r0 + (radius - r0) * j / rings for j in range(rings + 1)]
    for k in range(segments):
        t0, t1 = 2 * math.pi * k / segments, 2 * math.pi * (k + 1) / segments
        c0, s0, c1, s1 = math.cos(t0), math.sin(t0), math.cos(t1), math.sin(t1)
        for j in range(rings):
            ra, rb = radii[j], radii[j + 1]
            quad(tris, (ra * c0, ra * s0, 0.0), (rb * c0, rb * s0, 0.0), (rb * c1, rb * s1, 0.0),
                 (ra * c1, ra * s1, 0.0))
        for j in range(layers):
            za, zb = height * j / layers, height * (j + 1) / layers
            quad(tris, (radius * c0, radius * s0, za), (radius * c1, radius * s1, za),
                 (radius * c1, radius * s1, zb), (radius * c0, radius * s0, zb))
    return fix_winding(tris, lambda m, n: (n[2] > 0) if abs(m[2]) < 1e-12 else (n[0] * m[0] + n[1] * m[1] < 0))


def cone(outlet, radius, cone_height, height, segments, rings, layers):
    """A conical hopper with an open outlet: a cone (axis z) from the outlet
    circle of radius `outlet` at z = 0 up to radius `radius` at z =
    cone_height, in `rings` bands, then a vertical cylinder up to z =
    height in `layers` bands (none when height <= cone_height); open at
    the outlet and at the top. 2 x segments x (rings + layers) facets,
    normals into the hopper (towards the axis)."""
    tris = []
    zs = [(outlet + (radius - outlet) * j / rings, cone_height * j / rings) for j in range(rings + 1)]
    if height > cone_height:
        zs += [(radius, cone_height + (height - cone_height) * j / layers) for j in range(1, layers + 1)]
    for k in range(segments):
        t0, t1 = 2 * math.pi * k / segments, 2 * math.pi * (k + 1) / segments
        c0, s0, c1, s1 = math.cos(t0), math.sin(t0), math.cos(t1), math.sin(t1)
        for (ra, za), (rb, zb) in zip(zs, zs[1:]):
            quad(tris, (ra * c0, ra * s0, za), (ra * c1, ra * s1, za), (rb * c1, rb * s1, zb), (rb * c0, rb * s0, zb))
    return fix_winding(tris, lambda m, n: n[0] * m[0] + n[1] * m[1] < 0)


def chute(length, width, height, angle, cells):
    """An open chute: a flat floor `width` wide and `length` long between two
    vertical side walls `height` high, open at both ends and on top,
    falling along +x at `angle` degrees below the horizontal (the top end
    at the origin, the centre line on y = 0). Each of the three faces in
    `cells` squares along the length. Normals into the chute (up off the
    floor, towards the centre line on the sides)."""
    tris = []
    h = 0.5 * width
    for i in range(cells):
        xa, xb = length * i / cells, length * (i + 1) / cells
        quad(tris, (xa, -h, 0.0), (xb, -h, 0.0), (xb, h, 0.0), (xa, h, 0.0))  # floor
        quad(tris, (xa, -h, 0.0), (xa, -h, height), (xb, -h, height), (xb, -h, 0.0))  # side y = -w/2
        quad(tris, (xa, h, 0.0), (xb, h, 0.0), (xb, h, height), (xa, h, height))  # side y = +w/2
    tris = fix_winding(tris, lambda m, n: (n[2] > 0) if abs(m[2]) < 1e-12 else (n[1] * m[1] < 0))
    a = math.radians(angle)
    ca, sa = math.cos(a), math.sin(a)
    # tilt about y: x' = x cos a + z sin a, z' = -x sin a + z cos a (down along +x)
    return [tuple((p[0] * ca + p[2] * sa, p[1], -p[0] * sa + p[2] * ca) for p in t) for t in tris]


def silo(radius, height, corrugations, amplitude, segments, layers):
    """A silo: a cylinder (axis z, z in [0, height]) whose radius is
    radius + amplitude cos(corrugations theta) (vertical corrugations, as
    the corrugated-sheet silo of seed 000 §4.1 scaled down), a flat closed
    floor at z = 0 and an open top. Normals inward."""
    tris = []
    pts = []
    for k in range(segments):
        t = 2 * math.pi * k / segments
        r = radius + amplitude * math.cos(corrugations * t)
        pts.append((r * math.cos(t), r * math.sin(t)))
    for k in range(segments):
        (x0, y0), (x1, y1) = pts[k], pts[(k + 1) % segments]
        tris.append(((0.0, 0.0, 0.0), (x0, y0, 0.0), (x1, y1, 0.0)))
        for j in range(layers):
            za, zb = height * j / layers, height * (j + 1) / layers
            quad(tris, (x0, y0, za), (x1, y1, za), (x1, y1, zb), (x0, y0, zb))
    return fix_winding(tris, lambda m, n: (n[2] > 0) if abs(m[2]) < 1e-12 else (n[0] * m[0] + n[1] * m[1] < 0))


def plane(lx, ly, nx, ny, seed):
    """The rectangle [0, lx] x [0, ly] at z = 0 in nx x ny cells, two
    triangles each, normal +z. seed >= 0: interior points jittered by up to
    a third of a cell and each cell's diagonal chosen at random (an
    irregular triangulation of the same plane)."""
    rng = random.Random(seed) if seed >= 0 else None
    p = {}
    for i in range(nx + 1):
        for j in range(ny + 1):
            x, y = lx * i / nx, ly * j / ny
            if rng and 0 < i < nx and 0 < j < ny:
                x += (rng.random() - 0.5) * 0.66 * lx / nx
                y += (rng.random() - 0.5) * 0.66 * ly / ny
            p[i, j] = (x, y, 0.0)
    tris = []
    for i in range(nx):
        for j in range(ny):
            a, b, c, d = p[i, j], p[i + 1, j], p[i + 1, j + 1], p[i, j + 1]
            if rng and rng.random() < 0.5:
                tris += [(a, b, d), (b, c, d)]
            else:
                tris += [(a, b, c), (a, c, d)]
    return tris


def box(lo, hi, cells):
    """A closed box, each face in cells x cells squares; normals inward."""
    tris = []
    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3
        for side in (0, 1):
            for i in range(cells):
                for j in range(cells):
                    def pt(u, v):
                        x = [0.0, 0.0, 0.0]
                        x[a] = hi[a] if side else lo[a]
                        x[b] = lo[b] + (hi[b] - lo[b]) * u / cells
                        x[c] = lo[c] + (hi[c] - lo[c]) * v / cells
                        return tuple(x)
                    q = [pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1)]
                    tris += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    centre = tuple(0.5 * (lo[k] + hi[k]) for k in range(3))
    return fix_winding(tris, lambda m, n: sum(n[k] * (centre[k] - m[k]) for k in range(3)) > 0)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("kind", choices=["drum", "hopper", "cone", "chute", "silo", "plane", "box", "examples"])
    ap.add_argument("out")
    ap.add_argument("--radius", type=float)
    ap.add_argument("--length", type=float)
    ap.add_argument("--height", type=float)
    ap.add_argument("--outlet", type=float, default=0.009, help="cone: outlet radius")
    ap.add_argument("--cone-height", type=float, default=0.035, help="cone: height of the conical part")
    ap.add_argument("--width", type=float, default=0.05, help="chute: floor width")
    ap.add_argument("--angle", type=float, default=30.0, help="chute: inclination, degrees")
    ap.add_argument("--orifice", type=float, default=0.03)
    ap.add_argument("--segments", type=int, default=48)
    ap.add_argument("--rings", type=int)
    ap.add_argument("--layers", type=int)
    ap.add_argument("--corrugations", type=int, default=24)
    ap.add_argument("--amplitude", type=float, default=0.004)
    ap.add_argument("--size", type=float, nargs=2, default=[0.2, 0.2])
    ap.add_argument("--cells", type=int, nargs="+", default=None)
    ap.add_argument("--random", type=int, default=-1, help="plane: seed of the irregular triangulation")
    ap.add_argument("--min", type=float, nargs=3, default=[0.0, 0.0, 0.0])
    ap.add_argument("--max", type=float, nargs=3, default=[0.1, 0.1, 0.1])
    a = ap.parse_args(argv)
    if a.kind == "drum":
        write_stl(a.out, drum(a.radius or 0.1, a.length or 0.1, a.segments), "drum")
    elif a.kind == "hopper":
        write_stl(a.out, hopper(a.radius or 0.1, a.height or 0.3, a.orifice, a.segments, a.rings or 4, a.layers or 12), "hopper")
    elif a.kind == "cone":
        # defaults: the hopper of issue 30 (outlet 9 mm, cone to 30 mm at
        # 35 mm, cylinder to 60 mm; 48 segments, 2 + 2 bands: 384 facets)
        write_stl(a.out, cone(a.outlet, a.radius or 0.03, a.cone_height, a.height or 0.06, a.segments,
                              a.rings or 2, a.layers or 2), "cone")
    elif a.kind == "chute":
        cells = a.cells or [10]
        write_stl(a.out, chute(a.length or 0.5, a.width, a.height or 0.03, a.angle, cells[0]),
                  "chute")
    elif a.kind == "silo":
        write_stl(a.out, silo(a.radius or 0.06, a.height or 0.25, a.corrugations, a.amplitude, a.segments, a.layers or 12),
                  "silo")
    elif a.kind == "plane":
        cells = a.cells or [8, 8]
        if len(cells) != 2:
            ap.error("plane: --cells NX NY")
        write_stl(a.out, plane(a.size[0], a.size[1], cells[0], cells[1], a.random), "plane")
    elif a.kind == "box":
        cells = a.cells or [1]
        write_stl(a.out, box(a.min, a.max, cells[0]), "box")
    else:
        # the meshes of examples/mesh-*.yaml, committed as examples/meshes/*.obj
        # (tests/cli/example_meshes.sh checks they are what this writes)
        os.makedirs(a.out, exist_ok=True)
        write_stl(os.path.join(a.out, "drum.obj"), drum(0.06, 0.04, 48), "drum")
        write_stl(os.path.join(a.out, "hopper.obj"), hopper(0.02, 0.08, 0.015, 48, 2, 1), "hopper")
        write_stl(os.path.join(a.out, "silo.obj"), silo(0.03, 0.1, 12, 0.0025, 96, 1), "silo")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
