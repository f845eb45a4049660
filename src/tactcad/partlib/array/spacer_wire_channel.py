"""A spacer variant (a made part): the spacer plate with a channel cut into
its top edge, midway along it, through which the strain gauges' lead wires
drop between neighbouring elements instead of bridging the stack.

Chosen by giving the design file's ``[spacer_wire_channel]`` table (every
field has its default, so an empty table chooses it); it then stands in for
the plain spacer (:mod:`tactcad.partlib.array.spacer`) under the same part
name, so the array places it alike. The outline, thickness and bolt holes are
the plain spacer's (the plan's ``spacer``); the channel's inside corners are
rounded for the wire. Part frame: the element frame, as the plain spacer's.
Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from tactcad.geometry.profile import Arc, Line, Profile, rectangle_profile
from tactcad.kernel.shapes import extrude_profile
from tactcad.partlib.array import spacer
from tactcad.partlib.array.prism import hole_circles, prism_bbox
from tactcad.partlib.base import ArrayContext, ArrayPart, BuildStep, DrawingRecord, PartData
from tactcad.vocabulary.schema import Problems, Section, number

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

#: Material left between the channel's floor and the bolt holes, mm.
MIN_LIGAMENT_MM = 1.0


class SpacerWireChannelSection(Section):
    """``[spacer_wire_channel]`` of the design file (every field has its default)."""

    width_mm: number(0.5, 40.0) = 2.0
    depth_mm: number(0.2, 10.0) = 1.5
    corner_radius_mm: number(0.05, 2.0) = 0.3


@dataclass(frozen=True)
class ChanneledSpacerGeometry(spacer.SpacerGeometry):
    """The plain spacer's plate with a channel in its top edge (mm), centred
    along the spacer's length."""

    channel_width_mm: float
    channel_depth_mm: float
    channel_corner_radius_mm: float


def channeled_profile(s: ChanneledSpacerGeometry) -> Profile:
    """The spacer's outline with the channel (its floor's corners rounded,
    clockwise: inside corners) and the bolt holes (sketch plane, mm)."""
    L, H = s.length_mm, s.height_mm
    x0, x1 = (L - s.channel_width_mm) / 2, (L + s.channel_width_mm) / 2
    r, floor = s.channel_corner_radius_mm, H - s.channel_depth_mm
    outer = (Line((0.0, 0.0), (L, 0.0)), Line((L, 0.0), (L, H)), Line((L, H), (x1, H)),
             Line((x1, H), (x1, floor + r)),
             Arc((x1, floor + r), (x1 - r, floor), (x1 - r, floor + r), False),
             Line((x1 - r, floor), (x0 + r, floor)),
             Arc((x0 + r, floor), (x0, floor + r), (x0 + r, floor + r), False),
             Line((x0, floor + r), (x0, H)), Line((x0, H), (0.0, H)), Line((0.0, H), (0.0, 0.0)))
    plain = rectangle_profile(L, H, hole_circles(s.holes))
    return Profile(outer=outer, holes=plain.holes, start_holes=plain.start_holes)


def build(s: ChanneledSpacerGeometry) -> Solid:
    """The channeled spacer in the element frame, thickness along +z (mm)."""
    return extrude_profile(channeled_profile(s), s.thickness_mm)


def channel_of(plain: spacer.SpacerGeometry, table: SpacerWireChannelSection,
               min_inside_radius_mm: float) -> ChanneledSpacerGeometry:
    """The plain spacer ``plain`` with the table's channel.

    Raises:
        DesignErrors: the channel is wider than the spacer leaves room for,
            reaches within :data:`MIN_LIGAMENT_MM` of a bolt hole, or its
            corner radius is below the wire's (``min_inside_radius_mm``) or
            does not fit the channel.
    """
    p = Problems()
    p.within("spacer_wire_channel.width_mm", table.width_mm, hi=plain.length_mm - 2.0,
             why=f"the spacer is {plain.length_mm:g} mm long and keeps 1 mm at each end")
    hole_top = max(h.y_mm + h.diameter_mm / 2 for h in plain.holes)
    p.within("spacer_wire_channel.depth_mm", table.depth_mm,
             hi=plain.height_mm - hole_top - MIN_LIGAMENT_MM,
             why=f"the channel's floor stays {MIN_LIGAMENT_MM:g} mm above the bolt holes")
    p.within("spacer_wire_channel.corner_radius_mm", table.corner_radius_mm,
             min_inside_radius_mm, min(table.width_mm / 2, table.depth_mm),
             why="inside corners >= wire radius + spark gap, within the channel")
    p.raise_if_any()
    return ChanneledSpacerGeometry(
        length_mm=plain.length_mm, height_mm=plain.height_mm, thickness_mm=plain.thickness_mm,
        holes=plain.holes, channel_width_mm=table.width_mm, channel_depth_mm=table.depth_mm,
        channel_corner_radius_mm=table.corner_radius_mm)


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """The channeled spacer, named ``spacer``, when the array has spacers.

    Raises:
        DesignErrors: see :func:`channel_of`.
    """
    plan = context.plan
    if not plan.spacer_placements:
        return ()
    s = channel_of(plan.spacer, context.tables[PART.key], plan.edm.min_inside_radius_mm)
    prof = channeled_profile(s)
    return (PartData(
        name="spacer", kind="fabricated", process=spacer.spacer_process(context, s.thickness_mm),
        material=context.materials["spacer"], color=spacer.COLOR,
        expected_volume_mm3=prof.area_mm2 * s.thickness_mm,
        expected_bbox_mm=prism_bbox(prof, s.thickness_mm), geometry=s, profile=prof,
        thickness_mm=s.thickness_mm),)


def notes(d, pen) -> list[str]:
    """The plain spacer's note, then where the channel is and what it is for."""
    s = d.spec.geometry
    return spacer.notes(d, pen) + [
        f"Wire channel {pen.fmt_mm(s.channel_width_mm)} wide x {pen.fmt_mm(s.channel_depth_mm)} "
        f"deep in the top edge, centred along the spacer: the strain gauges' lead wires pass "
        f"through it; break its edges."]


PART = ArrayPart(key="spacer_wire_channel", build=build, specs=specs, order=21,
                 section=SpacerWireChannelSection, replaces="spacer",
                 drawing=DrawingRecord(notes_of=notes, plan_values=spacer.plan_values),
                 assembly=BuildStep("array-stack"))
