"""A design's requirements (stated or derived) and its verification matrix.

:func:`requirements_of` reads the ``[requirements]`` section
(:mod:`tactcad.design.requirements_section`); every key the file leaves out is
derived from the design's own nominal geometry at the corrected closed form,
rounded to the safe side, with the reason stated:

* full-scale force: the largest force every element carries within all its
  limits (:mod:`tactcad.mechanics.limits`), rounded down;
* K_r / K_m: the stiffest element over the softest, rounded down;
* K_obj range: [K_min, K_max] of the elements (eq. 2 reads best where the
  elements straddle the object);
* K band: the largest relative K change over the web tolerance, rounded up;
* K_obj resolution: the worst over the range at the full-scale force,
  rounded up.

Sensing units. The reference is the stiffest element; each softer element
is a measuring element paired with it. Pressed until the reference carries
the full-scale force F, each unit reads K_obj with the resolution of
:func:`tactcad.studies.inverse_design.unit_resolution` (forces read to 0.01 N);
the array's resolution at a K_obj is its best unit's.

:func:`verification_matrix` evaluates every requirement at one ladder level:
one record per requirement with ``requirement``, ``target``, ``predicted``,
``error_estimate_rel``, ``margin_rel``, ``model``, ``pass``.

Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from tactcad.design.array_plan import Plan
from tactcad.design.requirements_section import (REQUIREMENT_KEYS, cites_paper, requirements_source,
                                         stated_footprint, stated_requirements)
from tactcad.mechanics.stack_crosstalk import crosstalk_records
from tactcad.mechanics.resolution import KOBJ_POINTS
from tactcad.studies.resonance import resonance_records, resonance_summary
from tactcad.mechanics.thermal_drift import thermal_record

#: The predicted readable range is searched this factor beyond the required one.
KOBJ_SEARCH_FACTOR = 100.0


@dataclass(frozen=True)
class Requirements:
    """The requirement values of a design and where each comes from.

    Attributes:
        full_scale_force_N (N), kobj_range_N_per_mm ((LO, HI) N/mm),
        kr_over_km, k_tolerance_rel, kobj_resolution_rel: the values.
        reasons: per key, "stated in the design file" or the derivation.
        stated: the keys the design file states.
        source: the file's citation (``requirements.source``) or None.
        cites_paper: True for the paper's design.
    """

    full_scale_force_N: float
    kobj_range_N_per_mm: tuple[float, float]
    kr_over_km: float
    k_tolerance_rel: float
    kobj_resolution_rel: float
    reasons: Mapping[str, str] = field(default_factory=dict)
    stated: frozenset = frozenset()
    source: str | None = None
    cites_paper: bool = False
    footprint_mm: tuple[float, ...] | None = None

    def as_json(self) -> dict:
        return {"full_scale_force_N": self.full_scale_force_N,
                "kobj_range_N_per_mm": list(self.kobj_range_N_per_mm),
                "kr_over_km": self.kr_over_km, "k_tolerance_rel": self.k_tolerance_rel,
                "kobj_resolution_rel": self.kobj_resolution_rel, "reasons": dict(self.reasons),
                "stated": sorted(self.stated), "source": self.source,
                **({} if self.footprint_mm is None else
                   {"footprint_mm": list(self.footprint_mm)})}


def round_down(x: float, digits: int = 2) -> float:
    """``x`` rounded down to ``digits`` significant digits (x > 0)."""
    if x <= 0:
        return x
    e = math.floor(math.log10(x)) - digits + 1
    return _clean(math.floor(x / 10 ** e + 1e-9) * 10 ** e)


def round_up(x: float, digits: int = 2) -> float:
    """``x`` rounded up to ``digits`` significant digits (x > 0)."""
    if x <= 0:
        return x
    e = math.floor(math.log10(x)) - digits + 1
    return _clean(math.ceil(x / 10 ** e - 1e-9) * 10 ** e)


def _clean(x: float) -> float:
    return float(f"{x:.6g}")


# ---------------------------------------------------------------------------
# Per-element figures at one level
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Figures:
    """K, its error and the stress response of each distinct element at one level."""

    model: str
    k: dict[str, float]
    k_error: dict[str, float]
    stresses: dict[str, Any]
    by_element: dict[int, str]

    def k_of(self, number: int) -> float:
        return self.k[self.by_element[number]]


def element_figures(plan: Plan, model: str = "closed-form",
                    progress: Callable[[str], None] | None = None,
                    stress: Callable | None = None) -> Figures:
    """K (Richardson at FEM levels), its error estimate and the peak stress of
    every distinct element of ``plan`` at ``model``.

    Args:
        stress: (geometry, material, model) -> ElementStress; default the
            closed form's (closed form and beam). The FEM levels pass
            :func:`tactcad.studies.strength_studies.element_stress`.

    Raises:
        ValueError: an FEM model without ``stress``.
    """
    from tactcad.mechanics.ladder import estimate
    from tactcad.mechanics.ladder import is_meshed
    from tactcad.mechanics.element_strength import closed_form_stress

    if stress is None:
        if is_meshed(model):
            raise ValueError(f"model {model} runs the FEM: pass its stress "
                             "(tactcad.studies.strength_studies.element_stress)")
        stress = closed_form_stress
    element_stress = stress

    k, k_err, st = {}, {}, {}
    for name, g in plan.distinct_elements.items():
        if progress:
            progress(f"{model}: {name}")
        opts = {"progress": progress} if progress and is_meshed(model) else {}
        r = estimate(model, g, plan.material, **opts)
        k[name], k_err[name] = r.stiffness_N_per_mm, r.error_estimate_rel
        st[name] = element_stress(g, plan.material, model)
    return Figures(model, k, k_err, st, {s.number: s.geometry.part_name for s in plan.slots})


def web_band_rel(plan: Plan) -> float:
    """Largest relative K change of any element over web +/- web tolerance
    (corrected closed form; a derivative of K, so the level hardly matters)."""
    from dataclasses import replace

    from tactcad.mechanics.ladder import estimate

    worst = 0.0
    for g in plan.distinct_elements.values():
        k0 = estimate("closed-form", g, plan.material).stiffness_N_per_mm
        for sign in (-1, 1):
            t = g.web_thickness_mm + sign * g.web_tolerance_mm
            if t <= 0:
                continue
            k = estimate("closed-form", replace(g, web_thickness_mm=t),
                         plan.material).stiffness_N_per_mm
            worst = max(worst, abs(k / k0 - 1.0))
    return worst


def closed_form_k_error(plan: Plan) -> float:
    """Largest error estimate of the corrected closed-form K over the design's elements."""
    from tactcad.mechanics.ladder import estimate

    return max(estimate("closed-form", g, plan.material).error_estimate_rel
               for g in plan.distinct_elements.values())


