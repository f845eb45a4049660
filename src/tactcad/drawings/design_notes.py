"""Drawing notes that depend on the design's requirements and on whether the
design cites the paper (``requirements.source``): the full-scale force with
its binding limit, the first natural frequency where the design states a
minimum, the web-tolerance note, where the strain gauge goes and the element
numbering.

A design that does not cite the paper gets no paper text, load or sample.
Units: mm, N, N/mm.
"""

from __future__ import annotations

from functools import lru_cache

from tactcad.design.array_plan import ElementGeometry, Plan
from tactcad.design.readout_section import readout_of
from tactcad.errors import DesignError
from tactcad.design.requirements_section import cites_paper
from tactcad.drawings.drawing import web_text
from tactcad.drawings.sheet import fmt_mm


@lru_cache(maxsize=8)
def _force_figures(plan: Plan) -> tuple[float, dict]:
    """(rated full-scale force N, {part name: (element force limit N, limit words, its
    relative error)}), closed form. Cached per plan (its design hash covers the
    requirements)."""
    from tactcad.mechanics.limits import LIMIT_WORDS, plan_limits
    from tactcad.studies.verification import requirements_of

    req = requirements_of(plan)
    per_part: dict[str, tuple[float, str, float]] = {}
    for lim in plan_limits(plan, "closed-form"):
        if lim.part_name not in per_part or lim.force_N < per_part[lim.part_name][0]:
            per_part[lim.part_name] = (lim.force_N, LIMIT_WORDS[lim.limit],
                                       lim.error_estimate_rel)
    return req.full_scale_force_N, per_part


def rating_verdict_words(limit_N: float, rated_N: float, error_rel: float) -> str:
    """The rating judged against one element's force limit by verify's rule
    (:func:`tactcad.mechanics.verdicts.verdict`): ``met``, ``NOT met``, or, where the
    margin lies inside the closed form's error, ``undecided`` with the margin, the error
    and the command that decides it.

    Args:
        limit_N: the element force limit (N). rated_N: the rated full-scale force (N).
        error_rel: the limit's relative error estimate at the closed form.

    Returns:
        The words the note prints after "the design's, ".
    """
    from tactcad.mechanics.verdicts import verdict

    margin = limit_N / rated_N - 1.0
    said = verdict(margin, error_rel, 0.0, limit_N >= rated_N)
    if said == "undecided":
        return (f"undecided at the closed form: margin {margin:+.1%} inside its "
                f"{error_rel:.1%} error; tactcad verify decides")
    return "met" if said == "pass" else "NOT met"


def full_scale_note(plan: Plan, part_name: str, yield_MPa: float, grade: str) -> str:
    """The element's full-scale force note: the design's rated full-scale
    force, judged against this element's force limit (the largest force it carries) as
    verify judges it (:func:`rating_verdict_words`), and the limit that binds it."""
    rated, per_part = _force_figures(plan)
    limit, words, error = per_part[part_name]
    verdict = rating_verdict_words(limit, rated, error)
    return (f"Rated full-scale force {rated:.3g} N (the design's, {verdict}): element force "
            f"limit {limit:.3g} N, bound by {words} (closed form; yield "
            f"{yield_MPa:g} MPa, {grade}). Do not load the tip beyond {rated:.3g} N.")


def row_full_scale_note(plan: Plan, row: int, yield_MPa: float, grade: str) -> str:
    """A sheet of a whole row's elements (a comb's row): the stacked element's full-scale
    force note (:func:`full_scale_note`) for the row, the rating judged as verify judges it
    (:func:`rating_verdict_words`) against the lowest element force limit of the row's
    elements, with the element that has it and the limit that binds it.

    Args:
        plan: the design. row: the row (0-based). yield_MPa: the material's yield
            strength (MPa). grade: the material's name on the drawing.

    Returns:
        The note (N).

    Raises:
        DesignError: no element of ``plan`` is in ``row`` (naming the rows there are).
    """
    rated, per_part = _force_figures(plan)
    slots = [s for s in plan.slots if s.row == row]
    if not slots:
        raise DesignError("row", row + 1, f"1 ... {plan.rows}", "a row of the design")
    limit, words, error, number = min(((*per_part[s.geometry.part_name], s.number)
                                       for s in slots), key=lambda t: (t[0], t[3]))
    verdict = rating_verdict_words(limit, rated, error)
    return (f"Rated full-scale force {rated:.3g} N on every tip (the design's, {verdict}): "
            f"element force limit {limit:.3g} N, the row's lowest (element {number}), bound "
            f"by {words} (closed form; yield {yield_MPa:g} MPa, {grade}). Do not load a tip "
            f"beyond {rated:.3g} N.")


