"""Axis carrier (a made part): the L plate on the vertical linear axis's
block in the array-evaluation rig; its shelf carries the weights on top and
the hanger bar below.

Part frame: x along the rail (up), y across, z away from the block (z = 0 on
the block's top face), centred in x and y; the shelf at the upper end (+x).
Units: mm.
"""

from __future__ import annotations

from tactcad.partlib.base import PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import box, fuse
from tactcad.partlib.stock import PLATE_ALUMINIUM
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, fmt, number

COLOR = (0.62, 0.58, 0.70)


class CarrierSection(Section):
    """``[carrier]`` of ``rigs.toml``."""

    width_mm: number(5.0, 300.0)
    height_mm: number(10.0, 500.0)
    thickness_mm: number(1.0, 50.0)
    shelf_depth_mm: number(5.0, 300.0)


class CarrierGeometry(table_values(CarrierSection)):
    """The carrier as its table gives it (mm)."""


def derive(c: CarrierSection, context, p: Problems) -> PartData:
    """The carrier, its shelf deep enough for the hanger bar (``hanger_bar``)."""
    bar = context.part("hanger_bar").geometry
    if c.shelf_depth_mm - c.thickness_mm < bar.section_mm + 2.0:
        p.add("carrier.shelf_depth_mm", c.shelf_depth_mm,
              f">= {fmt(c.thickness_mm + bar.section_mm + 2.0)} mm",
              "the hanger bar hangs from the shelf clear of the carrier plate")
    p.within("carrier.thickness_mm", c.thickness_mm, hi=c.height_mm / 2)
    g = values_from(CarrierGeometry, c)
    zc = g.thickness_mm + (g.shelf_depth_mm - g.thickness_mm) / 2
    return PartData(
        name="axis_carrier", kind="fabricated", process=Process("milling from plate", Method.PLATE),
        material=PLATE_ALUMINIUM, color=COLOR,
        expected_volume_mm3=g.width_mm * (g.height_mm * g.thickness_mm
                                          + (g.shelf_depth_mm - g.thickness_mm) * g.thickness_mm),
        expected_bbox_mm=(-g.height_mm / 2, -g.width_mm / 2, 0.0, g.height_mm / 2, g.width_mm / 2,
                          float(g.shelf_depth_mm)),
        geometry=g,
        frames={"back": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "shelf_top": Seat((g.height_mm / 2, 0, zc), (1, 0, 0), (0, 0, 1)),
                "shelf_bottom": Seat((g.height_mm / 2 - g.thickness_mm, 0, zc), (-1, 0, 0),
                                     (0, 0, 1))})


def build(g: CarrierGeometry):
    """L plate (build123d ``Solid``): the plate on the block (z = 0 ... thickness)
    and the shelf at its upper end (+x) reaching ``shelf_depth`` away from the block."""
    H, W, t = g.height_mm, g.width_mm, g.thickness_mm
    plate = box(-H / 2, -W / 2, 0, H / 2, W / 2, t)
    shelf = box(H / 2 - t, -W / 2, 0, H / 2, W / 2, g.shelf_depth_mm)
    return fuse(plate, shelf)


PART = RigPart(key="carrier", section=CarrierSection, host="", derive=derive, build=build,
               needs=("hanger_bar",), order=100, builder="axis_carrier")
