"""The tolerances an export's drawings take from the analyses, worked out once per design.

The drawings layer prints what it is handed; this module, where the export plans its
drawings, hands it the tip-height decision of the K_obj budget
(:mod:`tactcad.in_use.tip_height_drawing`) and names the parts it applies to. The build
book reads the same decision for its zeroing step.

Units: mm.
"""

from __future__ import annotations

import hashlib
from typing import Mapping

from tactcad.design.array_plan import Plan
from tactcad.in_use.tip_height_drawing import TipHeightDrawing, tip_height_from_budget

#: The parts whose drawing dimensions the contact face's height (builder keys): the
#: stacked array's element and the monolithic comb's sheet.
TIP_PARTS = ("element", "comb_sheet")

_CHOSEN: dict[str, TipHeightDrawing | None] = {}


def tip_height_drawing(plan: Plan) -> TipHeightDrawing | None:
    """The tip-height decision of ``plan``'s drawings
    (:func:`tactcad.in_use.tip_height_drawing.choose_tip_height_tolerance`).

    Args:
        plan: the validated design.

    Returns:
        The decision from the closed-form K_obj budget at the full-scale force and the
        default temperature step over the required range (as the manifest's); None without
        ``requirements.kobj_accuracy_rel``, or where the budget cannot be evaluated (a
        material of unknown CTE: the drawing keeps its stated tolerance). Kept per design
        content: the export plans it once, its worker again.
    """
    from tactcad.design.requirements_section import stated_kobj_accuracy

    if stated_kobj_accuracy(plan.raw) is None:
        return None
    # the rigs' force gauge sets the calibration term the budget's tolerance rests on
    key = hashlib.sha256(repr((sorted(_flat(plan.raw)), plan.rigs_force_gauge)).encode()
                         ).hexdigest()
    if key not in _CHOSEN:
        _CHOSEN[key] = _from_closed_form_budget(plan)
    return _CHOSEN[key]


def tip_height_for(plan: Plan, builder: str | None) -> TipHeightDrawing | None:
    """The tip-height decision a part's drawing is handed.

    Args:
        plan: the validated design.
        builder: the part's builder key (``PartSpec.builder``).

    Returns:
        :func:`tip_height_drawing` for a part that carries tips (:data:`TIP_PARTS`), None
        for any other part.
    """
    return tip_height_drawing(plan) if builder in TIP_PARTS else None


def _flat(table: Mapping, prefix: str = "") -> list[tuple[str, str]]:
    """A design's tables as (dotted key, value text) pairs: a key for its content."""
    out = []
    for k, v in table.items():
        if isinstance(v, Mapping):
            out += _flat(v, f"{prefix}{k}.")
        else:
            out.append((f"{prefix}{k}", repr(v)))
    return out


def _from_closed_form_budget(plan: Plan) -> TipHeightDrawing | None:
    from tactcad.errors import DesignError
    from tactcad.in_use.kobj_budget import DEFAULT_DELTA_T_K, kobj_budget
    from tactcad.studies.verification import calibration_gauge
    from tactcad.studies.verification import requirements_of

    req = requirements_of(plan)
    try:
        budget = kobj_budget(plan, req.kobj_range_N_per_mm, req.full_scale_force_N,
                             DEFAULT_DELTA_T_K, force_gauge=calibration_gauge(plan),
                             readable_within_rel=req.kobj_resolution_rel)
    except DesignError:
        return None
    return tip_height_from_budget(plan, budget)
