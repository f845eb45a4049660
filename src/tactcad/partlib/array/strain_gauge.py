"""The strain gauge's body (a bought part, one per element): a thin box
bonded over each element's web, modelled as its carrier's envelope.

Here under the key ``gauge``: its dimensions (:class:`GaugeBody`), spec and
builder. Its size comes from the design's ``[readout]`` grid with its carrier
(:func:`tactcad.catalogue.gauges.gauge_body`, above this layer), handed over
in the context. Part frame: centred on x (along the arm) and z (across the
sheet), y from 0 (the bonded face) to the thickness. Units: mm, ohm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from tactcad.kernel.shapes import box_at_origin, translated
from tactcad.partlib.base import RGB, ArrayContext, ArrayPart, BuildStep, PartData
from tactcad.vocabulary.process import Method, Process

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

COLOR: RGB = (0.85, 0.55, 0.15)  # amber polyimide carrier
#: Part name of the strain gauge body (one per element).
GAUGE_PART = "strain_gauge"


@dataclass(frozen=True)
class GaugeBody:
    """A foil gauge's body (mm): carrier ``length_mm`` along the arm, ``width_mm``
    across the sheet, ``thickness_mm``; the active grid ``grid_length_mm`` x
    ``grid_width_mm`` centred in it. Part frame: centred on x and z, y from 0 (the
    bonded face) to the thickness."""

    length_mm: float
    width_mm: float
    thickness_mm: float
    grid_length_mm: float
    grid_width_mm: float

    @property
    def volume_mm3(self) -> float:
        return self.length_mm * self.width_mm * self.thickness_mm

    @property
    def bbox_mm(self) -> tuple[float, float, float, float, float, float]:
        return (-self.length_mm / 2, 0.0, -self.width_mm / 2, self.length_mm / 2,
                self.thickness_mm, self.width_mm / 2)


def build(g: GaugeBody) -> Solid:
    """Carrier box, centred on x and z, from y = 0 (the bonded face) to the thickness."""
    box = box_at_origin(g.length_mm, g.thickness_mm, g.width_mm)
    # translated, not moved: the geometry itself shifts, so STEP writes one product, not a
    # located copy of it
    return translated(box, (-g.length_mm / 2, 0.0, -g.width_mm / 2))


def specs(context: ArrayContext) -> tuple[PartData, ...]:
    """The gauge body (``context.gauge``) of the design's library gauge (``plan.strength.gauge``)."""
    gb, gauge = context.gauge, context.plan.strength.gauge
    return (PartData(
        name=GAUGE_PART, kind="purchased",
        process=Process(f"{gauge.description}; grid {gb.grid_length_mm:g} x {gb.grid_width_mm:g} "
                        f"mm, {gauge.resistance_ohm:g} ohm ({gauge.name}), bonded over the web",
                        Method.BOUGHT),
        material=f"{gauge.alloy} foil", color=COLOR,  # the carrier is the description's
        expected_volume_mm3=gb.volume_mm3, expected_bbox_mm=gb.bbox_mm, geometry=gb),)


def bonding_notes(book) -> tuple[str, ...]:
    """Gauge installation after Micro-Measurements instruction bulletins B-127
    (surface preparation) and B-129 (soldering)."""
    return (f"One gauge per element on the top face over the web ({book.gauge_text}).",
            "Prepare each bonding area: degrease, abrade with 320 then 400 grit, condition, "
            "neutralize; handle no more after that.",
            f"Bond with {book.adhesive_text}; press with thumb pressure through PTFE film for 1 min, "
            "let it cure 24 h at room temperature before wiring.",
            "Bond a solder terminal pair beside each gauge as strain relief; coat gauge and "
            "terminals after wiring.")


PART = ArrayPart(key="gauge", build=build, specs=specs, order=40,
                 assembly=BuildStep("array-gauges", "Bond and cure the strain gauges",
                                    tools=lambda book: ("tweezers", "PTFE film", "magnifier"),
                                    notes=bonding_notes))
