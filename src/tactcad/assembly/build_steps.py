"""The build book's steps, derived from the design's parts (no CAD kernel).

Every BOM item is consumed by exactly one step, found from what the item is
(its part builder, or a read-out/consumable item's name) and, for the rig
parts, the first scene whose rig shows it; so a design with other parts,
rigs or samples gets its own steps and no step names a part the design lacks.

Step order: the array (gauges bonded and cured; leads wired to the terminal
board; elements, spacers and clamp plates stacked; bolts torqued; read-out
connected), then each rig in scene order, then the sample kit cast.

Sources of the notes: gauge installation after Micro-Measurements
instruction bulletin B-127 (surface preparation) and B-129 (soldering);
tightening torque T = K F d with nut factor K = 0.2 and preload
F = 0.75 x proof stress x stress area (Shigley, Mechanical Engineering Design,
ch. 8; proof stress 580 MPa of property class 8.8 and stress area
A_s = pi/4 (d - 0.9382 P)^2 from ISO 898-1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Sequence

#: Nut factor K of a dry steel thread (Shigley, ch. 8).
NUT_FACTOR = 0.2
#: Proof stress of property class 8.8 below M16 (MPa, ISO 898-1).
PROOF_STRESS_MPA = 580.0


@dataclass(frozen=True)
class Step:
    """One step of the build book.

    Attributes:
        key: stable identifier (``array-gauges``, ``rig-calibration-rig`` ...).
        title: one line.
        sub_assembly: ``array``, a scene name, or ``samples``.
        parts: (BOM part, quantity) the step consumes.
        tools: tools it needs.
        consumables: consumable BOM items it uses (also in ``parts``).
        notes: instructions, one sentence each.
        highlight: parts drawn highlighted (and exploded) in its picture.
        scene: the assembly its picture shows.
    """

    key: str
    title: str
    sub_assembly: str
    parts: tuple[tuple[str, int], ...]
    tools: tuple[str, ...]
    consumables: tuple[str, ...]
    notes: tuple[str, ...]
    highlight: tuple[str, ...]
    scene: str

    def as_dict(self) -> dict:
        return {"key": self.key, "title": self.title, "sub_assembly": self.sub_assembly,
                "parts": [{"part": p, "quantity": q} for p, q in self.parts],
                "tools": list(self.tools), "consumables": list(self.consumables),
                "notes": list(self.notes), "highlight": list(self.highlight), "scene": self.scene}


@dataclass(frozen=True)
class Consumable:
    """A consumable BOM item the array's steps use (quantity per element, plus a fixed part)."""

    part: str
    per_element: float
    fixed: float
    unit: str
    material: str
    reference: str
    step: str
    size: str

    def quantity(self, elements: int) -> int:
        """Whole units to buy for ``elements`` elements (rounded up)."""
        return math.ceil(self.per_element * elements + self.fixed - 1e-9)


#: Consumables of the array's steps (not placed in any model, so listed here).
CONSUMABLES = (
    Consumable("gauge_surface_prep_kit", 0, 1, "kit", "silicon-carbide abrasive 320/400, conditioner, "
               "neutralizer, cotton swabs", "degrease, abrade, condition and neutralize the "
               "bonding area (instruction bulletin B-127 order)", "array-gauges",
               "one kit per array"),
    Consumable("solder_wire", 0.5, 0, "m", "Sn96.5Ag3Cu0.5, rosin flux core",
               "Ø0.5 mm solder for the gauge tabs and terminals", "array-wiring", "Ø0.5"),
    Consumable("heat_shrink_sleeve", 0.1, 0, "m", "polyolefin 2:1",
               "Ø1.6 mm sleeve over each lead's solder joint at the terminal board",
               "array-wiring", "Ø1.6"),
    Consumable("gauge_protective_coating", 0, 1, "bottle", "silicone rubber (RTV)",
               "coat over gauge and terminals against moisture and handling", "array-gauges",
               "about 90 g"),
)

