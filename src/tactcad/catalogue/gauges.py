"""The read-out's bought items per element: strain gauge, terminals, lead wire,
bridge completion, and the adhesive, with quantities per element and spares.

Catalogue data: the design's library gauge (:mod:`tactcad.design.materials`)
and its ``[readout]`` grid (:mod:`tactcad.design.readout`); the quantities
follow ``[bom]`` (:mod:`tactcad.design.bom`). No kernel, no files.

Units: mm, m, ohm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.design.array import Plan
from tactcad.design.bom import bom_settings
from tactcad.design.readout import readout_of


@dataclass(frozen=True)
class SensorItem:
    """One bought item of the read-out.

    Attributes:
        part: BOM part name. per_element: quantity per sensing element (0: per array).
        per_array: quantity for the array without spares when ``per_element`` is 0.
        spares: bought beyond the array's need. unit: "pcs", "m" or "kit".
        material, reference, key_dimensions: as the BOM prints them.
    """

    part: str
    per_element: float
    per_array: float
    spares: int
    unit: str
    material: str
    reference: str
    key_dimensions: str

    def quantity(self, elements: int) -> int:
        """For ``elements`` sensing elements, spares included, whole units."""
        need = self.per_element * elements if self.per_element else self.per_array
        return int(math.ceil(need - 1e-9)) + self.spares

    def need(self, elements: int) -> int:
        """For ``elements`` sensing elements, without spares, whole units."""
        return int(math.ceil((self.per_element * elements if self.per_element else
                              self.per_array) - 1e-9))


def sensor_items(plan: Plan) -> list[SensorItem]:
    """The read-out's bought items of ``plan``: gauge (one per element + spares), a pair of
    bondable solder terminals per gauge, lead wire, three bridge completion resistors per
    element (quarter bridge) and one adhesive kit."""
    gauge = plan.strength.gauge
    ro = readout_of(plan.raw, gauge)
    bom = bom_settings(plan.raw)
    return [
        SensorItem("strain_gauge", 1, 0, bom.spares, "pcs", f"{gauge.alloy} foil",
                   f"{gauge.description}; {ro.gauge_resistance_ohm:g} ohm, gauge factor "
                   f"{ro.gauge_factor:g}, bonded on the top face over the web ({gauge.name})",
                   f"grid {ro.grid_length_mm:g} x {ro.grid_width_mm:g}"),
        SensorItem("solder_terminal_pair", 1, 0, bom.spares, "pcs", "copper on polyimide",
                   "bondable solder terminals beside each gauge (strain relief for the leads)",
                   "pair"),
        SensorItem("lead_wire", bom.lead_wire_m_per_element, 0, 0, "m", "PTFE-insulated copper",
                   f"stranded lead wire, {bom.lead_wire_m_per_element:g} m per element "
                   "(three-wire quarter bridge)", "AWG 32-36"),
        SensorItem("bridge_completion_resistor", 3, 0, 0, "pcs", "metal foil",
                   f"precision resistor {ro.gauge_resistance_ohm:g} ohm 0.1 % 5 ppm/K, three per "
                   "quarter bridge", ""),
        SensorItem("gauge_adhesive", 0, 1, 0, "kit", "cyanoacrylate", bom.adhesive, ""),
    ]
