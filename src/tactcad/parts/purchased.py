"""The wheels' ball bearings of the cart, bought: ISO 15 boundary dimensions
d x D x B as an annulus (the catalogue reference is the part's ``process``,
:mod:`tactcad.catalogue.rigs`; sources in ``hardware/purchased-parts.md``).
The other bought rig parts are written one module each in :mod:`tactcad.partlib`.
"""

from __future__ import annotations

import build123d as bd

from tactcad.design.rigs import BearingSpec
from tactcad.partlib.shapes import ring


def build_bearing(b: BearingSpec) -> bd.Solid:
    """Deep groove ball bearing envelope: annulus d ... D, z = 0 ... B."""
    return ring(b.bore_mm / 2, b.outer_diameter_mm / 2, b.width_mm)