# BOM items by what they are: builder of a placed part, or name of a bought item.
_ARRAY_STEPS = {
    "array-gauges": ("gauge", "strain_gauge", "solder_terminal_pair", "gauge_adhesive",
                     "gauge_surface_prep_kit", "gauge_protective_coating"),
    "array-wiring": ("terminal_board", "lead_wire", "bridge_completion_resistor",
                     "solder_wire", "heat_shrink_sleeve"),
    "array-stack": ("element", "spacer", "clamp_plate"),
    "array-bolts": ("bolt", "nut"),
    "array-readout": ("instrumentation_amplifier", "daq", "signal_cable"),
}
_SAMPLES = "samples-cast"
_ARRAY_SCENE = "array"


def tightening_torque_Nm(d_mm: float, pitch_mm: float) -> float:
    """Tightening torque (N m) of a class 8.8 metric screw of nominal
    diameter ``d_mm`` and pitch ``pitch_mm``: T = K F d (see module doc)."""
    stress_area = math.pi / 4 * (d_mm - 0.9382 * pitch_mm) ** 2
    preload_N = 0.75 * PROOF_STRESS_MPA * stress_area
    return NUT_FACTOR * preload_N * d_mm / 1000.0


def step_of_item(part: str, builder: str | None, first_assembly: str) -> str:
    """The key of the step consuming a BOM item (see module doc)."""
    for key, what in _ARRAY_STEPS.items():
        if part in what or builder in what:
            return key
    if builder == "sample":
        return _SAMPLES
    if first_assembly == _ARRAY_SCENE:
        return "array-stack"
    return f"rig-{first_assembly}"


def screw_notes(parts: Sequence[tuple[str, int]], screws: Mapping) -> tuple[str, ...]:
    """One note per screw part of a step: its size and tightening torque
    (:func:`tightening_torque_Nm`, class 8.8 into steel; a tapped light-alloy
    or plastic part takes less, as its thread allows).

    Args:
        parts: (BOM part, quantity) of the step.
        screws: part name -> its :class:`~tactcad.vocabulary.standards.BoltSpec`.
    """
    notes = []
    for part, qty in parts:
        bolt = screws.get(part)
        if bolt is None:
            continue
        torque = tightening_torque_Nm(bolt.nominal_diameter_mm, bolt.thread_pitch_mm)
        notes.append(f"Tighten the {qty:g} {bolt.size} screws ({part}) to {torque:.2f} N m with a "
                     f"{bolt.socket_across_flats_mm:g} mm hex key (class 8.8 into a steel nut or "
                     "thread, K = 0.2, preload 75 % of proof load); into a tapped aluminium or "
                     "plastic part, less, as its thread allows.")
    return tuple(notes)


