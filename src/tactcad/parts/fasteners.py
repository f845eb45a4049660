"""Simplified ISO metric fasteners (envelopes): ISO 4762 socket head cap screw
and ISO 4032 hex nut. Dimensions from :data:`tactcad.design.array.BOLTS`."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from tactcad.design.array import BoltSpec
from tactcad.kernel.shapes import cylinder_z, difference, extrude, moved, polygon_face, union

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid


def build_bolt(spec: BoltSpec, length_mm: float) -> Solid:
    """Socket head cap screw, axis +z; underside of the head at z = 0, the head
    in z < 0 with a hexagon socket, the plain shank (nominal diameter) to z = length."""
    head = cylinder_z(spec.head_diameter_mm / 2, spec.head_height_mm, z0=-spec.head_height_mm)
    shank = cylinder_z(spec.nominal_diameter_mm / 2, length_mm)
    socket = extrude(moved(polygon_face(_hexagon(spec.socket_across_flats_mm)),
                           (0, 0, -spec.head_height_mm)), spec.head_height_mm / 2)
    return difference(union(head, shank), socket)


def build_nut(spec: BoltSpec) -> Solid:
    """Hex nut, axis +z, from z = 0 to the nut height, bore = nominal diameter."""
    prism = extrude(polygon_face(_hexagon(spec.nut_width_across_flats_mm)), spec.nut_height_mm)
    bore = cylinder_z(spec.nominal_diameter_mm / 2, spec.nut_height_mm)
    return difference(prism, bore)


def _hexagon(across_flats: float) -> list[tuple[float, float, float]]:
    r = across_flats / math.sqrt(3)  # corner radius of a regular hexagon
    return [(r * math.cos(k * math.pi / 3), r * math.sin(k * math.pi / 3), 0.0) for k in range(6)]

