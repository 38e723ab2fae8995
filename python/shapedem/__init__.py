"""shapedem: the discrete element method engine for granular materials of real shape.

The classes are the C library's own objects (the extension shapedem._shapedem,
a thin layer over include/shapedem/*.h):

    World        a world built in Python: materials, shapes, walls, particles; step()
    View         a live, zero-copy numpy view of one particle field (World.positions, ...)
    Scene, Run   a scene file loaded and run with its output, as `shapedem run` does
    Error        the engine's errors (InputError, PhysicsError, StaleViewError)

docs/python.md shows a worked example.
"""
from ._shapedem import (  # noqa: F401
    Error,
    InputError,
    PhysicsError,
    Run,
    Scene,
    StaleViewError,
    View,
    World,
    checkpoint_info,
    fields,
    memory_in_use,
    version,
)

__version__ = version
__all__ = [
    "Error",
    "InputError",
    "PhysicsError",
    "Run",
    "Scene",
    "StaleViewError",
    "View",
    "World",
    "checkpoint_info",
    "fields",
    "memory_in_use",
    "version",
]
