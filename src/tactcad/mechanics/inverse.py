"""Inverse design: from sensing targets to element geometry and a design file.

Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

import copy
import math
from typing import Any, Mapping, Sequence

from ..design import BOLTS, MIN_LIGAMENT_MM

#: Clearance (mm) between the notch bottom and the arm's underside when the
#: arm height has to grow with the web and notch radius (as the correction fit).
ARM_HEIGHT_CLEARANCE_MM = 0.5
#: Overall element lengths are rounded up to this step (mm).
LENGTH_STEP_MM = 0.5


def required_overall_length_mm(data: Mapping[str, Any], longest_arm_mm: float,
                               notch_radius_mm: float) -> float:
    """Shortest overall element length (mm) whose clamped base still holds the
    bolt pattern with the longest arm: the rule of
    :func:`tactcad.design.plan_from_dict` solved for the length.

    base = overall - tip_width/2 - arm - R, and base - arm clearance must
    hold bolt spacing + clearance hole + two 1 mm ligaments.
    """
    el, cl = data["element"], data["clamp"]
    bolt = BOLTS.get(cl["bolt_size"])
    hole = bolt.clearance_hole_mm if bolt else 0.0
    return (longest_arm_mm + notch_radius_mm + el["tip_width_mm"] / 2 + cl["arm_clearance_mm"]
            + cl["bolt_spacing_mm"] + hole + 2 * MIN_LIGAMENT_MM)


def design_variant(data: Mapping[str, Any], *, web_mm: float | None = None,
                   notch_radius_mm: float | None = None,
                   arms_mm: Sequence[float] | None = None,
                   pitch_mm: float | None = None) -> dict[str, Any]:
    """Raw design tables with web, notch radius, arm lengths and pitch replaced.

    Dimensions that the change forces are adjusted with it: the arm height
    grows to web + notch radius + 0.5 mm when the notch would otherwise open
    through the arm, and the overall length grows (in 0.5 mm steps) when the
    longest arm leaves the clamped base too short for its bolt pattern. The
    result is not validated: pass it to :func:`tactcad.design.plan_from_dict`.

    Args:
        data: raw tables of a design (e.g. ``Plan.raw`` or
            :func:`tactcad.design.default_design_data`); not modified.
        web_mm, notch_radius_mm, pitch_mm: new values (mm) or ``None``.
        arms_mm: one arm length per element (mm), paper numbering order.

    Returns:
        A new dict of raw tables.
    """
    out = copy.deepcopy(dict(data))
    el = out["element"]
    if web_mm is not None:
        el["web_thickness_mm"] = float(web_mm)
    if notch_radius_mm is not None:
        el["notch_radius_mm"] = float(notch_radius_mm)
    if arms_mm is not None:
        out["arms"]["lengths_mm"] = [float(a) for a in arms_mm]
    if pitch_mm is not None:
        out["array"]["pitch_mm"] = float(pitch_mm)
    t, R = el["web_thickness_mm"], el["notch_radius_mm"]
    if el["arm_height_mm"] <= t + R:
        el["arm_height_mm"] = round(t + R + ARM_HEIGHT_CLEARANCE_MM, 6)
    arms = out["arms"]["lengths_mm"]
    if arms and all(isinstance(a, (int, float)) for a in arms):
        need = required_overall_length_mm(out, max(arms), R)
        if el["overall_length_mm"] < need:
            el["overall_length_mm"] = math.ceil(need / LENGTH_STEP_MM) * LENGTH_STEP_MM
    return out
