#!/usr/bin/env python3
"""composites-analyse.py - pictures of the composite examples (glued convex
particles, [Rakotonirina 2019]) from a finished run's output directory.

Usage:
  /usr/bin/python3 examples/composites-analyse.py beds out/composites-clumps-bed out/composites-convex-bed [PNG]
  /usr/bin/python3 examples/composites-analyse.py reactor out/composites-reactor [PNG]
  /usr/bin/python3 examples/composites-analyse.py drum out/composites-drum [PNG]

beds:    the two beds seen from the side (x, z of the centres of the last
         frame), their heights (bed_height.csv) and the cost of each per
         particle-step from summary.txt's profile (the stage `elements` is
         the clumps' pairs, `convex` the cylinders'; and the whole step);
         writes composites-beds.png and .csv.
reactor: the bed of crosses from the side and the radial porosity of the
         last radial_porosity row set (the loose crown by the wall);
         writes composites-reactor.png and .csv.
drum:    the crosses seen along the drum's axis (last frame) and the free
         surface's angle over time (surface_angle.csv); writes
         composites-drum.png and .csv.
The PNG and the CSV of the plotted numbers go next to PNG (default:
docs/examples/). Needs matplotlib (/usr/bin/python3 has it); the frame is
read with scripts/frame_to_csv.py's reader.
"""
import csv
import glob
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
import importlib.util  # noqa: E402

# the repository's frame reader (scripts/frame_to_csv.py), loaded by path:
# it is a file of this tree, not an installed module
_spec = importlib.util.spec_from_file_location(
    'frame_to_csv', os.path.join(HERE, '..', 'scripts', 'frame_to_csv.py'))
frame_to_csv = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(frame_to_csv)


def last_frame(out):
    frames = sorted(glob.glob(os.path.join(out, 'particles_*.vtu')))
    if not frames:
        sys.exit('composites-analyse: no particles_*.vtu in %s' % out)
    return frames[-1]


def frame_rows(path):
    """(x, z, shape name or '') per particle of a frame"""
    arrays, names = frame_to_csv.read_frame(path)
    shapes = names['shape_names']
    return [(x[0], x[2], shapes[sh] if sh >= 0 else '') for x, (sh,) in zip(arrays['position'], arrays['shape'])]


def profile(out):
    """stage -> seconds, and the steps run, from summary.txt"""
    sec, steps = {}, None
    with open(os.path.join(out, 'summary.txt')) as f:
        for line in f:
            m = re.match(r'profile (\w+): seconds ([0-9.eE+-]+), calls (\d+)', line)
            if m:
                sec[m.group(1)] = float(m.group(2))
            m = re.match(r'steps\s*[:=]?\s*(\d+)', line)
            if m and steps is None:
                steps = int(m.group(1))
    return sec, steps


def last_row(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows[-1] if rows else {}


def beds(out_clumps, out_convex, png):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(7, 4.6), sharey=True)
    table = []
    for ax, out, stage, label in ((axes[0], out_clumps, 'elements', 'spheres9 clumps'),
                                  (axes[1], out_convex, 'convex', 'true cylinders')):
        pts = frame_rows(last_frame(out))
        sec, _ = profile(out)
        hb = last_row(os.path.join(out, 'bed_height.csv'))
        steps = int(float(hb.get('step', 0) or 0))
        n = len(pts)
        pair_us = 1e6 * sec.get(stage, 0.0) / max(1, n * steps)
        step_us = 1e6 * sum(v for k, v in sec.items() if k != 'output') / max(1, n * steps)
        table.append((label, n, hb.get('top'), hb.get('mean_height'), stage, sec.get(stage, 0.0), pair_us,
                      step_us))
        ax.scatter([p[0] * 1e3 for p in pts], [p[1] * 1e3 for p in pts], s=16)
        ax.axvline(-25, color='k')
        ax.axvline(25, color='k')
        ax.set_aspect('equal')
        ax.set_xlabel('x (mm)')
        ax.set_title('%s: top %.1f mm\n%s %.2f us, step %.2f us per particle-step\n(wall time: unverified on a loaded machine)'
                     % (label, 1e3 * float(hb.get('top', 'nan')), stage, pair_us, step_us), fontsize=8)
    axes[0].set_ylabel('z (mm)')
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    with open(os.path.splitext(png)[0] + '.csv', 'w') as f:
        f.write('bed,particles,top_m,mean_height_m,pair_stage,pair_stage_s,pair_us_per_particle_step,'
                'step_us_per_particle_step\n')
        for row in table:
            f.write('%s,%d,%s,%s,%s,%.6g,%.6g,%.6g\n' % row)
    for row in table:
        print('%s: %d particles, top %s m, %s %.3f us and the whole step %.3f us per particle-step'
              % (row[0], row[1], row[2], row[4], row[6], row[7]))


