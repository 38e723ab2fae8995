"""Every public name of the package is called by some python.* test (as
unit.api_states does for the C headers): a function added without a test
fails here."""
import pathlib
import re

import shapedem as sd


def public_names():
    names = set(sd.__all__)
    for cls in (sd.World, sd.View, sd.Scene, sd.Run):
        names |= {n for n in dir(cls) if not n.startswith("_")}
    return names


def test_every_public_name_is_used_by_a_test():
    here = pathlib.Path(__file__).parent
    text = "\n".join(p.read_text() for p in here.glob("test_*.py") if p.name != pathlib.Path(__file__).name)
    missing = sorted(n for n in public_names() if not re.search(r"\b" + re.escape(n) + r"\b", text))
    print(f"{len(public_names())} public names, {len(missing)} not used by a test: {missing}")
    assert not missing


def test_every_public_name_has_a_stub_and_a_docstring():
    stubs = (pathlib.Path(sd.__file__).parent / "_shapedem.pyi").read_text()
    for cls in (sd.World, sd.View, sd.Scene, sd.Run):
        assert f"class {cls.__name__}" in stubs and cls.__doc__
        for n in dir(cls):
            if not n.startswith("_"):
                assert re.search(r"\b" + n + r"\b", stubs), f"{cls.__name__}.{n} has no stub"
                assert getattr(cls, n).__doc__, f"{cls.__name__}.{n} has no docstring"
    for n in sd.__all__:
        assert re.search(r"\b" + n + r"\b", stubs), n
