"""The grasper's shaft (a bought-in instrument's tube, 17-4PH or 316L
stainless steel): a tube of the trocar class's diameter whose bore is the
lead channel the insert's leads run through to the handle
(:func:`tactcad.checks.grasper_fit.shaft_leads_result` checks they fit,
with :mod:`tactcad.in_use.shaft_leads`).

Shafts are typically 270-360 mm long (Khan et al., Int J Surg 2024); the
default 330 mm lies inside that. Not in the rigs file: the ``grasper``
rig places it, like the jaw (:mod:`tactcad.partlib.grasper_jaw`). Part frame: axis along +x from the
distal end (x = 0, where the jaw's pivot sits), centred in y and z. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping, Optional

from tactcad.kernel.shapes import cut, cylinder
from tactcad.partlib.base import DrawingRecord, PartData, RigPart, Seat
from tactcad.partlib.grasper_jaw import JAW_STEELS, SHAFT_CLASSES_MM, part_from_table
from tactcad.vocabulary.schema import Derived, Problems, Section, choice, fmt, number
from tactcad.vocabulary.process import Method, Process

COLOR = (0.60, 0.62, 0.66)
#: Least lead channel (bore) diameter, mm: a smaller bore is no longer a tube to draw leads through.
MIN_BORE_MM = 0.5


class GrasperShaftSection(Section):
    """``[grasper_shaft]``: the shaft tube (mm)."""

    shaft_class_mm: choice(SHAFT_CLASSES_MM, why="the trocar the instrument passes") = "10"
    outer_diameter_mm: Optional[number(2.0, 20.0, why="the tube's diameter; left out: the "
                                       "class's")] = None
    length_mm: number(100.0, 500.0) = 330.0  # typical 270-360 mm
    wall_mm: number(0.1, 3.0) = 0.5
    material: choice(JAW_STEELS) = JAW_STEELS[1]


@dataclass(frozen=True)
class GrasperShaftGeometry:
    """The shaft tube (mm)."""

    outer_diameter_mm: float
    bore_diameter_mm: float
    length_mm: float


def derive(s: GrasperShaftSection, context, p: Problems) -> PartData:
    """The shaft tube of the table's class.

    Args:
        s: the validated ``[grasper_shaft]`` table.
        context: unused (the shaft does not follow the array).
        p: refusals are added here.

    Returns:
        The shaft's :class:`PartData`; its bore is the lead channel.
    """
    od = shaft_diameter_mm(s)
    p.within("grasper_shaft.wall_mm", s.wall_mm, hi=(od - MIN_BORE_MM) / 2,
             why=f"a lead channel of at least {fmt(MIN_BORE_MM)} mm inside the {fmt(od)} mm tube")
    bore = max(od - 2 * s.wall_mm, MIN_BORE_MM)
    g = GrasperShaftGeometry(od, bore, s.length_mm)
    r = od / 2
    return PartData(
        name="grasper_shaft", kind="fabricated",
        process=Process(f"bought-in grasper shaft, tube {fmt(od)} x {fmt(s.wall_mm)} mm wall, cut to "
                        "length", Method.ROUND_BAR),
        material=s.material, color=COLOR, expected_volume_mm3=shaft_volume_mm3(g),
        expected_bbox_mm=(0.0, -r, -r, s.length_mm, r, r), geometry=g,
        derived=(Derived("grasper_shaft_lead_channel", bore, "mm",
                         f"the {fmt(od)} mm tube's bore: wall {fmt(s.wall_mm)} mm"),),
        attributes={"lead_channel_diameter_mm": bore},
        frames={"distal": Seat((0, 0, 0), (-1, 0, 0), (0, 1, 0)),
                "proximal": Seat((s.length_mm, 0, 0), (1, 0, 0), (0, 1, 0))})


def shaft_diameter_mm(s: GrasperShaftSection) -> float:
    """The tube's outer diameter (mm): stated, else the class's."""
    return s.outer_diameter_mm if s.outer_diameter_mm is not None \
        else SHAFT_CLASSES_MM[s.shaft_class_mm]


def shaft_volume_mm3(g: GrasperShaftGeometry) -> float:
    """The tube's volume (mm^3): π/4 (D² - d²) L."""
    return math.pi / 4 * (g.outer_diameter_mm ** 2 - g.bore_diameter_mm ** 2) * g.length_mm


def build(g: GrasperShaftGeometry):
    """The tube along +x (build123d ``Solid``)."""
    outer = cylinder(g.outer_diameter_mm / 2, (0, 0, 0), (1, 0, 0), g.length_mm)
    bore = cylinder(g.bore_diameter_mm / 2, (0, 0, 0), (1, 0, 0), g.length_mm)
    return cut(outer, bore)


def shaft_part(table: Mapping[str, Any] | None = None, file: str = "") -> PartData:
    """The shaft from a ``[grasper_shaft]`` table (defaults where left out).

    Raises:
        DesignErrors: every refusal, each naming the field, value and allowed range.
    """
    return part_from_table("grasper_shaft", GrasperShaftSection, derive, table, file)


IN_USE_PART = RigPart(key="grasper_shaft", section=GrasperShaftSection, host="", derive=derive,
                build=build, drawing=DrawingRecord(hole_table=False))
