"""The monolithic comb's hardware, placed: the spacer between the rows (a plate of the
spine's outline with its holes), the ISO 8734 dowel pins that locate the rows, the
miniature socket head cap screws with their nuts that clamp them, and the shims bonded on
the stop ledges that close a gap the wire cuts wider to the stop gap
(:class:`~tactcad.partlib.array.comb_sheet.CombGeometry` gives every size; the comb's
derivation is :mod:`tactcad.design.comb_plan`'s).

Part frames: the spacer as a comb sheet (x along the row, y up the spine, extruded along
+z); a shim as a comb sheet too (its corner at the origin, the length along x, its
thickness along y, the sheet's thickness along z); a dowel pin along +z from z = 0; the
screw and nut as :mod:`tactcad.partlib.array.fasteners` builds them (head underside, nut
seat at z = 0).
The screw and nut have builder keys of their own so the comb's build step, not the
stacked array's bolt step, consumes them. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from tactcad.geometry.profile import Circle, Profile, _chain
from tactcad.kernel.shapes import box, cylinder, extrude_profile
from tactcad.partlib.array.fasteners import build_nut, build_screw, nut_data, screw_data
from tactcad.partlib.array.prism import hole_circles, prism_bbox
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, BuildStep, PartData
from tactcad.vocabulary.process import Method, Process, cut_process
from tactcad.vocabulary.schema import name_number

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

SPACER_COLOR: RGB = (0.55, 0.60, 0.68)
DOWEL_COLOR: RGB = (0.78, 0.78, 0.74)  # ground, hardened steel
SCREW_COLOR: RGB = (0.20, 0.20, 0.22)  # black oxide
SHIM_COLOR: RGB = (0.85, 0.72, 0.45)  # brass-coloured, to stand out on the ledge
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


@dataclass(frozen=True)
class StopShim:
    """A shim bonded on a stop ledge under an element's tip (mm): as long as the tip is
    wide, ``thickness_mm`` high (the cut gap less the stop gap), as wide as the sheet."""

    length_mm: float
    thickness_mm: float
    width_mm: float


def stop_shims(comb) -> list[tuple[int, int, StopShim, tuple[float, float]]]:
    """Every shim of the comb: (row, element's column, the shim, its corner (x, y) in the
    row's sheet frame), for each element whose gap is cut wider than its stop gap."""
    out = []
    for sheet in comb.sheets:
        for c, (g, x0, ledge, shim) in enumerate(zip(sheet.elements, sheet.offsets_mm,
                                                     sheet.ledges_mm, sheet.shims_mm)):
            if shim > 0:
                s = StopShim(g.tip_width_mm, shim, sheet.thickness_mm)
                out.append((sheet.row, c, s, (x0 + g.overall_length_mm - g.tip_width_mm, ledge)))
    return out


def shim_name(s: StopShim) -> str:
    """Part name of a stop shim, safe for file names and STEP labels: ``stop_shim_0p11x1x1``."""
    return (f"stop_shim_{name_number(s.thickness_mm)}x{name_number(s.length_mm)}"
            f"x{name_number(s.width_mm)}")


def build_shim(s: StopShim) -> "Solid":
    return box(0.0, 0.0, 0.0, s.length_mm, s.thickness_mm, s.width_mm)


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
    """Part name of a dowel pin, safe for file names and STEP labels: ``dowel_pin_1p5x4``."""
    return f"dowel_pin_{name_number(p.diameter_mm)}x{name_number(p.length_mm)}"


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """The spacer, a dowel pin, the screw and its nut, and a shim of each thickness the
    stops take, of the plan's comb (none without)."""
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
                 process=cut_process(comb.spacer_process, "comb.spacer_process").part_process(),
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
        *(shim_data(s, k) for k, s in enumerate(sorted({s for _, _, s, _ in stop_shims(comb)},
                                                       key=lambda s: s.thickness_mm))),
    )


def shim_data(s: StopShim, k: int = 0) -> PartData:
    """The ``k``-th thinnest stop shim, cut from stainless shim foil (bought to thickness);
    each thickness a shade of its own (a scene tells its parts by colour)."""
    return PartData(name=shim_name(s), kind="purchased",
                    process=Process(f"stainless steel shim foil {s.thickness_mm:g} mm, cut to "
                                    f"{s.length_mm:g} x {s.width_mm:g} mm and bonded on the "
                                    "stop ledge", Method.BOUGHT),
                    material="stainless steel shim foil",
                    color=(SHIM_COLOR[0], max(SHIM_COLOR[1] - 0.04 * k, 0.0), SHIM_COLOR[2]),
                    expected_volume_mm3=s.length_mm * s.thickness_mm * s.width_mm,
                    expected_bbox_mm=(0.0, 0.0, 0.0, s.length_mm, s.thickness_mm, s.width_mm),
                    geometry=s, builder="stop_shim")


PART = ArrayPart(key="comb_hardware", build=build_spacer, specs=specs, order=6,
                 companion_builders={"dowel_pin": build_dowel, "comb_screw": build_screw,
                                     "comb_nut": build_nut, "stop_shim": build_shim},
                 # consumed where the comb sheet's step stacks the rows (its title and notes)
                 assembly=BuildStep("comb-rows",
                                    companions=("dowel_pin", "comb_screw", "comb_nut",
                                                "stop_shim")))
