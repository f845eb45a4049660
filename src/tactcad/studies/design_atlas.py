"""The design atlas of a grasper's jaw: over the products that seat in it and the materials
each allows, a scrambled Sobol sample of targets (K_r/K_m, the K_obj range's centre and
span, the rated full-scale force, the columns), each point judged as ``tactcad design
--jaw J --construction C`` judges it.

Every point is design's own verdict, reached by design's own functions:

* the monolithic comb: first the candidates in the order design prefers them, up to the
  first that counts with margin (:func:`tactcad.studies.comb_design.first_preferred`: the
  one design chooses, found without judging the rest, nor the verification matrices of
  those whose closed-form limits already fall short of the margin, nor the stops and
  plans of those whose yield or fatigue limit alone does:
  :func:`~tactcad.studies.comb_design.short_by_strength`); where none does, every sheet at
  every K_m scale whose stops can fit (:func:`~tactcad.studies.comb_design.atlas_scales`:
  the others are refused on every sheet and change no record) has been judged at the
  closed form as far as the record needs (those whose limits already fail the force:
  :func:`~tactcad.studies.comb_design.settled_short`; those short by strength only where
  their bound reaches the nearest failure's margin or none else is rated:
  :func:`~tactcad.studies.comb_design.settled_walk`), taken in
  :func:`~tactcad.studies.comb_design.comb_candidates`' order
  (:func:`~tactcad.studies.comb_design.in_search_order`); where one counts, the comb design writes
  (:func:`~tactcad.studies.comb_design.comb_of_candidates`, a screw and dowel too tall for
  the jaw refused by its height alone: the figures read no reasons); where none does, the
  limit of the candidate nearest to counting
  (:func:`~tactcad.studies.comb_design.nearest_failure`, the refusal's own rule). The
  refusal's pasteable force, a bisection over the candidates that costs ten times the
  verdict, is left out: it does not change the verdict;
* the silicon die: :func:`tactcad.products.silicon_die.studies.die_doping.doped_die_plan`
  and its mount in the jaw, refused or planned.

Points are grouped in batches, each one Dask task (:func:`run_atlas`). Units: mm, N, N/mm,
Hz, um (a die's layer).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

from tactcad.errors import DesignError

#: The comb construction and the die, as ``design --construction`` names them.
COMB = "monolithic-comb"
DIE = "mems-die"
#: The die's material: single-crystal silicon (``design`` takes no ``--material`` for it).
SILICON = "silicon"

#: The target space's axes, in the sample's column order.
AXES = ("kr_over_km", "kobj_centre_N_per_mm", "kobj_span", "full_scale_force_N", "columns")
#: Each axis's option (named in errors), whether it is sampled on a log scale, and the
#: widest range design's options allow (``design``'s own option bounds; columns: the die's
#: least 2, the comb's most 12).
AXIS_LIMITS = {
    "kr_over_km": ("--kr-over-km-range", True, (1.0, 1000.0)),
    "kobj_centre_N_per_mm": ("--kobj-centre", True, (1e-4, 1e4)),
    # a span of 1 is one K_obj, which design refuses (LO < HI); the least keeps the
    # range's ends apart in the six digits design's command line writes
    "kobj_span": ("--kobj-span", True, (1.001, 1e4)),
    "full_scale_force_N": ("--force-range", True, (1e-4, 1000.0)),
    "columns": ("--columns-range", False, (2, 12)),
}
#: Why an axis's limits are what they are, where it is not design's own option range.
AXIS_WHY = {"kobj_span": "a span of 1 is one K_obj, and design reads a range (--kobj-range LO < "
                         "HI); the least span keeps its ends apart in the six digits design "
                         "writes"}
#: The default target space: ratios about the paper's 10, soft to firm tissue (N/mm), ranges
#: of 2 ... 50 x, forces from a die's tens of mN to a comb's newtons, 2 ... 8 columns.
DEFAULT_RANGES = {"kr_over_km": (3.0, 30.0), "kobj_centre_N_per_mm": (0.1, 10.0),
                  "kobj_span": (2.0, 50.0), "full_scale_force_N": (0.005, 5.0),
                  "columns": (2, 8)}

def atlas_targets(n: int, ranges: Mapping[str, tuple[float, float]] | None = None,
                  seed: int = 0) -> list[dict]:
    """A scrambled Sobol sample of ``n`` targets over the target space (scipy.stats.qmc;
    log-uniform on every axis but the columns, which are uniform integers).

    Args:
        n: points (1 ... 100 000).
        ranges: axis (:data:`AXES`) -> (low, high); axes left out take
            :data:`DEFAULT_RANGES`.
        seed: the scramble's seed (an integer >= 0): the same seed, the same sample.

    Returns:
        ``n`` dicts: ``point`` (its index), ``kr_over_km``, ``kobj_lo_N_per_mm``,
        ``kobj_hi_N_per_mm`` (the range, centred geometrically on ``kobj_centre_N_per_mm``
        and ``kobj_span`` = high / low wide), ``full_scale_force_N`` (N) and ``columns``.

    Raises:
        DesignError: ``--points``, ``--seed`` or a range out of its bounds (the option, the
            value and the allowed range named).

    Source: Owen's scrambled Sobol' sequence (scipy.stats.qmc.Sobol, Owen 1998).
    """
    from scipy.stats import qmc

    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 100_000:
        raise DesignError("--points", n, "an integer 1 ... 100000")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise DesignError("--seed", seed, "an integer >= 0")
    bounds = checked_ranges(ranges or {})
    with warnings.catch_warnings():  # a count not a power of two loses balance, not validity
        warnings.simplefilter("ignore", UserWarning)
        unit = qmc.Sobol(len(AXES), scramble=True, seed=seed).random(n)
    return [target_of(i, row, bounds) for i, row in enumerate(unit)]


def checked_ranges(ranges: Mapping[str, tuple[float, float]]) -> dict[str, tuple[float, float]]:
    """Every axis's (low, high), the defaults filled in, each held to :data:`AXIS_LIMITS`.

    Args:
        ranges: axis (:data:`AXES`) -> (low, high) asked for.

    Returns:
        axis -> (low, high) for every axis of :data:`AXES` (floats).

    Raises:
        DesignError: an unknown axis, or a range not low <= high inside its limits.
    """
    unknown = set(ranges) - set(AXES)
    if unknown:
        raise DesignError("ranges", sorted(unknown)[0], "one of " + ", ".join(AXES))
    out = {}
    for axis in AXES:
        lo, hi = ranges.get(axis, DEFAULT_RANGES[axis])
        option, _, (least, most) = AXIS_LIMITS[axis]
        if not (_finite(lo) and _finite(hi) and least <= lo <= hi <= most):
            raise DesignError(option, f"{lo:g} {hi:g}" if _finite(lo) and _finite(hi)
                              else [lo, hi], f"LO <= HI within {least:g} ... {most:g}",
                              AXIS_WHY.get(axis, ""))
        if axis == "kr_over_km" and _g(lo) <= 1.0:  # a point's ratio is written to 6 digits
            raise DesignError(option, f"{lo:.10g} {hi:.10g}", "LO > 1 (a reference stiffer than "
                              "the measuring element) in the six digits design writes, "
                              "at least 1.00001")
        out[axis] = (float(lo), float(hi))
    check_kobj_reach(out)
    return out


def check_kobj_reach(bounds: Mapping[str, tuple[float, float]]) -> None:
    """Refuse a K_obj centre and span whose ranges reach past what design takes: the
    softest low end, centre / sqrt(span), and the stiffest high end, centre x sqrt(span),
    within ``MIN_KOBJ_N_PER_MM ... MAX_KOBJ_N_PER_MM`` (N/mm), so that no point is refused
    inside a task.

    Args:
        bounds: axis -> (low, high), every axis of :data:`AXES`.

    Raises:
        DesignError: ``--kobj-centre``, with the K_obj ends it reaches and the allowed range.
    """
    from tactcad.design.requirements_section import MAX_KOBJ_N_PER_MM, MIN_KOBJ_N_PER_MM

    (c_lo, c_hi), (_, span) = bounds["kobj_centre_N_per_mm"], bounds["kobj_span"]
    softest, stiffest = _g(c_lo / math.sqrt(span)), _g(c_hi * math.sqrt(span))
    if softest < MIN_KOBJ_N_PER_MM or stiffest > MAX_KOBJ_N_PER_MM:
        raise DesignError("--kobj-centre", f"{c_lo:g} {c_hi:g}",
                          f"centres whose ranges, at the widest --kobj-span {span:g}, lie within "
                          f"{MIN_KOBJ_N_PER_MM:g} ... {MAX_KOBJ_N_PER_MM:g} N/mm (design's "
                          f"--kobj-range)", f"they reach {softest:g} ... {stiffest:g} N/mm")


def _finite(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def target_of(index: int, unit_row: Sequence[float], bounds: Mapping[str, tuple[float, float]]
              ) -> dict:
    """One sample point scaled to the target space.

    Args:
        index: the point's number in the sample.
        unit_row: its coordinates in the unit cube, :data:`AXES` order.
        bounds: axis -> (low, high) (:func:`checked_ranges`).

    Returns:
        The target (see :func:`atlas_targets`' Returns), rounded to the six digits the
        design command line writes.
    """
    value = {}
    for u, axis in zip(unit_row, AXES):
        lo, hi = bounds[axis]
        _, log, _ = AXIS_LIMITS[axis]
        if axis == "columns":  # each integer an equal share of the unit interval
            value[axis] = min(int(lo + math.floor(u * (hi - lo + 1))), int(hi))
        elif log:
            value[axis] = math.exp(math.log(lo) + u * (math.log(hi) - math.log(lo)))
        else:
            value[axis] = lo + u * (hi - lo)
    centre, span = value["kobj_centre_N_per_mm"], value["kobj_span"]
    # rounded as the design command line writes them (%g), so the line repeats the point
    kr = _g(value["kr_over_km"])
    lo_k, hi_k = _g(centre / math.sqrt(span)), _g(centre * math.sqrt(span))
    return {"point": index, "kr_over_km": kr, "kobj_lo_N_per_mm": lo_k,
            "kobj_hi_N_per_mm": hi_k, "full_scale_force_N": _g(value["full_scale_force_N"]),
            "columns": int(value["columns"])}


def _g(x: float) -> float:
    """``x`` to the six significant digits ``%g`` writes."""
    return float(f"{x:g}")


@dataclass(frozen=True)
class JawAtlas:
    """What every point of one jaw's atlas is judged in (picklable: sent to each task).

    Attributes:
        jaw: the ``--jaw`` value (a trocar class or a jaw file's path).
        room: the jaw's room (:class:`tactcad.partlib.grasper_jaw.JawRoom`, mm).
        comb_base: the comb template's tables (the construction's ``jaw_template``), or
            None when no comb seats in the jaw.
        envelope_of: plan -> its footprint envelope (mm; the array's inventory).
        products: (product, material) pairs judged at each point.
        left_out: (product, its misfit in words: "does not fit: ...") of each product
            that does not seat in the jaw at any count of the columns asked for, so it
            is judged at no point.
    """

    jaw: str
    room: Any
    comb_base: dict | None
    envelope_of: Callable | None
    products: tuple[tuple[str, str], ...] = field(default=())
    left_out: tuple[tuple[str, str], ...] = field(default=())


def tissue_default():
    """The tissue ``design`` centres on by default (``--tissue-coupling on``, Poisson 0.5, a
    half-space)."""
    from tactcad.in_use.tissue_coupling import Tissue

    return Tissue(poisson_ratio=0.5, thickness_mm=None)


def targets_of(point: Mapping[str, Any]):
    """The targets ``design`` makes of a point's options.

    Args:
        point: a target of :func:`atlas_targets`.

    Returns:
        :class:`~tactcad.studies.inverse_design.Targets` with the tissue coupling on at its
        defaults (:func:`tissue_default`).

    Raises:
        DesignError: a target out of design's own range (the option named).
    """
    from tactcad.studies.inverse_design import Targets

    return Targets(point["kr_over_km"], (point["kobj_lo_N_per_mm"], point["kobj_hi_N_per_mm"]),
                   point["full_scale_force_N"], tissue=tissue_default())


def evaluate_point(atlas: JawAtlas, product: str, material: str, point: Mapping[str, Any]
                   ) -> dict:
    """One target judged for one product and material as ``design --jaw`` judges it.

    Args:
        atlas: the jaw and what the products need (:class:`JawAtlas`).
        product: :data:`COMB` or :data:`DIE`.
        material: a library grade (the comb) or :data:`SILICON` (the die).
        point: a target of :func:`atlas_targets`.

    Returns:
        A flat record: ``product``, ``material``, the point's fields, ``feasible``,
        ``binding_limit`` (the refusal's limit code,
        :data:`tactcad.vocabulary.binding_limits.BINDING_LIMITS`; "" when feasible),
        ``binding_detail`` (design's words), ``design_field`` (the option design's refusal
        names) and, for a feasible point, the design's figures: ``kobj_resolution_rel``,
        ``max_force_N`` (N), ``lowest_first_Hz`` (Hz), ``sheet_mm`` or ``layer_um``; and
        ``command``,
        the ``tactcad design`` line that writes it.

    Raises:
        DesignError: an unknown product.
    """
    record = {"product": product, "material": material, **dict(point),
              "feasible": False, "binding_limit": "", "binding_detail": "", "design_field": "",
              "kobj_resolution_rel": math.nan, "max_force_N": math.nan,
              "lowest_first_Hz": math.nan, "sheet_mm": math.nan, "layer_um": math.nan,
              "command": design_command(atlas.jaw, product, material, point)}
    try:
        targets = targets_of(point)
        if product == COMB:
            figures = comb_figures(atlas, material, targets, point["columns"])
        elif product == DIE:
            figures = die_figures(atlas, targets, point["columns"])
        else:
            raise DesignError("product", product, f"{COMB} or {DIE}")
    except RefusedPoint as refused:
        return {**record, "binding_limit": refused.limit,
                "binding_detail": refused.detail, "design_field": refused.field}
    return {**record, "feasible": True, **figures}


class RefusedPoint(Exception):
    """design refuses a point: the option its refusal names, its first reason and that
    reason's limit code (:mod:`tactcad.vocabulary.binding_limits`)."""

    def __init__(self, field_: str, detail: str, limit: str):
        super().__init__(detail)
        self.field = field_
        self.detail = detail
        self.limit = limit


def refusal_of(exc: DesignError) -> RefusedPoint:
    """design's refusal as the atlas records it.

    Args:
        exc: the refusal: a comb's carries its candidates (``candidates``), any other its
            fields and reasons.

    Returns:
        The option it names, its first reason and that reason's limit code: for a comb,
        the first failure of the candidate nearest to counting
        (:func:`~tactcad.studies.comb_design.nearest_failure`, the refusal's own rule for
        each sheet's line) and the code its check set; else the code the refusal carries
        (:data:`~tactcad.vocabulary.binding_limits.OTHER` where it carries none).
    """
    from tactcad.studies.comb_design import nearest_failure
    from tactcad.vocabulary.binding_limits import OTHER

    tried = getattr(exc, "candidates", None)
    if tried:
        nearest = nearest_failure(list(tried))
        if nearest is None:
            return RefusedPoint(exc.field, "", OTHER)
        return RefusedPoint(exc.field, nearest.failures[0],
                            nearest.limits[0] if nearest.limits else OTHER)
    errors = getattr(exc, "errors", None) or (exc,)
    first = errors[0]
    words = first.why or first.allowed or str(first)
    return RefusedPoint(first.field, words.split("; ")[0],
                        getattr(first, "limit", "") or OTHER)


def comb_figures(atlas: JawAtlas, grade: str, targets, columns: int) -> dict:
    """A feasible comb's figures, as design writes it; design's verdict otherwise.

    Raises:
        RefusedPoint: no candidate counts (the nearest's first failure), or the columns are
            out of the comb's range.
    """
    from tactcad.studies.comb_design import candidates_weighed, web_solves_kept
    from tactcad.vocabulary.binding_limits import FOOTPRINT

    if atlas.comb_base is None:
        raise RefusedPoint("--jaw", "the comb's smallest build does not fit the jaw's pocket",
                           FOOTPRINT)
    # the full search and the refusal meet the same webs again, and the written comb's
    # figures the elements its search judged (their closed-form estimates kept: the
    # batch says no range warning)
    with web_solves_kept(), candidates_weighed():
        return searched_comb_figures(atlas, grade, targets, columns)


def searched_comb_figures(atlas: JawAtlas, grade: str, targets, columns: int) -> dict:
    """:func:`comb_figures` inside its kept web solves.

    Args:
        atlas, grade, targets, columns: as :func:`comb_figures`.

    Returns:
        The feasible comb's figures.

    Raises:
        RefusedPoint: as :func:`comb_figures`.
    """
    from tactcad.studies.comb_design import (atlas_scales, comb_of_candidates, counting,
                                             first_preferred, in_search_order, refusal_option,
                                             searched_base)
    from tactcad.studies.inverse_design import InverseDesignError

    try:
        # a comb that counts with margin, in the chosen one's order, saves the full search
        judged: list = []
        # scales whose stops cannot fit change no verdict, limit or option: not judged
        # and of the candidates that cannot have the margin, only those that can change
        # the record are weighed when none has it
        preferred = first_preferred(targets, atlas.room, columns, atlas.comb_base,
                                    grade=grade, envelope_of=atlas.envelope_of, judged=judged,
                                    scales=atlas_scales(targets), only_what_decides=True)
        if preferred is not None:
            base, tried = None, [preferred]
        else:  # every candidate was judged: the full search's, in its order
            base = searched_base(atlas.comb_base, columns)
            tried = in_search_order(judged, base)
    except DesignError as exc:
        raise refusal_of(exc) from None
    if not counting(tried):
        option = refusal_option(base, tried, targets, atlas.room, columns, grade,
                                atlas.envelope_of)
        refused = InverseDesignError("no comb counts", option)
        refused.candidates = tuple(tried)
        raise refusal_of(refused)
    # the plan's figures read no reasons: a screw and dowel too tall is refused by its height
    design = comb_of_candidates(tried, targets, atlas.room, columns,
                                envelope_of=atlas.envelope_of, fastener_reasons=False)
    # the written comb is the chosen candidate named and reasoned: its search's matrix holds
    predicted = design.chosen.predicted if design.chosen is not None else None
    return plan_figures(design.plan, atlas.envelope_of, predicted) | {
        "sheet_mm": float(design.data["sheet"]["thickness_mm"])}


def plan_figures(plan, envelope_of: Callable | None,
                 predicted: Mapping[str, Any] | None = None) -> dict:
    """A metal plan's figures at the closed form.

    Args:
        plan: the comb's plan. envelope_of: plan -> its footprint envelope (mm).
        predicted: requirement -> its predicted figure in the closed-form verification
            matrix of tables the plan's differ from in their name and reasons alone (the
            chosen candidate's, :attr:`tactcad.studies.comb_design.CombCandidate.predicted`),
            where its search worked that matrix out; None: worked out here.

    Returns:
        ``kobj_resolution_rel`` and ``max_force_N`` (N) as its verification matrix predicts
        them (what ``verify`` reads at the closed form: ``max_force_N`` is the predicted
        figure of its ``full_scale_force_N`` row, the force the binding limit allows), and
        ``lowest_first_Hz``, the lowest first natural frequency of its elements with their
        gauge installations' mass (Hz; Rayleigh's quotient, ``tactcad modal --json``'s
        ``lowest_first_Hz`` at the closed form, under its name:
        :func:`tactcad.studies.project_reports.modes_record`).
    """
    from tactcad.studies.project_reports import modes_record
    from tactcad.studies.verification import verification_matrix

    if predicted is None:
        env = envelope_of(plan) if envelope_of is not None else None
        predicted = {r["requirement"]: r["predicted"]
                     for r in verification_matrix(plan, "closed-form", envelope_mm=env,
                                                  reported=False)}
    lowest = modes_record(plan, "closed-form", modes=1)[0]["lowest_first_Hz"]
    return {"kobj_resolution_rel": float(predicted.get("kobj_resolution_rel", math.nan)),
            "max_force_N": float(predicted.get("full_scale_force_N", math.nan)),
            "lowest_first_Hz": float(lowest)}


def die_figures(atlas: JawAtlas, targets, columns: int) -> dict:
    """A feasible die's figures, as design plans it; design's verdict otherwise: its K_obj
    resolution (relative, the read-out noise term), the largest rating it verifies
    (``max_force_N``, N: the least of its rating limits, in use and on its stops, each with
    its model error's room,
    :func:`~tactcad.products.silicon_die.design.mems_die.largest_verified_rating`; what
    ``tactcad strength --json`` reports as ``largest_rating_N`` on the written die), its
    beams' lowest first resonance (Hz, ``tactcad modal``'s) and its SOI device layer (um).

    Raises:
        RefusedPoint: the die's own refusal.
    """
    from tactcad.products.silicon_die.design.die_mount import die_mount
    from tactcad.products.silicon_die.design.mems_die import largest_verified_rating
    from tactcad.products.silicon_die.mechanics.die_dynamics import first_resonance_Hz
    from tactcad.products.silicon_die.studies.die_doping import (doped_die_plan,
                                                                 worst_readout_error_rel)

    try:
        plan = doped_die_plan(targets, atlas.room, columns=columns)
        die_mount(plan, dict(atlas.room.table or {}))
    except DesignError as exc:
        raise refusal_of(exc) from None
    return {"kobj_resolution_rel": float(worst_readout_error_rel(plan)),
            "max_force_N": float(largest_verified_rating(plan)[0]),
            "lowest_first_Hz": float(min(first_resonance_Hz(plan, b) for b in plan.beams)),
            "layer_um": float(plan.stack.device_um)}


def design_command(jaw: str, product: str, material: str, point: Mapping[str, Any]) -> str:
    """The ``tactcad design`` line that answers a point.

    Args:
        jaw: ``--jaw``. product: :data:`COMB` or :data:`DIE`. material: the comb's grade
            (the die takes none). point: a target of :func:`atlas_targets`.

    Returns:
        The command line; for a feasible point it writes the design.
    """
    import shlex

    words = ["tactcad design", f"--jaw {shlex.quote(jaw)}", f"--construction {product}",
             f"--kr-over-km {point['kr_over_km']:g}",
             f"--kobj-range {point['kobj_lo_N_per_mm']:g} {point['kobj_hi_N_per_mm']:g}",
             f"--full-scale-force {point['full_scale_force_N']:g}",
             f"--columns {point['columns']}"]
    if product == COMB:
        words.append(f"--material {material}")
    return " ".join(words + [f"--out {written_name(product, material, point['point'])}"])


#: Each product's word in the files its commands write.
PRODUCT_KEYS = {COMB: "comb", DIE: "die"}
#: The shipped comb grades' short words in those names (letters and digits).
GRADE_KEYS = {"6061-T6": "al6061", "7075-T6": "al7075", "17-4PH-H900": "174ph",
              "Ti-6Al-4V-annealed": "ti64", "CuBe-C17200-TF00": "cube"}
#: Most characters of a design's name (the name rule) and of a die's (its cell name).
DESIGN_NAME_CHARS, DIE_NAME_CHARS = 64, 32
#: Most characters a grade's word takes in a written name.
GRADE_KEY_CHARS = 10


def grade_key(material: str) -> str:
    """A comb grade's short word in the names an atlas writes: :data:`GRADE_KEYS`' for a
    shipped grade; for another, its letters and digits in lower case when they are at most
    :data:`GRADE_KEY_CHARS` and no shipped grade's word, else their first six and four hex
    digits of the grade's sha256 (two grades never share a word).

    Args:
        material: the grade as the material library names it (``Ti-6Al-4V-annealed``).

    Returns:
        Lower-case letters and digits, 1 ... :data:`GRADE_KEY_CHARS` characters.
    """
    import hashlib
    import re

    if material in GRADE_KEYS:
        return GRADE_KEYS[material]
    word = re.sub(r"[^a-z0-9]+", "", material.lower())
    if word and len(word) <= GRADE_KEY_CHARS and word not in GRADE_KEYS.values():
        return word
    return word[:6] + hashlib.sha256(material.encode("utf-8")).hexdigest()[:4]


def written_name(product: str, material: str, point: int) -> str:
    """The design file a point's command writes: one name per product, material and point,
    so the commands of one point's materials can all be pasted in one folder; short, so the
    design's name (the file's stem) leaves its drawings' title blocks room.

    Args:
        product: :data:`COMB` or :data:`DIE`. material: the comb's grade (the die's is
            :data:`SILICON`, left out of the name). point: the point's index.

    Returns:
        ``<product>[_<grade>]_<point>.toml`` (``comb_ti64_0.toml``, ``die_6.toml``: the
        words of :data:`PRODUCT_KEYS` and :func:`grade_key`), at most 27 characters of
        letters, digits and underscores.
    """
    parts = [PRODUCT_KEYS[product]] + ([] if product == DIE else [grade_key(material)])
    return "_".join(parts + [str(point)]) + ".toml"


def command_beside_project(command: str, project: str, jaw: str = "",
                           jaw_here: str = "", beside: str = "..") -> str:
    """A point's design command writing a new project folder beside a sensor project's
    (``<beside>/<project>_comb_...``), since a second design file in the project's folder
    would leave every later command there refused.

    Args:
        command: a line of :func:`design_command` (ending ``--out comb_....toml``).
        project: the project folder's name.
        jaw: the line's ``--jaw``; jaw_here: the same jaw named from the folder the line is
            pasted in (a jaw file's path); either empty: the line's ``--jaw`` is kept.
        beside: the folder holding the project's folder, named from the folder the line is
            pasted in (``..`` from the project's own folder).

    Returns:
        The line with its ``--out`` a folder beside the project, named after it and the point
        (:func:`beside_folder_name`, within a die's 32 characters for a die's line).
    """
    import posixpath
    import shlex

    head, _, name = command.rpartition(" --out ")
    given = f"tactcad design --jaw {shlex.quote(jaw)} "
    if jaw and jaw_here and head.startswith(given):
        head = f"tactcad design --jaw {shlex.quote(jaw_here)} " + head[len(given):]
    most = DIE_NAME_CHARS if f" --construction {DIE} " in f"{head} " else DESIGN_NAME_CHARS
    folder = beside_folder_name(project, name.removesuffix(".toml"), most)
    out = folder if beside in ("", ".") else posixpath.join(beside, folder)
    return f"{head} --out {shlex.quote(out)}"


def beside_folder_name(project: str, point_name: str, most: int = DESIGN_NAME_CHARS) -> str:
    """The project folder a point's command writes beside a sensor project's:
    ``<project>_<point name>``, the project's part cut so the whole is at most ``most``
    characters (design names the project after its folder: a design name takes 64, a die's
    cell name 32; the point's part keeps the lines apart).

    Args:
        project: the project folder's name. point_name: :func:`written_name`'s stem.
        most: the most characters of the name.

    Returns:
        The folder's name.
    """
    head = project[:max(0, most - len(point_name) - 1)].rstrip("_.-")
    return f"{head}_{point_name}" if head else point_name


def evaluate_batch(atlas: JawAtlas, points: Sequence[Mapping[str, Any]]) -> list[dict]:
    """One Dask task: every point judged for every product and material.

    Args:
        atlas: the jaw (:class:`JawAtlas`). points: targets of :func:`atlas_targets`.

    Returns:
        The records of :func:`evaluate_point`, point by point, products in their order.
    """
    from tactcad.mechanics.correction import range_warnings_unsaid
    from tactcad.products.silicon_die.design.mems_die import lighter_rating_unsaid

    # a refused rating's pasteable lighter one does not change the verdict a record keeps
    with range_warnings_unsaid(), lighter_rating_unsaid(), warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the candidates' warnings are not the design's
        return [evaluate_point(atlas, product, material, p)
                for p in points for product, material in atlas.products]


#: Tasks each worker thread is handed on average when ``--batch`` is not given: enough that
#: the last ones even out the workers' finish (a comb's point costs seconds).
TASKS_PER_WORKER = 32
#: Most points a task takes when ``--batch`` is not given: each task carries the jaw and
#: its records over the wire, so a die's points (milliseconds each) go in batches, but one
#: Ctrl-C loses at most this many points' work a worker.
MAX_AUTO_BATCH = 32


def auto_batch(points: int, threads: int) -> int:
    """Points per Dask task when ``--batch`` is not given: about :data:`TASKS_PER_WORKER`
    tasks for each worker thread, 1 to :data:`MAX_AUTO_BATCH` points each. (On two workers,
    10 000 die points took 131 s judged two to a task and 102 s 32 to a task: a task's
    overhead is several of a die's points.)

    Args:
        points: target points of the run. threads: the cluster's worker threads (0 is
            taken as 1).

    Returns:
        Points per task, an integer >= 1.
    """
    share = points // (max(1, threads) * TASKS_PER_WORKER)
    return max(1, min(MAX_AUTO_BATCH, share))


def batches(points: Sequence[dict], size: int) -> list[list[dict]]:
    """``points`` cut into batches, each one Dask task.

    Args:
        points: the targets. size: points per batch (the last one shorter).

    Returns:
        The batches, in the points' order.

    Raises:
        DesignError: ``--batch`` below 1.
    """
    if isinstance(size, bool) or not isinstance(size, int) or size < 1:
        raise DesignError("--batch", size, "an integer >= 1")
    return [list(points[i:i + size]) for i in range(0, len(points), size)]


def run_atlas(atlas: JawAtlas, points: Sequence[dict], client, batch_size: int = 1,
              progress: Callable[[int, int], None] | None = None) -> tuple[list[dict], bool]:
    """Every point judged on a Dask ``client``, one task per batch.

    Args:
        atlas: the jaw (:class:`JawAtlas`). points: targets of :func:`atlas_targets`.
        client: a ``distributed.Client`` (a LocalCluster's or an existing scheduler's).
        batch_size: points per task.
        progress: called with (batches done, batches) as each finishes.

    Returns:
        (the records in point, product and material order; True when every batch ran,
        False when Ctrl-C stopped the run: what finished is kept, the rest cancelled).
    """
    from distributed import as_completed

    work = batches(points, batch_size)
    futures = [client.submit(evaluate_batch, atlas, b, pure=False) for b in work]
    done: list[dict] = []
    try:
        for count, future in enumerate(as_completed(futures), start=1):
            done += future.result()
            if progress:
                progress(count, len(work))
    except KeyboardInterrupt:
        client.cancel(futures)
        return ordered(done, atlas), False
    return ordered(done, atlas), True


def ordered(records: list[dict], atlas: JawAtlas) -> list[dict]:
    """The records sorted.

    Args:
        records: records of :func:`evaluate_point`. atlas: the jaw, its products' order.

    Returns:
        ``records`` in point order, then in ``atlas.products``' order.
    """
    rank = {pair: i for i, pair in enumerate(atlas.products)}
    return sorted(records, key=lambda r: (r["point"], rank[(r["product"], r["material"])]))


#: The front's objectives: the rated force and the K_obj span the larger the better, the
#: K_obj resolution (relative) the smaller.
FRONT_OBJECTIVES = {"full_scale_force_N": "max", "kobj_span": "max",
                    "kobj_resolution_rel": "min"}


def pareto_front(records: Sequence[Mapping[str, Any]],
                 objectives: Mapping[str, str] = FRONT_OBJECTIVES) -> list[dict]:
    """The records no other record dominates (as good in every objective, better in one);
    records with a missing or NaN objective are left out.

    Args:
        records: flat records (an objective's key read from each; a ``kobj_span`` not given
            is hi / lo of the K_obj range).
        objectives: field -> ``"max"`` or ``"min"``.

    Returns:
        The non-dominated records, in their given order.

    Raises:
        DesignError: an objective's sense not ``max`` or ``min``.

    Source: the Pareto dominance of multi-objective optimisation (Deb, Multi-Objective
    Optimization using Evolutionary Algorithms, 2001, ch. 2).
    """
    for key, sense in objectives.items():
        if sense not in ("max", "min"):
            raise DesignError("objectives", f"{key}={sense}", "max or min")
    scored = []
    for r in records:
        row = [objective_value(r, key) for key in objectives]
        if all(math.isfinite(v) for v in row):
            signs = [1.0 if s == "max" else -1.0 for s in objectives.values()]
            scored.append((dict(r), [s * v for s, v in zip(signs, row)]))
    return [r for r, v in scored
            if not any(dominates(w, v) for _, w in scored if w is not v)]


def objective_value(record: Mapping[str, Any], key: str) -> float:
    """A record's value of one objective.

    Args:
        record: a flat record. key: the objective's field (``kobj_span``: hi / lo of the
            K_obj range where the record states none).

    Returns:
        The value; NaN when missing or not a finite number.
    """
    if key == "kobj_span" and key not in record:
        lo, hi = record.get("kobj_lo_N_per_mm"), record.get("kobj_hi_N_per_mm")
        return hi / lo if _finite(lo) and _finite(hi) and lo > 0 else math.nan
    value = record.get(key)
    return float(value) if _finite(value) else math.nan


def dominates(a: Sequence[float], b: Sequence[float]) -> bool:
    """Pareto dominance (Deb 2001, ch. 2).

    Args:
        a, b: objective values, each to be maximised.

    Returns:
        True when ``a`` is at least ``b`` in every objective and above it in one.
    """
    return all(x >= y for x, y in zip(a, b)) and any(x > y for x, y in zip(a, b))


def feasible_boundary(records: Sequence[Mapping[str, Any]], bins: int = 8
                      ) -> list[tuple[float, float, float]]:
    """The feasible region's upper boundary in the (K_obj span, rated force) plane: the
    sampled spans cut into ``bins`` equal steps of log(span), and in each the largest rated
    force of a feasible record (the limit above it is what refuses the points there).

    Args:
        records: flat records of one product and material (``feasible``,
            ``full_scale_force_N`` in N, the K_obj range in N/mm).
        bins: steps of log(span) (>= 1).

    Returns:
        (the step's lowest span, its highest span, the largest feasible force in it, N) for
        each step holding a feasible record, in increasing span; empty when none is
        feasible.

    Raises:
        DesignError: ``bins`` below 1.
    """
    if isinstance(bins, bool) or not isinstance(bins, int) or bins < 1:
        raise DesignError("bins", bins, "an integer >= 1")
    spans = [objective_value(r, "kobj_span") for r in records]
    finite = [s for s in spans if math.isfinite(s) and s > 0]
    if not finite:
        return []
    lo, hi = math.log(min(finite)), math.log(max(finite))
    width = (hi - lo) / bins or 1.0
    best: dict[int, float] = {}
    for r, s in zip(records, spans):
        if r.get("feasible") and math.isfinite(s) and s > 0:
            i = min(int((math.log(s) - lo) / width), bins - 1)
            best[i] = max(best.get(i, 0.0), float(r["full_scale_force_N"]))
    return [(math.exp(lo + i * width), math.exp(lo + (i + 1) * width), best[i])
            for i in sorted(best)]
