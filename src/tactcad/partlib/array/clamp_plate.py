"""The U-shaped clamp plate (a made part, one at each end of the stack): two
legs press the two rows' bases, the bridge below the arms ties the rows
together and carries the two mounting holes.

Here under the key ``clamp_plate``: the design file's ``[clamp]`` table (the
plates, the bolts that clamp the stack and the spacers' grade), the plate's
dimensions (:class:`ClampPlateGeometry`), spec, builder and shop drawing.
The plate, the bolt pattern and the elements' bases are one coupled
derivation in :mod:`tactcad.design.array_plan` (above this layer), which this
module reads from the plan. Part frame: the array frame's x and y, thickness
along +z. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from tactcad.geometry.profile import Profile, u_plate_profile
from tactcad.kernel.shapes import extrude_profile
from tactcad.partlib.array.prism import DrilledPlate, hole_circles, prism_bbox
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, BuildStep, DrawingRecord, PartData
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Section, Text, choice, number
from tactcad.vocabulary.standards import BOLTS

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

COLOR: RGB = (0.25, 0.40, 0.70)  # anodised blue


class ClampSection(Section):
    """``[clamp]`` of the design file: the clamp plates, their bolts (mm) and
    the library grades of plates and spacers (:mod:`tactcad.design.bom_section`)."""

    bolt_size: choice(BOLTS, "ISO 4762 socket head cap screws of the catalogue")
    bolt_spacing_mm: number(0.0, 40.0, lo_open=True)
    plate_thickness_mm: number(1.0, 10.0)
    bridge_height_mm: number(1.0, 30.0)
    arm_clearance_mm: number(0.2, 3.0)
    material: Text = None  # library grade of the clamp plates (tactcad.design.bom_section)
    spacer_material: Text = None  # library grade of the spacers


@dataclass(frozen=True)
class ClampPlateGeometry(DrilledPlate):
    """U-shaped clamp plate (array frame x/y, thickness along z; mm).

    Two legs press the two rows' bases; the bridge below the arms ties the
    rows together and carries the mounting holes.
    """

    half_length_mm: float  # |x| of the outer edges
    window_half_width_mm: float  # |x| of the legs' inner edges
    height_mm: float
    bridge_height_mm: float
    thickness_mm: float
    window_corner_radius_mm: float


def clamp_profile(c: ClampPlateGeometry) -> Profile:
    """The U outline with its bolt and mounting holes (sketch plane, mm)."""
    return u_plate_profile(c.half_length_mm, c.window_half_width_mm, c.height_mm,
                           c.bridge_height_mm, c.window_corner_radius_mm, hole_circles(c.holes))


def build(c: ClampPlateGeometry) -> Solid:
    """U-shaped clamp plate in the array frame (x, y), thickness along +z, mm."""
    return extrude_profile(clamp_profile(c), c.thickness_mm)


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """The clamp plate (``plan.clamp``), milled from its grade's plate."""
    c = context.plan.clamp
    prof = clamp_profile(c)
    return (PartData(
        name="clamp_plate", kind="fabricated", process=Process("milling", Method.PLATE),
        material=context.materials["clamp_plate"], color=COLOR,
        expected_volume_mm3=prof.area_mm2 * c.thickness_mm,
        expected_bbox_mm=prism_bbox(prof, c.thickness_mm), geometry=c, profile=prof,
        thickness_mm=c.thickness_mm),)


def dimensions(d, solid, pen) -> None:
    """The general set plus the window's width and the bridge's height."""
    c = d.spec.geometry
    f = d.front
    pen.dim(d, f, (-c.window_half_width_mm, c.height_mm), (c.window_half_width_mm, c.height_mm),
            "h", "top", 0, pen.fmt_mm(2 * c.window_half_width_mm), "window_width")
    pen.dim(d, f, (c.half_length_mm, 0.0), (c.window_half_width_mm, c.bridge_height_mm), "v",
            "right", 0, pen.fmt_mm(c.bridge_height_mm), "bridge_height")
    pen.generic_dims(d, solid, top_k=1, right_k=1)


def notes(d, pen) -> list[str]:
    """Stock, window corners, bolt clearance."""
    bolt = d.plan.bolt
    return [f"{pen.sentence(d.spec.process)} from {pen.fmt_mm(pen.part_thickness(d.spec))} mm "
            f"{d.spec.material} plate. Window corners R = cutter radius. Holes "
            f"Ø{pen.fmt_mm(bolt.clearance_hole_mm)}: ISO 273 medium clearance for {bolt.size}."]


def plan_values(plan, spec, pen) -> tuple:
    """What of the plan the drawing prints: the plate and the bolt."""
    return (plan.clamp, plan.bolt)


PART = ArrayPart(key="clamp_plate", build=build, specs=specs, order=30,
                 drawing=DrawingRecord(dimensions=dimensions, notes_of=notes,
                                       plan_values=plan_values),
                 assembly=BuildStep("array-stack"))