def units_of(fig: Figures, plan: Plan) -> tuple[float, list[float]]:
    """(K_r, distinct K_m softer than K_r) of the array's sensing units (N/mm)."""
    ks = [fig.k_of(s.number) for s in plan.slots]
    kr = max(ks)
    kms = sorted({k for k in ks if k < kr * (1 - 1e-9)})
    return kr, kms


@dataclass(frozen=True)
class RowPair:
    """A row's reference and the softest measuring element of that row at one level.

    Attributes:
        row: 0-based row; reference, measuring: element numbers.
        ratio: K_r / K_m of the pair; *_error_rel: the level's K error estimates.
    """

    row: int
    reference: int
    measuring: int
    ratio: float
    reference_error_rel: float
    measuring_error_rel: float

    def as_json(self, target: float) -> dict:
        return {"row": self.row + 1, "reference_element": self.reference,
                "measuring_element": self.measuring, "kr_over_km": self.ratio,
                "margin_rel": self.ratio / target - 1.0}


def row_pairs(plan: Plan, fig: Figures) -> list[RowPair]:
    """Per row, its reference (:attr:`~tactcad.design.array_plan.Plan.references`)
    over the softest other element of the row (the row's smallest K_r / K_m);
    a row of one element pairs the reference with itself (ratio 1)."""
    out = []
    for row in range(plan.rows):
        ref = plan.reference_of(row)
        others = [s for s in plan.row_slots(row) if s.number != ref.number] or [ref]
        soft = min(others, key=lambda s: (fig.k_of(s.number), s.number))
        out.append(RowPair(row, ref.number, soft.number, fig.k_of(ref.number) / fig.k_of(soft.number),
                           fig.k_error[ref.geometry.part_name],
                           fig.k_error[soft.geometry.part_name]))
    return out


