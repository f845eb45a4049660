"""The strain gauge's body: a thin box bonded over each element's web.

Dimensions: :class:`tactcad.catalogue.gauges.GaugeBody` (the ``[readout]`` grid
with its carrier). Units: mm.
"""

from __future__ import annotations

import build123d as bd

from tactcad.catalogue.gauges import GaugeBody


def build_gauge(g: GaugeBody) -> bd.Solid:
    """Carrier box, centred on x and z, from y = 0 (the bonded face) to the thickness."""
    box = bd.Solid.make_box(g.length_mm, g.thickness_mm, g.width_mm)
    # translate, not move: the geometry itself shifts, so STEP writes one product, not a
    # located copy of it
    return box.translate(bd.Vector(-g.length_mm / 2, 0.0, -g.width_mm / 2))
