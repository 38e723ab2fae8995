"""World: building every kind of thing, stepping, reading and writing the state."""
import numpy as np
import pytest

import shapedem as sd
from conftest import glass_world


def test_world_spheres_fall_and_settle():
    w, glass = glass_world()
    ids = w.add_spheres(positions=[[0, 0, 0.01], [0.005, 0, 0.02]], radii=[0.001, 0.0015], material=glass,
                        velocities=[[0, 0, 0], [0.1, 0, 0]], angular_velocities=np.zeros((2, 3)))
    assert ids.dtype == np.uint64 and list(ids) == [0, 1]
    assert len(w) == 2 and w.particle_count == 2 and w.wall_count == 1
    assert w.dt == 1e-5 and w.step_count == 0 and w.time == 0
    assert w.threads >= 1 and w.backend.startswith("cpu")
    assert w.material_names == ["glass"] and w.find_material("glass") == glass and w.find_material("x") == -1
    w.prepare()
    w.step(2000)
    assert w.step_count == 2000 and w.time == pytest.approx(0.02)
    z = w.get("position")[:, 2]
    # free fall over 0.02 s from rest: 0.5 g t^2 = 1.962 mm
    assert z[0] == pytest.approx(0.01 - 0.5 * 9.81 * 0.02**2, rel=1e-6)
    st = w.stats()
    assert st["step"] == 2000 and st["kinetic_translational"] > 0
    assert w.kinetic_energy() == pytest.approx(st["kinetic_translational"] + st["kinetic_rotational"])
    dt, tc = w.recommended_dt()
    assert 0 < dt < tc
    wall = w.wall(0)
    assert wall["name"] == "floor" and wall["normal"] == (0, 0, 1)
    with pytest.raises(IndexError):
        w.wall(5)


def test_get_and_set_by_id():
    w, glass = glass_world(10)
    ids = w.ids()
    assert list(ids) == list(range(10))
    v = np.tile([0.5, 0.0, -0.25], (3, 1))
    w.set("velocity", v, ids=ids[[7, 2, 5]])
    got = w.get("velocity", ids=[2, 5, 7])
    assert np.array_equal(got, v)
    assert np.array_equal(w.get("velocity")[[0, 1]], np.zeros((2, 3)))
    assert w.get("radius").shape == (10,) and np.all(w.get("radius") == 0.001)
    assert w.get("mass").shape == (10,)
    assert w.get("orientation").shape == (10, 4)
    assert set(sd.fields()) == {"position", "velocity", "angular_velocity", "orientation", "force", "torque",
                                "radius", "mass"}
    assert sd.fields()["force"]["writable"] is False


def test_bad_arguments_raise_before_anything_changes():
    w, glass = glass_world(4)
    before = w.get("position")
    cases = [
        (lambda: w.add_spheres([[0, 0, 0.1]], -0.001, glass), "radii"),
        (lambda: w.add_spheres([[0, 0, np.nan]], 0.001, glass), "positions"),
        (lambda: w.add_spheres(np.zeros((2, 2)), 0.001, glass), "positions"),
        (lambda: w.add_spheres(np.zeros((2, 3)) + 0.1, [0.001], glass), "radii"),
        (lambda: w.add_spheres([[0, 0, 0.1]], 0.001, glass, velocities=[[0, np.inf, 0]]), "velocities"),
        (lambda: w.set("position", np.zeros((3, 3))), "values"),
        (lambda: w.set("force", np.zeros((4, 3))), "force"),
        (lambda: w.set("orientation", np.ones((4, 4))), "orientation"),
        (lambda: w.get("nothing"), "unknown field"),
        (lambda: w.add_plane("p", (0, 0), (0, 0, 1), glass), "point"),
        (lambda: sd.World(law="nope"), "law"),
        (lambda: sd.World(solver="nope"), "solver"),
    ]
    for call, word in cases:
        with pytest.raises(sd.InputError) as e:
            call()
        assert word in str(e.value)
        assert isinstance(e.value, ValueError) and isinstance(e.value, sd.Error)
    assert len(w) == 4 and np.array_equal(w.get("position"), before)


def test_engine_errors_carry_the_engine_message():
    w, glass = glass_world()
    with pytest.raises(sd.InputError) as e:
        w.add_spheres([[0, 0, 0.1]], 0.001, material=7)
    assert e.value.status == "bad input"
    assert "unknown material index 7" in e.value.message
    assert e.value.key == "material" and str(e.value).startswith("material: ")
    with pytest.raises(sd.InputError) as e:
        w.add_material(name="bad", density=-1, youngs_modulus=1e7, poisson_ratio=0.3)
    assert "density" in str(e.value)
    with pytest.raises(sd.InputError):
        w.step(-1)