def resolution_rel(kr: float, kms: list[float], k_obj: np.ndarray, force_N: float) -> np.ndarray:
    """The array's relative K_obj resolution at each K_obj: its best unit's
    (inf where no element is softer than the reference)."""
    from tactcad.mechanics.resolution import unit_resolution

    best = np.full(np.shape(k_obj), np.inf)
    for km in kms:
        best = np.minimum(best, unit_resolution(km, kr, k_obj, force_N)["K_obj_resolution_rel"])
    return best


def worst_resolution(kr, kms, rng, force_N) -> float:
    return float(np.max(resolution_rel(kr, kms, np.geomspace(*rng, KOBJ_POINTS), force_N)))


def resolution_error_rel(kr: float, kms: list[float], rng, force_N: float, err_r: float,
                         err_m: float) -> float:
    """The worst K_obj resolution's relative error from the K errors of the
    reference (``err_r``) and the measuring elements (``err_m``): its largest
    change with each K moved by its error, every sign combination."""
    worst = worst_resolution(kr, kms, rng, force_N)
    moved = [worst_resolution(kr * (1 + sr * err_r), [k * (1 + sm * err_m) for k in kms],
                              rng, force_N) for sr in (-1, 1) for sm in (-1, 1)]
    return max(abs(w / worst - 1.0) for w in moved)


def readable_range(kr, kms, rng, force_N, target_rel) -> tuple[float, float] | None:
    """The widest K_obj interval around the range's geometric mean where the
    resolution is at most ``target_rel`` (N/mm), or None when the mean is not."""
    lo, hi = rng
    centre = math.sqrt(lo * hi)
    grid = np.geomspace(lo / KOBJ_SEARCH_FACTOR, hi * KOBJ_SEARCH_FACTOR, 801)
    grid = np.unique(np.append(grid, [lo, hi, centre]))
    ok = resolution_rel(kr, kms, grid, force_N) <= target_rel
    i = int(np.searchsorted(grid, centre))
    if not ok[i]:
        return None
    a = i
    while a > 0 and ok[a - 1]:
        a -= 1
    b = i
    while b < len(grid) - 1 and ok[b + 1]:
        b += 1
    return float(grid[a]), float(grid[b])


