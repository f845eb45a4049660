"""A silicon die's verification matrix: one record per requirement in the array's keys
(:func:`tactcad.studies.verification.verification_matrix`), at the closed form, for
``tactcad verify`` on a die's file and the die's requirements check group.

Units: N, um, MPa.
"""

from __future__ import annotations

import math


def die_verification(plan, mount=None) -> list[dict]:
    """The die's verification matrix, one record per requirement in the array's keys
    (:func:`tactcad.studies.verification.verification_matrix`), at the closed form:

    * ``full_scale_force_N``: the rated force against the largest rating the die's limits
      allow (:func:`tactcad.products.silicon_die.design.mems_die.rating_limits`: each root at its own beam's
      rated force at the mean strength of Bosch-etched silicon, a stop engaging before its
      root breaks, the cavities' depth, the posts' height): failed at or past it, else
      undecided (a mean strength without its Weibull modulus gives no failure
      probability: only for a plan made without any pair); with its Weibull pair (the
      lab's, or the design default every designed die carries), the die's failure
      probability;
    * ``kr_over_km``: the rows' K_r / K_m against the target, within the 'about' band, each
      K the closed form's on its frame within :data:`tactcad.products.silicon_die.design.mems_die.
      CLOSED_FORM_K_ERROR_REL` of the fem3d level (so the ratio within twice that);
    * ``hard_stop``: each row's cavity floor against its beam: the post's travel when the
      beam's end meets the floor, in the shallowest cavity the depth tolerance allows, past
      the beam's rated travel (it reads its whole range), and in the deepest below the
      travel at which its root reaches the mean strength (an overload rests on the floor
      before the beam breaks, and before the post sinks to the face (the posts stand proud);
      margin: the worse row's fracture travel or post height over its deepest engagement,
      less one.
    """
    from tactcad.products.silicon_die.design.mems_die import (CLOSED_FORM_K_ERROR_REL,
                                                              fracture_travel_um)
    from tactcad.mechanics.verdicts import verdict
    from tactcad.studies.verification import KR_OVER_KM_BAND_REL

    rows = plan.beams[:: plan.columns]
    stiffness = {"reference": plan.k_r_N_per_mm, "measuring": plan.k_m_N_per_mm}
    target_ratio = plan.targets[0] / plan.targets[1]
    ratio = plan.k_r_N_per_mm / plan.k_m_N_per_mm
    ratio_error = 2 * CLOSED_FORM_K_ERROR_REL  # each K's error, the worst way round
    fracture = {b.role: fracture_travel_um(stiffness[b.role], b.length_um, b.width_um,
                                           b.thickness_um, plan.root_stress_concentration(b))
                for b in rows}
    stop = _stop_row(plan, rows, fracture)
    return [
        _rated_row(plan) if plan.weibull is None else _weibull_rated_row(plan),
        {"requirement": "kr_over_km", "target": target_ratio, "predicted": ratio,
         "error_estimate_rel": ratio_error, "margin_rel": ratio / target_ratio - 1.0,
         "allowed_margin_rel": -KR_OVER_KM_BAND_REL, "model": "closed-form",
         "verdict": verdict(ratio / target_ratio - 1.0, ratio_error, -KR_OVER_KM_BAND_REL,
                            ratio / target_ratio - 1.0 >= -KR_OVER_KM_BAND_REL),
         "binding_words": "each column's reference and measuring beam, each on its frame "
                          "(the closed form's K within +-"
                          f"{100 * CLOSED_FORM_K_ERROR_REL:g} % of fem3d's)"},
        stop,
        _resolution_row(plan),
        *([_grasp_row(plan, mount)]
          if plan.max_grasp_force_N is not None and mount is not None else []),
        *(_accuracy_rows(plan) if plan.kobj_accuracy_rel is not None else []),
    ]


def _accuracy_rows(plan) -> list[dict]:
    """The accuracy row and the post-height row, on one budget."""
    from tactcad.products.silicon_die.in_use.die_budget import die_budget

    budget = die_budget(plan)
    return [accuracy_row(plan, float(max(budget.total_rel))), post_height_row(budget)]