def test_step_refuses_an_unstable_time_step_with_the_engine_message():
    w = sd.World(dt=1e-5, gravity=(0, 0, -9.81))
    g = w.add_material(name="glass", density=2500, youngs_modulus=1e7, poisson_ratio=0.3, restitution=0.5,
                       friction=0.5)
    w.add_spheres([[0, 0, 0.01], [0.01, 0, 0.01]], 0.001, g, velocities=[[1e4, 0, 0], [0, 0, 0]])
    with pytest.raises(sd.InputError) as e:
        w.step(10)
    assert e.value.key == "simulation.dt" and "stability limit" in e.value.message
    assert w.step_count == 0
    assert issubclass(sd.PhysicsError, sd.Error) and issubclass(sd.StaleViewError, sd.Error)


def test_every_shape_kind_and_wall_kind():
    w = sd.World(dt=1e-6, gravity=(0, 0, -9.81))
    m = w.add_material(name="m", density=2000, youngs_modulus=1e7, poisson_ratio=0.3, restitution=0.5,
                       friction=0.3)
    w.set_interaction(m, m, friction=0.4, restitution=0.6)
    shapes = {
        "ball": w.add_shape("ball", "sphere", size=0.001),
        "cube": w.add_shape("cube", "box", size=(0.002, 0.002, 0.002), rounding=0.0001),
        "rod": w.add_shape("rod", "cylinder", size=(0.001, 0.0, 0.003), margin=0.0001),
        "cone": w.add_shape("cone", "cone", size=(0.002, 0.0, 0.002), margin=0.0001),
        "egg": w.add_shape("egg", "ellipsoid", size=(0.001, 0.0008, 0.0012)),
        "tet": w.add_shape("tet", "polyhedron", vertices=np.array(
            [[0, 0, 0], [0.002, 0, 0], [0, 0.002, 0], [0, 0, 0.002]])),
    }
    pair = w.add_composite("pair", [(shapes["ball"], (0, 0, 0)), (shapes["ball"], (0.0015, 0, 0), (1, 0, 0, 0))])
    cross = w.add_composite_preset("cross", "cross3d", length=0.003, diameter=0.001)
    assert w.shape_count >= 8 and w.find_shape("pair") == pair and w.find_shape("none") == -1
    info = w.shape(shapes["tet"])
    assert info["kind"] == "polyhedron" and info["volume"] == pytest.approx(0.002**3 / 6, rel=1e-9)
    assert w.shape(pair)["element_count"] == 2 and w.shape(cross)["element_count"] == 3
    with pytest.raises(IndexError):
        w.shape(99)
    for k, s in enumerate(list(shapes.values()) + [pair, cross]):
        q = np.array([[np.cos(0.1 * k), np.sin(0.1 * k), 0, 0]])
        ids = w.add_bodies(s, [[0.006 * k, 0, 0.004]], m, orientations=q, velocities=[[0, 0, -0.1]],
                           angular_velocities=[[0, 0, 1]])
        assert ids.shape == (1,)
    kinds = dict(zip(w.storage_ids, w.shapes))
    assert sorted(kinds.values()) == sorted(list(shapes.values()) + [pair, cross])
    w.add_box("box", lo=(-0.005, -0.01, 0), hi=(0.06, 0.01, 0.05), material=m, open_faces=["zmax"])
    plane = w.add_plane("lid", point=(0, 0, 0.04), normal=(0, 0, -1), material=m)
    w.set_wall_motion(plane, velocity=(0, 0, -0.01), move_start=0, move_end=0.001)
    verts = np.array([[-0.01, -0.02, 0.03], [0.07, -0.02, 0.03], [0.07, 0.02, 0.03], [-0.01, 0.02, 0.03]])
    mesh = w.add_mesh("shelf", verts, [[0, 1, 2], [0, 2, 3]], m, outside=True)
    w.set_mesh_motion(mesh, "translate", velocity=(0, 0, 0.01))
    with pytest.raises(sd.InputError):
        w.add_mesh("bad", verts, [[0, 1, 9]], m)
    with pytest.raises(sd.InputError):
        w.add_box("bad", lo=(0, 0, 0), hi=(1, 1, 1), material=m, open_faces=["top"])
    w.step(200)
    assert w.step_count == 200 and w.wall(plane)["velocity"] == pytest.approx((0, 0, -0.01))
    assert w.wall(mesh)["name"] == "shelf"