# ---------------------------------------------------------------------------
# The requirements
# ---------------------------------------------------------------------------
def requirements_of(plan: Plan, figures: Figures | None = None) -> Requirements:
    """The design's requirements: stated values from ``[requirements]``,
    the rest derived from its nominal geometry (corrected closed form) with
    the reason (see the module docstring).

    Raises:
        DesignError: the material has no yield strength.
    """
    from tactcad.mechanics.limits import LIMIT_WORDS, binding, plan_limits

    stated = stated_requirements(plan.raw)
    fig = figures if figures is not None and figures.model == "closed-form" \
        else element_figures(plan, "closed-form")
    values: dict[str, Any] = dict(stated)
    reasons = {k: "stated in the design file" for k in stated}
    if "full_scale_force_N" not in values:
        b = binding(plan_limits(plan, "closed-form", fig.stresses, fig.k_error))
        values["full_scale_force_N"] = round_down(b.force_N)
        reasons["full_scale_force_N"] = (
            f"not stated: the largest force every element carries, {b.force_N:.4g} N, bound by "
            f"{LIMIT_WORDS[b.limit]} (element {b.element}, closed form), rounded down")
    kr, kms = units_of(fig, plan)
    if "kr_over_km" not in values:
        ratio = kr / kms[0] if kms else 1.0
        values["kr_over_km"] = round_down(ratio) if ratio > 1 else 1.0
        reasons["kr_over_km"] = (f"not stated: the stiffest element over the softest, "
                                 f"{ratio:.4g} (closed form), rounded down")
    if "kobj_range_N_per_mm" not in values:
        k_min = kms[0] if kms else kr
        values["kobj_range_N_per_mm"] = (_clean(k_min), _clean(kr))
        reasons["kobj_range_N_per_mm"] = (
            "not stated: the elements' own stiffness span (closed form); eq. 2 reads best "
            "where the elements straddle the object")
    if "k_tolerance_rel" not in values:
        band = web_band_rel(plan)
        values["k_tolerance_rel"] = round_up(band) if band > 0 else 0.01
        reasons["k_tolerance_rel"] = (f"not stated: the largest K change over the web "
                                      f"tolerance, {100 * band:.3g} %, rounded up")
    if "kobj_resolution_rel" not in values:
        worst = worst_resolution(kr, kms, values["kobj_range_N_per_mm"],
                                 values["full_scale_force_N"]) if kms else math.inf
        values["kobj_resolution_rel"] = round_up(worst) if math.isfinite(worst) else 10.0
        reasons["kobj_resolution_rel"] = (
            f"not stated: the worst K_obj resolution over the range at the full-scale force, "
            f"{100 * worst:.3g} % (closed form, forces read to 0.01 N), rounded up"
            if math.isfinite(worst) else
            "not stated: no element is softer than the reference, so no K_obj can be read")
    return Requirements(
        full_scale_force_N=float(values["full_scale_force_N"]),
        kobj_range_N_per_mm=tuple(float(v) for v in values["kobj_range_N_per_mm"]),
        kr_over_km=float(values["kr_over_km"]), k_tolerance_rel=float(values["k_tolerance_rel"]),
        kobj_resolution_rel=float(values["kobj_resolution_rel"]),
        reasons={k: reasons[k] for k in REQUIREMENT_KEYS}, stated=frozenset(stated),
        source=requirements_source(plan.raw), cites_paper=cites_paper(plan.raw),
        footprint_mm=stated_footprint(plan.raw))


def rated_full_scale_force(plan: Plan) -> float:
    """The design's rated full-scale force (N), the one force every command,
    drawing and page calls full scale: ``[requirements] full_scale_force_N``,
    derived from the elements' limits when absent (:func:`requirements_of`).

    Raises:
        DesignError: the material has no yield strength.
    """
    return requirements_of(plan).full_scale_force_N


