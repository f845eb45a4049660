"""Plan placements as CAD locations."""

from __future__ import annotations

from tactcad.design.array_plan import Placement
from tactcad.kernel.locations import Location, frame, offset


def location(p: Placement) -> Location:
    """CAD location of a plan placement (mm): turned = 180 degrees about y; a
    quarter turn (a comb's row along the array's z) as the frame whose axes
    :meth:`Placement.apply` gives, so the solids lie where the plan's numbers say."""
    if not p.quarter_turn:
        return offset(p.dx_mm, p.dy_mm, p.dz_mm, p.turned)
    origin = p.apply(0.0, 0.0, 0.0)
    x_dir = tuple(a - o for a, o in zip(p.apply(1.0, 0.0, 0.0), origin))
    z_dir = tuple(a - o for a, o in zip(p.apply(0.0, 0.0, 1.0), origin))
    return frame(origin, x_dir, z_dir)
