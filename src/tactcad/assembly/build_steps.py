"""The build book's steps, derived from the design's parts (no CAD kernel).

Every BOM item is consumed by exactly one step: a part module's parts by the
step its module declares (:class:`tactcad.partlib.base.BuildStep`: the gauge's
bonding, the terminal board's wiring, the element's stack, the clamp bolt's
torque, the sample kit's casting, each with its module's title, tools and
notes), a bought or consumable item by the step named here, and any other
rig part by the step of the first scene whose rig shows it; so a design with
other parts, rigs or samples gets its own steps and no step names a part the
design lacks. A nut is the one exception: the BOM's count of it is shared over the
steps that fit bolts of its size, each as many as its bolts
(:func:`nuts_with_their_bolts`), so the book's nuts follow the BOM's fasteners.

Step order: the array (gauges bonded and cured; leads wired to the terminal
board; elements, spacers and clamp plates stacked; bolts torqued; read-out
connected), then each rig in scene order, then the sample kit cast.

Sources: tightening torque T = K F d
(:func:`tactcad.vocabulary.standards.tightening_torque_Nm`: Shigley ch. 8, ISO
898-1); gauge installation after Micro-Measurements instruction bulletins
B-127 and B-129 (in :mod:`tactcad.partlib.array.strain_gauge` and
:mod:`tactcad.partlib.terminal_board`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

from tactcad.partlib.base import BuildStep
from tactcad.vocabulary.standards import NUT_FACTOR, PROOF_STRESS_MPA, tightening_torque_Nm  # noqa: F401

#: The array's steps in build order (a construction's own: ``array-stack`` for the stacked
#: array, ``comb-rows`` for the monolithic comb; a design has the steps of its parts only).
ARRAY_STEP_ORDER = ("array-gauges", "array-wiring", "array-stack", "comb-rows", "array-bolts",
                    "array-readout")


@dataclass(frozen=True)
class BookContext:
    """What the steps' notes read: the array's element count, the gauge's and
    the adhesive's catalogue texts, the clamp bolt (a
    :class:`~tactcad.vocabulary.standards.BoltSpec`), the terminal board's
    hole pairs, each sample's stiffness (N/mm) and, where the drawings rely on it for
    the tips' coplanarity, the zeroing step's instruction (``tip_zeroing``)."""

    elements: int
    gauge_text: str
    adhesive_text: str
    bolt: Any
    terminal_pairs: int
    sample_stiffness: Mapping[str, float]
    tip_zeroing: str | None = None


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

#: Bought items of the sensor (not part modules) by the step that consumes them.
BOUGHT_ITEM_STEPS = {
    "solder_terminal_pair": "array-gauges", "gauge_adhesive": "array-gauges",
    "lead_wire": "array-wiring", "bridge_completion_resistor": "array-wiring",
    "instrumentation_amplifier": "array-readout", "daq": "array-readout",
    "signal_cable": "array-readout",
} | {c.part: c.step for c in CONSUMABLES}
#: The read-out chain's step: bought items only, so declared here.
READOUT_STEP = BuildStep(
    "array-readout", "Connect the read-out chain", tools=lambda book: ("multimeter",),
    notes=lambda book: ("One signal cable and one amplifier channel per element, then the DAQ; "
                        "zero each channel unloaded.",
                        *((book.tip_zeroing,) if book.tip_zeroing else ())))
_SAMPLES = "samples-cast"
_ARRAY_SCENE = "array"


def module_steps() -> dict[str, BuildStep]:
    """Builder key -> the build step of every part module that declares one
    (its own builder and the companions it names)."""
    from tactcad.partlib.registry import array_parts_lib, rig_parts_lib

    out: dict[str, BuildStep] = {}
    for part in [*array_parts_lib().values(), *rig_parts_lib().values()]:
        if part.assembly is not None:
            for builder in (part.builder_key, *part.assembly.companions):
                out[builder] = part.assembly
    return out


def step_of_item(part: str, builder: str | None, first_assembly: str,
                 modules: Mapping[str, BuildStep] | None = None) -> str:
    """The key of the step consuming a BOM item (see module doc); ``modules``:
    :func:`module_steps`, if already at hand."""
    modules = module_steps() if modules is None else modules
    if builder in modules:
        return modules[builder].key
    if part in BOUGHT_ITEM_STEPS:
        return BOUGHT_ITEM_STEPS[part]
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


#: A rig's own step: title and notes (the others are assembled "as the scene model shows").
RIG_STEPS: dict[str, tuple[str, tuple[str, ...]]] = {
    "grasper": ("Seat the insert in the grasper's jaw", (
        "Slide the insert into the jaw's pocket from its back, the first column at the pin "
        "end, each contact face through the window in the face wall.",
        "Check that every contact face stands proud of the jaw's face by the same height "
        "before fixing the insert in the pocket.",
        "Lead the gauges' wires back through the shaft's bore (the lead channel) without "
        "pulling on the terminals.")),
}


def nuts_with_their_bolts(by_step: Mapping[str, Sequence[tuple[str, int]]],
                          fasteners: Mapping[str, tuple[str, str]],
                          order: Sequence[str]) -> dict[str, list[tuple[str, int]]]:
    """The steps' parts with each nut fitted where the bolts of its size are: a nut row's
    count (the BOM's) is shared over the steps in build order, each taking as many as the
    bolts of that size it fits; what is left stays in the nut's own step. The nuts counted
    are the BOM's, so no step counts nuts for bolts it does not fit and none is lost.

    Args:
        by_step: step key -> (part, quantity) it consumes, each nut in one step.
        fasteners: part -> (``"bolt"`` or ``"nut"``, its thread size, e.g. ``"M2"``).
        order: the step keys in build order.

    Returns:
        step key -> (part, quantity), nuts shared out; a step's other parts unchanged.
    """
    out = {k: [pq for pq in v if fasteners.get(pq[0], ("",))[0] != "nut"]
           for k, v in by_step.items()}
    keys = [k for k in order if k in by_step] + [k for k in by_step if k not in order]
    for home in keys:
        for part, qty in by_step[home]:
            kind, size = fasteners.get(part, ("", ""))
            if kind != "nut":
                continue
            left = qty
            for key in keys:
                bolts = sum(q for p, q in by_step[key] if fasteners.get(p) == ("bolt", size))
                given = min(bolts, left)
                if given > 0:
                    out[key].append((part, given))
                    left -= given
            if left > 0:  # nuts no bolt of the steps takes stay where the BOM puts them
                shared = dict(out[home])
                shared[part] = shared.get(part, 0) + left
                out[home] = list(shared.items())
    return out


def fastener_sizes(specs: Mapping[str, Any]) -> dict[str, tuple[str, str]]:
    """Part -> (``"bolt"`` or ``"nut"``, thread size) of the screws and nuts among ``specs``
    (part name -> spec): a screw's geometry is (BoltSpec, length), a nut's its BoltSpec."""
    from tactcad.vocabulary.standards import BoltSpec

    out: dict[str, tuple[str, str]] = {}
    for name, spec in specs.items():
        geometry = getattr(spec, "geometry", None)
        if isinstance(geometry, BoltSpec):
            out[name] = ("nut", geometry.size)
        elif isinstance(geometry, tuple) and geometry and isinstance(geometry[0], BoltSpec):
            out[name] = ("bolt", geometry[0].size)
    return out


def build_steps(items: Sequence[tuple[str, int, str | None, str]], elements: int,
                gauge_text: str, adhesive_text: str, bolt, terminal_pairs: int,
                scenes: Sequence[str], sample_stiffness: Mapping[str, float],
                screws: Mapping | None = None, rigs: Mapping[str, str] | None = None,
                spares: Mapping[str, int] | None = None,
                tip_zeroing: str | None = None,
                fasteners: Mapping[str, tuple[str, str]] | None = None) -> list[Step]:
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
        rigs: scene -> its rig; a rig of :data:`RIG_STEPS` gives its scene's step its own
            title and notes (the others: "Assemble the <scene>").
        spares: part -> units bought beyond those fitted (not in ``items``' quantities);
            the step that fits the part says how many stay in the kit.
        tip_zeroing: the instruction to zero the tips on a rigid flat, when the drawings
            rely on it for the tips' coplanarity (:func:`tip_zeroing_note`); the read-out's
            step gives it.
        fasteners: part -> (``"bolt"`` or ``"nut"``, thread size) (:func:`fastener_sizes`);
            given, each nut is fitted in the steps that fit the bolts of its size
            (:func:`nuts_with_their_bolts`), its spares said in its own step.

    Returns:
        Steps in build order, each with the items it consumes; steps that
        would consume nothing are left out.
    """
    modules = module_steps()
    spares = spares or {}
    by_step: dict[str, list[tuple[str, int]]] = {}
    for part, qty, builder, first in items:
        by_step.setdefault(step_of_item(part, builder, first, modules), []).append((part, qty))
    book = BookContext(elements, gauge_text, adhesive_text, bolt, terminal_pairs,
                       dict(sample_stiffness), tip_zeroing)
    declared = {m.key: m for m in modules.values() if m.title}
    declared[READOUT_STEP.key] = READOUT_STEP
    consumable = {c.part for c in CONSUMABLES} | {"gauge_adhesive", "solder_wire", "lead_wire"}
    order = list(ARRAY_STEP_ORDER) + [f"rig-{s}" for s in scenes] + [_SAMPLES]
    order += [k for k in by_step if k not in order]
    home = {p: k for k, parts in by_step.items() for p, _ in parts}  # the BOM's step
    if fasteners:
        by_step = nuts_with_their_bolts(by_step, fasteners, order)
    steps = []
    for key in order:
        parts = by_step.get(key)
        if not parts:
            continue
        if key.startswith("rig-"):
            scene = key[4:]
            title, notes = RIG_STEPS.get((rigs or {}).get(scene), (f"Assemble the {scene}", (
                "Fit the parts on their joints as the scene model shows; screws finger-tight "
                "first, then tighten.",)))
            notes = tuple(notes) + screw_notes(parts, screws or {})
            sub, tool = scene, ("hex keys",)
        else:
            lead = declared.get(key, BuildStep(key, key))
            title, notes, tool = lead.title, lead.notes(book), lead.tools(book)
            sub = "samples" if key == _SAMPLES else _ARRAY_SCENE
            scene = _ARRAY_SCENE
            if key == _SAMPLES:
                scene = next((s for s in scenes if "sample" in s), _ARRAY_SCENE)
        notes = tuple(notes) + tuple(
            f"{spares[p]} spare {p} beyond the {q} fitted here stay in the kit "
            f"(bom.csv: spares)." for p, q in parts if spares.get(p) and home.get(p) == key)
        steps.append(Step(key, title, sub, tuple(parts), tool,
                          tuple(p for p, _ in parts if p in consumable), notes,
                          tuple(p for p, _ in parts), scene))
    return steps


def tip_zeroing_note(tip_height) -> str | None:
    """The build book's instruction to zero the tips on a rigid flat, when the drawings
    rely on that procedure for the tips' coplanarity.

    Args:
        tip_height: the drawings' tip-height decision
            (:class:`tactcad.in_use.tip_height_drawing.TipHeightDrawing`) or None.

    Returns:
        One sentence naming the procedure, the tolerance drawn and the mismatch the
        procedure leaves (um); None without a decision or when the drawn tolerance alone
        holds the K_obj budget's allowance.
    """
    if tip_height is None or tip_height.procedure is None:
        return None
    return (f"As the element drawings require: {tip_height.procedure}. They hold the tip "
            f"height to +/-{tip_height.drawn_mm:g} mm only, so every K_obj reading relies on "
            f"this zeroing (it leaves {1e3 * tip_height.residual_mm:.2g} um of mismatch).")