def build_steps(items: Sequence[tuple[str, int, str | None, str]], elements: int,
                gauge_text: str, adhesive_text: str, bolt, terminal_pairs: int,
                scenes: Sequence[str], sample_stiffness: Mapping[str, float],
                screws: Mapping | None = None) -> list[Step]:
    """The ordered steps consuming ``items``.

    Args:
        items: (part, quantity, builder or None, first assembly showing it) per BOM row.
        elements: elements of the array (one quarter bridge each).
        gauge_text, adhesive_text: the gauge's and adhesive's catalogue texts.
        bolt: the array's :class:`~tactcad.vocabulary.standards.BoltSpec`.
        terminal_pairs: terminal hole pairs of the terminal board.
        scenes: the rig scenes in file order (their steps follow the array's).
        sample_stiffness: measured stiffness (N/mm) of every sample part.
        screws: the rigs' screw parts -> their BoltSpec (each rig step gives
            their torques, :func:`screw_notes`).

    Returns:
        Steps in build order, each with the items it consumes; steps that
        would consume nothing are left out.
    """
    by_step: dict[str, list[tuple[str, int]]] = {}
    for part, qty, builder, first in items:
        by_step.setdefault(step_of_item(part, builder, first), []).append((part, qty))
    torque = tightening_torque_Nm(bolt.nominal_diameter_mm, bolt.thread_pitch_mm)
    wiring = [f"Element {k}: gauge leads to terminals {2 * k - 1} and {2 * k}; a third lead from "
              f"terminal {2 * k} carries the sense line (three-wire quarter bridge), the three "
              "completion resistors sit at the amplifier end." for k in range(1, min(
                  elements, terminal_pairs) + 1)]
    text = {
        "array-gauges": ("Bond and cure the strain gauges", (
            f"One gauge per element on the top face over the web ({gauge_text}).",
            "Prepare each bonding area: degrease, abrade with 320 then 400 grit, condition, "
            "neutralize; handle no more after that.",
            f"Bond with {adhesive_text}; press with thumb pressure through PTFE film for 1 min, "
            "let it cure 24 h at room temperature before wiring.",
            "Bond a solder terminal pair beside each gauge as strain relief; coat gauge and "
            "terminals after wiring.")),
        "array-wiring": ("Wire the quarter bridges through the terminal board", tuple(wiring) + (
            "Solder at the lowest iron temperature that wets (about 300 degC); check each "
            "bridge arm reads the gauge's resistance before closing the clamp.",)),
        "array-stack": ("Stack elements and spacers between the clamp plates", (
            "Stack in the order the assembly model shows: clamp plate, element, spacer, "
            "element ... clamp plate; align on the bolt holes before tightening.",
            "Keep the gauges' leads free of the clamp faces.")),
        "array-bolts": ("Torque the clamp bolts", (
            f"Tighten the {bolt.size} clamp bolts crosswise in three passes to "
            f"{torque:.2f} N m (class 8.8, K = {NUT_FACTOR:g}, preload 75 % of proof load).",)),
        "array-readout": ("Connect the read-out chain", (
            "One signal cable and one amplifier channel per element, then the DAQ; "
            "zero each channel unloaded.",)),
        _SAMPLES: ("Cast the sample kit", (
            "Cast one block per stiffness of the rigs file; measure each block's stiffness on the "
            "sample-stiffness rig and label it with the value.",) + tuple(
                f"{part}: {k:g} N/mm" for part, k in sample_stiffness.items())),
    }
    tools = {"array-gauges": ("tweezers", "PTFE film", "magnifier"),
             "array-wiring": ("temperature-controlled soldering iron", "multimeter"),
             "array-stack": ("flat granite or glass plate",),
             "array-bolts": (f"torque screwdriver with {bolt.socket_across_flats_mm:g} mm hex bit",),
             "array-readout": ("multimeter",), _SAMPLES: ("mould", "scale")}
    consumable = {c.part for c in CONSUMABLES} | {"gauge_adhesive", "solder_wire", "lead_wire"}
    order = list(_ARRAY_STEPS) + [f"rig-{s}" for s in scenes] + [_SAMPLES]
    order += [k for k in by_step if k not in order]
    steps = []
    for key in order:
        parts = by_step.get(key)
        if not parts:
            continue
        if key.startswith("rig-"):
            scene = key[4:]
            title, notes = f"Assemble the {scene}", (
                "Fit the parts on their joints as the scene model shows; screws finger-tight "
                "first, then tighten.",) + screw_notes(parts, screws or {})
            sub, tool = scene, ("hex keys",)
        else:
            title, notes = text[key]
            sub = "samples" if key == _SAMPLES else _ARRAY_SCENE
            scene, tool = (_ARRAY_SCENE, tools[key])
            if key == _SAMPLES:
                scene = next((s for s in scenes if "sample" in s), _ARRAY_SCENE)
        steps.append(Step(key, title, sub, tuple(parts), tool,
                          tuple(p for p, _ in parts if p in consumable), notes,
                          tuple(p for p, _ in parts), scene))
    return steps
