"""Column (a made part): the upright plate on the base plate that carries
the Z axis (calibration, sample stiffness) or the vertical linear axis's
rail (array evaluation).

Part frame: x through its thickness (front face at -x), y across, z up from
its foot (z = 0), centred in x and y. Units: mm.
"""

from __future__ import annotations

from tactcad.partlib.base import PartData, RigPart, Seat, table_values, values_from
from tactcad.kernel.shapes import box
from tactcad.partlib.stock import PLATE_ALUMINIUM
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, number

COLOR = (0.50, 0.53, 0.58)


class ColumnSection(Section):
    """``[column]`` of ``rigs.toml``."""

    thickness_mm: number(5.0, 60.0)
    width_mm: number(20.0, 300.0)
    height_mm: number(50.0, 1000.0)


class ColumnGeometry(table_values(ColumnSection)):
    """The column as its table gives it (mm)."""


def derive(c: ColumnSection, context, p: Problems) -> PartData:
    """The column carrying the linear axis's rail (``linear_axis``) on its front
    (the base plate checks that it stands between its corner holes)."""
    rail = context.part("linear_axis").geometry
    p.within("linear_axis.rail_mount_height_mm", rail.rail_mount_height_mm,
             hi=c.height_mm - rail.rail_length_mm)
    g = values_from(ColumnGeometry, c)
    t = g.thickness_mm
    return PartData(
        name="column", kind="fabricated", process=Process("milling from plate", Method.PLATE),
        material=PLATE_ALUMINIUM, color=COLOR,
        expected_volume_mm3=t * g.width_mm * g.height_mm,
        expected_bbox_mm=(-t / 2, -g.width_mm / 2, 0.0, t / 2, g.width_mm / 2, float(g.height_mm)),
        geometry=g,
        frames={"foot": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "front": Seat((-t / 2, 0, 0), (-1, 0, 0), (0, 0, 1)),
                "rail_seat": Seat((-t / 2, 0, rail.rail_mount_height_mm),
                                  (-1, 0, 0), (0, 0, 1))})


def build(g: ColumnGeometry):
    """Upright plate (build123d ``Solid``): x through the thickness (front face
    at -x), foot at z = 0."""
    return box(-g.thickness_mm / 2, -g.width_mm / 2, 0, g.thickness_mm / 2, g.width_mm / 2,
               g.height_mm)


PART = RigPart(key="column", section=ColumnSection, host="", derive=derive, build=build,
               needs=("linear_axis",), order=45)
