"""The accepted design domain, drawn at random: every field of the design file
over its whole range, each drawn inside the limits the earlier draws leave
(the same rules :mod:`tactcad.design.array_plan` applies), so that a draw is a
design the validator should accept. The property test and ``make fuzz`` use it.

A draw is driven by two callables, so the same description serves hypothesis
(``pick = lambda lo, hi: draw(st.floats(lo, hi))``) and a seeded
:class:`random.Random` (``pick = rng.uniform``).

Units: mm, MPa.
"""

from __future__ import annotations

import math
from typing import Any, Callable, Sequence

from tactcad.design.array_plan import (ARM_RANGE_MM, MAX_COLUMNS, MIN_ARM_STEP_MM, MIN_BASE_BELOW_ARM_MM,
                                  MIN_FASTENER_GAP_MM, MIN_LIGAMENT_MM, MIN_SPACER_MM,
                                  MIN_TIP_GAP_MM, MIN_TIP_WALL_MM, NOTCH_RADIUS_MAX_MM,
                                  STACKED_COLUMNS_RANGE, WEB_RANGE_MM, default_design_data)
from tactcad.design.readout_section import DEFAULTS, GRID_WIDTH_RANGE_MM
from tactcad.design.rig_plan import default_rigs_data
from tactcad.partlib.array.element import WEB_TOLERANCE_RANGE_MM
from tactcad.partlib.bracket import EAR_HEAD_CLEARANCE_MM
from tactcad.vocabulary.process import WIRE_TOLERANCE_MM
from tactcad.vocabulary.standards import BOLTS, BoltSpec

Pick = Callable[[float, float], float]
Choose = Callable[[Sequence[Any]], Any]


def longest_grip_mm(bolt: BoltSpec) -> float:
    """The longest grip (mm) of ``bolt``'s longest stock length: the clamp plates
    and the element/spacer stack it can hold with its nut, two thread pitches
    beyond it (:func:`tactcad.design.array_plan.bolt_length`) and the rigs'
    bracket ear, which the bracket bolt grips as well (the default rigs' ear)."""
    ear = default_rigs_data()["bracket"]["ear_thickness_mm"]
    return max(bolt.catalogue_lengths_mm) - bolt.nut_height_mm - 2 * bolt.thread_pitch_mm - ear


def _count(pick: Pick, lo: int, hi: int) -> int:
    return min(hi, lo + int(pick(0.0, 1.0) * (hi - lo + 1)))


