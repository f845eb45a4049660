"""Vertical linear axis on the column's front (bought parts, modelled as
envelopes with catalogue dimensions): a miniature guide rail and its
carriage block, which carries the axis carrier in the array-evaluation rig
(default HIWIN MGNR12R rail and MGN12H block: W_R, H_R, W, L, H, H1 of the
maker's catalogue; sources in ``hardware/purchased-parts.md``).

Part frames: rail x = 0 ... length, y across, z = 0 (mounting face) ...
rail height; block centred in x and y, z = H1 ... H above the rail's
mounting face, with the channel the rail runs in. Units: mm.
"""

from __future__ import annotations

from tactcad.partlib.base import PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import box, single
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, Text, number

RAIL_COLOR, BLOCK_COLOR = (0.52, 0.52, 0.55), (0.40, 0.41, 0.44)


class LinearAxisSection(Section):
    """``[linear_axis]`` of ``rigs.toml``."""

    rail: Text
    block: Text
    rail_width_mm: number(3.0, 60.0)
    rail_height_mm: number(2.0, 60.0)
    rail_length_mm: number(20.0, 2000.0)
    block_width_mm: number(5.0, 200.0)
    block_length_mm: number(5.0, 300.0)
    block_height_mm: number(3.0, 100.0)
    block_clearance_mm: number(0.0, 20.0)
    rail_mount_height_mm: number(0.0, 1000.0)


class LinearAxisSpec(table_values(LinearAxisSection)):
    """Rail and block as the table gives them (mm)."""


def rail_name(a: LinearAxisSpec) -> str:
    """Part name of the rail, e.g. ``rail_MGNR12R``."""
    return "rail_" + a.rail.split()[-1]


def block_name(a: LinearAxisSpec) -> str:
    """Part name of the block, e.g. ``block_MGN12H``."""
    return "block_" + a.block.split()[-1]


def derive(a: LinearAxisSection, context, p: Problems) -> PartData:
    """Rail and block (the column checks that it carries the rail)."""
    p.within("linear_axis.block_height_mm", a.block_height_mm, a.rail_height_mm, lo_open=True)
    p.within("linear_axis.block_clearance_mm", a.block_clearance_mm, hi=a.rail_height_mm,
             hi_open=True)
    p.within("linear_axis.block_length_mm", a.block_length_mm, hi=a.rail_length_mm)
    p.within("linear_axis.block_width_mm", a.block_width_mm, a.rail_width_mm + 2.0)
    g = values_from(LinearAxisSpec, a)
    L, W = g.block_length_mm, g.block_width_mm
    block = PartData(
        name=block_name(g), kind="purchased",
        process=Process(f"{g.block} carriage block (envelope)", Method.BOUGHT), material="steel",
        color=BLOCK_COLOR,
        expected_volume_mm3=L * (W * (g.block_height_mm - g.block_clearance_mm)
                                 - g.rail_width_mm * (g.rail_height_mm - g.block_clearance_mm)),
        expected_bbox_mm=(-L / 2, -W / 2, float(g.block_clearance_mm), L / 2, W / 2,
                          float(g.block_height_mm)),
        geometry=g, builder="block",
        frames={"rail_seat": Seat((0, 0, g.rail_height_mm), (0, 0, -1), (1, 0, 0)),
                "top": Seat((0, 0, g.block_height_mm), (0, 0, 1), (1, 0, 0))})
    return PartData(
        name=rail_name(g), kind="purchased",
        process=Process(f"{g.rail} miniature guide rail, {g.rail_length_mm:g} mm", Method.BOUGHT),
        material="steel", color=RAIL_COLOR,
        expected_volume_mm3=g.rail_length_mm * g.rail_width_mm * g.rail_height_mm,
        expected_bbox_mm=(0.0, -g.rail_width_mm / 2, 0.0, float(g.rail_length_mm),
                          g.rail_width_mm / 2, float(g.rail_height_mm)),
        geometry=g,
        frames={"bottom": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "top": Seat((0, 0, g.rail_height_mm), (0, 0, 1), (1, 0, 0))},
        companions=(block,))


def build_rail(a: LinearAxisSpec):
    """Guide rail (build123d ``Solid``): x = 0 ... length, z = 0 ... rail height."""
    return box(0, -a.rail_width_mm / 2, 0, a.rail_length_mm, a.rail_width_mm / 2, a.rail_height_mm)


def build_block(a: LinearAxisSpec):
    """Carriage block around the rail (build123d ``Solid``), with the channel
    the rail runs in (up to the rail's top)."""
    L, W = a.block_length_mm, a.block_width_mm
    block = box(-L / 2, -W / 2, a.block_clearance_mm, L / 2, W / 2, a.block_height_mm)
    channel = box(-L / 2, -a.rail_width_mm / 2, a.block_clearance_mm, L / 2, a.rail_width_mm / 2,
                  a.rail_height_mm)
    return single(block.cut(channel))


PART = RigPart(key="linear_axis", section=LinearAxisSection, host="", derive=derive,
               build=build_rail, order=90, builder="rail",
               companion_builders={"block": build_block})
