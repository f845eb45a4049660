"""Crossed XY micro-stages on the base plate (bought parts, modelled as
envelopes): two single-axis stages, each a fixed base and a moving table;
they bring each element's tip under the indenter in the calibration rig
(sources in ``hardware/purchased-parts.md``).

Part frames: a base or table is ``size`` square, centred in x and y, z = 0
on its underside. Units: mm.
"""

from __future__ import annotations

import math
from typing import Optional

from tactcad.partlib.base import PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import box
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, fmt, number

COLORS = {"xy_stage_base": (0.20, 0.22, 0.26), "xy_stage_table": (0.28, 0.30, 0.35)}
#: Travel of the crossed micro-stages when the rigs file gives none, mm (a
#: usual 60 mm stage); more when the array's tips spread wider.
STAGE_TRAVEL_MM = 25.0


class XYStageSection(Section):
    """``[xy_stage]`` of ``rigs.toml``."""

    size_mm: number(10.0, 300.0)
    base_height_mm: number(2.0, 100.0)
    table_height_mm: number(2.0, 100.0)
    travel_mm: Optional[number(1.0, 200.0)] = None  # default: enough to reach every tip


class XYStageSpec(table_values(XYStageSection)):
    """One stage (mm), its travel filled in."""


def stage_reach(plan) -> float:
    """Largest offset (mm, along x or z) of a tip from the centroid of all tips
    of the array's ``plan``: the stages move the array by this much to put any
    element under the indenter."""
    tips = [s.tip_centre_world_mm for s in plan.slots]
    cx = sum(t[0] for t in tips) / len(tips)
    cz = sum(t[2] for t in tips) / len(tips)
    return max(max(abs(t[0] - cx), abs(t[2] - cz)) for t in tips)


def derive(xy: XYStageSection, context, p: Problems) -> PartData:
    """The stages between the base plate's grooves (``base_plate``), with the
    travel to reach every tip of the array (``context.plan``)."""
    base = context.part("base_plate").geometry
    if xy.size_mm / 2 > base.track_half_mm - base.groove_width_mm / 2:
        p.add("xy_stage.size_mm", xy.size_mm,
              f"<= {fmt(2 * (base.track_half_mm - base.groove_width_mm / 2))} mm",
              "the stages stand on the base plate between the grooves")
    reach = stage_reach(context.plan)
    travel = xy.travel_mm if xy.travel_mm is not None else max(STAGE_TRAVEL_MM, math.ceil(2 * reach + 1))
    if xy.travel_mm is not None:
        p.within("xy_stage.travel_mm", travel, 2 * reach,
                 why="the stages must bring every element's tip under the indenter")
    g = values_from(XYStageSpec, xy, travel_mm=travel)
    table = PartData(**_stage(g, "xy_stage_table", g.table_height_mm, "moving table"),
                     builder="xy_stage_table")
    return PartData(**_stage(g, "xy_stage_base", g.base_height_mm, "fixed base"),
                    companions=(table,))


def _stage(g: XYStageSpec, name: str, height: float, extra: str) -> dict:
    """The fields of one stage's :class:`PartData`."""
    a = g.size_mm / 2
    return dict(
        name=name, kind="purchased",
        process=Process(f"manual linear micro-stage {g.size_mm:g} mm square, "
                        f"{g.travel_mm:g} mm travel: envelope of the {extra}", Method.BOUGHT),
        material="aluminium", color=COLORS[name], expected_volume_mm3=g.size_mm ** 2 * height,
        expected_bbox_mm=(-a, -a, 0.0, a, a, float(height)), geometry=g,
        frames={"bottom": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "top": Seat((0, 0, height), (0, 0, 1), (1, 0, 0)),
                "top_rot": Seat((0, 0, height), (0, 0, 1), (0, 1, 0)),
                "top_rot_neg": Seat((0, 0, height), (0, 0, 1), (0, -1, 0))})


def build_base(s: XYStageSpec):
    """Fixed part of a single-axis stage (build123d ``Solid``), z = 0 ... base height."""
    a = s.size_mm / 2
    return box(-a, -a, 0, a, a, s.base_height_mm)


def build_table(s: XYStageSpec):
    """Moving table of a single-axis stage (build123d ``Solid``), z = 0 ... table height."""
    a = s.size_mm / 2
    return box(-a, -a, 0, a, a, s.table_height_mm)


PART = RigPart(key="xy_stage", section=XYStageSection, host="", derive=derive, build=build_base,
               needs=("base_plate",), order=80, builder="xy_stage_base",
               companion_builders={"xy_stage_table": build_table})