# ---------------------------------------------------------------------------
# The verification matrix
# ---------------------------------------------------------------------------
def _finite_or_none(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def _record(requirement: str, target, predicted, error: float, margin: float, model: str,
            passed: bool, **extra) -> dict:
    return {"requirement": requirement, "target": target, "predicted": predicted,
            "error_estimate_rel": _finite_or_none(error), "margin_rel": _finite_or_none(margin),
            "model": model, "pass": bool(passed), **extra}


def verification_matrix(plan: Plan, model: str = "closed-form",
                        progress: Callable[[str], None] | None = None,
                        requirements: Requirements | None = None,
                        stress: Callable | None = None,
                        envelope_mm: Sequence[float] | None = None) -> list[dict]:
    """One record per requirement, evaluated at ``model``.

    margin_rel: predicted / target - 1 for a lower bound (full-scale force,
    K_r/K_m), target / predicted - 1 for an upper bound (K band, K_obj
    resolution), the smaller end ratio - 1 for the readable K_obj range;
    positive means met. K_r / K_m passes within the K band the requirements
    allow (margin >= -k_tolerance_rel); the others pass with margin >= 0.
    The full-scale-force record lists every limit (``limits``) and the one
    that binds (``binding_limit``). ``stress``: as :func:`element_figures`
    (an FEM level needs :func:`tactcad.studies.strength_studies.element_stress`).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
        DesignError: the material has no yield strength.
    """
    from tactcad.mechanics.limits import LIMIT_WORDS, binding, per_kind_binding, plan_limits

    fig = element_figures(plan, model, progress, stress)
    req = requirements or requirements_of(plan, fig)
    out = []
    lims = plan_limits(plan, model, fig.stresses, fig.k_error)
    b = binding(lims)
    kinds = per_kind_binding(lims)
    F = req.full_scale_force_N
    out.append(_record("full_scale_force_N", F, b.force_N, b.error_estimate_rel,
                       b.force_N / F - 1.0, model, b.force_N >= F,
                       binding_limit=b.limit, binding_words=LIMIT_WORDS[b.limit],
                       binding_element=b.element,
                       limits=[lim.as_json(lim is b) for lim in kinds.values()]))
    kr, kms = units_of(fig, plan)
    pairs = row_pairs(plan, fig)
    worst = min(pairs, key=lambda q: (q.ratio, q.row))
    err_r, err_m = worst.reference_error_rel, worst.measuring_error_rel
    m = worst.ratio / req.kr_over_km - 1.0
    out.append(_record("kr_over_km", req.kr_over_km, worst.ratio, err_r + err_m, m, model,
                       m >= -req.k_tolerance_rel, reference_element=worst.reference,
                       measuring_element=worst.measuring, row=worst.row + 1,
                       pairs=[q.as_json(req.kr_over_km) for q in pairs]))
    band = web_band_rel(plan)
    out.append(_record("k_tolerance_rel", req.k_tolerance_rel, band, closed_form_k_error(plan),
                       req.k_tolerance_rel / band - 1.0 if band > 0 else math.inf,
                       "closed-form", band <= req.k_tolerance_rel))
    rng = req.kobj_range_N_per_mm
    if kms:
        worst = worst_resolution(kr, kms, rng, F)
        res_err = resolution_error_rel(kr, kms, rng, F, err_r, err_m)
        span = readable_range(kr, kms, rng, F, req.kobj_resolution_rel)
    else:
        worst, res_err, span = math.inf, 0.0, None
    out.append(_record("kobj_resolution_rel", req.kobj_resolution_rel, _finite_or_none(worst),
                       res_err, req.kobj_resolution_rel / worst - 1.0, model,
                       worst <= req.kobj_resolution_rel))
    m_rng = min(rng[0] / span[0], span[1] / rng[1]) - 1.0 if span else -1.0
    out.append(_record("kobj_range_N_per_mm", list(rng), list(span) if span else None, res_err,
                       m_rng, model, m_rng >= 0))
    out.append(readout_resolution_record(plan, fig, req, res_err))
    from tactcad.studies.tolerance_budget import toleranced_band_record

    out.append(toleranced_band_record(plan, req.k_tolerance_rel, closed_form_k_error(plan)))
    if req.footprint_mm is not None:
        if envelope_mm is None:
            raise ValueError("the design states requirements.footprint_mm: pass the array's "
                             "envelope (tactcad.assembly.inventory.array_envelope_mm)")
        out.append(footprint_record(req.footprint_mm, envelope_mm))
    out.extend(resonance_records(plan, model, progress))
    out.extend(r for r in [thermal_record(plan, fig, req)] if r is not None)
    out += crosstalk_records(plan)
    for r in out:
        r["stated"] = r["requirement"] in req.stated
        # the K band is the closed form's derivative at every level: no level decides it anew
        r["level_fixed"] = r["model"] != model or r["requirement"] in LEVEL_FIXED
        threshold = -req.k_tolerance_rel if r["requirement"] == "kr_over_km" else 0.0
        r["verdict"] = verdict(r["margin_rel"], r["error_estimate_rel"], threshold, r["pass"])
    return out


def footprint_record(footprint_mm: Sequence[float], envelope_mm: Sequence[float]) -> dict:
    """``footprint_mm``: the array's envelope (X, Y and, when the footprint
    states it, Z; mm) against the footprint; the margin is the tightest axis's
    room (footprint / envelope - 1). Geometry, not a model: no error estimate."""
    axes = "XYZ"[:len(footprint_mm)]
    env = [float(e) for e in envelope_mm[:len(footprint_mm)]]
    margins = [f / e - 1.0 for f, e in zip(footprint_mm, env)]
    worst = min(range(len(margins)), key=lambda k: margins[k])
    return {"requirement": "footprint_mm", "target": list(footprint_mm), "predicted": env,
            "error_estimate_rel": 0.0, "margin_rel": margins[worst], "model": "geometry",
            "pass": margins[worst] >= 0, "binding_axis": axes[worst],
            "basis": "the assembly STEP's box from the parts' expected boxes"}


#: Requirements computed the same way at every level (the K band over the web tolerance).
LEVEL_FIXED = ("k_tolerance_rel", "k_tolerance_rel_toleranced", "footprint_mm",
               "max_crosstalk_rel")

#: A requirement's verdict at one level (:func:`verdict`).
VERDICTS = ("pass", "fail", "undecided")


def verdict(margin_rel: float | None, error_rel: float | None, threshold_rel: float,
            nominal_pass: bool) -> str:
    """``pass`` when the margin clears its threshold by more than the level's
    error estimate, ``fail`` when it misses it by more, else ``undecided``
    (the level cannot tell). Without a finite margin or error: the nominal
    verdict.

    Args:
        margin_rel: the record's margin (positive: met), or None (infinite).
        error_rel: the prediction's relative error estimate, or None.
        threshold_rel: the margin the requirement needs (0; -K band for K_r/K_m).
        nominal_pass: the verdict on the nominal prediction.
    """
    if margin_rel is None or error_rel is None or not math.isfinite(error_rel):
        return "pass" if nominal_pass else "fail"
    clearance = margin_rel - threshold_rel
    if clearance >= error_rel:
        return "pass"
    if clearance < -error_rel:
        return "fail"
    return "undecided"


def verification_auto(plan: Plan, progress: Callable[[str], None] | None = None,
                      requirements: Requirements | None = None,
                      stress: Callable | None = None,
                      levels: tuple[str, ...] | None = None,
                      envelope_mm: Sequence[float] | None = None) -> tuple[list[dict], list[dict]]:
    """The verification matrix at the cheapest level that decides each
    requirement: the closed form first, then each level up the ladder
    (:func:`tactcad.mechanics.ladder.models`) only while a requirement is
    ``undecided`` and a higher level computes it anew (the K band over the
    web tolerance is the closed form's at every level, so it does not climb).
    Each record holds the figures of the level that decided it, ``decided_by``
    (that level, or None when still undecided) and ``levels_tried``.

    Args:
        stress: as :func:`verification_matrix` (needed once a FEM level runs).
        levels: the ladder to climb; default every level, cheapest first.

    Returns:
        (records in the matrix's order, [{"model", "seconds", "undecided_before"}]
        per level run).
    """
    import time

    from tactcad.mechanics.ladder import models

    ladder = tuple(levels or models())
    req = requirements or requirements_of(plan)
    chosen: dict[str, dict] = {}
    order: list[str] = []
    spent: list[dict] = []
    for i, level in enumerate(ladder):
        open_before = [k for k in order if k not in chosen] if order else None
        t0 = time.perf_counter()
        records = verification_matrix(plan, level, progress, req, stress, envelope_mm)
        spent.append({"model": level, "seconds": time.perf_counter() - t0,
                      "undecided_before": open_before})
        order = order or [r["requirement"] for r in records]
        top = i == len(ladder) - 1
        # a record another level computes the same way (the K band is always the
        # closed form's) cannot be decided by climbing: it stays undecided
        climbable = [r for r in records if r["requirement"] not in chosen
                     and r["verdict"] == "undecided" and not r["level_fixed"]]
        for r in records:
            key = r["requirement"]
            if key in chosen:
                continue
            if r["verdict"] != "undecided" or top or not climbable:
                r["decided_by"] = None if r["verdict"] == "undecided" else level
                r["levels_tried"] = list(ladder[:i + 1])
                chosen[key] = r
        if len(chosen) == len(order):
            break
    return [chosen[k] for k in order], spent


def readout_resolution_record(plan: Plan, fig: Figures, req: Requirements, error: float) -> dict:
    """``kobj_resolution_rel`` with each element read through the design's read-out chain
    (:mod:`tactcad.mechanics.readout_chain`: its noise-limited force resolution instead of a fixed
    0.01 N); requirement ``kobj_resolution_rel_readout``."""
    from tactcad.mechanics.readout_chain import readout_report

    rep = readout_report(plan, req, fig.model, stiffness=fig.k)
    worst = rep.array_kobj_resolution_rel
    worst = math.inf if worst is None else worst
    return _record("kobj_resolution_rel_readout", req.kobj_resolution_rel, _finite_or_none(worst),
                   error, req.kobj_resolution_rel / worst - 1.0, fig.model,
                   worst <= req.kobj_resolution_rel,
                   force_resolution_N={str(r["element"]): r["force_resolution_N"]
                                       for r in rep.records},
                   basis="read-out chain: noise of one averaged reading / sensitivity")


# ---------------------------------------------------------------------------
# A record in words: one wording for verify, check and the review page
# ---------------------------------------------------------------------------
def value_text(v) -> str:
    """A record's target or prediction: 4 significant digits, a list in
    brackets, ``none`` for a missing value."""
    if v is None:
        return "none"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value_text(x) for x in v) + "]"
    return f"{v:.4g}" if isinstance(v, (int, float)) and not isinstance(v, bool) else str(v)


