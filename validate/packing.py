#!/usr/bin/env python3
"""packing.py SHAPEDEM OUTDIR SHAPE N [--aspect A] [--threads T]

One packing of seed 004 §4.1, configuration 1, with the paper's protocol
([Rakotonirina 2019]; validate/cases/packing_six, cross3d_aspect):

- N particles of SHAPE (sphere, cube, cylinder, tetrahedron, cross2d,
  cross3d), every one of the volume of a sphere of radius 2 mm (the
  templates are sized here, not scaled by the insertion, so that the
  settled packing reads back as it is);
- inserted one at a time at random positions and orientations in a thin
  slab (1.5 bounding diameters thick: the particle inside it, its centre
  drawn over one bounding radius) at the top of a box periodic along x
  and y: each particle gets one position per time step, and one that does
  not fit tries again at the next step (`insert:` with `attempts: 1` and a
  rate of one per step: the run owes a particle every step, so the slab is
  kept as full as the shower below it allows, "a moderately dense
  shower");
- settled until the kinetic energy is negligible (1e-9 J per particle:
  an rms speed of about 0.4 mm/s), for at most 1 s + 3 ms per particle
  (the shower of 1,000 takes about 1 s to go in and fall);
- porosity by voxels over the box embedding the packing (x and y the
  periodic cell, z from the floor to the highest point of any particle,
  seed 004 §4.1), at two voxel sizes (an eighth and a sixteenth of the
  shape's thinnest feature: a tenth and a twentieth of the equivalent
  diameter left the 2D crosses' beams 4.6 voxels thick, and the two
  porosities 0.008 apart), from the settled frame loaded again
  (scripts/frame_to_csv.py) into a scene that only measures.

The contact parameters are the paper's two (e_n 0.73, mu 0.55) with the
packing examples' linear law (k_n 1e5 N/m, 2500 kg/m^3, dt 2e-6 s).
--aspect: the beam length over diameter of the crosses (default 3.2, the
packing examples' 8 / 2.5 mm).

Prints one line `result SHAPE N top_m eps_coarse eps_fine voxels_coarse
voxels_fine sim_s wall_s settled` (settled: 1 when the run stopped on its
kinetic energy before its end) and writes OUTDIR/result.txt with the same.
Exit status 1 when a run fails.
"""
import csv
import math
import os
import subprocess
import sys
import time

V0 = 4.0 / 3.0 * math.pi * 0.002 ** 3  # m^3, every shape's volume
D_EQ = 0.004                             # m, its equivalent diameter
CELL = 0.05                              # m, the periodic cell along x and y
DT = 2.0e-6


def template(shape, aspect):
    """The shape's scene entry of volume V0, its bounding radius and its
    thinnest feature (a sphere's, a cube's, a cylinder's diameter, a
    tetrahedron's inscribed diameter, a cross's beam), which sets the voxels."""
    if shape == 'sphere':
        return None, 0.002, D_EQ
    if shape == 'cube':
        a = V0 ** (1 / 3)
        return 'type: box, size: %.9g' % a, 0.5 * math.sqrt(3) * a, a
    if shape == 'cylinder':
        d = (4 * V0 / math.pi) ** (1 / 3)  # length = diameter
        return 'type: cylinder, diameter: %.9g, length: %.9g' % (d, d), 0.5 * math.sqrt(2) * d, d
    if shape == 'tetrahedron':
        a = (6 * math.sqrt(2) * V0) ** (1 / 3)  # regular: V = a^3 / (6 sqrt 2)
        return 'type: polyhedron, preset: tetrahedron, edge: %.9g' % a, a * math.sqrt(6) / 4, a / math.sqrt(6)
    if shape == 'cross2d':
        # two bars L x W of thickness T = W glued (the centre once):
        # V = T (2 L W - W^2), W = L / aspect
        w = 1.0 / aspect
        L = (V0 / (w * (2 * w - w * w))) ** (1 / 3)
        W = L * w
        return ('type: composite, preset: cross2d, length: %.9g, width: %.9g, thickness: %.9g' % (L, W, W),
                0.5 * math.sqrt(L * L + W * W), W)
    if shape == 'cross3d':
        # three orthogonal cylinders of diameter D and length L = aspect D:
        # 3 pi D^2 L / 4 minus the pairwise (Steinmetz, 2 D^3 / 3 each)
        # plus the triple ((2 - sqrt 2) D^3) intersections
        D = (V0 / (3 * math.pi * aspect / 4 - math.sqrt(2))) ** (1 / 3)
        L = aspect * D
        return ('type: composite, preset: cross3d, diameter: %.9g, length: %.9g' % (D, L),
                0.5 * math.sqrt(L * L + D * D), D)
    raise SystemExit('packing.py: unknown shape %s' % shape)


# a first guess of the porosity, only to size the box above the bed
EPS_GUESS = {'sphere': 0.42, 'cube': 0.45, 'cylinder': 0.45, 'tetrahedron': 0.5, 'cross2d': 0.6, 'cross3d': 0.8}


