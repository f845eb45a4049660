"""Base plate of the rigs (two wheel grooves, corner holes).

Part frame: x along the grooves, y across, z up from the underside, centred
in x and y. Dimensions: :class:`tactcad.design.rigs.BasePlateGeometry`
(``hardware/rigs.toml``).
"""

from __future__ import annotations

import build123d as bd

from tactcad.design.rigs import BasePlateGeometry
from tactcad.partlib.shapes import box, cylinder, single


def build_base_plate(g: BasePlateGeometry) -> bd.Solid:
    """Plate ``length x width x thickness`` with two full-length rectangular
    grooves (the cart's guides) under the wheel track and four corner holes."""
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
