"""The monolithic comb's hardware, placed: the spacer between the rows (a plate of the
spine's outline with its holes), the ISO 8734 dowel pins that locate the rows, and the
miniature socket head cap screws with their nuts that clamp them
(:class:`~tactcad.partlib.array.comb_sheet.CombGeometry` gives every size; the comb's
derivation is :mod:`tactcad.design.comb_plan`'s).

Part frames: the spacer as a comb sheet (x along the row, y up the spine, extruded along
+z); a dowel pin along +z from z = 0; the screw and nut as
:mod:`tactcad.partlib.array.fasteners` builds them (head underside, nut seat at z = 0).
The screw and nut have builder keys of their own so the comb's build step, not the
stacked array's bolt step, consumes them. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from tactcad.geometry.profile import Circle, Profile, _chain
from tactcad.kernel.shapes import cylinder, extrude_profile
from tactcad.partlib.array.fasteners import build_nut, build_screw, nut_data, screw_data
from tactcad.partlib.array.prism import hole_circles, prism_bbox
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, BuildStep, PartData
from tactcad.vocabulary.process import Method, Process

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

SPACER_COLOR: RGB = (0.55, 0.60, 0.68)
DOWEL_COLOR: RGB = (0.78, 0.78, 0.74)  # ground, hardened steel
SCREW_COLOR: RGB = (0.20, 0.20, 0.22)  # black oxide
#: Part names of the comb's hardware.
SPACER_PART = "comb_spacer"
#: ISO 4762 screws and ISO 4032 nuts start at M1.6; a smaller size is DIN 912 / DIN 934.
ISO_SMALLEST_MM = 1.6


@dataclass(frozen=True)
class SpacerPlate:
    """The comb's spacer (mm): the spine's outline ``length_mm`` x ``height_mm`` with the
    fastener holes, ``thickness_mm`` thick."""

    length_mm: float
    height_mm: float
    thickness_mm: float
    holes: tuple


@dataclass(frozen=True)
class DowelPin:
    """An ISO 8734 dowel pin (mm): diameter and length."""

    diameter_mm: float
    length_mm: float


def spacer_plate(comb) -> SpacerPlate:
    sheet = comb.sheets[0]
    return SpacerPlate(sheet.length_mm, sheet.spine_height_mm, comb.spacer_thickness_mm,
                       sheet.holes)


def spacer_profile(p: SpacerPlate) -> Profile:
    """The spacer's outline (the spine's rectangle) and its holes."""
    outer = _chain([(0.0, 0.0), (p.length_mm, 0.0), (p.length_mm, p.height_mm),
                    (0.0, p.height_mm)])
    return Profile(outer=outer, holes=tuple(Circle((x, y), d / 2) for x, y, d in hole_circles(p.holes)),
                   start_holes=())


def build_spacer(p: SpacerPlate) -> "Solid":
    return extrude_profile(spacer_profile(p), p.thickness_mm)


def build_dowel(p: DowelPin) -> "Solid":
    return cylinder(p.diameter_mm / 2, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), p.length_mm)


def dowel_name(p: DowelPin) -> str:
    return f"dowel_pin_{p.diameter_mm:g}x{p.length_mm:g}"


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """The spacer, a dowel pin, the screw and its nut of the plan's comb (none without)."""
    comb = context.plan.comb
    if comb is None:
        return ()
    plate = spacer_plate(comb)
    prof = spacer_profile(plate)
    pin = DowelPin(comb.dowel_diameter_mm, comb.dowel_length_mm)
    r = pin.diameter_mm / 2
    screw = screw_data(comb.screw, comb.screw_length_mm, SCREW_COLOR, "comb_screw")
    nut = nut_data(comb.screw)
    if comb.screw.nominal_diameter_mm < ISO_SMALLEST_MM:  # the tables' sizes below ISO's start
        screw = replace(screw, process=Process(
            f"DIN 912 {comb.screw.size}x{comb.screw_length_mm:g} socket head cap screw",
            Method.BOUGHT))
        nut = replace(nut, process=Process(f"DIN 934 {comb.screw.size} hex nut", Method.BOUGHT))
    return (
        PartData(name=SPACER_PART, kind="fabricated",
                 process=Process("wire EDM or laser cut from sheet", Method.SHEET),
                 material=context.plan.material.name, color=SPACER_COLOR,
                 expected_volume_mm3=prof.area_mm2 * plate.thickness_mm,
                 expected_bbox_mm=prism_bbox(prof, plate.thickness_mm), geometry=plate,
                 profile=prof, thickness_mm=plate.thickness_mm),
        PartData(name=dowel_name(pin), kind="purchased",
                 process=Process(f"ISO 8734 {pin.diameter_mm:g} m6 x {pin.length_mm:g} dowel pin",
                                 Method.BOUGHT),
                 material="hardened steel", color=DOWEL_COLOR,
                 expected_volume_mm3=math.pi * r * r * pin.length_mm,
                 expected_bbox_mm=(-r, -r, 0.0, r, r, pin.length_mm), geometry=pin,
                 builder="dowel_pin"),
        screw,
        replace(nut, builder="comb_nut"),
    )


PART = ArrayPart(key="comb_hardware", build=build_spacer, specs=specs, order=6,
                 companion_builders={"dowel_pin": build_dowel, "comb_screw": build_screw,
                                     "comb_nut": build_nut},
                 # consumed where the comb sheet's step stacks the rows (its title and notes)
                 assembly=BuildStep("comb-rows",
                                    companions=("dowel_pin", "comb_screw", "comb_nut")))
