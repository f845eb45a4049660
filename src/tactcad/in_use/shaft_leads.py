"""The insert's lead wires through the grasper's shaft: count, bundle and the lead channel.

Each element carries one quarter bridge; a three-wire quarter bridge (Micro-Measurements
Tech Note TN-514) runs three leads to the gauge, a two-wire one two. The wire is the one
the gauge catalogue's lead mass assumes (``data/materials.toml``, ``lead_mass_mg_per_mm``):
AWG 36 copper, 0.127 mm, in PTFE insulation to 0.25 mm outside diameter.

The bundle of n round wires of diameter d fills a circle of diameter
D = d sqrt(n / η), η the packing factor: the wires' cross-section over the circle's. Equal
circles packed densely in a circle reach η ≈ 0.75-0.8 for a few dozen (best known packings,
E. Specht, packomania.com); a loose, hand-laid bundle that must be pulled through a channel
reaches less: 0.6 is taken, an assumption at the lower end of the 0.6-0.7 wire-harness
designers use for round wires. Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from tactcad.design.readout_section import LEAD_WIRE
from tactcad.errors import DesignError

#: Leads per quarter bridge by connection (``readout.lead_wires``).
LEADS_PER_BRIDGE = {"three-wire": 3, "two-wire": 2}
#: The design's lead wire (:data:`tactcad.design.readout_section.LEAD_WIRE`): its copper
#: conductor's and its PTFE insulation's outside diameter (mm).
CONDUCTOR_DIAMETER_MM = LEAD_WIRE["conductor_diameter_mm"]
INSULATED_DIAMETER_MM = LEAD_WIRE["insulated_diameter_mm"]
#: Packing factor of a loose bundle of round wires (assumption, see the module docstring).
PACKING_FACTOR = 0.6


@dataclass(frozen=True)
class LeadsCheck:
    """The leads against the shaft's lead channel.

    Attributes:
        bridges: quarter bridges (one per element).
        connection: ``three-wire`` or ``two-wire``.
        leads: wires in the bundle.
        wire_diameter_mm: each wire's outside diameter (mm).
        conductor_diameter_mm: its copper (mm).
        packing_factor: wire cross-section over the bundle's circle.
        bundle_diameter_mm: the bundle's diameter (mm).
        channel_diameter_mm: the lead channel's diameter (mm).
        fits: bundle <= channel.
    """

    bridges: int
    connection: str
    leads: int
    wire_diameter_mm: float
    conductor_diameter_mm: float
    packing_factor: float
    bundle_diameter_mm: float
    channel_diameter_mm: float
    fits: bool

    @property
    def fill(self) -> float:
        """The wires' cross-section over the channel's."""
        return self.leads * (self.wire_diameter_mm / self.channel_diameter_mm) ** 2

    def as_json(self) -> dict:
        return {**asdict(self), "channel_fill": self.fill}


def bundle_diameter_mm(leads: int, wire_diameter_mm: float,
                       packing_factor: float = PACKING_FACTOR) -> float:
    """The diameter (mm) of a bundle of ``leads`` round wires: d sqrt(n / η).

    Raises:
        DesignError: leads < 1, a diameter <= 0 or η outside (0, 0.907] (hexagonal packing).
    """
    if not (isinstance(leads, int) and leads >= 1):
        raise DesignError("leads", leads, "an integer >= 1")
    if not (math.isfinite(wire_diameter_mm) and wire_diameter_mm > 0):
        raise DesignError("wire_diameter_mm", wire_diameter_mm, "> 0 mm")
    if not (math.isfinite(packing_factor) and 0 < packing_factor <= 0.907):
        raise DesignError("packing_factor", packing_factor,
                          "> 0 ... 0.907 (hexagonal packing of equal circles)")
    return wire_diameter_mm * math.sqrt(leads / packing_factor)


def leads_check(bridges: int, channel_diameter_mm: float, connection: str = "three-wire",
                wire_diameter_mm: float = INSULATED_DIAMETER_MM,
                packing_factor: float = PACKING_FACTOR) -> LeadsCheck:
    """The leads of ``bridges`` quarter bridges against a lead channel.

    Args:
        bridges: quarter bridges (the insert's elements), >= 1.
        channel_diameter_mm: the shaft's lead channel (mm), > 0.
        connection: ``three-wire`` (default) or ``two-wire``.
        wire_diameter_mm: outside diameter of one insulated lead (mm).
        packing_factor: η (see the module docstring).

    Raises:
        DesignError: a value outside its range.
    """
    if connection not in LEADS_PER_BRIDGE:
        raise DesignError("connection", connection, " | ".join(LEADS_PER_BRIDGE))
    if not (isinstance(bridges, int) and bridges >= 1):
        raise DesignError("bridges", bridges, "an integer >= 1")
    if not (math.isfinite(channel_diameter_mm) and channel_diameter_mm > 0):
        raise DesignError("channel_diameter_mm", channel_diameter_mm, "> 0 mm")
    leads = bridges * LEADS_PER_BRIDGE[connection]
    bundle = bundle_diameter_mm(leads, wire_diameter_mm, packing_factor)
    return LeadsCheck(bridges, connection, leads, wire_diameter_mm, CONDUCTOR_DIAMETER_MM,
                      packing_factor, bundle, channel_diameter_mm, bundle <= channel_diameter_mm)
