"""Hanger bar (a made part): the square aluminium bar that hangs the array's
bracket from the axis carrier's shelf in the array-evaluation rig.

Part frame: the bar along z, z = 0 at its top end (on the shelf's
underside), hanging to z = -length, centred in x and y. Units: mm.
"""

from __future__ import annotations

from tactcad.partlib.base import PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import box
from tactcad.partlib.stock import BAR_ALUMINIUM
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, number

COLOR = (0.58, 0.66, 0.62)


class HangerBarSection(Section):
    """``[hanger_bar]`` of ``rigs.toml``."""

    section_mm: number(2.0, 100.0)
    length_mm: number(5.0, 1000.0)


class HangerBarGeometry(table_values(HangerBarSection)):
    """The bar as its table gives it (mm)."""


def derive(b: HangerBarSection, context, p: Problems) -> PartData:
    """The bar as the table gives it (the carrier and the bracket check their
    room for it)."""
    g = values_from(HangerBarGeometry, b)
    sh = g.section_mm / 2
    return PartData(
        name="hanger_bar", kind="fabricated",
        process=Process("sawing and facing bar stock", Method.BAR), material=BAR_ALUMINIUM,
        color=COLOR, expected_volume_mm3=g.section_mm ** 2 * g.length_mm,
        expected_bbox_mm=(-sh, -sh, -float(g.length_mm), sh, sh, 0.0), geometry=g,
        frames={"top": Seat((0, 0, 0), (0, 0, 1), (1, 0, 0)),
                "bottom": Seat((0, 0, -g.length_mm), (0, 0, -1), (1, 0, 0))})


def build(g: HangerBarGeometry):
    """Square bar (build123d ``Solid``), top end at z = 0, hanging to z = -length."""
    s = g.section_mm / 2
    return box(-s, -s, -g.length_mm, s, s, 0)


PART = RigPart(key="hanger_bar", section=HangerBarSection, host="", derive=derive, build=build,
               order=110)
