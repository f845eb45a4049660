"""What the strain gauge installation adds to an element's moving mass: the gauge
with its adhesive, the solder terminals with their solder and the lead between
them, each placed where it sits, as point masses for the modal levels
(:class:`~tactcad.mechanics.modal_result.PointMass`).

The masses per gauge come from the material library's gauge entry
(``installed_mass_mg``, ``terminal_pair_mass_mg``, ``lead_mass_mg_per_mm``,
each with its source: estimates from the build's areas, thicknesses and
densities, stated as such). Their places are the assumptions below: the gauge
centred over the web on the flat top face (as ``readout`` and the drawings put
it), the terminal pair bonded on the base behind the notch, where nothing
moves (strain relief off the flexure), and :data:`LEAD_ON_ELEMENT_MM` of lead
from the gauge's tabs to the terminals, half way between them. The lead beyond
the terminals leaves the element and is not counted.

Units: mm, g (the point masses), mg (the library's figures).
"""

from __future__ import annotations

from tactcad.design.array_plan import ElementGeometry, Plan
from tactcad.mechanics.modal_result import PointMass

#: Where the terminal pair sits: this far behind the web centre on the base (mm).
TERMINALS_BEHIND_WEB_MM = 2.5
TERMINALS_REASON = ("assumption: the solder terminal pair bonded on the base "
                    f"{TERMINALS_BEHIND_WEB_MM:g} mm behind the web centre, where nothing moves")
#: Lead on the element: from the gauge's tabs to the terminals (mm).
LEAD_ON_ELEMENT_MM = 2.0
LEAD_REASON = (f"assumption: {LEAD_ON_ELEMENT_MM:g} mm of the three-wire lead from the gauge's "
               "tabs to the terminals, half way between them; the rest leaves the element")


def gauge_installation_masses(plan: Plan, g: ElementGeometry) -> tuple[PointMass, ...]:
    """The gauge, its lead on the element and its terminal pair on element ``g`` as point
    masses (g), placed as the module docstring says, each with its source."""
    gauge = plan.strength.gauge
    src = dict(gauge.sources)
    xh, _ = g.web_centre_mm
    top = g.base_height_mm
    terminals_x = xh - TERMINALS_BEHIND_WEB_MM
    return (PointMass("gauge and adhesive", gauge.installed_mass_mg * 1e-3, xh, top,
                      src.get("installed_mass_mg", "")),
            PointMass("lead to the terminals", gauge.lead_mass_mg_per_mm * LEAD_ON_ELEMENT_MM
                      * 1e-3, 0.5 * (xh + terminals_x), top,
                      f"{LEAD_REASON}; {src.get('lead_mass_mg_per_mm', '')}"),
            PointMass("solder terminal pair", gauge.terminal_pair_mass_mg * 1e-3, terminals_x,
                      top, f"{TERMINALS_REASON}; {src.get('terminal_pair_mass_mg', '')}"))