def test_drum_and_its_surface():
    w = sd.World(dt=2e-6, gravity=(0, 0, -9.81))
    m = w.add_material(name="m", density=2500, youngs_modulus=1e7, poisson_ratio=0.3, restitution=0.5,
                       friction=0.5)
    drum = w.add_drum("drum", center=(0, 0, 0), axis=(0, 1, 0), radius=0.02, length=0.01, material=m, rpm=30)
    k = np.arange(60)
    pos = np.stack([-0.012 + (k % 8) * 0.0032, -0.0035 + (k // 8 % 3) * 0.0032, -0.015 + (k // 24) * 0.0032],
                   axis=1)
    w.add_spheres(pos, 0.0012, m)
    w.step(500)
    fit = w.drum_surface(center=(0, 0, 0), axis=(0, 1, 0), radius=0.02, length=0.01, bins=10)
    assert set(fit) == {"angle", "slope", "rms", "columns"} and fit["columns"] >= 0
    bed = w.bed_height(fraction=0.5)
    assert bed["particles"] == 60 and bed["top"] > bed["mean"]
    assert w.bed_height(lo=(-1, -1, -1), hi=(1, 1, 0))["particles"] <= 60
    heap = w.heap_angle(bins=5)
    assert "angle" in heap
    assert w.wall(drum)["angular_velocity"][1] == pytest.approx(30 * 2 * np.pi / 60)


def test_planar_world():
    w = sd.World(dimension=2, dt=1e-5, gravity=(0, -9.81, 0))
    m = w.add_material(name="m", density=2500, youngs_modulus=1e7, poisson_ratio=0.3, restitution=0.5,
                       friction=0.5)
    disc = w.add_shape2d("disc", "circle", radius=0.001)
    ell = w.add_shape2d("ell", "ellipse", semi_axes=(0.0015, 0.001))
    poly = w.add_shape2d("tri", "polygon", points=[[0, 0], [0.002, 0], [0, 0.002]])
    four = w.add_shape2d("four", "fourier", fourier_a=[0.002, 0, 0.0001], fourier_b=[0, 0])
    w.add_plane("floor", point=(0, 0, 0), normal=(0, 1, 0), material=m)
    for k, s in enumerate([disc, ell, poly, four]):
        w.add_bodies(s, [[0.005 * k, 0.003, 0]], m)
    w.step(100)
    assert len(w) == 4 and np.all(w.get("position")[:, 2] == 0)


def test_periodic_and_grid_worlds():
    w = sd.World(periodic="xy", domain_lo=(0, 0, 0), domain_hi=(0.01, 0.01, 0.02), multi_contact="sum",
                 local_damping=0.1, seed=7, threads=1, skin=0.0002, max_overlap=0.4, backend="cpu")
    m = w.add_material(density=2500, youngs_modulus=1e7, poisson_ratio=0.3, restitution=0.5, friction=0.5)
    w.add_spheres([[0.0095, 0.005, 0.005]], 0.001, m, velocities=[[1, 0, 0]])
    w.step(200)
    assert 0 <= w.get("position")[0, 0] < 0.01  # wrapped round x
    g = sd.World(solver="grid", law="linear")
    with pytest.raises(sd.InputError) as e:
        g.positions
    assert "grid" in str(e.value)
    with pytest.raises(sd.InputError):
        sd.World(periodic="w")


def test_checkpoint_of_a_world(tmp_path):
    w, glass = glass_world(12)
    w.step(100)
    path = tmp_path / "w.h5"
    w.checkpoint(str(path))
    text = sd.checkpoint_info(str(path))
    assert "step 100" in text or "100" in text
    w2, _ = glass_world(12)
    w2.restore(str(path))
    assert w2.step_count == 100
    w.step(50)
    w2.step(50)
    assert np.array_equal(w.get("position"), w2.get("position"))  # the restart continues bit for bit
    with pytest.raises(sd.Error):
        w2.restore(str(tmp_path / "missing.h5"))
    with pytest.raises(sd.Error):
        sd.checkpoint_info(str(tmp_path / "missing.h5"))
    assert sd.memory_in_use() > 0 and sd.version == sd.__version__
