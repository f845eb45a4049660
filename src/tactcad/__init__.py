"""tactcad: CAD-driven generator for spring-based tactile sensor arrays.

Data flows one way: design file (TOML) -> validated plan (:mod:`tactcad.design.array_plan`)
-> part modules (:mod:`tactcad.partlib`) -> solids (:mod:`tactcad.solids`) -> exports and checks. Units are mm, N, MPa,
N/mm and s throughout.

The public Python API (:mod:`tactcad.api`) is reachable from here:
``tactcad.load``, ``tactcad.Project``, and the build123d part classes
``tactcad.FlexureElement`` and ``tactcad.FlexureArray``
(:mod:`tactcad.assembly.part_objects`). They are imported on first use, so
``import tactcad`` stays cheap and loads no CAD kernel. The errors a user
can catch (``tactcad.DesignErrors``, ``tactcad.DesignError``,
``tactcad.TactcadError``, ...) are here too.
"""

import importlib
from typing import TYPE_CHECKING

from tactcad.errors import (CheckFailure, DesignError, DesignErrors, ExportPathError, SceneError,
                            TactcadError, Terminated)

from tactcad.version import VERSION as __version__

if TYPE_CHECKING:  # what type checkers see of the names imported on first use
    from tactcad.api import (CheckReport, DieProject, Element, Project, Verification, load,
                             load_die)
    from tactcad.assembly.part_objects import FlexureArray, FlexureElement, show

#: Public name -> the module that defines it (imported on first access).
_PUBLIC = {
    "load": "tactcad.api",
    "load_die": "tactcad.api",
    "Project": "tactcad.api",
    "DieProject": "tactcad.api",
    "Element": "tactcad.api",
    "CheckReport": "tactcad.api",
    "Verification": "tactcad.api",
    "FlexureElement": "tactcad.assembly.part_objects",
    "FlexureArray": "tactcad.assembly.part_objects",
    "show": "tactcad.assembly.part_objects",
}

#: Every error a user can catch, each naming the field, value and allowed range.
ERRORS = ["TactcadError", "DesignError", "DesignErrors", "SceneError", "ExportPathError",
          "CheckFailure", "Terminated"]

__all__ = ["__version__", *_PUBLIC, *ERRORS]


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
