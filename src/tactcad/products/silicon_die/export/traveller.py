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
                                                                 DRIE_ASPECT_RATIO, MASK_BY_NAME,
                                                                 PAD_OPEN_INSET_UM)

#: Parameters stated as assumptions (a fab's recipe replaces them).
SCREEN_OXIDE_NM = 100.0
METAL_NM = 500.0
HARD_MASK_NM = 1000.0
ANNEAL_C, ANNEAL_MIN = 1000.0, 30.0
SINTER_C = 400.0
#: The alignment marks' depth in the handle (um).
MARK_DEPTH_UM = 2.0
#: The device wafer's bond oxide (nm): the share of the buried oxide that spans the cavities
#: under the beams, the front DRIE's etch stop until the release removes it.
ETCH_STOP_OXIDE_NM = 300.0
#: Thermal oxidations (C, wet or dry) and the bond anneal (C, h).
HANDLE_OXIDATION_C, DEVICE_OXIDATION_C, SCREEN_OXIDATION_C = 1050.0, 1000.0, 950.0
BOND_ANNEAL_C, BOND_ANNEAL_H = 1100.0, 2.0
#: The implant: species and energy (keV) through the screen oxide, tilted 7 degrees.
IMPLANT_SPECIES, IMPLANT_KEV = "boron (11B+)", 50.0

#: What a step does, as the traveller check reads it: ``litho`` (a resist patterned through
#: its mask), ``etch`` (must name what it stops on), ``deposit``, ``implant``, ``metal``
#: (the aluminium), ``anneal``, ``bond``, ``dice``, ``release`` (frees the beams), ``tall``
#: (leaves features standing tens of um proud: no resist is spun over them after),
#: ``covers_pads`` (a film over the bond pads), ``opens_pads``.
KINDS = ("litho", "etch", "deposit", "implant", "metal", "anneal", "bond", "dice", "release",
         "tall", "covers_pads", "opens_pads", "wafer")


@dataclass(frozen=True)
class Step:
    """One step: its name, the mask it uses (or ""), what is done, what it leaves, what it
    is (:data:`KINDS`) and, for an etch, what stops it."""

    name: str
    mask: str
    action: str
    leaves: str
    kinds: tuple[str, ...] = ()
    stop: str = ""


