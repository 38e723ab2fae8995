"""Shared set-up of the python.* tests (ctest runs each file with pytest).

ctest sets PYTHONPATH to the build tree's python/ folder, SHAPEDEM_BIN to the
shapedem program and SHAPEDEM_ROOT to the source tree (tests/CMakeLists.txt).
"""
import os

import numpy as np
import pytest

import shapedem as sd

ROOT = os.environ.get("SHAPEDEM_ROOT", os.path.join(os.path.dirname(__file__), "..", ".."))
BIN = os.environ.get("SHAPEDEM_BIN", os.path.join(ROOT, "build", "shapedem"))

# a small settling box: 48 glass spheres on a lattice (no overlaps) in an open steel box
SMALL_SCENE = """\
simulation:
  dt: 5.0e-6
  steps: 300
  gravity: [0, 0, -9.81]
  seed: 1
materials:
  - {name: glass, density: 2500, youngs_modulus: 5.0e6, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
  - {name: steel, density: 7800, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
particles:
  - generator: lattice
    material: glass
    radius: {min: 0.0010, max: 0.0015}
    origin: [0.0024, 0.0024, 0.0024]
    spacing: 0.0032
    count: [4, 4, 3]
    velocity_jitter: 0.05
walls:
  - {name: container, type: box, min: [0, 0, 0], max: [0.0144, 0.0144, 0.1], open: [zmax], material: steel}
output:
  every: 100
  stats_every: 50
  formats: [vtk, csv]
"""


@pytest.fixture
def small_scene(tmp_path):
    """The path of SMALL_SCENE written into the test's own directory."""
    p = tmp_path / "small.yaml"
    p.write_text(SMALL_SCENE)
    return p


def glass_world(n=0, **kw):
    """A world with a glass material and a floor, and n spheres on a lattice that touch nothing."""
    w = sd.World(dt=1e-5, gravity=(0, 0, -9.81), **kw)
    glass = w.add_material(name="glass", density=2500, youngs_modulus=1e7, poisson_ratio=0.3,
                           restitution=0.5, friction=0.5)
    w.add_plane("floor", point=(0, 0, 0), normal=(0, 0, 1), material=glass)
    if n:
        k = np.arange(n)
        pos = np.stack([(k % 5) * 0.003, (k // 5 % 5) * 0.003, 0.002 + (k // 25) * 0.003], axis=1)
        w.add_spheres(pos, 0.001, glass)
    return w, glass