def reactor(out, png):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    pts = frame_rows(last_frame(out))
    with open(os.path.join(out, 'radial_porosity.csv')) as f:
        rows = list(csv.DictReader(f))
    last_t = rows[-1]['time']
    prof = [r for r in rows if r['time'] == last_t]
    hb = last_row(os.path.join(out, 'bed_height.csv'))
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(8, 4.2), gridspec_kw={'width_ratios': [1, 1.3]})
    a1.scatter([p[0] * 1e3 for p in pts], [p[1] * 1e3 for p in pts], s=10)
    a1.axvline(-25, color='k')
    a1.axvline(25, color='k')
    a1.set_xlabel('x (mm)')
    a1.set_ylabel('z (mm)')
    a1.set_aspect('equal')
    a1.set_title('%d crosses, bed top %.1f mm' % (len(pts), 1e3 * float(hb.get('top', 'nan'))), fontsize=9)
    r = [0.5e3 * (float(p['r_inner']) + float(p['r_outer'])) for p in prof]
    eps = [float(p['porosity']) for p in prof]
    a2.plot(r, eps, 'o-')
    a2.set_xlabel('r (mm)')
    a2.set_ylabel('porosity')
    a2.set_ylim(0, 1)
    a2.set_title('radial porosity, z in [5, 35] mm, t = %s s' % last_t, fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    with open(os.path.splitext(png)[0] + '.csv', 'w') as f:
        f.write('r_mm,porosity\n')
        for a, b in zip(r, eps):
            f.write('%.4g,%.6g\n' % (a, b))
    print('reactor: %d crosses, top %s m; porosity by annulus: %s' % (len(pts), hb.get('top'),
                                                                     ' '.join('%.3f' % e for e in eps)))


def drum(out, png):
    import math
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    pts = frame_rows(last_frame(out))
    with open(os.path.join(out, 'surface_angle.csv')) as f:
        rows = list(csv.DictReader(f))
    t = [float(r['time']) for r in rows]
    ang = [float(r['angle_deg']) for r in rows]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(8, 4.2), gridspec_kw={'width_ratios': [1, 1.3]})
    a1.scatter([p[0] * 1e3 for p in pts], [p[1] * 1e3 for p in pts], s=10)
    th = [2 * math.pi * k / 120 for k in range(121)]
    a1.plot([50 * math.cos(x) for x in th], [50 * math.sin(x) for x in th], 'k-')
    a1.set_aspect('equal')
    a1.set_xlabel('x (mm)')
    a1.set_ylabel('z (mm)')
    a1.set_title('%d crosses at t = %.2f s, 20 rpm' % (len(pts), t[-1] if t else 0), fontsize=9)
    a2.plot(t, ang, 'o-')
    a2.set_xlabel('t (s)')
    a2.set_ylabel('free-surface angle (deg)')
    a2.set_title('surface_angle.csv (middle 60 % of the diameter)', fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    with open(os.path.splitext(png)[0] + '.csv', 'w') as f:
        f.write('time_s,angle_deg,rms_m\n')
        for r in rows:
            f.write('%s,%s,%s\n' % (r['time'], r['angle_deg'], r.get('rms', '')))
    print('drum: %d crosses; surface angle at the end %.1f deg' % (len(pts), ang[-1] if ang else float('nan')))


def main(argv):
    docs = os.path.join(HERE, '..', 'docs', 'examples')
    if len(argv) in (4, 5) and argv[1] == 'beds':
        beds(argv[2], argv[3], argv[4] if len(argv) > 4 else os.path.join(docs, 'composites-beds.png'))
    elif len(argv) in (3, 4) and argv[1] == 'drum':
        drum(argv[2], argv[3] if len(argv) > 3 else os.path.join(docs, 'composites-drum.png'))
    elif len(argv) in (3, 4) and argv[1] == 'reactor':
        reactor(argv[2], argv[3] if len(argv) > 3 else os.path.join(docs, 'composites-reactor.png'))
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main(sys.argv)
