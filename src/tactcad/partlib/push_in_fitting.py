"""Push-in vacuum fitting in the cart's hose port (a bought part, modelled as
its catalogue envelope).

The cart's vacuum channel ends in a tapped M5 hose port on the cart's -x end
face (:mod:`tactcad.partlib.cart`); a straight push-in male connector
screws into it and takes the vacuum hose. Default: SMC KQ2H04-M5A (M5x0.8
male thread, Ø4 mm tube); its envelope sizes are rounded from the maker's
catalogue drawing of the KQ2 series and are the ``[push_in_fitting]`` table's
defaults, so a rigs file without the table stays valid.

Part frame: z along the fitting's axis, z = 0 on the hex's seat face, the
thread along -z (into the port), hex and collet body along +z; x through a
corner of the hex. Envelope: thread cylinder at its nominal diameter (as the
rig screws), hexagon prism, collet body cylinder. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.kernel.shapes import disc_prism, polygon_prism, single, union
from tactcad.partlib.base import PartData, RigPart, Seat
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Derived, Problems, Section, Text, fmt, name_number, number

COLOR = (0.15, 0.42, 0.78)  # the release collet's blue; distinct from every rig part


class PushInFittingSection(Section):
    """``[push_in_fitting]`` of ``rigs.toml`` (every field has its default)."""

    catalogue_reference: Text = "SMC KQ2H04-M5A"
    thread_diameter_mm: number(2.0, 12.0) = 5.0
    thread_length_mm: number(1.0, 20.0) = 3.5
    hex_across_flats_mm: number(3.0, 30.0) = 8.0
    hex_height_mm: number(1.0, 20.0) = 4.0
    body_diameter_mm: number(3.0, 30.0) = 9.0
    body_length_mm: number(2.0, 60.0) = 10.5
    tube_outer_diameter_mm: number(2.0, 16.0) = 4.0


@dataclass(frozen=True)
class FittingGeometry:
    """The envelope the builder reads (mm)."""

    thread_diameter_mm: float
    thread_length_mm: float
    hex_across_flats_mm: float
    hex_height_mm: float
    body_diameter_mm: float
    body_length_mm: float

    @property
    def hex_across_corners_mm(self) -> float:
        return self.hex_across_flats_mm * 2 / math.sqrt(3)

    @property
    def reach_mm(self) -> float:
        """How far the fitting stands out of the cart's end face."""
        return self.hex_height_mm + self.body_length_mm


def derive(s: PushInFittingSection, context, p: Problems) -> PartData:
    """The fitting against the cart's hose port (``cart``)."""
    cart = context.part("cart").geometry
    if abs(s.thread_diameter_mm - cart.port_diameter_mm) > 1e-9:
        p.add("push_in_fitting.thread_diameter_mm", s.thread_diameter_mm,
              f"= cart.port_diameter_mm = {fmt(cart.port_diameter_mm)} mm",
              "the fitting screws into the cart's tapped hose port")
    p.within("push_in_fitting.thread_length_mm", s.thread_length_mm, hi=cart.port_depth_mm,
             why="the thread must fit in the port (cart.port_depth_mm)")
    p.within("push_in_fitting.hex_across_flats_mm", s.hex_across_flats_mm, s.thread_diameter_mm,
             cart.thickness_mm, lo_open=True,
             why="the hex is wider than the thread and seals on the cart's end face "
                 "(cart.thickness_mm)")
    p.within("push_in_fitting.body_diameter_mm", s.body_diameter_mm, s.tube_outer_diameter_mm,
             lo_open=True, why="the collet body holds the tube")
    g = FittingGeometry(s.thread_diameter_mm, s.thread_length_mm, s.hex_across_flats_mm,
                        s.hex_height_mm, s.body_diameter_mm, s.body_length_mm)
    rt, rb, af = g.thread_diameter_mm / 2, g.body_diameter_mm / 2, g.hex_across_flats_mm
    volume = (math.sqrt(3) / 2 * af * af * g.hex_height_mm + math.pi * rb * rb * g.body_length_mm
              + math.pi * rt * rt * g.thread_length_mm)
    half_x, half_y = max(g.hex_across_corners_mm / 2, rb), max(af / 2, rb)
    name = "push_in_fitting_M" + name_number(g.thread_diameter_mm)
    return PartData(
        name=name, kind="purchased",
        process=Process(f"{s.catalogue_reference} push-in male connector, M{g.thread_diameter_mm:g} "
                        f"thread to Ø{s.tube_outer_diameter_mm:g} mm tube (catalogue envelope)",
                        Method.BOUGHT),
        material="nickel-plated brass, PBT collet", color=COLOR, expected_volume_mm3=volume,
        expected_bbox_mm=(-half_x, -half_y, -g.thread_length_mm, half_x, half_y, g.reach_mm),
        geometry=g,
        seat=Seat((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), (1.0, 0.0, 0.0)),
        # the hose port: centre of the cart's -x end face, at mid-thickness
        host_seat=Seat((-cart.length_mm / 2, 0.0, cart.thickness_mm / 2), (-1.0, 0.0, 0.0),
                       (0.0, 0.0, 1.0)),
        derived=(Derived("push_in_fitting_reach", g.reach_mm, "mm",
                         f"hex {fmt(g.hex_height_mm)} + collet body {fmt(g.body_length_mm)}: the "
                         "hose end stands this far out of the cart's end face"),),
        attributes={"catalogue_reference": s.catalogue_reference})


def build(g: FittingGeometry):
    """The envelope solid (a kernel ``Solid``) in the part frame."""
    hexagon = polygon_prism(g.hex_across_corners_mm / 2, 6, g.hex_height_mm)
    body = disc_prism(g.body_diameter_mm / 2, g.body_length_mm, z0=g.hex_height_mm)
    thread = disc_prism(g.thread_diameter_mm / 2, g.thread_length_mm, z0=-g.thread_length_mm)
    return single(union(hexagon, body, thread))


PART = RigPart(key="push_in_fitting", section=PushInFittingSection, host="cart", derive=derive,
               build=build, drawing=None, needs=("cart",))