def post_height_row(budget) -> dict:
    """``tip_height_tolerance_mm`` of a die: the posts' height tolerance the drawing holds
    against the one the K_obj budget's accuracy needs
    (:func:`tactcad.products.silicon_die.in_use.die_budget.post_height_drawing`). It passes
    when the process's tolerance holds the allowance (margin allowance / drawn - 1), or when
    the drawing names the zeroing on an optical flat and the mismatch it leaves fits the
    twice-the-allowance mismatch the accuracy permits (margin 2 allowance / residual - 1);
    it fails where the other terms leave no room.

    Args:
        budget: the die's :class:`~tactcad.products.silicon_die.in_use.die_budget.DieBudget`,
            its ``kobj_accuracy_rel`` stated.

    Returns:
        The verification record.
    """
    from tactcad.products.silicon_die.in_use.die_budget import post_height_drawing
    from tactcad.studies.verification import TIP_HEIGHT_REQUIREMENT

    tip = post_height_drawing(budget)
    base = {"requirement": TIP_HEIGHT_REQUIREMENT, "error_estimate_rel": None,
            "model": "closed-form", "tip_height": tip.as_json(),
            "basis": "post height: tolerance drawn vs tolerance needed (the die's K_obj "
                     "budget, +/- mm); with the zeroing, half the mismatch it leaves"}
    needed = tip.allowance_mm
    if needed is None:
        return {**base, "target": None, "predicted": tip.drawn_mm, "margin_rel": None,
                "verdict": "fail",
                "binding_words": "no post tolerance fits: the other terms fill the accuracy"}
    if tip.holds_allowance:
        return {**base, "target": needed, "predicted": tip.drawn_mm,
                "margin_rel": needed / tip.drawn_mm - 1.0, "verdict": "pass",
                "binding_words": f"the posts' +/-{1e3 * tip.drawn_mm:.3g} um holds it"}
    return {**base, "target": needed, "predicted": tip.residual_mm / 2,
            "margin_rel": 2 * needed / tip.residual_mm - 1.0,
            "verdict": "pass" if tip.residual_fits else "fail",
            "binding_words": f"zeroed on an optical flat: {1e3 * tip.residual_mm:.2g} um "
                             f"mismatch left; the posts' process holds +/-"
                             f"{1e3 * tip.drawn_mm:.3g} um, +/-{1e3 * needed:.3g} um needed"}


def _grasp_row(plan, mount) -> dict:
    """``max_grasp_force_N``: the die's jaw closed to that force on the default tissue
    (:func:`tactcad.products.silicon_die.in_use.die_grasp.grasp_at_force`); each beam's force
    on its spring against its breaking force (its root's peak at the mean strength of etched
    silicon), a hard stop taking the rest; fails when a beam passes it or the jaw cannot
    reach the force. ``predicted`` is a grasp force, as the target is
    (:func:`grasp_force_columns`; the deciding beam's force and breaking force are
    ``element_force_N`` and ``overload_limit_N``). Undecided, not passed, where a post rests
    on its stop (the posts' and the cavity floor's strength under it is not judged) or the
    die's face meets the tissue (past the punch model)."""
    from tactcad.errors import DesignError
    from tactcad.products.silicon_die.in_use.die_grasp import grasp_at_force
    from tactcad.studies.verification import grasp_force_columns

    target = plan.max_grasp_force_N
    base = {"requirement": "max_grasp_force_N", "target": target, "error_estimate_rel": None,
            "model": "closed-form"}
    try:
        result = grasp_at_force(plan, mount, target)
    except DesignError as exc:
        return {**base, "predicted": None, "margin_rel": None, "verdict": "fail",
                "binding_words": f"the grasp is out of the jaw's reach: {exc.allowed}"}
    loaded = [t for t in result.tips if t["element_force_N"] > 0 and t["overload_limit_N"]]
    worst = max(loaded, key=lambda t: t["element_force_N"] / t["overload_limit_N"],
                default=None)
    if worst is None:
        return {**base, "predicted": 0.0, "margin_rel": None, "verdict": "pass",
                "binding_words": "no post meets the tissue at that force"}
    over = [t["site"] for t in result.tips if t["over_overload_limit"]]
    stopped = [t["site"] for t in result.tips if t["on_stop"]]
    face = [t["site"] for t in result.tips if t.get("face_in_contact")]
    stop_N = max(t["stop_force_N"] for t in result.tips)
    margin = worst["overload_limit_N"] / worst["element_force_N"] - 1.0
    # a stop's load and the face in the tissue lie outside what the row judges: a grasp
    # the beams survive is then undecided, not passed
    unjudged = bool(over == [] and (stopped or face))
    return {**base, **grasp_force_columns(target, margin, worst["on_stop"]),
            "element_force_N": worst["element_force_N"],
            "overload_limit_N": worst["overload_limit_N"],
            "verdict": "fail" if over else "undecided" if unjudged else "pass",
            "binding_words": f"beam {worst['site']}: {1e3 * worst['element_force_N']:.3g} mN "
                             f"on its spring at the {target:g} N grasp (jaw at "
                             f"{result.angle_deg:.3g} degrees), breaking force "
                             f"{1e3 * worst['overload_limit_N']:.3g} mN; on their stops: "
                             f"{', '.join(map(str, stopped)) or 'none'} (the most a stop "
                             f"takes {stop_N:.3g} N: the posts' and the cavity floor's "
                             "strength under it is not judged)"
                             + (f"; the die's face in the tissue beside posts "
                                f"{', '.join(map(str, face))} (past the punch model)"
                                if face else "")
                             + (f"; past breaking: {', '.join(map(str, over))}" if over else "")
                             + ("" if worst["on_stop"] else
                                f"; predicted: the grasp at which beam {worst['site']} "
                                f"reaches its breaking force, its force in proportion to "
                                f"the grasp")}


