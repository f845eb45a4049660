"""What the bill of materials needs beyond the parts: ``[bom]`` and the clamp's materials.

``[bom]`` (every key optional, defaults with reasons in :data:`DEFAULTS`):

* ``spares``: strain gauges (and their terminals) bought beyond one per element;
* ``lead_wire_m_per_element``: lead wire per element, all its conductors together (m);
* ``adhesive``: the gauge adhesive (one kit per array).

``[clamp] material`` and ``[clamp] spacer_material`` name the library grade
(:mod:`tactcad.vocabulary.material_library`) of the clamp plates and the spacers; they
default to :data:`DEFAULT_CLAMP_GRADE`, not to the elements' material: these
parts carry no spring load.

Units: m for wire, counts otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from tactcad.vocabulary.schema import Section, Text, integer, number, section_with_defaults

#: Grade of clamp plates and spacers when the design names none.
DEFAULT_CLAMP_GRADE = "6061-T6"
DEFAULT_CLAMP_REASON = ("clamp plates and spacers carry no spring load: 6061-T6 aluminium plate "
                        "is the usual stock for milled and cut fixtures")

DEFAULTS: dict[str, tuple[Any, str]] = {
    "spares": (2, "a gauge lost in bonding or soldering, or a web that fails its measurement, "
                  "is replaced from stock; 2 spares cover that for an array of up to about 12 "
                  "elements (gauges are sold in packs of 5 or 10)"),
    "lead_wire_m_per_element": (1.5, "three conductors (three-wire quarter bridge, which "
                                     "cancels the leads' temperature drift) of 0.5 m from the "
                                     "gauge to the bridge completion"),
    "adhesive": ("cyanoacrylate strain-gauge adhesive with catalyst (e.g. M-Bond 200, HBM Z70)",
                 "room-temperature cure, suited to foil gauges on metal for static loads"),
}


class BomSection(Section):
    """``[bom]``: every key optional (defaults in :data:`DEFAULTS`)."""

    spares: integer(0, 1000, why="strain gauges bought beyond one per element") = None
    lead_wire_m_per_element: number(0.01, 100.0, unit="m", why="lead wire per element") = None
    adhesive: Text = None


@dataclass(frozen=True)
class BomSettings:
    """A design's resolved ``[bom]`` with each value's source."""

    spares: int
    lead_wire_m_per_element: float
    adhesive: str
    sources: tuple[tuple[str, str], ...] = ()


def bom_settings(raw: Mapping[str, Any]) -> BomSettings:
    """The resolved ``[bom]`` of a design's raw tables (validated before)."""
    values, sources = section_with_defaults(raw, "bom", DEFAULTS)
    return BomSettings(int(values["spares"]), float(values["lead_wire_m_per_element"]),
                       str(values["adhesive"]), tuple(sorted(sources.items())))


def clamp_grades(raw: Mapping[str, Any]) -> dict[str, str]:
    """Library grade of the clamp plates and the spacers: ``{"clamp_plate": ..., "spacer": ...}``
    (matched names; an unknown one is refused when the design is validated)."""
    from tactcad.vocabulary.material_library import material_grade

    clamp = raw.get("clamp", {}) if isinstance(raw, Mapping) else {}
    return {"clamp_plate": material_grade(clamp.get("material", DEFAULT_CLAMP_GRADE),
                                          "clamp.material").name,
            "spacer": material_grade(clamp.get("spacer_material", DEFAULT_CLAMP_GRADE),
                                     "clamp.spacer_material").name}


def check_clamp_materials(d: Any, p) -> None:
    """Cross-field rule: clamp and spacer grades are library grades."""
    from tactcad.vocabulary.material_library import material_grade
    from tactcad.errors import DesignError

    for key in ("material", "spacer_material"):
        value = getattr(d.clamp, key, None)
        if value is None:
            continue
        try:
            material_grade(value, f"clamp.{key}")
        except DesignError as exc:
            p.add(exc.field, exc.value, exc.allowed, exc.why)
