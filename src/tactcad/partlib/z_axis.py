"""Manual Z axis with a micrometer head on the column (bought parts, modelled
as envelopes): its fixed body and its moving carriage, which carries the
force gauge (the paper names no model; sources in
``hardware/purchased-parts.md``).

Part frames: body y = -depth (back, on the column) ... 0 (front, the
carriage slides on it), z = 0 ... height, the micrometer head standing on
its top; carriage y = 0 (on the body) ... thickness, centred in x and z.
Units: mm.
"""

from __future__ import annotations

import math

from tactcad.partlib.base import PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import box, cylinder, fuse
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, fmt, number

BODY_COLOR, CARRIAGE_COLOR = (0.16, 0.17, 0.20), (0.24, 0.25, 0.29)


class ZAxisSection(Section):
    """``[z_axis]`` of ``rigs.toml``."""

    body_width_mm: number(10.0, 300.0)
    body_depth_mm: number(5.0, 300.0)
    body_height_mm: number(10.0, 500.0)
    carriage_thickness_mm: number(2.0, 100.0)
    carriage_height_mm: number(5.0, 500.0)
    travel_mm: number(0.5, 200.0)
    position_mm: number(0.0, 200.0)
    micrometer_diameter_mm: number(3.0, 60.0)
    micrometer_length_mm: number(5.0, 200.0)
    micrometer_resolution_mm: number(1e-6, 0.1)


class ZAxisSpec(table_values(ZAxisSection)):
    """The Z axis as its table gives it (mm)."""


def derive(z: ZAxisSection, context, p: Problems) -> PartData:
    """Body and carriage, the body standing on the column (``column``)."""
    column = context.part("column").geometry
    p.within("z_axis.carriage_height_mm", z.carriage_height_mm, hi=z.body_height_mm)
    p.within("z_axis.travel_mm", z.travel_mm, hi=z.body_height_mm - z.carriage_height_mm,
             why="the carriage travels along the body")
    p.within("z_axis.position_mm", z.position_mm, 0.0, z.travel_mm)
    if z.micrometer_diameter_mm > min(z.body_width_mm, z.body_depth_mm):
        p.add("z_axis.micrometer_diameter_mm", z.micrometer_diameter_mm,
              f"<= {fmt(min(z.body_width_mm, z.body_depth_mm))} mm",
              "the micrometer stands on the body's top face")
    if z.body_height_mm > column.height_mm:
        p.add("z_axis.body_height_mm", z.body_height_mm,
              f"<= column.height_mm = {fmt(column.height_mm)} mm")
    g = values_from(ZAxisSpec, z)
    rm, w = g.micrometer_diameter_mm / 2, g.body_width_mm
    carriage = PartData(
        name="z_stage_carriage", kind="purchased",
        process=Process("manual vertical stage: envelope of the moving carriage", Method.BOUGHT),
        material="aluminium", color=CARRIAGE_COLOR,
        expected_volume_mm3=w * g.carriage_thickness_mm * g.carriage_height_mm,
        expected_bbox_mm=(-w / 2, 0.0, -g.carriage_height_mm / 2, w / 2,
                          float(g.carriage_thickness_mm), g.carriage_height_mm / 2),
        geometry=g, builder="z_stage_carriage",
        frames={"back": Seat((0, 0, 0), (0, -1, 0), (0, 0, 1)),
                "front": Seat((0, g.carriage_thickness_mm, 0), (0, 1, 0), (0, 0, 1))})
    return PartData(
        name="z_stage_body", kind="purchased",
        process=Process(f"manual vertical stage with micrometer head "
                        f"({g.micrometer_resolution_mm * 1000:g} um), {g.travel_mm:g} mm travel: "
                        f"envelope of the fixed body", Method.BOUGHT),
        material="aluminium, steel", color=BODY_COLOR,
        expected_volume_mm3=w * g.body_depth_mm * g.body_height_mm
        + math.pi * rm * rm * g.micrometer_length_mm,
        expected_bbox_mm=(-w / 2, -float(g.body_depth_mm), 0.0, w / 2, 0.0,
                          g.body_height_mm + g.micrometer_length_mm),
        geometry=g,
        frames={"back": Seat((0, -g.body_depth_mm, 0), (0, -1, 0), (0, 0, 1)),
                "front": Seat((0, 0, 0), (0, 1, 0), (0, 0, 1))},
        companions=(carriage,))


def build_body(z: ZAxisSpec):
    """Fixed body with the micrometer head on its top (build123d ``Solid``)."""
    body = box(-z.body_width_mm / 2, -z.body_depth_mm, 0, z.body_width_mm / 2, 0, z.body_height_mm)
    head = cylinder(z.micrometer_diameter_mm / 2, (0, -z.body_depth_mm / 2, z.body_height_mm),
                    (0, 0, 1), z.micrometer_length_mm)
    return fuse(body, head)


def build_carriage(z: ZAxisSpec):
    """Moving carriage (build123d ``Solid``)."""
    return box(-z.body_width_mm / 2, 0, -z.carriage_height_mm / 2, z.body_width_mm / 2,
               z.carriage_thickness_mm, z.carriage_height_mm / 2)


PART = RigPart(key="z_axis", section=ZAxisSection, host="", derive=derive, build=build_body,
               needs=("column",), order=70, builder="z_stage_body",
               companion_builders={"z_stage_carriage": build_carriage})
