"""No leak over 10^5 calls: the process's Python allocations (tracemalloc)
and the engine's (memory_in_use) stay flat, and the objects passed in keep
their reference counts."""
import gc
import sys
import tracemalloc

import numpy as np

import shapedem as sd
from conftest import glass_world

CALLS = 100_000


def test_no_leak_over_many_calls():
    w, glass = glass_world(8)
    ids = w.ids()
    vel = np.zeros((8, 3))
    name = "velocity"
    refs = (sys.getrefcount(ids), sys.getrefcount(vel), sys.getrefcount(name), sys.getrefcount(w))

    def calls(n):
        for _ in range(n):
            x = w.positions
            x[0]
            np.asarray(x)
            w.get(name, ids)
            w.set(name, vel, ids)
            w.stats()
            w.wall(0)
            try:
                w.add_spheres([[0, 0, np.nan]], 0.001, glass)
            except sd.InputError:
                pass

    calls(1000)  # warm-up: caches of numpy and the interpreter
    gc.collect()
    tracemalloc.start()
    engine0 = sd.memory_in_use()
    before = tracemalloc.get_traced_memory()[0]
    calls(CALLS // 8)
    calls(CALLS - CALLS // 8)
    gc.collect()
    after = tracemalloc.get_traced_memory()[0]
    tracemalloc.stop()
    grown = after - before
    print(f"python allocations grew by {grown} bytes over {CALLS} rounds of 8 calls (bound 65536)")
    assert grown < 65536, grown  # one leaked object per call would be megabytes
    assert sd.memory_in_use() == engine0
    assert (sys.getrefcount(ids), sys.getrefcount(vel), sys.getrefcount(name), sys.getrefcount(w)) == refs
