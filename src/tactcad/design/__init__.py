"""Design files -> validated, immutable plans (no CAD kernel).

* the vocabulary they are written in (schema mechanism, ISO standards, materials):
  :mod:`tactcad.vocabulary`; the optional rig parts written one module each: :mod:`tactcad.partlib`;
* :mod:`tactcad.design.array_plan`: the array design file (``hardware/macro_array.toml``)
  and its plan: element profiles, bolt pattern, spacers, clamp plates;
* :mod:`tactcad.design.rig_plan`: the test-rig file (``hardware/rigs.toml``), derived
  against the array's plan;
* :mod:`tactcad.design.scene_specs`: the scenes file (``hardware/scenes.toml``);
* :mod:`tactcad.design.project`: the three files validated together
  (:func:`~tactcad.design.project.load_project`);
* :mod:`tactcad.design.domain`: random designs over the accepted domain (fuzzing).

Units: mm, N, MPa throughout.
"""

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # what type checkers see of the names imported on first use
    from tactcad.design.array_plan import (DEFAULT_DESIGN, ElementGeometry, Material, Plan,
                                           load_design, plan_from_dict)

__all__ = ["DEFAULT_DESIGN", "ElementGeometry", "Material", "Plan", "load_design", "plan_from_dict"]


def __getattr__(name: str):
    # PEP 562: the plan's names are imported on first use, so that a module of this
    # package read for its constants (a command's --help) does not load the design model
    # (numpy, pydantic and every part module: a second)
    if name not in __all__:
        raise AttributeError(f"module 'tactcad.design' has no attribute {name!r}")
    value = getattr(importlib.import_module("tactcad.design.array_plan"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