def worst_budget_rel(plan) -> float:
    """The die's K_obj budget's worst root sum square over its range.

    Args:
        plan: the die (:class:`~tactcad.products.silicon_die.design.mems_die.DiePlan`).

    Returns:
        The worst relative error, 1 sigma
        (:func:`tactcad.products.silicon_die.in_use.die_budget.die_budget`: each term before
        any calibration, so an upper bound; inf where a K_obj is unreadable).
    """
    from tactcad.products.silicon_die.in_use.die_budget import die_budget

    return float(max(die_budget(plan).total_rel))


def accuracy_row(plan, worst: float | None = None) -> dict:
    """``kobj_accuracy_rel``: the die's K_obj budget's worst root sum square over the range
    against the stated accuracy; fails where it is larger.

    Args:
        plan: the die, its ``kobj_accuracy_rel`` stated (relative).
        worst: :func:`worst_budget_rel` of the plan when already computed.

    Returns:
        The verification record (requirement, target, predicted, margin_rel, verdict, ...).
    """
    worst = worst_budget_rel(plan) if worst is None else worst
    target = plan.kobj_accuracy_rel
    readable = math.isfinite(worst) and worst > 0
    return {"requirement": "kobj_accuracy_rel", "target": target, "predicted": worst,
            "error_estimate_rel": None,
            "margin_rel": target / worst - 1.0 if readable else None,
            "model": "closed-form", "verdict": "pass" if worst <= target else "fail",
            "binding_words": "the root sum square of the die's K_obj budget (tactcad budget: "
                             "read-out noise, device layer, cavity alignment, temperature, "
                             "resistor zero drift, the coupled inversion's residue and the "
                             "posts' mismatch after zeroing on a flat), worst "
                             "over the K_obj range, each term before calibration (an upper "
                             "bound)"}


def _resolution_row(plan) -> dict:
    """``kobj_resolution_rel``: the largest K_obj error the bridges' noise leaves over the
    range at the rated force against the die's requirement."""
    from tactcad.products.silicon_die.studies.die_doping import worst_readout_error_rel

    worst = worst_readout_error_rel(plan)
    return {"requirement": "kobj_resolution_rel", "target": plan.kobj_resolution_rel,
            "predicted": worst, "error_estimate_rel": None,
            "margin_rel": plan.kobj_resolution_rel / worst - 1.0
            if math.isfinite(worst) and worst > 0 else None,
            "model": "closed-form",
            "verdict": "pass" if worst <= plan.kobj_resolution_rel else "fail",
            "binding_words": "the read-out noise term of the budget, worst over the K_obj "
                             "range, the reference at the rated force"}


