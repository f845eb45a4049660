"""Design files -> validated, immutable plans (no CAD kernel).

* :mod:`tactcad.design.array`: the array design file (``hardware/macro_array.toml``)
  and its plan: element profiles, bolt pattern, spacers, clamp plates;
* :mod:`tactcad.design.rigs`: the test-rig file (``hardware/rigs.toml``);
* :mod:`tactcad.design.scenes`: the scenes file (``hardware/scenes.toml``).

Units: mm, N, MPa throughout.
"""

from tactcad.design.array import (DEFAULT_DESIGN, ElementGeometry, Material, Plan, load_design,
                                  plan_from_dict)

__all__ = ["DEFAULT_DESIGN", "ElementGeometry", "Material", "Plan", "load_design", "plan_from_dict"]
