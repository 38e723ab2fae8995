"""Scene and Run: a scene file run from Python writes what `shapedem run` writes."""
import subprocess

import numpy as np
import pytest

import shapedem as sd
from conftest import BIN, SMALL_SCENE


def test_python_run_writes_the_same_stats_as_shapedem_run(small_scene, tmp_path):
    cli = tmp_path / "cli"
    subprocess.run([BIN, "run", str(small_scene), "-o", str(cli), "--quiet"], check=True)
    scene = sd.Scene.load(str(small_scene))
    assert scene.steps == 300 and scene.info["dt"] == 5e-6 and scene.info["stats_every"] == 50
    py = tmp_path / "py"
    run = scene.run(output=str(py), threads=2)
    assert run.directory == str(py) and not run.closed
    times = []
    for t in run.every(0.00035):  # 70 steps a chunk: chunks that do not fall on the output steps
        x = run.world.positions  # a fresh view each chunk
        assert x.shape == (48, 3) and np.asarray(x)[:, 2].max() > 0
        times.append(t)
    assert run.progress["done"] == 300 and len(times) == 5 and times[-1] == pytest.approx(300 * 5e-6)
    assert run.advance() is False
    run.close()
    assert run.closed
    run.close()  # a second close does nothing
    a, b = (cli / "stats.csv").read_bytes(), (py / "stats.csv").read_bytes()
    assert a == b and a.count(b"\n") == 8  # header and steps 0, 50, ..., 300
    assert (py / "frames.pvd").read_bytes() == (cli / "frames.pvd").read_bytes()
    assert (py / "summary.txt").exists()


def test_run_in_a_with_block_advance_and_checkpoint(small_scene, tmp_path):
    scene = sd.Scene.load(str(small_scene))
    with scene.run(str(tmp_path / "a"), steps=100) as run:
        assert run.advance(40) is True
        ck = run.checkpoint()
        assert ck.endswith("checkpoint-000040.h5")
        assert run.advance() is False and run.progress["done"] == 100
        assert run.world.step_count == 100
    assert run.closed
    with pytest.raises(sd.Error):
        run.advance(1)
    assert "40" in sd.checkpoint_info(ck)
    # a restart continues bit for bit: the same state at step 100 as the run that did not stop
    with scene.run(str(tmp_path / "b"), restart=ck, steps=100) as again:
        assert again.progress["first"] == 40
        again.advance()
        assert np.array_equal(again.world.get("position"), run.world.get("position"))
    w = scene.build()
    assert len(w) == 48 and w.step_count == 0
    with scene.run(files=False) as quiet:
        assert quiet.directory == ""
        quiet.advance(10)


def test_scene_errors_name_the_file_line_and_key(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(SMALL_SCENE.replace("dt: 5.0e-6", "dt: -1"))
    with pytest.raises(sd.InputError) as e:
        sd.Scene.load(str(bad))
    assert e.value.file.endswith("bad.yaml") and e.value.line == 2 and e.value.key == "simulation.dt"
    assert str(e.value).startswith(str(bad) + ":2: simulation.dt: ")
    with pytest.raises(sd.Error) as e:
        sd.Scene.load(str(tmp_path / "missing.yaml"))
    assert "missing.yaml" in str(e.value)
    scene_dir = tmp_path / "full"
    scene_dir.mkdir()
    (scene_dir / "someone-elses.txt").write_text("x")
    good = tmp_path / "good.yaml"
    good.write_text(SMALL_SCENE)
    with pytest.raises(sd.Error):
        sd.Scene.load(str(good)).run(str(scene_dir))  # a directory holding files the run did not make
    with pytest.raises(sd.InputError):
        sd.Scene.load(str(good)).run(threads=0)
