"""The strain gauge's body: a thin box bonded over each element's web.

Dimensions: :class:`tactcad.catalogue.gauges.GaugeBody` (the ``[readout]`` grid
with its carrier). Units: mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from tactcad.catalogue.gauges import GaugeBody
from tactcad.kernel.shapes import box_at_origin, translated

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid


def build_gauge(g: GaugeBody) -> Solid:
    """Carrier box, centred on x and z, from y = 0 (the bonded face) to the thickness."""
    box = box_at_origin(g.length_mm, g.thickness_mm, g.width_mm)
    # translated, not moved: the geometry itself shifts, so STEP writes one product, not a
    # located copy of it
    return translated(box, (-g.length_mm / 2, 0.0, -g.width_mm / 2))
