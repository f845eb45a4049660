"""A silicon die's verification matrix: one record per requirement in the array's keys
(:func:`tactcad.studies.verification.verification_matrix`), at the closed form, for
``tactcad verify`` on a die's file and the die's requirements check group.

Every row carries the error estimate of the model that predicts it (``error_estimate_rel``,
relative, in the unit of its margin) and is judged as the array's rows are
(:func:`tactcad.mechanics.verdicts.verdict`): a margin inside its error is ``undecided``,
not passed. The estimates:

* the root fillets' K_t: :func:`tactcad.products.silicon_die.design.mems_die.root_kt_error_rel`
  (4 % inside its fit, 8 % outside it, as the die's range warning states);
* each beam's K: :data:`tactcad.products.silicon_die.design.mems_die.CLOSED_FORM_K_ERROR_REL`
  of the fem3d level; a root's stress at a travel (a stop's force, K x travel) carries both;
* a failure probability: the die's Weibull model
  (:mod:`tactcad.products.silicon_die.mechanics.die_strength`, P_f = 1 - exp(-(A_eff / A_0)
  (sigma / sigma_0)^m)) moves by (1 + e)^m - 1 (about m e at small P_f) for a stress error
  e, and the force at which it reaches the accepted probability by e: the margin is in
  force, so the row's error is e (``failure_probability_error_rel`` gives the P_f's);
* the K_obj read-out and budget figures: their largest change with each K moved by its
  error, every sign combination (as the array's
  :func:`tactcad.studies.verification.worst_and_error`).

Units: N, um, MPa; errors and margins relative.
"""

from __future__ import annotations

import math

# the K-moved error and the read-out's error live with the design that keeps their room;
# named here too, as the rows carry them
from tactcad.products.silicon_die.design.mems_die import k_moved_error_rel  # noqa: F401
from tactcad.products.silicon_die.studies.die_doping import resolution_error_rel  # noqa: F401


def kt_error_rel(plan) -> float:
    """The largest error of the root fillets' K_t over the die's beams
    (:func:`tactcad.products.silicon_die.design.mems_die.root_kt_error_rel`: twice the fit's
    outside its (r / t, w / t) range).

    Args:
        plan: the die (:class:`~tactcad.products.silicon_die.design.mems_die.DiePlan`).

    Returns:
        The relative error of a root's peak stress at a given force.
    """
    from tactcad.products.silicon_die.design.mems_die import root_kt_error_rel

    return max(root_kt_error_rel(plan.root_fillet_um, b.width_um, b.thickness_um)
               for b in plan.beams)


def travel_stress_error_rel(plan) -> float:
    """The relative error of a root's peak stress at a given post travel: K_t's
    (:func:`kt_error_rel`) and the closed form's K (the force the travel takes, K x travel;
    :data:`tactcad.products.silicon_die.design.mems_die.CLOSED_FORM_K_ERROR_REL`), added
    (:func:`tactcad.products.silicon_die.design.mems_die.stress_at_travel_error_rel`, the
    rule the die's design keeps room for).

    Args:
        plan: the die.

    Returns:
        The relative error.
    """
    from tactcad.products.silicon_die.design.mems_die import stress_at_travel_error_rel

    return stress_at_travel_error_rel(kt_error_rel(plan))


def force_stress_error_rel(plan) -> float:
    """The relative error of a root's peak stress at a given force (the rating's failure
    probability, its margin in force): K_t's
    (:func:`tactcad.products.silicon_die.design.mems_die.stress_at_force_error_rel`, the
    rule the die's design keeps room for).

    Args:
        plan: the die.

    Returns:
        The relative error.
    """
    from tactcad.products.silicon_die.design.mems_die import stress_at_force_error_rel

    return stress_at_force_error_rel(kt_error_rel(plan))


