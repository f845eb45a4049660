"""The read-out's bought items per element: strain gauge, terminals, lead wire,
bridge completion, and the adhesive, with quantities per element and spares.

Catalogue data: the design's library gauge (:mod:`tactcad.vocabulary.material_library`)
and its ``[readout]`` grid (:mod:`tactcad.design.readout_section`); the quantities
follow ``[bom]`` (:mod:`tactcad.design.bom_section`). No kernel, no files.

Units: mm, m, ohm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.design.array_plan import Plan
from tactcad.design.bom_section import bom_settings
from tactcad.design.readout_section import LEAD_WIRE, carrier_width_mm, readout_of
from tactcad.partlib.array.strain_gauge import GaugeBody


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
    element (quarter bridge), one adhesive kit, and the ``[readout]`` chain: an
    instrumentation amplifier and a signal cable per element and the DAQ."""
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
                   f"({ro.lead_wires} quarter bridge)", f"AWG {LEAD_WIRE['awg']}"),
        SensorItem("bridge_completion_resistor", 3, 0, 0, "pcs", "metal foil",
                   f"precision resistor {ro.gauge_resistance_ohm:g} ohm 0.1 % 5 ppm/K, three per "
                   "quarter bridge", "0805 SMD or axial 0.6 W"),
        SensorItem("gauge_adhesive", 0, 1, 0, "kit", "cyanoacrylate", bom.adhesive,
                   "bottle with catalyst, about 20 g"),
        # the rest of the [readout] chain: one amplifier per quarter bridge, one DAQ
        SensorItem("instrumentation_amplifier", 1, 0, 0, "pcs", "electronic assembly",
                   f"{ro.amplifier}, gain {ro.amplifier_gain:g}, one per quarter bridge "
                   f"(excitation {ro.excitation_V:g} V)" + (
                       f", anti-alias low-pass {ro.filter_corner_Hz:g} Hz order {ro.filter_order}"
                       if ro.filter_order else ""), f"bandwidth {ro.bandwidth_Hz:g} Hz"),
        SensorItem("daq", 0, 1, 0, "pcs", "electronic instrument",
                   f"{ro.daq}, +/-{ro.daq_range_V:g} V range, {ro.daq_bits}-bit; one "
                   "differential input per element", "one channel per element"),
        SensorItem("signal_cable", 1, 0, 0, "pcs", "shielded twisted pair",
                   "amplifier output to the DAQ input, one per element", "about 1 m"),
    ]


# ---------------------------------------------------------------------------
# The gauge as a part: a foil gauge body bonded over each element's web
# ---------------------------------------------------------------------------
#: Carrier beyond the grid at each end along the arm (mm): the usual build of an open
#: foil gauge on a polyimide carrier (catalogue outlines of 0.6 mm grids are about
#: 2.5 x 2 mm; the side margin is :data:`~tactcad.design.readout_section.CARRIER_SIDE_MM`).
#: The body's thickness is the catalogue gauge's glue line + carrier (``[readout]``
#: grid height; the 5 um foil is left out).
CARRIER_END_MM = 0.8


def gauge_body(plan: Plan) -> GaugeBody:
    """The gauge body of ``plan``: the ``[readout]`` grid with its carrier, no wider than
    the sheet, as thick as glue line + carrier."""
    ro = readout_of(plan.raw, plan.strength.gauge)
    width = carrier_width_mm(ro.grid_width_mm, plan.sheet_thickness_mm)
    return GaugeBody(ro.grid_length_mm + 2 * CARRIER_END_MM, width, ro.grid_height_mm,
                     ro.grid_length_mm, ro.grid_width_mm)


def gauge_placements(plan: Plan):
    """(element number, placement) of each element's gauge: on the flat top face, centred
    over the web (x = notch centre) and across the sheet, in the element's own placement."""
    from tactcad.design.array_plan import Placement

    out = []
    for s in plan.slots:
        g, p = s.geometry, s.placement
        centre = p.apply(g.hinge_x_mm, g.base_height_mm, g.sheet_thickness_mm / 2)
        out.append((s.number, Placement(*centre, p.turned, p.quarter_turn)))
    return out
