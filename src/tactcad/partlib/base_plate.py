"""Base plate of the rigs (a made part): two wheel grooves along x that guide
the cart, four corner holes, and the column standing near one end; the XY
stages stand on it between the grooves.

Part frame: x along the grooves, y across, z up from the underside, centred
in x and y. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.partlib.base import DrawingRecord, PartData, RigPart, Seat
from tactcad.kernel.shapes import box, cylinder, single
from tactcad.partlib.stock import PLATE_ALUMINIUM
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Derived, Problems, Section, fmt, number

COLOR = (0.55, 0.57, 0.60)


class BasePlateSection(Section):
    """``[base_plate]`` of ``rigs.toml``."""

    length_mm: number(100.0, 1000.0)
    width_mm: number(40.0, 500.0)
    thickness_mm: number(4.0, 40.0)
    groove_width_mm: number(1.0, 30.0)
    groove_depth_mm: number(0.5, 10.0)
    mount_hole_diameter_mm: number(2.0, 20.0)
    mount_hole_inset_mm: number(3.0, 50.0)
    column_inset_mm: number(0.0, 200.0)


@dataclass(frozen=True)
class BasePlateGeometry:
    """Base plate with two wheel grooves along x (mm; part frame in the module doc)."""

    length_mm: float
    width_mm: float
    thickness_mm: float
    groove_width_mm: float
    groove_depth_mm: float
    track_half_mm: float  # |y| of the groove centre lines
    mount_hole_diameter_mm: float
    mount_hole_inset_mm: float
    column_x_mm: float  # x of the column's centre on the plate


def derive(b: BasePlateSection, context, p: Problems) -> PartData:
    """The plate under the cart's wheels (``cart``), the column (``column``)
    standing between its corner holes."""
    cart, col = context.part("cart").geometry, context.part("column").geometry
    bearing, axle_bolt = cart.bearing, cart.axle_bolt
    p.within("base_plate.groove_width_mm", b.groove_width_mm, bearing.width_mm,
             bearing.width_mm + 2.0, lo_open=True,
             why=f"wider than the {bearing.designation} wheel (guided, not jammed)")
    p.within("base_plate.groove_depth_mm", b.groove_depth_mm, hi=b.thickness_mm / 2)
    if cart.wheel_clearance_mm - b.groove_depth_mm < 0.5:
        p.add("base_plate.groove_depth_mm", b.groove_depth_mm,
              f"<= {fmt(cart.wheel_clearance_mm - 0.5)} mm",
              "the cart's underside must clear the base plate by 0.5 mm")
    track = cart.width_mm / 2 + cart.spacer_thickness_mm + bearing.width_mm / 2
    if track + bearing.width_mm / 2 + axle_bolt.head_height_mm > b.width_mm / 2 - 2.0:
        p.add("base_plate.width_mm", b.width_mm,
              f">= {fmt(2 * (track + bearing.width_mm / 2 + axle_bolt.head_height_mm + 2))} mm",
              "the wheels and their screw heads must stay on the plate")
    if bearing.outer_diameter_mm / 2 - axle_bolt.head_diameter_mm / 2 < b.groove_depth_mm + 0.5 - 1e-9:
        p.add("base_plate.groove_depth_mm", b.groove_depth_mm,
              f"<= {fmt(bearing.outer_diameter_mm / 2 - axle_bolt.head_diameter_mm / 2 - 0.5)} mm",
              "the wheel screw heads must clear the plate beside the groove")
    hole_d = b.mount_hole_diameter_mm
    p.within("base_plate.mount_hole_inset_mm", b.mount_hole_inset_mm, hole_d / 2 + 1.0,
             b.width_mm / 2 - hole_d)
    p.within("column.width_mm", col.width_mm, hi=b.width_mm - 2 * (b.mount_hole_inset_mm + hole_d / 2),
             why="the column must stand between the corner holes")
    p.within("base_plate.column_inset_mm", b.column_inset_mm, hi=b.length_mm / 3)
    column_x = b.length_mm / 2 - b.column_inset_mm - col.thickness_mm / 2
    g = BasePlateGeometry(b.length_mm, b.width_mm, b.thickness_mm, b.groove_width_mm,
                          b.groove_depth_mm, track, hole_d, b.mount_hole_inset_mm, column_x)
    L, W, T = g.length_mm, g.width_mm, g.thickness_mm
    r = g.mount_hole_diameter_mm / 2
    frames = {"column_seat": Seat((g.column_x_mm, 0, T), (0, 0, 1), (1, 0, 0)),
              "top": Seat((0, 0, T), (0, 0, 1), (1, 0, 0))}
    for s in (-1, 1):
        frames[f"groove_{'m' if s < 0 else 'p'}"] = Seat(
            (0, s * g.track_half_mm, T - g.groove_depth_mm), (0, 0, 1), (1, 0, 0))
    return PartData(
        name="base_plate", kind="fabricated", process=Process("milling from plate", Method.PLATE),
        material=PLATE_ALUMINIUM, color=COLOR,
        expected_volume_mm3=L * W * T - 2 * L * g.groove_width_mm * g.groove_depth_mm
        - 4 * math.pi * r * r * T,
        expected_bbox_mm=(-L / 2, -W / 2, 0.0, L / 2, W / 2, float(T)), geometry=g, frames=frames,
        derived=(Derived("groove_track_half", track, "mm",
                         "cart half-width + spacer + half a wheel: the grooves lie under the "
                         "wheels"),))


def build(g: BasePlateGeometry):
    """Plate ``length x width x thickness`` (build123d ``Solid``) with two
    full-length rectangular grooves (the cart's guides) under the wheel track
    and four corner holes."""
    L, W, T = g.length_mm, g.width_mm, g.thickness_mm
    plate = box(-L / 2, -W / 2, 0, L / 2, W / 2, T)
    tools = []
    for s in (-1, 1):
        y = s * g.track_half_mm
        tools.append(box(-L / 2, y - g.groove_width_mm / 2, T - g.groove_depth_mm,
                         L / 2, y + g.groove_width_mm / 2, T))
    r = g.mount_hole_diameter_mm / 2
    for sx in (-1, 1):
        for sy in (-1, 1):
            tools.append(cylinder(r, (sx * (L / 2 - g.mount_hole_inset_mm),
                                      sy * (W / 2 - g.mount_hole_inset_mm), 0), (0, 0, 1), T))
    return single(plate.cut(*tools))


def dimensions(d, solid, pen) -> None:
    """The shop drawing's dimension set (drawn with the drawings layer's
    ``pen``): the general set, and the two full-length grooves in the view
    from the left (u = z, v = y): width, depth and centre distance."""
    g = d.spec.geometry
    pen.generic_dims(d, solid)
    lv = d.views["left"]
    T, yc, gw = g.thickness_mm, g.track_half_mm, g.groove_width_mm
    pen.dim(d, lv, (T - g.groove_depth_mm, yc + gw / 2), (T, yc + gw / 2), "h", "top", 0,
            pen.fmt_mm(g.groove_depth_mm), "groove_depth")
    pen.dim(d, lv, (T, yc - gw / 2), (T, yc + gw / 2), "v", "right", 0, pen.fmt_mm(gw),
            "groove_width")
    pen.dim(d, lv, (T - g.groove_depth_mm, -yc), (T - g.groove_depth_mm, yc), "v", "right", 1,
            pen.fmt_mm(2 * yc), "groove_spacing")
    for s_ in (-1, 1):
        d.sheet.line("centre-lines", lv.paper(T - g.groove_depth_mm - 1.0, s_ * yc),
                     lv.paper(T + 1.0, s_ * yc), "centre")


PART = RigPart(key="base_plate", section=BasePlateSection, host="", derive=derive, build=build,
               needs=("cart", "column"), order=40, drawing=DrawingRecord(dimensions=dimensions))
