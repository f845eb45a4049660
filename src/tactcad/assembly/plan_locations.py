"""Plan placements as CAD locations."""

from __future__ import annotations

from tactcad.design.array_plan import Placement
from tactcad.kernel.locations import Location, offset


def location(p: Placement) -> Location:
    """CAD location of a plan placement (turned = 180 degrees about y; mm)."""
    return offset(p.dx_mm, p.dy_mm, p.dz_mm, p.turned)