def _rated_row(plan) -> dict:
    """``full_scale_force_N`` without a Weibull pair: the rating against the largest the die's
    limits allow (:func:`tactcad.products.silicon_die.design.mems_die.rating_limits`: the more stressed root at the
    etched bars' mean strength, a stop engaging before its root breaks, the cavities' depth,
    the posts' height): failed at or past it, else undecided (a mean strength without its
    Weibull modulus gives no failure probability)."""
    from tactcad.products.silicon_die.design.mems_die import BOSCH_STRENGTH_SOURCE, rating_limits

    largest, binds = min(rating_limits(plan), key=lambda lw: lw[0])
    return {"requirement": "full_scale_force_N", "target": plan.full_scale_force_N,
            "predicted": largest, "error_estimate_rel": None,
            "margin_rel": largest / plan.full_scale_force_N - 1.0, "model": "closed-form",
            "verdict": "fail" if largest <= plan.full_scale_force_N else "undecided",
            "binding_words": f"the largest rating the die's limits allow: {binds}; no Weibull "
                             f"modulus, so no failure probability ({BOSCH_STRENGTH_SOURCE})"}


def _weibull_rated_row(plan) -> dict:
    """``full_scale_force_N`` with the plan's Weibull pair (the lab's, or the design
    default's): the die's failure probability with the rated force on every beam against
    the largest the pair accepts."""
    from tactcad.products.silicon_die.mechanics.die_strength import (die_failure_probability,
                                                force_scale_at_probability)

    pair = plan.weibull
    p_f = die_failure_probability(plan, plan.rated_force_N)
    scale = force_scale_at_probability(plan, plan.rated_force_N, pair.failure_probability_max)
    return {"requirement": "full_scale_force_N",
            "target": f"failure probability <= {pair.failure_probability_max:g}",
            "predicted": p_f, "error_estimate_rel": None,
            "margin_rel": scale - 1.0, "model": "closed-form",
            "verdict": "pass" if p_f <= pair.failure_probability_max else "fail",
            "binding_words": f"the die's failure probability with every beam at its rated "
                             f"force, {pair.whose} (m {pair.modulus:g}, "
                             f"sigma_0 {pair.characteristic_MPa:g} MPa on "
                             f"{pair.reference_area_um2:g} um^2; {pair.source}); it reaches "
                             f"{pair.failure_probability_max:g} at {scale:.3g} x the rating "
                             f"({scale * plan.full_scale_force_N:.3g} N): the margin is in "
                             "force"}


def _stop_row(plan, rows, fracture_travel_um: dict) -> dict:
    """The ``hard_stop`` record of :func:`die_verification`: each row's cavity floor."""
    from tactcad.products.silicon_die.design.mems_die import STOP_MULTIPLE
    from tactcad.products.silicon_die.vocabulary.soi_process import CAVITY_DEPTH_TOLERANCE_REL

    words, margins, ok = [], [], True
    for beam in rows:
        _, shallow, deep = plan.stop_engagement_um(beam)
        rated, breaks = plan.rated_tip_um(beam), fracture_travel_um[beam.role]
        ok = ok and rated < shallow and deep < min(breaks, plan.post_height_um)
        margins.append(min(breaks, plan.post_height_um) / deep - 1.0)
        words.append(f"{beam.role}: cavity {plan.cavity_depth_of(beam):g} um, engages at "
                     f"{shallow:.3g} ... {deep:.3g} um of post travel (rated {rated:.3g} um, "
                     f"breaks at {breaks:.3g} um: its root fillets' peak, K_t "
                     f"{plan.root_stress_concentration(beam):.3g} x the nominal, at the mean "
                     "strength)")
    words.append(f"posts {plan.post_height_um:g} um proud: still proud on their stops")
    if plan.weibull is not None:  # every beam resting on its floor: the most it carries
        from tactcad.products.silicon_die.mechanics.die_strength import (die_failure_probability,
                                                    force_scale_at_probability)

        stiffness = {"reference": plan.k_r_N_per_mm, "measuring": plan.k_m_N_per_mm}

        def on_stop(b):
            return stiffness[b.role] * 1e-3 * plan.stop_engagement_um(b)[2]

        p_stop = die_failure_probability(plan, on_stop)
        accepted = plan.weibull.failure_probability_max
        ok = ok and p_stop <= accepted
        scale = force_scale_at_probability(plan, on_stop, accepted)
        margins.append(scale - 1.0)  # in force, as the travels' margins
        words.append(f"the die's failure probability with every beam on its deepest stop "
                     f"{p_stop:.3g} (accepted up to {accepted:g}, {plan.weibull.whose}; "
                     f"reached at {scale:.3g} x the stops' forces)")
    return {"requirement": "hard_stop",
            "target": f"engages past the rated travel (at {STOP_MULTIPLE:g} x) and before the "
                      "root breaks",
            "predicted": "; ".join(words), "error_estimate_rel": None,
            "margin_rel": min(margins), "model": "closed-form",
            "verdict": "pass" if ok else "fail",
            "binding_words": f"each row's cavity floor under its beams' free ends (the depth "
                             f"+-{100 * CAVITY_DEPTH_TOLERANCE_REL:g} %, the root's peak on its "
                             "fillets at the mean strength of etched bars)"}