def weibull_probability_error_rel(stress_error_rel: float, modulus: float) -> float:
    """The relative change of a small failure probability for a stress error e under the
    die's Weibull model (:mod:`tactcad.products.silicon_die.mechanics.die_strength`: the
    risk goes as sigma^m, so P_f by (1 + e)^m - 1, about m e).

    Args:
        stress_error_rel: e (relative). modulus: the Weibull modulus m (> 0).

    Returns:
        The relative error of P_f.
    """
    return (1.0 + stress_error_rel) ** modulus - 1.0


def _finite_or_none(x: float) -> float | None:
    return float(x) if x is not None and math.isfinite(x) else None


def die_verification(plan, mount=None) -> list[dict]:
    """The die's verification matrix, one record per requirement in the array's keys
    (:func:`tactcad.studies.verification.verification_matrix`), at the closed form:

    Each record states ``error_estimate_rel`` (finite; see the module's words) and a
    ``verdict`` by :func:`tactcad.mechanics.verdicts.verdict`: a margin inside its error is
    ``undecided``.

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
      less one; each of these (and with a Weibull pair the die's failure probability on
      its stops) an item of ``items``, judged on its own margin and error, the record the
      worst item's (:func:`tactcad.mechanics.verdicts.deciding_item`).

    Args:
        plan: the die (:class:`~tactcad.products.silicon_die.design.mems_die.DiePlan`).
        mount: the die's mount in its jaw, for the grasp row (None: no grasp row).

    Returns:
        The records (requirement, target, predicted, error_estimate_rel, margin_rel, model,
        verdict, binding_words, ...).
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
    error = budget_error_rel(plan)
    return [accuracy_row(plan, float(max(budget.total_rel)), error),
            post_height_row(budget, error)]


def budget_error_rel(plan) -> float:
    """The error of the die's K_obj budget's worst root sum square: its largest change with
    each K moved by the closed form's error (:func:`k_moved_error_rel`).

    Args:
        plan: the die.

    Returns:
        The relative error (inf where the budget is unreadable).
    """
    return k_moved_error_rel(plan, worst_budget_rel)


def post_height_row(budget, error_rel: float = 0.0) -> dict:
    """``tip_height_tolerance_mm`` of a die: the posts' height tolerance the drawing holds
    against the one the K_obj budget's accuracy needs
    (:func:`tactcad.products.silicon_die.in_use.die_budget.post_height_drawing`). It passes
    when the process's tolerance holds the allowance (margin allowance / drawn - 1), or when
    the drawing names the zeroing on an optical flat and the mismatch it leaves fits the
    twice-the-allowance mismatch the accuracy permits (margin 2 allowance / residual - 1);
    it fails where the other terms leave no room. A margin inside ``error_rel`` (the
    allowance scales with the budget's room) is undecided.

    Args:
        budget: the die's :class:`~tactcad.products.silicon_die.in_use.die_budget.DieBudget`,
            its ``kobj_accuracy_rel`` stated.
        error_rel: the budget's error (:func:`budget_error_rel`, relative); 0 judges the
            nominal margin.

    Returns:
        The verification record.
    """
    from tactcad.products.silicon_die.in_use.die_budget import post_height_drawing
    from tactcad.studies.verification import TIP_HEIGHT_REQUIREMENT

    tip = post_height_drawing(budget)
    from tactcad.mechanics.verdicts import verdict

    error = _finite_or_none(error_rel)
    base = {"requirement": TIP_HEIGHT_REQUIREMENT, "error_estimate_rel": error,
            "model": "closed-form", "tip_height": tip.as_json(),
            "basis": "post height: tolerance drawn vs tolerance needed (the die's K_obj "
                     "budget, +/- mm); with the zeroing, half the mismatch it leaves"}
    needed = tip.allowance_mm
    if needed is None:
        return {**base, "target": None, "predicted": tip.drawn_mm, "margin_rel": None,
                "verdict": "fail",
                "binding_words": "no post tolerance fits: the other terms fill the accuracy"}
    if tip.holds_allowance:
        margin = needed / tip.drawn_mm - 1.0
        return {**base, "target": needed, "predicted": tip.drawn_mm,
                "margin_rel": margin, "verdict": verdict(margin, error, 0.0, True),
                "binding_words": f"the posts' +/-{1e3 * tip.drawn_mm:.3g} um holds it"}
    margin = 2 * needed / tip.residual_mm - 1.0
    return {**base, "target": needed, "predicted": tip.residual_mm / 2,
            "margin_rel": margin, "verdict": verdict(margin, error, 0.0, tip.residual_fits),
            "binding_words": f"zeroed on an optical flat: {1e3 * tip.residual_mm:.2g} um "
                             f"mismatch left; the posts' process holds +/-"
                             f"{1e3 * tip.drawn_mm:.3g} um, +/-{1e3 * needed:.3g} um needed"}


def _grasp_row(plan, mount) -> dict:
    """``max_grasp_force_N``: the die's jaw closed to that force on the default tissue
    (:func:`tactcad.products.silicon_die.in_use.die_grasp.grasp_at_force`), one item per load
    path (``items``), each judged on its own margin and error, the record the worst item's
    (:func:`tactcad.mechanics.verdicts.deciding_item`):

    * the beams: each beam's force on its spring against its breaking force (its root's peak
      at the mean strength of etched silicon), a hard stop taking the rest; error the
      breaking force's K_t error (:func:`kt_error_rel`) and the beam's force, the closed
      form's K and the tissue model's in quadrature (as the array's
      :func:`tactcad.studies.verification.grasp_error_rel`), added;
    * the posts: the most loaded post's whole force over its footprint against the posts'
      compressive limit
      (:data:`tactcad.products.silicon_die.mechanics.die_strength.POST_STRENGTH_MPA`);
      error the post's force's (the K and the tissue model's in quadrature);
    * the cavity floors (with a post on its stop): each stop's force pressing its beam's end
      on its floor over the post's footprint, the contact's edge tension at most half its
      mean pressure, judged on the die's Weibull pair over the ring it falls off in
      (:func:`tactcad.products.silicon_die.mechanics.die_strength.floors_force_scale`, the
      mean strength without a pair); error the force's and the footprint's shape
      (:data:`~tactcad.products.silicon_die.mechanics.die_strength.FOOTPRINT_SHAPE_ERROR_REL`),
      added.

    Each margin is in force, every force taken in proportion to the grasp, so ``predicted``
    is the grasp at which the deciding item reaches its limit (target x (1 + margin); None
    where a beam on its stop decides, whose force the stop holds whatever the grasp,
    :func:`tactcad.studies.verification.grasp_force_columns`); the deciding beam's force and
    breaking force are ``element_force_N`` and ``overload_limit_N``. Where the die's face
    meets the tissue the punch model puts the whole grasp on the posts: an upper bound on
    every force judged, as the face takes its share. A grasp the jaw cannot reach fails."""
    from tactcad.errors import DesignError
    from tactcad.mechanics.verdicts import deciding_item, verdict
    from tactcad.products.silicon_die.design.mems_die import CLOSED_FORM_K_ERROR_REL
    from tactcad.products.silicon_die.in_use.die_grasp import grasp_at_force
    from tactcad.studies.verification import TISSUE_MODEL_ERROR_REL, grasp_force_columns

    target = plan.max_grasp_force_N
    force_error = math.hypot(CLOSED_FORM_K_ERROR_REL, TISSUE_MODEL_ERROR_REL)
    error = kt_error_rel(plan) + force_error
    base = {"requirement": "max_grasp_force_N", "target": target, "error_estimate_rel": error,
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
    face = [t["site"] for t in result.tips if t.get("face_in_contact")]
    beam_margin = worst["overload_limit_N"] / worst["element_force_N"] - 1.0
    beams = {"item": f"beam {worst['site']}: its force on its spring against its breaking "
                     "force", "margin_rel": beam_margin, "error_estimate_rel": error,
             "verdict": verdict(beam_margin, error, 0.0, not over)}
    items = [beams, *_stop_path_items(plan, result.tips, force_error)]
    decides = deciding_item(items)
    if decides is beams:
        columns = grasp_force_columns(target, beam_margin, worst["on_stop"])
    else:  # a post's or a floor's force goes with the grasp
        m = decides["margin_rel"]
        columns = {"predicted": None if m is None else target * (1.0 + m), "margin_rel": m}
    return {**base, **columns, "error_estimate_rel": decides["error_estimate_rel"],
            "element_force_N": worst["element_force_N"],
            "overload_limit_N": worst["overload_limit_N"],
            "verdict": decides["verdict"], "items": items, "binding_item": decides["item"],
            "binding_words": _grasp_words(plan, result, worst, decides, over, face, target)}


def grasp_row(plan, mount, grasp_N: float) -> dict:
    """The ``max_grasp_force_N`` record of :func:`die_verification` at the grasp ``grasp_N``
    (N), whatever the plan states.

    Args:
        plan: the die. mount: its mount in its jaw. grasp_N: the grasp force (N, > 0).

    Returns:
        The verification record.
    """
    from dataclasses import replace

    return _grasp_row(replace(plan, max_grasp_force_N=float(grasp_N)), mount)


def surviving_grasp_N(plan, mount, start_N: float, tries: int = 12) -> float | None:
    """A grasp, two significant digits rounded down, at most ``start_N`` (N), whose
    :func:`grasp_row` passes, near the largest: from ``start_N`` down, each next grasp the
    one the last row predicts less its error (every force goes nearly in proportion to the
    grasp), at least one step of the second digit lower, a tenth lower where the row
    predicts none.

    Args:
        plan, mount: the die and its mount. start_N: the first grasp tried (N).
        tries: the most grasps tried.

    Returns:
        The grasp (N), or None where none of them passes.
    """
    from tactcad.vocabulary.rounding import round_down

    grasp = start_N
    for _ in range(tries):
        if not grasp > 0:
            return None
        paste = round_down(grasp, 2)
        row = grasp_row(plan, mount, paste)
        if row["verdict"] == "pass":
            return paste
        step = 10.0 ** (math.floor(math.log10(paste)) - 1)  # one unit of the second digit
        guess = (row["predicted"] / (1.0 + row["error_estimate_rel"]) if row.get("predicted")
                 else 0.9 * paste)
        grasp = min(guess, paste - step)
    return None


def _stop_path_items(plan, tips, force_error_rel: float) -> list[dict]:
    """The grasp row's items for a stop's load path (see :func:`_grasp_row`): the most
    loaded post, and the cavity floors under the posts on their stops (none on a stop: no
    floor item)."""
    from tactcad.mechanics.verdicts import judged
    from tactcad.products.silicon_die.mechanics.die_strength import (
        FOOTPRINT_SHAPE_ERROR_REL, POST_STRENGTH_MPA, bearing_area_um2, floors_force_scale,
        post_stress_MPa)

    post = max(tips, key=lambda t: t["tip_force_N"])
    stress = post_stress_MPa(post["tip_force_N"], plan.post_um)
    items = [judged({"item": f"post {post['site']}: {stress:.3g} MPa on its "
                             f"{plan.post_um:g} um footprint against {POST_STRENGTH_MPA:g} MPa",
                     "margin_rel": POST_STRENGTH_MPA / stress - 1.0 if stress > 0 else None,
                     "error_estimate_rel": force_error_rel})]
    stops = [t["stop_force_N"] for t in tips if t["on_stop"]]
    if stops:
        area = bearing_area_um2(plan.post_um, plan.beam_width_um)
        scale = floors_force_scale(stops, area, plan.weibull)
        items.append(judged({"item": f"the cavity floors under {len(stops)} stops (the most "
                                     f"{max(stops):.3g} N on {area:g} um^2)",
                             "margin_rel": scale - 1.0 if math.isfinite(scale) else None,
                             "error_estimate_rel": force_error_rel + FOOTPRINT_SHAPE_ERROR_REL}))
    return items


def _grasp_words(plan, result, worst, decides, over, face, target) -> str:
    """The grasp row's words: the deciding item, the beam that decides the beams, the
    stops' load path's model and sources, the face and the beams past breaking."""
    from tactcad.products.silicon_die.mechanics.die_strength import POST_STRENGTH_SOURCE

    stopped = [t["site"] for t in result.tips if t["on_stop"]]
    stop_N = max(t["stop_force_N"] for t in result.tips)
    strength = (plan.weibull.whose if plan.weibull is not None
                else "the mean strength of etched silicon")
    return (f"deciding: {decides['item']} (error {100 * decides['error_estimate_rel']:.2g} %); "
            f"beam {worst['site']}: {1e3 * worst['element_force_N']:.3g} mN "
            f"on its spring at the {target:g} N grasp (jaw at {result.angle_deg:.3g} degrees), "
            f"breaking force {1e3 * worst['overload_limit_N']:.3g} mN; on their stops: "
            f"{', '.join(map(str, stopped)) or 'none'} (the most a stop takes {stop_N:.3g} N: "
            f"the post's whole force over its footprint against {POST_STRENGTH_SOURCE}; the "
            f"beam's end on the cavity floor over the footprint, the contact's edge tension "
            f"at most half its mean pressure (Johnson, Contact Mechanics, 1985, 3.4), judged "
            f"by {strength})"
            + (f"; the die's face in the tissue beside posts {', '.join(map(str, face))}: "
               "the punch model puts the whole grasp on the posts, an upper bound on their "
               "forces" if face else "")
            + (f"; past breaking: {', '.join(map(str, over))}" if over else "")
            + ("" if decides["margin_rel"] is None or (decides["item"].startswith("beam")
                                                       and worst["on_stop"]) else
               "; predicted: the grasp at which the deciding item reaches its limit, every "
               "force in proportion to the grasp"))


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


def accuracy_row(plan, worst: float | None = None, error: float | None = None) -> dict:
    """``kobj_accuracy_rel``: the die's K_obj budget's worst root sum square over the range
    against the stated accuracy; fails where it is larger by more than its error
    (:func:`budget_error_rel`), undecided within it.

    Args:
        plan: the die, its ``kobj_accuracy_rel`` stated (relative).
        worst: :func:`worst_budget_rel` of the plan when already computed.
        error: :func:`budget_error_rel` of the plan when already computed.

    Returns:
        The verification record (requirement, target, predicted, margin_rel, verdict, ...).
    """
    from tactcad.mechanics.verdicts import verdict

    worst = worst_budget_rel(plan) if worst is None else worst
    error = _finite_or_none(budget_error_rel(plan) if error is None else error)
    target = plan.kobj_accuracy_rel
    readable = math.isfinite(worst) and worst > 0
    margin = target / worst - 1.0 if readable else None
    return {"requirement": "kobj_accuracy_rel", "target": target, "predicted": worst,
            "error_estimate_rel": error, "margin_rel": margin,
            "model": "closed-form", "verdict": verdict(margin, error, 0.0, worst <= target),
            "binding_words": "the root sum square of the die's K_obj budget (tactcad budget: "
                             "read-out noise, device layer, cavity alignment, temperature, "
                             "resistor zero drift, the coupled inversion's residue and the "
                             "posts' mismatch after zeroing on a flat), worst "
                             "over the K_obj range, each term before calibration (an upper "
                             "bound); its error: the largest change with each K moved by "
                             "the closed form's K error"}


def _resolution_row(plan) -> dict:
    """``kobj_resolution_rel``: the largest K_obj error the bridges' noise leaves over the
    range at the rated force against the die's requirement; its error the largest change
    with each K moved by the closed form's K error (:func:`k_moved_error_rel`). Where the
    die's file states none (the die sized to the default), reported, not judged
    (:func:`tactcad.mechanics.verdicts.reported_not_judged`), as an array's."""
    from tactcad.mechanics.verdicts import reported_not_judged, verdict
    from tactcad.products.silicon_die.studies.die_doping import worst_readout_error_rel

    worst = worst_readout_error_rel(plan)
    error = _finite_or_none(resolution_error_rel(plan))
    margin = (plan.kobj_resolution_rel / worst - 1.0
              if math.isfinite(worst) and worst > 0 else None)
    record = {"requirement": "kobj_resolution_rel", "target": plan.kobj_resolution_rel,
              "predicted": worst, "error_estimate_rel": error, "margin_rel": margin,
              "model": "closed-form",
              "verdict": verdict(margin, error, 0.0, worst <= plan.kobj_resolution_rel),
              "binding_words": "the read-out noise term of the budget, worst over the K_obj "
                               "range, the reference at the rated force (its error: each K "
                               "moved by the closed form's K error)"}
    if getattr(plan, "kobj_resolution_stated", False):
        return record
    return reported_not_judged({**record, "binding_words": record["binding_words"] + (
        f"; not stated: the die is sized to {plan.kobj_resolution_rel:g}, its default, "
        "reported, not judged")})


def _rated_row(plan) -> dict:
    """``full_scale_force_N`` without a Weibull pair: the rating against the largest the die's
    limits allow (:func:`tactcad.products.silicon_die.design.mems_die.rating_limits`: the more stressed root at the
    etched bars' mean strength, a stop engaging before its root breaks, the cavities' depth,
    the posts' height): failed at or past it, else undecided (a mean strength without its
    Weibull modulus gives no failure probability); its error K_t's and the K's, added
    (:func:`travel_stress_error_rel`), past which it fails."""
    from tactcad.mechanics.verdicts import verdict
    from tactcad.products.silicon_die.design.mems_die import BOSCH_STRENGTH_SOURCE, rating_limits

    largest, binds = min(rating_limits(plan), key=lambda lw: lw[0])
    error = travel_stress_error_rel(plan)  # the worst of the limits' (K_t and K)
    margin = largest / plan.full_scale_force_N - 1.0
    judged = verdict(margin, error, 0.0, largest > plan.full_scale_force_N)
    return {"requirement": "full_scale_force_N", "target": plan.full_scale_force_N,
            "predicted": largest, "error_estimate_rel": error,
            "margin_rel": margin, "model": "closed-form",
            "verdict": "fail" if judged == "fail" else "undecided",
            "binding_words": f"the largest rating the die's limits allow: {binds}; no Weibull "
                             f"modulus, so no failure probability ({BOSCH_STRENGTH_SOURCE})"}


def _weibull_rated_row(plan) -> dict:
    """``full_scale_force_N`` with the plan's Weibull pair (the lab's, or the design
    default's): the die's failure probability with the rated force on every beam against
    the largest the pair accepts. Its error: the root's stress at the rated force is K_t's
    (:func:`kt_error_rel`), e; the force at which P_f reaches the accepted probability moves
    by e, P_f itself by (1 + e)^m - 1 (:func:`weibull_probability_error_rel`)."""
    from tactcad.mechanics.verdicts import verdict
    from tactcad.products.silicon_die.mechanics.die_strength import (die_failure_probability,
                                                force_scale_at_probability)

    pair = plan.weibull
    p_f = die_failure_probability(plan, plan.rated_force_N)
    scale = force_scale_at_probability(plan, plan.rated_force_N, pair.failure_probability_max)
    error = force_stress_error_rel(plan)
    p_error = weibull_probability_error_rel(error, pair.modulus)
    return {"requirement": "full_scale_force_N",
            "target": f"failure probability <= {pair.failure_probability_max:g}",
            "predicted": p_f, "error_estimate_rel": error,
            "failure_probability_error_rel": p_error,
            "margin_rel": scale - 1.0, "model": "closed-form",
            "verdict": verdict(scale - 1.0, error, 0.0, p_f <= pair.failure_probability_max),
            "binding_words": f"the die's failure probability with every beam at its rated "
                             f"force, {pair.whose} (m {pair.modulus:g}, "
                             f"sigma_0 {pair.characteristic_MPa:g} MPa on "
                             f"{pair.reference_area_um2:g} um^2; {pair.source}); it reaches "
                             f"{pair.failure_probability_max:g} at {scale:.3g} x the rating "
                             f"({scale * plan.full_scale_force_N:.3g} N): the margin is in "
                             f"force, its error K_t's {100 * error:.2g} % (P_f's "
                             f"{100 * p_error:.2g} %, (1 + e)^m - 1)"}


def _stop_row(plan, rows, fracture_travel_um: dict) -> dict:
    """The ``hard_stop`` record of :func:`die_verification`: each row's cavity floor, one
    item per check (``items``), each judged on its own margin and error
    (:func:`tactcad.mechanics.verdicts.judged`), the record the worst item's
    (:func:`tactcad.mechanics.verdicts.deciding_item`). The errors: the rated travel (force
    over K) and the post's travel at engagement (the closed form's deflected shape) the
    closed form's K error; the travel at which a root breaks and the die's failure
    probability on its stops (in force) K_t's and K's (:func:`travel_stress_error_rel`)."""
    from tactcad.mechanics.verdicts import deciding_item, judged
    from tactcad.products.silicon_die.design.mems_die import (CLOSED_FORM_K_ERROR_REL,
                                                              STOP_MULTIPLE)
    from tactcad.products.silicon_die.vocabulary.soi_process import CAVITY_DEPTH_TOLERANCE_REL

    stress_error = travel_stress_error_rel(plan)
    words, items = [], []
    for beam in rows:
        _, shallow, deep = plan.stop_engagement_um(beam)
        rated, breaks = plan.rated_tip_um(beam), fracture_travel_um[beam.role]
        items += [judged({"item": f"{beam.role}: engages past the rated travel",
                          "margin_rel": shallow / rated - 1.0,
                          "error_estimate_rel": CLOSED_FORM_K_ERROR_REL}),
                  judged({"item": f"{beam.role}: engages before the root breaks",
                          "margin_rel": breaks / deep - 1.0,
                          "error_estimate_rel": stress_error}),
                  judged({"item": f"{beam.role}: the posts still proud on the stop",
                          "margin_rel": plan.post_height_um / deep - 1.0,
                          "error_estimate_rel": CLOSED_FORM_K_ERROR_REL})]
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
        scale = force_scale_at_probability(plan, on_stop, accepted)
        p_error = weibull_probability_error_rel(stress_error, plan.weibull.modulus)
        items.append(judged({"item": "the die's failure probability on its stops",
                             "margin_rel": scale - 1.0,  # in force, as the travels' margins
                             "error_estimate_rel": stress_error,
                             "failure_probability_error_rel": p_error}))
        words.append(f"the die's failure probability with every beam on its deepest stop "
                     f"{p_stop:.3g} (accepted up to {accepted:g}, {plan.weibull.whose}; "
                     f"reached at {scale:.3g} x the stops' forces; its error "
                     f"{100 * stress_error:.2g} % in force, the stress's, {100 * p_error:.2g} "
                     "% in P_f, (1 + e)^m - 1)")
    worst = deciding_item(items)
    return {"requirement": "hard_stop",
            "target": f"engages past the rated travel (at {STOP_MULTIPLE:g} x) and before the "
                      "root breaks",
            "predicted": "; ".join(words), "error_estimate_rel": worst["error_estimate_rel"],
            "margin_rel": worst["margin_rel"], "model": "closed-form",
            "verdict": worst["verdict"], "items": items, "binding_item": worst["item"],
            "binding_words": f"each row's cavity floor under its beams' free ends (the depth "
                             f"+-{100 * CAVITY_DEPTH_TOLERANCE_REL:g} %, the root's peak on its "
                             "fillets at the mean strength of etched bars); deciding: "
                             f"{worst['item']} (error {100 * worst['error_estimate_rel']:.2g} %:"
                             f" K_t's {100 * kt_error_rel(plan):.2g} %, the closed form's K "
                             f"{100 * CLOSED_FORM_K_ERROR_REL:.2g} %)"}


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
