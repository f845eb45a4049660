"""Array bracket, axis carrier and hanger bar: the parts that hold the array
on an XY stage (calibration) or hang it from the vertical linear axis
(array evaluation).

* Bracket: an L of aluminium. Its ear bolts to the front clamp plate through
  the clamp plate's two bridge mounting holes (``plan.clamp.holes[-2:]``)
  with through bolts that also pass the back clamp plate; its foot stands on
  a stage table or takes the hanger bar (the M3 screw through the foot's
  hole is not modelled: the stage is an envelope without tapped holes). Part
  frame: the array frame shifted
  so that the origin lies on the ear's inner face at the mounting holes'
  height (see :class:`tactcad.design.rigs.BracketGeometry`).
* Carrier: an L plate on the linear block; the shelf carries the weights and
  the hanger bar. Part frame: x along the rail (up), y across, z away from
  the block (z = 0 on the block's top face), centred in x and y.
* Hanger bar: square bar, z = 0 at its top end, hanging along -z.
"""

from __future__ import annotations

import build123d as bd

from tactcad.design.rigs import BracketGeometry, CarrierGeometry, HangerBarGeometry
from tactcad.partlib.shapes import box, cylinder, fuse, single


def build_bracket(g: BracketGeometry) -> bd.Solid:
    """L bracket with two through-bolt holes in the ear and one screw hole in the foot."""
    w = g.width_mm
    ear = box(-w / 2, g.foot_bottom_mm, -g.ear_thickness_mm, w / 2, g.ear_top_mm, 0)
    foot = box(-w / 2, g.foot_bottom_mm, -g.foot_length_mm, w / 2, g.foot_top_mm, 0)
    body = fuse(ear, foot)
    holes = [cylinder(g.hole_diameter_mm / 2, (x, 0, -g.ear_thickness_mm), (0, 0, 1),
                      g.ear_thickness_mm) for x in g.hole_xs_mm]
    holes.append(cylinder(g.foot_hole_diameter_mm / 2, (0, g.foot_bottom_mm, -g.foot_length_mm / 2),
                          (0, 1, 0), g.foot_thickness_mm))
    return single(body.cut(*holes))


def build_carrier(g: CarrierGeometry) -> bd.Solid:
    """L plate: the plate on the block (z = 0 ... thickness) and the shelf at
    its upper end (+x) reaching ``shelf_depth`` away from the block."""
    H, W, t = g.height_mm, g.width_mm, g.thickness_mm
    plate = box(-H / 2, -W / 2, 0, H / 2, W / 2, t)
    shelf = box(H / 2 - t, -W / 2, 0, H / 2, W / 2, g.shelf_depth_mm)
    return fuse(plate, shelf)


def build_hanger_bar(g: HangerBarGeometry) -> bd.Solid:
    """Square bar, top end at z = 0, hanging to z = -length."""
    s = g.section_mm / 2
    return box(-s, -s, -g.length_mm, s, s, 0)