def percent_text(v: float | None, sign: bool = True) -> str:
    """A relative figure in percent: signed with one decimal (a margin), or
    unsigned with two (an error estimate); ``n/a`` without one."""
    if v is None:
        return "n/a"
    return f"{100 * v:+.1f} %" if sign else f"{100 * v:.2f} %"


def binding_text(record: dict) -> str:
    """What a record's figure comes from: the row's pair for K_r/K_m
    (``row 1: element 2 / 1``), the binding limit and its element for the
    full-scale force, the tightest axis for the footprint, the element with
    the lowest first resonance; empty otherwise."""
    if "measuring_element" in record:
        return (f"row {record['row']}: element {record['reference_element']} / "
                f"{record['measuring_element']}")
    if "binding_words" in record:
        element = record.get("binding_element")
        return record["binding_words"] + ("" if element is None else f" (element {element})")
    if "binding_axis" in record:
        return f"axis {record['binding_axis']}"
    if "binding_part" in record:  # the lowest first resonance and the level that found it
        level = record.get("binding_model", record.get("modal_model"))
        return (f"element {record['binding_element']} ({record['binding_part']}, {level}, "
                f"{' and '.join(record['families'])} modes)")
    if "binding_element" in record:
        return f"element {record['binding_element']}"
    return ""


def matrix_passed(records: list[dict]) -> bool:
    """True when no requirement is ``fail`` (an ``undecided`` one does not fail the matrix)."""
    return not any(r["verdict"] == "fail" for r in records)


def undecided(records: list[dict]) -> list[str]:
    """The requirements no level decided (margin inside the error estimate)."""
    return [r["requirement"] for r in records if r["verdict"] == "undecided"]


def requirements_record(plan: Plan, envelope_mm: Sequence[float] | None = None) -> dict:
    """The manifest's record: the requirements with their reasons and the
    closed-form verification of each, the full-scale force with every limit
    and the one that binds; ``envelope_mm``: the array's, for a stated footprint."""
    req = requirements_of(plan)
    matrix = verification_matrix(plan, "closed-form", requirements=req, envelope_mm=envelope_mm)
    force = matrix[0]
    return {"values": req.as_json(), "closed_form_matrix": matrix,
            "first_resonance": resonance_summary(plan),
            "full_scale_force": {"required_N": req.full_scale_force_N,
                                 "largest_N": force["predicted"],
                                 "binding_limit": force["binding_words"],
                                 "binding_element": force["binding_element"],
                                 "met": force["pass"]}}
