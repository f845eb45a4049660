"""The first natural frequency of a design's elements against
``requirements.min_first_resonance_Hz``.

An array pressed and scanned over tissue rings where an element's first
resonance lies near the scan or sampling rate, and the ringing aliases; a
design states the lowest first frequency it accepts. Each distinct element
is taken at the modal level serving the verification's stiffness level
(:func:`tactcad.mechanics.modal_ladder.modal_level_for`); the record names
the element with the lowest first frequency.

Each element carries its gauge installation (gauge, adhesive, lead, terminals:
:func:`tactcad.mechanics.gauge_mass.gauge_installation_masses`) as added mass.
fem2d sees only the in-plane modes; the closed form adds an estimate of the
first out-of-plane one, verified for sheets of three webs and more. Where the sheet is
thinner than :data:`tactcad.mechanics.modal_closed_form.OUT_OF_PLANE_SHEET_OVER_WEB`
webs, the web bends (or
twists) out of the plane nearly as easily as in it, and fem3d found an
out-of-plane mode first at the domain's thin-sheet corner (0.5 mm sheet,
1 mm web: 2321 Hz against 6276 Hz in the plane; with a 0.05 mm web, ten webs
thick, the out-of-plane mode was 4.5 times the in-plane one). Such elements
are verified at fem3d whatever the level, so a verdict never rests on a
family the level cannot see.

Units: Hz, s.
"""

from __future__ import annotations

from typing import Any, Callable, Mapping

from tactcad.design.array_plan import Plan
from tactcad.design.requirements_section import stated_requirements
from tactcad.mechanics.verdicts import deciding_item, judged

REQUIREMENT = "min_first_resonance_Hz"

from tactcad.mechanics.modal_closed_form import out_of_plane_may_lead


def first_frequencies(plan: Plan, modal_model: str,
                      progress: Callable[[str], None] | None = None,
                      escalate: bool = True) -> list[dict[str, Any]]:
    """Per distinct element: its part, element numbers, first frequency (Hz),
    its family, the level's error estimate and the level used, lowest first.

    Args:
        escalate: take an element whose out-of-plane modes may come first
            (:func:`out_of_plane_may_lead`) at fem3d when ``modal_model`` does
            not see them; else keep the level and flag the row
            (``out_of_plane_unchecked``).

    Raises:
        DesignError: the material has no density.
    """
    from tactcad.mechanics.gauge_mass import gauge_installation_masses
    from tactcad.mechanics.modal_ladder import MODAL_LEVELS, estimate_modes

    numbers: dict[str, list[int]] = {}
    for s in plan.slots:
        numbers.setdefault(s.geometry.part_name, []).append(s.number)
    rows = []
    for part, g in plan.distinct_elements.items():
        level = modal_model
        blind = ("out-of-plane" not in MODAL_LEVELS[level].families
                 and out_of_plane_may_lead(g))
        if blind and escalate:
            level = "fem3d"
        opts = {"progress": progress} if progress and MODAL_LEVELS[level].meshed else {}
        r = estimate_modes(level, g, plan.material, element=numbers[part][0], modes=1,
                           added_masses=gauge_installation_masses(plan, g), **opts)
        rows.append({"part": part, "elements": numbers[part], "first_Hz": r.first_Hz,
                     "family": r.modes[0].family, "error_estimate_rel": r.error_estimate_rel,
                     "model": level, "out_of_plane_unchecked": blind and not escalate})
    return sorted(rows, key=lambda row: row["first_Hz"])


def resonance_records(plan: Plan, model: str,
                      progress: Callable[[str], None] | None = None) -> list[dict]:
    """The verification record of ``min_first_resonance_Hz`` at stiffness level
    ``model`` (``[]`` when the design does not state it): each element judged
    on its own margin (its first frequency / target - 1) and error, the record
    showing the one with the worst verdict (among equals the lowest first
    frequency, Hz; :func:`tactcad.mechanics.verdicts.deciding_item`),
    ``model`` the stiffness level verified (so ``verify --model auto`` climbs
    on an undecided record), ``modal_model`` the modal level that served it
    (``binding_model`` the one that gave the lowest element: fem3d for an element
    whose out-of-plane modes may come first),
    ``binding_element`` that element."""
    from tactcad.mechanics.modal_ladder import MODAL_LEVELS, modal_level_for

    target = stated_requirements(plan.raw).get(REQUIREMENT)
    if target is None:
        return []
    level = modal_level_for(model)
    rows = [judged({**row, "margin_rel": row["first_Hz"] / float(target) - 1.0})
            for row in first_frequencies(plan, level, progress)]
    low = deciding_item(rows)  # each element on its own error: the worst verdict decides
    return [{"requirement": REQUIREMENT, "target": float(target), "predicted": low["first_Hz"],
             "error_estimate_rel": low["error_estimate_rel"], "margin_rel": low["margin_rel"],
             "model": model, "modal_model": level,
             "pass": all(row["margin_rel"] >= 0 for row in rows),
             "binding_element": low["elements"][0],
             "binding_part": low["part"], "binding_model": low["model"],
             "families": list(MODAL_LEVELS[low["model"]].families),
             "elements": rows}]


def resonance_summary(plan: Plan) -> Mapping[str, Any]:
    """The manifest's report of the first frequencies (closed form, in-plane;
    an element whose out-of-plane modes may come first is flagged, not run at
    fem3d), whether or not the design states a requirement; without a density
    the reason instead."""
    from tactcad.errors import DesignError

    try:
        rows = first_frequencies(plan, "closed-form", escalate=False)
    except DesignError as e:
        return {"model": "closed-form", "unavailable": str(e)}
    target = stated_requirements(plan.raw).get(REQUIREMENT)
    return {"model": "closed-form", "families": ["in-plane"], "elements": rows,
            "lowest_first_Hz": rows[0]["first_Hz"],
            "required_min_Hz": None if target is None else float(target)}
