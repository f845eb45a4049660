"""Rubber sample (tissue phantom) and the frame that locates it on the cart.

Sample frame: block centred in x and y, z = 0 on its underside. Holder frame:
the same, with the window (sample + clearance, milled corner radius) and two
screw clearance holes on the y axis. The sample's measured stiffness is an
attribute of its part (:mod:`tactcad.catalogue.rigs`), not a geometry.
Dimensions: :class:`tactcad.design.rigs.SampleGeometry`,
:class:`tactcad.design.rigs.SampleHolderGeometry`.
"""

from __future__ import annotations

import build123d as bd

from tactcad.design.rigs import SampleGeometry, SampleHolderGeometry
from tactcad.partlib.shapes import box, cylinder, rounded_rect_face, single


def build_sample(g: SampleGeometry) -> bd.Solid:
    """Block ``length x width x height`` (mm)."""
    return box(-g.length_mm / 2, -g.width_mm / 2, 0, g.length_mm / 2, g.width_mm / 2, g.height_mm)


def build_sample_holder(g: SampleHolderGeometry) -> bd.Solid:
    """Frame plate with a rounded-corner window and two screw clearance holes."""
    t = g.thickness_mm
    plate = box(-g.outer_length_mm / 2, -g.outer_width_mm / 2, 0, g.outer_length_mm / 2,
                g.outer_width_mm / 2, t)
    window = bd.Solid.extrude(rounded_rect_face(g.window_length_mm, g.window_width_mm,
                                                g.corner_radius_mm), bd.Vector(0, 0, t))
    holes = [cylinder(g.screw.clearance_hole_mm / 2, (0, s * g.screw_y_mm, 0), (0, 0, 1), t)
             for s in (-1, 1)]
    return single(plate.cut(window, *holes))
