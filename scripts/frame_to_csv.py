#!/usr/bin/env python3
"""frame_to_csv.py - a particle frame written by shapedem, as a packing the
CSV generator loads again (generator: csv; docs/scene-format.md).

Usage: /usr/bin/python3 scripts/frame_to_csv.py FRAME.vtu > packing.csv

One row per particle, in id order (the generation order of the run that
wrote the frame): x, y, z, radius (spheres) or shape (bodies of a shape,
by the name the frame's field data gives the index), the orientation
qw, qx, qy, qz (empty for spheres, which take none), the velocity vx, vy,
vz and the angular velocity wx, wy, wz, and the material by name. Values
are written with 17 significant digits, so they read back exactly.

Python 3 standard library only. Exit status 2, with one line on stderr,
for a file that is not a shapedem particle frame.
"""
import re
import struct
import sys

# VTK type -> struct format, for the appended arrays shapedem writes
FORMATS = {'Float64': 'd', 'UInt64': 'Q', 'Int64': 'q', 'Int32': 'i', 'UInt8': 'B'}
NEEDED = ('id', 'position', 'radius', 'velocity', 'angular_velocity', 'material',
          'orientation', 'shape')


class NotAFrame(Exception):
    pass


def read_frame(path):
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except OSError as e:
        raise NotAFrame('cannot read: %s' % (e.strerror or e))
    cut = data.find(b'<AppendedData encoding="raw">')
    if not data.startswith(b'<?xml') or b'<VTKFile type="UnstructuredGrid"' not in data[:cut] or cut < 0:
        raise NotAFrame('not a shapedem particle frame (expected a VTK UnstructuredGrid '
                        '.vtu with raw appended data)')
    head = data[:cut].decode('utf-8', 'replace')
    if 'byte_order="LittleEndian"' not in head or 'header_type="UInt64"' not in head:
        raise NotAFrame('not a shapedem particle frame (expected LittleEndian, UInt64 headers)')
    m = re.search(r'<Piece NumberOfPoints="(\d+)"', head)
    if not m:
        raise NotAFrame('not a shapedem particle frame (no Piece with NumberOfPoints)')
    n = int(m.group(1))
    start = data.index(b'_', cut) + 1
    arrays = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)"(?: NumberOfComponents="(\d+)")? '
                         r'format="appended" offset="(\d+)"', head):
        kind, name, comps, off = m.group(1), m.group(2), int(m.group(3) or 1), int(m.group(4))
        if kind not in FORMATS:
            continue
        fmt = FORMATS[kind]
        try:
            size = struct.unpack_from('<Q', data, start + off)[0]
            count = size // struct.calcsize(fmt)
            if count != n * comps:
                raise NotAFrame('array %s holds %d values, expected %d' % (name, count, n * comps))
            vals = struct.unpack_from('<%d%s' % (count, fmt), data, start + off + 8)
        except struct.error:
            raise NotAFrame('array %s runs past the end of the file (truncated?)' % name)
        arrays[name] = [vals[i:i + comps] for i in range(0, count, comps)]
    missing = [a for a in NEEDED if a not in arrays]
    if missing:
        raise NotAFrame('not a shapedem particle frame of this version (no %s array%s; frames '
                        'carry shape and material names since issue 11)'
                        % (', '.join(missing), 's' if len(missing) > 1 else ''))
    names = {}
    for m in re.finditer(r'<Array type="String" Name="(\w+)" NumberOfTuples="(\d+)" '
                         r'format="ascii">([^<]*)</Array>', head):
        codes = [int(c) for c in m.group(3).split()]
        words, cur = [], bytearray()
        for c in codes:
            if c == 0:
                words.append(cur.decode('utf-8', 'replace'))
                cur = bytearray()
            else:
                cur.append(c)
        if len(words) != int(m.group(2)):
            raise NotAFrame('field data %s: %d names, expected %s'
                            % (m.group(1), len(words), m.group(2)))
        names[m.group(1)] = words
    for a in ('shape_names', 'material_names'):
        if a not in names:
            raise NotAFrame('not a shapedem particle frame of this version (no %s field data)' % a)
    return arrays, names


def g(x):
    return '%.17g' % x


def main(argv):
    if len(argv) != 2 or argv[1].startswith('-'):
        sys.stderr.write('usage: frame_to_csv.py FRAME.vtu > packing.csv\n')
        return 2
    path = argv[1]
    try:
        arrays, names = read_frame(path)
    except NotAFrame as e:
        sys.stderr.write('%s: %s\n' % (path, e))
        return 2
    shapes, materials = names['shape_names'], names['material_names']
    out = sys.stdout
    out.write('# written by scripts/frame_to_csv.py from %s\n' % path.replace('\n', ' '))
    out.write('x,y,z,radius,shape,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,material\n')
    rows = sorted(zip(arrays['id'], arrays['position'], arrays['radius'], arrays['shape'],
                      arrays['orientation'], arrays['velocity'], arrays['angular_velocity'],
                      arrays['material']))
    for (pid,), x, (r,), (sh,), q, v, w, (mat,) in rows:
        if sh >= len(shapes) or not (0 <= mat < len(materials)):
            sys.stderr.write('%s: particle %d: shape %d or material %d has no name in the '
                             'field data\n' % (path, pid, sh, mat))
            return 2
        for name in (shapes[sh] if sh >= 0 else '', materials[mat]):
            if any(c in name for c in ',\n\r#') or name != name.strip():
                sys.stderr.write('%s: the name %r cannot be written as a CSV cell (a comma, '
                                 'line break, # or outer space)\n' % (path, name))
                return 2
        if sh >= 0:  # a body of a shape: its bounding radius is the shape's
            cells = [g(x[0]), g(x[1]), g(x[2]), '', shapes[sh]] + [g(c) for c in q]
        else:
            cells = [g(x[0]), g(x[1]), g(x[2]), g(r), '', '', '', '', '']
        cells += [g(c) for c in v] + [g(c) for c in w] + [materials[mat]]
        out.write(','.join(cells) + '\n')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
