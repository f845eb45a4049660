"""tactcad: CAD-driven generator for spring-based tactile sensor arrays.

Data flows one way: design file (TOML) -> validated plan (:mod:`tactcad.design.array`)
-> geometry (:mod:`tactcad.parts`) -> exports and checks. Units are mm, N, MPa,
N/mm and s throughout.

The public Python API (:mod:`tactcad.api`) is reachable from here:
``tactcad.load``, ``tactcad.Project``, and the build123d part classes
``tactcad.FlexureElement`` and ``tactcad.FlexureArray``
(:mod:`tactcad.assembly.part_objects`). They are imported on first use, so
``import tactcad`` stays cheap and loads no CAD kernel.
"""

import importlib

__version__ = "0.1.0"

#: Public name -> the module that defines it (imported on first access).
_PUBLIC = {
    "load": "tactcad.api",
    "Project": "tactcad.api",
    "Element": "tactcad.api",
    "CheckReport": "tactcad.api",
    "FlexureElement": "tactcad.assembly.part_objects",
    "FlexureArray": "tactcad.assembly.part_objects",
    "show": "tactcad.assembly.part_objects",
}

__all__ = ["__version__", *_PUBLIC]


def __getattr__(name: str):
    # PEP 562: the API's modules sit at the top of the layers, so this
    # package (the foundation) reaches them only by name, when asked
    module = _PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module 'tactcad' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_PUBLIC))
