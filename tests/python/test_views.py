"""Views: the live particle arrays without a copy, and their invalidation."""
import numpy as np
import pytest

import shapedem as sd
from conftest import glass_world


def test_view_is_the_live_memory_and_sees_writes_through_the_c_api():
    w, glass = glass_world(10)
    v = w.velocities
    assert isinstance(v, sd.View)
    a = np.asarray(v)
    b = np.asarray(w.velocities)
    assert a.shape == (10, 3) and a.dtype == np.float64
    assert a.__array_interface__["data"][0] == b.__array_interface__["data"][0]  # the same memory: no copy
    assert not a.flags.writeable and not a.flags.owndata
    ids = np.asarray(w.storage_ids)
    row = int(np.nonzero(ids == 3)[0][0])
    w.set("velocity", [[1.5, -2.5, 3.5]], ids=[3])  # a write through sd_world_set_field ...
    assert v.valid and list(a[row]) == [1.5, -2.5, 3.5]  # ... is seen in the array taken before it
    assert list(v[row]) == [1.5, -2.5, 3.5]
    assert v.shape == (10, 3) and v.ndim == 2 and v.dtype == np.float64 and len(v) == 10
    assert v.field == "velocity" and v.generation == w.generation
    assert "velocity" in repr(v)
    with pytest.raises((BufferError, ValueError)):
        a[0, 0] = 1.0


def test_every_view_matches_the_copying_getters():
    w, glass = glass_world(30)
    w.step(300)  # a rebuild reorders storage
    order = np.argsort(np.asarray(w.storage_ids))
    for view, field in [(w.positions, "position"), (w.velocities, "velocity"),
                        (w.angular_velocities, "angular_velocity"), (w.orientations, "orientation"),
                        (w.forces, "force"), (w.torques, "torque"), (w.radii, "radius")]:
        assert np.array_equal(np.asarray(view)[order], w.get(field)), field
    assert np.asarray(w.materials).dtype == np.int32 and np.all(np.asarray(w.materials) == glass)
    assert np.all(np.asarray(w.shapes) == -1)
    assert np.asarray(w.storage_ids).dtype == np.uint64
    c = w.positions.copy()
    assert c.flags.owndata and np.array_equal(c, np.asarray(w.positions))
    assert np.array_equal(np.array(w.positions, dtype=np.float32), c.astype(np.float32))
    assert memoryview(w.radii).shape == (30,)


def test_a_rebuild_or_an_insertion_makes_a_view_stale():
    w, glass = glass_world(10)
    x = w.positions
    assert x.valid
    w.step(1)  # the first step's prepare rebuilds
    assert not x.valid
    for read in (lambda: x[0], lambda: np.asarray(x), lambda: len(x), lambda: x.shape, lambda: memoryview(x),
                 lambda: x.copy()):
        with pytest.raises(sd.StaleViewError) as e:
            read()
        assert "stale" in str(e.value) and "take it again" in str(e.value)
    assert "stale" in repr(x)
    y = w.positions
    assert y.valid
    w.add_spheres([[0.1, 0.1, 0.1]], 0.001, glass)
    with pytest.raises(sd.StaleViewError):
        y[0]
    assert len(w.positions) == 11


def test_view_indexing_returns_copies():
    w, glass = glass_world(5)
    x = w.positions
    col = x[:, 2]
    w.set("position", np.full((5, 3), 0.5))
    assert np.all(col != 0.5)  # taken before the write: a copy, not the live memory
    assert np.all(x[:, 2] == 0.5)
