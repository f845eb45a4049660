"""Wheeled cart: top plate with a vacuum clamping area, and the wheel spacers.

Cart frame: x along the base plate's grooves, y across, z up from the
underside, centred in x and y. The vacuum area: a shallow pocket on the top
face under the sample, suction holes from the pocket floor down into a
drilled channel at mid-thickness, and a tapped hose port on the -x end face
feeding the channel. Tapped holes (wheel axles, sample holder screws, port)
are modelled at the thread's nominal diameter. Dimensions:
:class:`tactcad.design.rigs.CartGeometry`.
"""

from __future__ import annotations

import build123d as bd

from tactcad.design.rigs import POCKET_CORNER_RADIUS_MM, CartGeometry
from tactcad.partlib.shapes import box, cylinder, ring, rounded_rect_face, single


def build_cart(g: CartGeometry) -> bd.Solid:
    """The cart's top plate (see module doc)."""
    L, W, T = g.length_mm, g.width_mm, g.thickness_mm
    plate = box(-L / 2, -W / 2, 0, L / 2, W / 2, T)
    pocket = bd.Solid.extrude(
        rounded_rect_face(g.pocket_length_mm, g.pocket_width_mm, POCKET_CORNER_RADIUS_MM,
                          z=T - g.pocket_depth_mm),
        bd.Vector(0, 0, g.pocket_depth_mm))
    zc = T / 2
    x_port = -L / 2
    tools = [pocket,
             cylinder(g.port_diameter_mm / 2, (x_port, 0, zc), (1, 0, 0), g.port_depth_mm),
             # the channel starts inside the port so the two cuts overlap (robust boolean)
             cylinder(g.channel_diameter_mm / 2, (x_port + g.port_depth_mm / 2, 0, zc), (1, 0, 0),
                      g.channel_end_x_mm - x_port - g.port_depth_mm / 2)]
    for x in g.suction_hole_xs_mm:  # from the channel axis up into the pocket
        tools.append(cylinder(g.suction_hole_diameter_mm / 2, (x, 0, zc), (0, 0, 1), T - zc))
    for s in (-1, 1):
        tools.append(cylinder(g.holder_screw_diameter_mm / 2,
                              (0, s * g.holder_screw_y_mm, T - g.holder_tapped_depth_mm),
                              (0, 0, 1), g.holder_tapped_depth_mm))
        for sx in (-1, 1):
            tools.append(cylinder(g.axle_bolt.nominal_diameter_mm / 2,
                                  (sx * g.axle_x_mm, s * W / 2, g.axle_height_mm), (0, -s, 0),
                                  g.axle_hole_depth_mm))
    return single(plate.cut(*tools))


def build_wheel_spacer(g: CartGeometry) -> bd.Solid:
    """Spacer ring between the cart side and the wheel's inner ring, axis z."""
    return ring(g.spacer_inner_diameter_mm / 2, g.spacer_outer_diameter_mm / 2,
                g.spacer_thickness_mm)