@lru_cache(maxsize=8)
def _first_frequencies(plan: Plan) -> dict[str, float]:
    """{part name: first in-plane natural frequency (Hz)}, closed form, cached per plan."""
    from tactcad.studies.resonance import first_frequencies

    return {row["part"]: row["first_Hz"]
            for row in first_frequencies(plan, "closed-form", escalate=False)}


def resonance_note(plan: Plan, part_name: str) -> str | None:
    """The element's first natural frequency against ``requirements.min_first_resonance_Hz``
    (None when the design states no minimum: the note binds only then)."""
    from tactcad.design.requirements_section import stated_requirements

    target = stated_requirements(plan.raw).get("min_first_resonance_Hz")
    if target is None:
        return None
    f = _first_frequencies(plan)[part_name]
    verdict = "met" if f >= float(target) else "NOT met"
    return (f"First natural frequency in the sheet's plane {f:.4g} Hz as clamped (closed "
            f"form; the design requires at least {float(target):g} Hz, {verdict}; tactcad "
            f"modal --model fem3d adds the out-of-plane modes): scan and sample well below it.")


def web_tolerance_note(plan: Plan, g: ElementGeometry, web: str, up: float, dn: float,
                       spread: tuple[float, float, float, float] | None) -> str:
    """The web-tolerance note; the paper's as-built spread (``spread``: arm,
    K low, K high, ratio) only for a design that cites the paper."""
    text = (f"Web thickness {web} is the critical dimension: its tolerance alone moves "
            f"stiffness by +{up * 100:.0f} % / -{dn * 100:.0f} % (closed form, as verify's K band). ")
    if spread is not None and cites_paper(plan.raw):
        a, k0, k1, ratio = spread
        text += (f"The paper's as-built elements (Table 1) of equal {a:g} mm arm measured "
                 f"{k0:.2f} and {k1:.2f} N/mm (x{ratio:.2f}). ")
    return text + "Measure the web of every part and record it."


def element_web_note(plan: Plan, g: ElementGeometry) -> str:
    """The web-tolerance note of element ``g``: its K's change over its web tolerance at the
    corrected closed form (:func:`tactcad.in_use.kobj_budget.web_tolerance_k_change`, the
    figures ``verify``'s K band reads) and the paper's Table 1 spread
    (:mod:`tactcad.paper.data`)."""
    from tactcad.in_use.kobj_budget import web_tolerance_k_change

    up, dn = web_tolerance_k_change(g, plan.material)
    spread = None
    if cites_paper(plan.raw):  # the paper's data only for the paper's design
        from tactcad.paper.data import largest_equal_arm_spread

        spread = largest_equal_arm_spread()
    return web_tolerance_note(plan, g, web_text(g), up, dn, spread)


def gauge_note(plan: Plan, g: ElementGeometry) -> str:
    """Where the strain gauge goes: its grid (``[readout]``) centred over the web."""
    ro = readout_of(plan.raw, plan.strength.gauge)
    return (f"A strain gauge (grid {fmt_mm(ro.grid_length_mm)} x {fmt_mm(ro.grid_width_mm)}, "
            f"{ro.gauge_resistance_ohm:g} ohm) is bonded on the flat top face, its grid centred "
            f"over the web {fmt_mm(g.hinge_x_mm)} from the back face and across the sheet."
            + thermal_note(plan))


def thermal_note(plan: Plan) -> str:
    """The gauge's STC the thermal drift assumes (it binds the gauge one orders) and, when
    ``requirements.max_thermal_drift_N_per_K`` is stated, the worst drift against it."""
    from tactcad.design.requirements_section import stated_thermal_drift
    from tactcad.mechanics.thermal_drift import thermal_report, thermal_setting
    from tactcad.studies.verification import requirements_of

    try:
        s = thermal_setting(plan)
    except DesignError:  # no CTE known: no thermal figure to state
        return ""
    text = (f" Gauge STC {s.stc_ppm_per_K:.3g} ppm/K on an element of "
            f"{s.substrate_cte_ppm_per_K:g} ppm/K"
            + (", half bridge with a dummy gauge." if s.dummy else "."))
    target = stated_thermal_drift(plan.raw)
    if target is not None:
        worst = thermal_report(plan, requirements_of(plan)).worst["drift_N_per_K"]
        text += f" Thermal drift {worst:.2g} N/K (required <= {target:g} N/K)."
    return text


def numbering_note(plan: Plan) -> str:
    """How the elements are numbered, for the assembly sheet."""
    if cites_paper(plan.raw):
        return "the element numbers follow the paper's Table 1."
    return f"elements are numbered 1 ... {len(plan.slots)} along row 1, then along row 2."
