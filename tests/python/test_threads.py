"""step releases the GIL: other Python threads run while the engine steps,
and none of them can reach the stepping world."""
import threading

import numpy as np
import pytest

import shapedem as sd
from conftest import glass_world


def test_another_thread_runs_while_step_runs():
    w, glass = glass_world(125, threads=1)
    started, counts = threading.Event(), []
    refused = []

    def stepper():
        started.set()
        w.step(20000)

    t = threading.Thread(target=stepper)
    t.start()
    started.wait()
    n = 0
    while t.is_alive():  # this loop holds the GIL only if step gave it up
        n += 1
        if n == 1000:
            try:
                w.positions
            except sd.Error as e:
                refused.append(str(e))
    t.join()
    counts.append(n)
    assert w.step_count == 20000
    # with the GIL held for the whole step this thread would not run at all between
    # start and the end of the step: a few iterations at most
    assert counts[0] > 10000, counts
    assert refused and "stepping in another thread" in refused[0]


def test_two_worlds_step_in_two_threads():
    worlds = [glass_world(50, threads=1)[0] for _ in range(2)]
    ts = [threading.Thread(target=w.step, args=(2000,)) for w in worlds]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert np.array_equal(worlds[0].get("position"), worlds[1].get("position"))
