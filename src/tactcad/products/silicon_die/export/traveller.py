"""The die's process traveller: the steps a fab runs, in order, each with the mask it uses,
its parameters and what it leaves (thicknesses, the implant's sheet resistance), as
Markdown a lab hands to the cleanroom with the GDS.

The steps are those of :mod:`tactcad.products.silicon_die.vocabulary.soi_process`'s flow. Each parameter is the
plan's or marked as an assumption; a fab's own recipes replace the assumed ones. Nothing
here is a recipe of a particular tool.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from tactcad.products.silicon_die.design import mems_die as md
from tactcad.products.silicon_die.design.mems_die import DiePlan
from tactcad.products.silicon_die.vocabulary.soi_process import (CAVITY_ALIGNMENT_UM,
                                                                 CAVITY_DEPTH_TOLERANCE_REL,
                                                                 DRIE_ASPECT_RATIO, MASK_BY_NAME)

#: Parameters stated as assumptions (a fab's recipe replaces them).
SCREEN_OXIDE_NM = 100.0
METAL_NM = 500.0
HARD_MASK_NM = 1000.0
ANNEAL_C, ANNEAL_MIN = 1000.0, 30.0
SINTER_C = 400.0


@dataclass(frozen=True)
class Step:
    """One step: its name, the mask it uses (or ""), what is done and what it leaves."""

    name: str
    mask: str
    action: str
    leaves: str


def traveller_steps(plan: DiePlan, sheet_resistance_ohm_per_sq: float) -> list[Step]:
    """The die's steps in process order (um, nm, C, cm^-2)."""
    s = plan.stack
    assumed = " (assumption)"
    depth_r, depth_m = plan.cavity_depths_um
    tol = 100 * CAVITY_DEPTH_TOLERANCE_REL
    return [
        Step("handle", "", f"handle wafer: (100) silicon, {s.handle_um:g} um "
             "(or a cavity SOI wafer ordered from a wafer maker with the two cavity masks: "
             "steps 1-5 are then its)", "the handle"),
        Step("cavity etch, measuring row", "cavity_measuring",
             f"timed DRIE {depth_m:g} um +-{tol:g} %{assumed}",
             "the measuring row's cavity: its floor the beams' hard stop"),
        Step("cavity etch, reference row", "cavity_reference",
             f"resist sprayed over the first cavity; timed DRIE {depth_r:g} um +-{tol:g} %"
             f"{assumed}", "the reference row's cavity: its floor the beams' hard stop"),
        Step("bond oxide", "", f"thermal oxidation of the handle, {s.box_um:g} um",
             "the buried oxide on the bond face (it lines the cavities too)"),
        Step("bond and thin", "", f"n-type (100) device wafer fusion-bonded in vacuum, "
             f"flat along <110>, annealed, ground and polished to {s.device_um:g} +-"
             f"{s.device_tolerance_um:g} um",
             f"{s.total_um:g} um stack over sealed cavities (the device layer bows into "
             "them under the atmosphere until the front DRIE opens them)"),
        Step("oxidation", "", f"thermal screen oxide {SCREEN_OXIDE_NM:g} nm{assumed}",
             "oxide on the device layer"),
        Step("implant", "piezo", f"boron, dose {plan.implant_dose_per_cm2:.2g} cm^-2 through the "
             f"screen oxide{assumed}",
             "p-type resistors at each beam's root"),
        Step("anneal", "", f"{ANNEAL_C:g} C, {ANNEAL_MIN:g} min, N2{assumed}",
             f"junction {md.JUNCTION_DEPTH_UM:g} um deep, {plan.acceptors_per_cm3:.2g} cm^-3, "
             f"sheet resistance {sheet_resistance_ohm_per_sq:.3g} ohm/sq (Masetti mobility)"),
        Step("contact", "contact", "oxide opened over each resistor's ends (buffered HF)",
             f"{4 * len(plan.beams)} contacts of {md.CONTACT_UM:g} um (each beam's resistor "
             "and its reference)"),
        Step("metal", "metal", f"aluminium {METAL_NM:g} nm sputtered, wet-etched{assumed}; "
             f"sintered {SINTER_C:g} C in forming gas{assumed}",
             f"leads and {3 * len(plan.beams)} bond pads of {md.PAD_UM:g} um (a half bridge "
             "per beam)"),
        Step("front DRIE mask", "device_etch", f"PECVD oxide {HARD_MASK_NM:g} nm{assumed}, "
             f"patterned aligned to the cavities to +-{CAVITY_ALIGNMENT_UM:g} um and etched "
             "(before the posts: no lithography over them after)",
             "the beams' outline in a hard mask over the device layer"),
        Step("posts", "tip", f"posts {plan.post_height_um:g} um high on each beam's free end "
             f"(SU-8 or plated{assumed})", f"{len(plan.beams)} posts of {plan.post_um:g} um"),
        Step("front DRIE", "", f"Bosch etch through the {s.device_um:g} um device layer in the "
             "hard mask's openings, breaking through into the cavities (aspect ratio at most "
             f"{DRIE_ASPECT_RATIO:g}:1)",
             f"{len(plan.beams)} free cantilevers over their cavities; the cavities' edges "
             "are the roots"),
        Step("dicing", "die", f"dies of {plan.die_length_um:g} x {plan.die_width_um:g} um "
             "(lanes outside the outline)", "the dies"),
    ]


def traveller_markdown(plan: DiePlan, sheet_resistance_ohm_per_sq: float, gds_name: str) -> str:
    """The traveller as Markdown: the masks, then the steps as a table."""
    lines = [f"# Process traveller: {plan.name}", "",
             f"Masks in `{gds_name}` (GDSII, um; layer/datatype):", ""]
    lines += [f"- {m.name} ({m.gds_layer}/{m.datatype}): {m.text}"
              for m in MASK_BY_NAME.values()]
    lines += ["", "| # | step | mask | what is done | leaves |", "| --- | --- | --- | --- | --- |"]
    for i, step in enumerate(traveller_steps(plan, sheet_resistance_ohm_per_sq), start=1):
        mask = (f"{step.mask} ({MASK_BY_NAME[step.mask].gds_layer})" if step.mask else "-")
        lines.append(f"| {i} | {step.name} | {mask} | {step.action} | {step.leaves} |")
    lines += ["", "Parameters marked '(assumption)' are stated, not derived: a fab's own recipe "
              "replaces them. The implant's sheet resistance assumes the boron uniform over the "
              "junction depth."]
    return "\n".join(lines) + "\n"


def write_traveller(plan: DiePlan, sheet_resistance_ohm_per_sq: float, gds_name: str,
                    path: Path) -> Path:
    """:func:`traveller_markdown` to ``path`` (UTF-8), written whole."""
    from tactcad.atomic import write_atomic

    text = traveller_markdown(plan, sheet_resistance_ohm_per_sq, gds_name)
    return write_atomic(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))