def settle_scene(shape, n, aspect, outdir):
    entry, b, _ = template(shape, aspect)
    eps = EPS_GUESS[shape] if shape != 'cross3d' else min(0.93, 0.8 + 0.03 * (aspect - 3.2))
    bed = n * V0 / (CELL * CELL) / (1 - eps)
    top = 1.5 * bed + 6 * b + 0.01
    slab = (top - 3.2 * b, top - 0.2 * b)  # the centres drawn over one bounding radius
    shapes = 'shapes:\n  - {name: grain, %s}\n' % entry if entry else ''
    mix = '{material: grain, shape: grain}' if entry else '{material: grain, radius: 0.002}'
    duration = 1.0 + 0.003 * n
    return """# seed 004 §4.1 configuration 1, one at a time (validate/packing.py)
simulation:
  dt: %(dt)g
  duration: %(duration)g
  seed: 23
  stop_when: {kinetic_energy_below: %(ke)g, after: 0.05}
  contact_law: linear
  periodic: [x, y]
  domain: {min: [0, 0, 0], max: [%(cell)g, %(cell)g, %(top).6g]}
materials:
  - {name: grain, density: 2500, stiffness: 1.0e5, restitution: 0.73, friction: 0.55}
%(shapes)sinsert:
  - name: shower
    region: box
    min: [0, 0, %(s0).6g]
    max: [%(cell)g, %(cell)g, %(s1).6g]
    count: %(n)d
    rate: %(rate)g
    attempts: 1
    mix:
      - %(mix)s
walls:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: grain}
output:
  directory: %(out)s
  formats: [vtk, csv]
  every: 10000000
  stats_every: 1000
analysis:
  - {type: bed_height, every: 5000}
""" % dict(dt=DT, ke=1e-9 * n, cell=CELL, top=top, shapes=shapes, s0=slab[0], s1=slab[1], n=n, rate=1.0 / DT,
           mix=mix, out=outdir, duration=duration)


def measure_scene(shape, aspect, csv_path, top, outdir):
    entry, _, thin = template(shape, aspect)
    shapes = 'shapes:\n  - {name: grain, %s}\n' % entry if entry else ''
    rows = ''.join("""  - {type: porosity, name: %s, region: box, min: [0, 0, 0], max: [%g, %g, %.9g], voxel: %.9g}
""" % (name, CELL, CELL, top, h) for name, h in (('coarse', thin / 8), ('fine', thin / 16)))
    return """# the settled packing, measured over the box embedding it (validate/packing.py)
simulation:
  dt: %(dt)g
  duration: %(dt)g
  contact_law: linear
  periodic: [x, y]
  domain: {min: [0, 0, 0], max: [%(cell)g, %(cell)g, %(dom).6g]}
materials:
  - {name: grain, density: 2500, stiffness: 1.0e5, restitution: 0.73, friction: 0.55}
%(shapes)sparticles:
  - generator: csv
    file: %(csv)s
    material: grain
walls:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: grain}
output:
  directory: %(out)s
  formats: [csv]
analysis:
%(rows)s""" % dict(dt=DT, cell=CELL, dom=2 * top + 0.01, shapes=shapes, csv=csv_path, out=outdir, rows=rows)


def last_row(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit('packing.py: %s has no rows' % path)
    return rows[-1]


def run(cmd, log):
    with open(log, 'w') as f:
        rc = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT)
    if rc != 0:
        sys.stdout.write(open(log).read()[-3000:])
        raise SystemExit('packing.py: %s exited %d (log %s)' % (' '.join(cmd), rc, log))


def main(argv):
    if len(argv) < 5:
        raise SystemExit(__doc__)
    bin_, out, shape, n = argv[1], os.path.abspath(argv[2]), argv[3], int(argv[4])
    aspect, threads = 3.2, '2'
    i = 5
    while i < len(argv):
        if argv[i] == '--aspect':
            aspect = float(argv[i + 1])
        elif argv[i] == '--threads':
            threads = argv[i + 1]
        i += 2
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    os.makedirs(out, exist_ok=True)
    t0 = time.time()
    scene = os.path.join(out, 'settle.yaml')
    with open(scene, 'w') as f:
        f.write(settle_scene(shape, n, aspect, os.path.join(out, 'settle')))
    run([bin_, 'run', scene, '--threads', threads, '--quiet'], os.path.join(out, 'settle.log'))
    summ = dict(l.split(':', 1) for l in open(os.path.join(out, 'settle', 'summary.txt')) if ':' in l)
    sim = float(summ.get('simulated_time_s', 'nan'))
    # settled: the run stopped on the kinetic energy before its end (a
    # sparse short-form layer of cylinders may roll on for ever)
    settled = 1 if sim < 1.0 + 0.003 * n - 1e-9 else 0
    frames = sorted(p for p in os.listdir(os.path.join(out, 'settle')) if p.startswith('particles_') and p.endswith('.vtu'))
    csv_path = os.path.join(out, 'settled.csv')
    with open(csv_path, 'w') as f:
        rc = subprocess.call(['/usr/bin/python3', os.path.join(root, 'scripts', 'frame_to_csv.py'),
                              os.path.join(out, 'settle', frames[-1])], stdout=f)
    if rc != 0:
        raise SystemExit('packing.py: frame_to_csv failed')
    bed = last_row(os.path.join(out, 'settle', 'bed_height.csv'))
    top = float(bed['top'])
    count = int(bed['particles'])
    if count != n:
        raise SystemExit('packing.py: %d of %d particles in the packing' % (count, n))
    scene = os.path.join(out, 'measure.yaml')
    with open(scene, 'w') as f:
        f.write(measure_scene(shape, aspect, csv_path, top, os.path.join(out, 'measure')))
    run([bin_, 'run', scene, '--threads', threads, '--quiet'], os.path.join(out, 'measure.log'))
    c = last_row(os.path.join(out, 'measure', 'coarse.csv'))
    fi = last_row(os.path.join(out, 'measure', 'fine.csv'))
    line = 'result %s %d %.6g %.6f %.6f %s %s %.4g %.0f %d' % (shape, n, top, float(c['porosity']),
                                                            float(fi['porosity']), c['voxels'], fi['voxels'], sim,
                                                            time.time() - t0, settled)
    print(line)
    with open(os.path.join(out, 'result.txt'), 'w') as f:
        f.write(line + '\n')


if __name__ == '__main__':
    main(sys.argv)