def draw_design(pick: Pick, choose: Choose, name: str = "fuzz") -> dict[str, Any]:
    """Raw tables of one in-domain design (the default file's texts and assumptions).

    Args:
        pick: ``pick(lo, hi)`` -> a float in ``[lo, hi]``.
        choose: ``choose(options)`` -> one of them.
    """
    data = default_design_data()
    data["design"]["name"] = name
    data.pop("assumptions", None)
    bolt = BOLTS[choose(tuple(BOLTS))]
    hole = bolt.clearance_hole_mm
    widest = max(bolt.nut_across_corners_mm, bolt.head_diameter_mm)

    sheet = pick(0.5, 10.0)
    plate = pick(1.0, 10.0)
    longest = longest_grip_mm(bolt)
    # the bolt holds both plates and at least the fewest columns a stacked array takes
    # (:data:`STACKED_COLUMNS_RANGE`): two sheets a spacer apart
    fewest = STACKED_COLUMNS_RANGE[0]
    plate = min(plate, max(1.0, (longest - fewest * sheet - MIN_SPACER_MM) / 2 - 0.01))
    sheet = min(sheet, (longest - 2 * plate - MIN_SPACER_MM) / fewest - 0.01)
    pitch = pick(sheet + MIN_SPACER_MM, min(20.0, (longest - 2 * plate - sheet) / (fewest - 1)))
    max_cols = int((longest - 2 * plate - sheet) // pitch) + 1
    columns = _count(pick, fewest, max(fewest, min(MAX_COLUMNS, max_cols)))

    wire, spark = pick(0.02, 0.35), pick(0.0, 0.1)
    r_min = wire / 2 + spark
    web = pick(*WEB_RANGE_MM)
    notch = pick(max(web, r_min), NOTCH_RADIUS_MAX_MM)
    arm_h = pick(web + notch + r_min, 5.0)
    corner = pick(r_min, 1.0)
    # the tip root must fit on the longest allowed arm
    tip_hi = min(pitch - MIN_TIP_GAP_MM, 2 * (ARM_RANGE_MM[1] - corner - notch - 0.5) - 0.01,
                 ARM_RANGE_MM[1] - 0.02)
    tip_w = pick(0.5, max(0.5, tip_hi))
    tip_root = tip_w / 2 + corner + notch + 0.5
    arm_lo = max(ARM_RANGE_MM[0], tip_root, tip_w + 0.01)
    # the mounting bolts sit between the rows' innermost bases: room for their heads
    arm_lo = max(arm_lo, min(ARM_RANGE_MM[1],
                             max(widest + MIN_FASTENER_GAP_MM, 2 * (0.2 + bolt.nominal_diameter_mm / 2))
                             - pitch / 2 - notch))
    arm_clear = pick(0.2, min(3.0, max(0.2, (pitch / 2 + arm_lo + notch) / 2
                                       - bolt.nominal_diameter_mm / 2)))
    # distinct arms differ by 0.01 mm at least: draw on that grid
    step = MIN_ARM_STEP_MM
    grid_lo, grid_hi = math.ceil(arm_lo / step - 1e-9), math.floor(ARM_RANGE_MM[1] / step + 1e-9)
    arms = [min(grid_hi, max(grid_lo, round(pick(arm_lo, ARM_RANGE_MM[1]) / step))) * step
            for _ in range(2 * columns)]

    base_h = pick(max(arm_h + MIN_BASE_BELOW_ARM_MM, arm_h + hole + 2 * MIN_LIGAMENT_MM,
                      arm_h + arm_clear + hole + 1.0), 30.0)
    bridge = pick(hole + 1.0, min(30.0, base_h - arm_h - arm_clear))
    spacing_lo = max(hole + MIN_LIGAMENT_MM, widest + MIN_FASTENER_GAP_MM)
    pattern = hole + 2 * MIN_LIGAMENT_MM
    reach = tip_w / 2 + max(arms) + notch + arm_clear + pattern  # overall - this = room for spacing
    # the rigs' bracket ear sits between the clamp bolt heads nearest the middle and
    # carries the two mounting holes: tip_centre_x >= spacing - ear_room
    inner_end = pitch / 2 + min(arms) + notch
    ear_room = (pitch + max(arms) + notch + arm_clear - 2 * bolt.head_diameter_mm
                - 2 * EAR_HEAD_CLEARANCE_MM - inner_end - hole)
    spacing_hi = min(40.0, 60.0 - reach, 60.0 - tip_w / 2 + ear_room)
    spacing = pick(spacing_lo, max(spacing_lo, spacing_hi))
    overall = pick(min(60.0, max(10.0, reach + spacing, spacing - ear_room + tip_w / 2)), 60.0)

    data["material"].update(youngs_modulus_MPa=pick(1e3, 1e6),
                            poisson_ratio=min(0.499, max(0.001, pick(0.0, 0.5))))
    data["sheet"]["thickness_mm"] = sheet
    if sheet < DEFAULTS["grid_width_mm"][0]:  # the gauge grid lies on the sheet's face
        data.setdefault("readout", {})["grid_width_mm"] = pick(GRID_WIDTH_RANGE_MM[0], sheet)
    data["array"].update(columns=columns, pitch_mm=pitch)
    data["element"].update(web_thickness_mm=web, notch_radius_mm=notch, tip_width_mm=tip_w,
                           tip_height_mm=pick(max(0.3, corner + MIN_TIP_WALL_MM), 5.0),
                           arm_height_mm=arm_h,
                           base_height_mm=base_h, overall_length_mm=overall,
                           inside_corner_radius_mm=corner,
                           # drawn no finer than the cut process holds (wire EDM standard finish)
                           web_tolerance_mm=pick(WIRE_TOLERANCE_MM, min(0.1, web / 2)))
    data["arms"]["lengths_mm"] = arms
    data["clamp"].update(bolt_size=bolt.size, bolt_spacing_mm=spacing, plate_thickness_mm=plate,
                         bridge_height_mm=bridge, arm_clearance_mm=arm_clear)
    data["edm"].update(wire_diameter_mm=wire, spark_gap_mm=spark,
                       start_hole_diameter_mm=pick(0.3, min(3.0, hole - 0.01)))
    return data


#: One field of the design per entry, with a value outside its range: (field, value).
def draw_out_of_domain(pick: Pick, choose: Choose) -> tuple[str, Any]:
    """A field and a value its static range refuses (the field the refusal must name)."""
    field, lo, hi = choose((
        ("element.web_thickness_mm", *WEB_RANGE_MM), ("arms.lengths_mm[2]", *ARM_RANGE_MM),
        ("element.tip_height_mm", 0.3, 5.0), ("sheet.thickness_mm", 0.5, 10.0),
        ("element.overall_length_mm", 10.0, 60.0), ("clamp.plate_thickness_mm", 1.0, 10.0),
        ("clamp.arm_clearance_mm", 0.2, 3.0), ("edm.wire_diameter_mm", 0.02, 0.35),
        ("material.youngs_modulus_MPa", 1e3, 1e6), ("element.web_tolerance_mm", *WEB_TOLERANCE_RANGE_MM)))
    kind = choose(("below", "above", "nan", "inf", "bool", "text"))
    value: Any = {"below": lo - pick(1e-6, 100.0), "above": hi + pick(1e-6, 100.0),
                  "nan": math.nan, "inf": -math.inf, "bool": True, "text": f"{lo}"}[kind]
    return field, value
