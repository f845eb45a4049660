"""Simplified ISO metric fasteners (envelopes): ISO 4762 socket head cap screw
and ISO 4032 hex nut. Dimensions from :data:`tactcad.design.array.BOLTS`."""

from __future__ import annotations

import math

import build123d as bd

from tactcad.design.array import BoltSpec


def build_bolt(spec: BoltSpec, length_mm: float) -> bd.Solid:
    """Socket head cap screw, axis +z; underside of the head at z = 0, the head
    in z < 0 with a hexagon socket, the plain shank (nominal diameter) to z = length."""
    head = bd.Solid.make_cylinder(spec.head_diameter_mm / 2, spec.head_height_mm,
                                  bd.Plane.XY.offset(-spec.head_height_mm))
    shank = bd.Solid.make_cylinder(spec.nominal_diameter_mm / 2, length_mm)
    socket_af = spec.socket_across_flats_mm
    socket = bd.Solid.extrude(
        bd.Face(bd.Wire.make_polygon(_hexagon(socket_af), close=True)).moved(
            bd.Location((0, 0, -spec.head_height_mm))),
        bd.Vector(0, 0, spec.head_height_mm / 2))
    return bd.Solid((head + shank - socket).solids()[0].wrapped)


def build_nut(spec: BoltSpec) -> bd.Solid:
    """Hex nut, axis +z, from z = 0 to the nut height, bore = nominal diameter."""
    prism = bd.Solid.extrude(bd.Face(bd.Wire.make_polygon(_hexagon(spec.nut_width_across_flats_mm),
                                                          close=True)),
                             bd.Vector(0, 0, spec.nut_height_mm))
    bore = bd.Solid.make_cylinder(spec.nominal_diameter_mm / 2, spec.nut_height_mm)
    return bd.Solid((prism - bore).solids()[0].wrapped)


def _hexagon(across_flats: float) -> list[tuple[float, float, float]]:
    r = across_flats / math.sqrt(3)  # corner radius of a regular hexagon
    return [(r * math.cos(k * math.pi / 3), r * math.sin(k * math.pi / 3), 0.0) for k in range(6)]

