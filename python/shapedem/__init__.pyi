# Type stubs of the package shapedem: the names of the extension (_shapedem.pyi).
from ._shapedem import (
    Error as Error,
    InputError as InputError,
    PhysicsError as PhysicsError,
    Run as Run,
    Scene as Scene,
    StaleViewError as StaleViewError,
    View as View,
    World as World,
    checkpoint_info as checkpoint_info,
    fields as fields,
    memory_in_use as memory_in_use,
    version as version,
)

__version__: str
__all__: list[str]
