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

from tactcad.design.array_plan import (DEFAULT_DESIGN, ElementGeometry, Material, Plan, load_design,
                                  plan_from_dict)

__all__ = ["DEFAULT_DESIGN", "ElementGeometry", "Material", "Plan", "load_design", "plan_from_dict"]
