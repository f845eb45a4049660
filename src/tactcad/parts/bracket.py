"""Array bracket: the L of aluminium that holds the array on an XY stage
(calibration) or hangs it from the hanger bar (array evaluation). Its ear
bolts to the front clamp plate through the clamp plate's two bridge mounting
holes (``plan.clamp.holes[-2:]``) with through bolts that also pass the back
clamp plate; its foot stands on a stage table or takes the hanger bar (the
M3 screw through the foot's hole is not modelled: the stage is an envelope
without tapped holes). Part frame: the array frame shifted so that the
origin lies on the ear's inner face at the mounting holes' height (see
:class:`tactcad.design.rigs.BracketGeometry`).
"""

from __future__ import annotations

import build123d as bd

from tactcad.design.rigs import BracketGeometry
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