def traveller_steps(plan: DiePlan, sheet_resistance_ohm_per_sq: float) -> list[Step]:
    """The die's steps in process order (um, nm, C, h, keV, cm^-2): every mask aligned to
    the handle's marks, the front DRIE stopped on the device wafer's bond oxide over the
    cavities, the pads opened before the posts, the wafer diced with the beams still held
    and the beams released die by die."""
    s = plan.stack
    a = " (assumption)"
    depth_r, depth_m = plan.cavity_depths_um
    tol = 100 * CAVITY_DEPTH_TOLERANCE_REL
    aligned = f"aligned to the handle's marks to +-{CAVITY_ALIGNMENT_UM:g} um"
    handle_oxide_um = s.box_um - ETCH_STOP_OXIDE_NM / 1e3
    n_beams = len(plan.beams)
    return [
        Step("handle", "", f"handle wafer: (100) silicon, {s.handle_um:g} um, double-side "
             "polished (or a cavity SOI wafer ordered from a wafer maker with the marks and "
             "the two cavity masks: steps 1-8 are then its)", "the handle", ("wafer",)),
        Step("alignment marks", "align", f"resist; RIE {MARK_DEPTH_UM:g} um into the handle"
             f"{a}; resist stripped", "two crosses in each die's ends, the reference of every "
             "later mask", ("litho", "etch"), f"timed, {MARK_DEPTH_UM:g} um"),
        Step("cavity etch, measuring row", "cavity_measuring",
             f"resist, {aligned}; timed DRIE {depth_m:g} um +-{tol:g} %{a}; resist stripped",
             "the measuring row's cavity: its floor the beams' hard stop", ("litho", "etch"),
             f"timed, {depth_m:g} um +-{tol:g} %"),
        Step("cavity etch, reference row", "cavity_reference",
             f"resist sprayed over the first cavity, {aligned}; timed DRIE {depth_r:g} um "
             f"+-{tol:g} %{a}; resist stripped",
             "the reference row's cavity: its floor the beams' hard stop", ("litho", "etch"),
             f"timed, {depth_r:g} um +-{tol:g} %"),
        Step("handle oxidation", "", f"wet thermal oxidation, {HANDLE_OXIDATION_C:g} C{a}, "
             f"{1e3 * handle_oxide_um:.0f} nm", "oxide on the bond face, lining the cavities "
             "(floor and walls move together: their depth is kept)", ("deposit",)),
        Step("device wafer oxidation", "", f"n-type (100) device wafer, wet thermal "
             f"oxidation {DEVICE_OXIDATION_C:g} C{a}, {ETCH_STOP_OXIDE_NM:g} nm on its bond "
             "face", f"the buried oxide's other {ETCH_STOP_OXIDE_NM:g} nm: over the cavities "
             "it spans under the device layer, the front DRIE's etch stop", ("deposit",)),
        Step("bond and thin", "", f"fusion-bonded in vacuum, flat along <110>, annealed "
             f"{BOND_ANNEAL_C:g} C {BOND_ANNEAL_H:g} h in N2{a}, ground and polished to "
             f"{s.device_um:g} +-{s.device_tolerance_um:g} um",
             f"{s.total_um:g} um stack (the die without its posts) over sealed cavities, "
             f"buried oxide {s.box_um:g} um "
             "(the device layer bows into the cavities under the atmosphere until the release)",
             ("bond",)),
        Step("mark windows", "mark_window", f"resist, aligned in infrared through the stack "
             f"to +-{CAVITY_ALIGNMENT_UM:g} um; DRIE through the device layer; resist "
             "stripped", "the handle's marks seen through the buried oxide by every front "
             "mask", ("litho", "etch"), "the buried oxide"),
        Step("screen oxidation", "", f"dry thermal oxidation {SCREEN_OXIDATION_C:g} C{a}, "
             f"{SCREEN_OXIDE_NM:g} nm", "oxide on the device layer", ("deposit",)),
        Step("implant", "piezo", f"resist, {aligned}; {IMPLANT_SPECIES}, {IMPLANT_KEV:g} keV"
             f"{a}, 7 degrees tilt, dose {plan.implant_dose_per_cm2:.2g} cm^-2 through the "
             "screen oxide; resist stripped", "p-type resistors at each beam's root",
             ("litho", "implant")),
        Step("anneal", "", f"{ANNEAL_C:g} C, {ANNEAL_MIN:g} min, N2{a}",
             f"junction {md.JUNCTION_DEPTH_UM:g} um deep, {plan.acceptors_per_cm3:.2g} cm^-3, "
             f"sheet resistance {sheet_resistance_ohm_per_sq:.3g} ohm/sq (Masetti mobility)",
             ("anneal",)),
        Step("contact", "contact", f"resist, {aligned}; oxide opened over each resistor's "
             "ends (buffered HF); resist stripped",
             f"{4 * n_beams} contacts of {md.CONTACT_UM:g} um (each beam's resistor "
             "and its reference)", ("litho", "etch"), "the silicon (HF stops on it)"),
        Step("metal", "metal", f"aluminium {METAL_NM:g} nm sputtered; resist, {aligned}; "
             f"wet-etched{a}; resist stripped; sintered {SINTER_C:g} C in forming gas{a}",
             f"leads and {3 * n_beams} bond pads of {md.PAD_UM:g} um (a half bridge "
             "per beam)", ("litho", "metal", "etch"), "the oxide (the etchant stops on it)"),
        Step("hard mask", "device_etch", f"PECVD oxide {HARD_MASK_NM:g} nm{a} over the "
             f"front; resist, {aligned}; the beams' outline etched into it (RIE); resist "
             "stripped", "the beams' outline in a hard mask over the device layer, the pads "
             "covered", ("deposit", "litho", "etch", "covers_pads"), "the device layer's "
             "silicon (the oxide RIE is selective to it)"),
        Step("pad opening", "pad_open", f"resist, {aligned}; the hard mask's oxide etched off "
             f"the bond pads (RIE), {PAD_OPEN_INSET_UM:g} um inside each pad's edge; resist "
             "stripped", f"{3 * n_beams} bare aluminium pads for the wire bonds",
             ("litho", "etch", "opens_pads"), "the aluminium"),
        Step("posts", "tip", f"posts {plan.post_height_um:g} um high on each beam's free end, "
             f"{aligned} (SU-8 or plated{a}): the last lithography",
             f"{n_beams} posts of {plan.post_um:g} um", ("litho", "tall")),
        Step("front DRIE", "", f"Bosch etch through the {s.device_um:g} um device layer in "
             f"the hard mask's openings (aspect ratio at most {DRIE_ASPECT_RATIO:g}:1; the "
             "aluminium pads stand it)", "the beams cut, still held by the oxide spanning "
             "their slots and cavities", ("etch",),
             f"the device wafer's {ETCH_STOP_OXIDE_NM:g} nm bond oxide over the cavities, "
             "the buried oxide elsewhere"),
        Step("dicing", "die", f"front under a sprayed resist coat{a}, on dicing tape; sawn into "
             f"dies of {plan.die_length_um:g} x {plan.die_width_um:g} um (lanes outside the "
             "outline); resist stripped in solvent", "the dies, their beams still held by the "
             "oxide: the saw's water and the tape's pull reach no free beam", ("dice",)),
        Step("release", "", "die by die, anhydrous HF vapour at 40 C (an aluminium-"
             f"compatible recipe{a}): the {ETCH_STOP_OXIDE_NM:g} nm oxide under the slots and "
             f"beams removed, the hard mask thinned to about {HARD_MASK_NM - 1.5 * ETCH_STOP_OXIDE_NM:g}"
             " nm over the resistors and leads; no liquid, so no stiction",
             f"{n_beams} free cantilevers over their cavities, each gap the cavity's depth + "
             f"{ETCH_STOP_OXIDE_NM / 1e3:g} um; the cavities' edges are the roots (the buried "
             "oxide undercut about 0.5 um at the slots)",
             ("etch", "release"), "timed, the oxide's thickness + 50 %"),
    ]


def traveller_markdown(plan: DiePlan, sheet_resistance_ohm_per_sq: float, gds_name: str) -> str:
    """The traveller as Markdown: the masks, then the steps as a table."""
    lines = [f"# Process traveller: {plan.name}", "",
             f"Masks in `{gds_name}` (GDSII, um; layer/datatype):", ""]
    lines += [f"- {m.name} ({m.gds_layer}/{m.datatype}): {m.text}"
              for m in MASK_BY_NAME.values()]
    lines += ["", "| # | step | mask | kind | what is done | stops on | leaves |",
              "| --- | --- | --- | --- | --- | --- | --- |"]
    for i, step in enumerate(traveller_steps(plan, sheet_resistance_ohm_per_sq), start=1):
        mask = (f"{step.mask} ({MASK_BY_NAME[step.mask].gds_layer})" if step.mask else "-")
        lines.append(f"| {i} | {step.name} | {mask} | {', '.join(step.kinds) or '-'} | "
                     f"{step.action} | {step.stop or '-'} | {step.leaves} |")
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