def die_tissue_coupling_record(plan) -> dict:
    """The K_obj bias the tissue's coupling between the posts causes on the die's middle unit,
    worst over the K_obj range, read by eq. 3 and by the coupled inversion, each judged
    against the die's K_obj resolution: the record the metal arrays' verify makes
    (:func:`tactcad.studies.verification.tissue_coupling_record`: ``tissue``,
    ``target_rel``, ``units``, ``eq3`` and ``coupled`` items), from the same per-unit solve
    (:func:`tactcad.in_use.tissue_coupling.unit_bias`) on the die's posts pressing one
    half-space (the budget's coupled sample). The coupled inversion's error is the budget's
    own: the punch model's share of the shift it predicts plus its mesh error.

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan`.

    Returns:
        The record (relative biases, N/mm); an item whose reading has no answer fails.

    Raises:
        ContactError: the coupled sample has no solution (as the budget).
    """
    from tactcad.in_use.kobj_budget import COUPLING_MODEL_ERROR_REL
    from tactcad.in_use.tissue_coupling import Tissue, unit_bias
    from tactcad.mechanics.verdicts import deciding_item, judged
    from tactcad.studies.verification import TISSUE_MODEL_ERROR_REL, TISSUE_POINTS, bias_verdict

    import numpy as np

    from tactcad.products.silicon_die.in_use.die_budget import _die_unit

    unit = _die_unit(plan)
    points = np.geomspace(*plan.kobj_range_N_per_mm, TISSUE_POINTS)
    record = unit_bias(unit.sample, unit.stiffness, unit.pair, points).as_json()
    target = plan.kobj_resolution_rel
    eq3, corrected = record["worst_eq3_rel"], record["worst_corrected_rel"]
    error = (COUPLING_MODEL_ERROR_REL * abs(eq3) if eq3 is not None else 0.0) \
        + float(unit.sample.error_rel)

    def margin(bias):
        return None if not bias else target / abs(bias) - 1.0

    eq3_item = judged({"unit": record["unit"], "bias_rel": eq3, "margin_rel": margin(eq3),
                       "error_estimate_rel": TISSUE_MODEL_ERROR_REL, "pass": eq3 is not None})
    coupled_item = {"unit": record["unit"], "bias_rel": corrected,
                    "margin_rel": margin(corrected),
                    "error_estimate_rel": error / abs(corrected) if corrected else None,
                    "bias_error_rel": error, "pass": corrected is not None,
                    "verdict": "fail" if corrected is None
                    else bias_verdict(corrected, error, target)}
    if eq3 is None:
        eq3_item["verdict"] = "fail"  # eq. 3 has no answer for the coupled R there
    return {"tissue": Tissue().describe(), "target_rel": target, "units": [record],
            "check_level": "the die's middle unit only; the coupled inversion's error is "
                           "the punch model's share of the shift plus its mesh error",
            **{name: {"items": [it], "verdict": deciding_item([it])["verdict"]}
               for name, it in (("eq3", eq3_item), ("coupled", coupled_item))}}
