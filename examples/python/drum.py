"""drum.py — fill a rotating drum with glass spheres from Python, turn it,
and plot the free-surface angle of the bed as it develops (docs/python.md).

    PYTHONPATH=build/python python3 examples/python/drum.py out/drum-python.png

A drum of radius 20 mm and depth 8 mm (axis y) holds 192 spheres of radius
1 mm; they settle for 0.05 s with the drum at rest, then it turns at 60 rpm
(spun up over 0.05 s) until t = 0.4 s. Every 0.01 s the bed's free surface
is fitted (World.drum_surface) and its angle recorded. Writes the PNG given
(two panels: the angle against time, the cross-section at the end with the
fitted line) and prints the final angle. About 10 s on one core.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import shapedem as sd  # noqa: E402

R, DEPTH, r = 0.02, 0.008, 0.001
out = sys.argv[1] if len(sys.argv) > 1 else "out/drum-python.png"

w = sd.World(dt=2e-6, gravity=(0, 0, -9.81), threads=1)
glass = w.add_material(name="glass", density=2500, youngs_modulus=1e7, poisson_ratio=0.3, restitution=0.5,
                       friction=0.5, rolling_friction=0.02)
w.add_drum("drum", center=(0, 0, 0), axis=(0, 1, 0), radius=R, length=DEPTH, material=glass,
           rpm=60, start=0.05, ramp=0.05)

# the fill: a lattice in the lower half of the drum, 2.5 mm apart (nothing touches)
g = np.arange(-0.0165, 0.0166, 0.0025)
x, y, z = np.meshgrid(g, [-0.002, 0.002], g[g < 0.002], indexing="ij")
pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
pos = pos[np.hypot(pos[:, 0], pos[:, 2]) < R - 1.5 * r][:192]
w.add_spheres(pos, r, glass)

times, angles = [], []
while w.time < 0.4 - 1e-9:
    w.step(5000)  # 0.01 s; the GIL is released while the engine steps
    fit = w.drum_surface(center=(0, 0, 0), axis=(0, 1, 0), radius=R, length=DEPTH, bins=12)
    times.append(w.time)
    angles.append(fit["angle"] if fit["columns"] >= 2 else np.nan)

fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 4))
a1.plot(times, angles, "o-")
a1.axvline(0.05, color="grey", ls=":")
a1.set_xlabel("time (s)")
a1.set_ylabel("free-surface angle (degrees)")
a1.set_title("the bed as the drum turns (60 rpm from 0.05 s)")
p = np.asarray(w.positions)  # a zero-copy view of the live state, read before the next step
a2.add_patch(plt.Circle((0, 0), R * 1000, fill=False))
a2.scatter(p[:, 0] * 1000, p[:, 2] * 1000, s=12)
s = np.linspace(-0.6 * R, 0.6 * R, 2)
zc = np.mean(p[:, 2]) + 0 * s
a2.plot(s * 1000, (zc + fit["slope"] * (s - 0)) * 1000 + 0 * s, "r-", label=f"{angles[-1]:.1f} degrees")
a2.set_aspect("equal")
a2.set_xlabel("x (mm)")
a2.set_ylabel("z (mm)")
a2.legend()
fig.tight_layout()
os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
fig.savefig(out, dpi=100)
print(f"t = {w.time:.2f} s, {len(w)} spheres, free-surface angle {angles[-1]:.1f} degrees -> {out}")
