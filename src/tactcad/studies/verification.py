"""A design's requirements (stated or derived) and its verification matrix.

:func:`requirements_of` reads the ``[requirements]`` section
(:mod:`tactcad.design.requirements_section`); every key the file leaves out is
derived from the design's own nominal geometry at the corrected closed form,
rounded to the safe side, with the reason stated:

* full-scale force: the largest force every element carries within all its
  limits (:mod:`tactcad.mechanics.limits`), rounded down;
* K_r / K_m: the smallest row's reference over its softest measuring
  element (the rule the record checks), rounded down;
* K_obj range: [K_min, K_max] of the elements (eq. 2 reads best where the
  elements straddle the object);
* K band: the largest relative K change over the web tolerance, rounded up;
* K_obj resolution: the worst over the range at the full-scale force,
  padded by its error estimate and rounded up.

Sensing units. Each element softer than its row's reference is a measuring
element paired with it (:func:`tactcad.mechanics.readout_chain.row_units`).
Pressed until the reference carries the full-scale force F, each unit reads
K_obj with the resolution of :func:`tactcad.mechanics.resolution.unit_resolution`,
each force read to the element's own force resolution through the design's
``[readout]`` chain (gauge, bridge, amplifier, DAQ:
:func:`tactcad.mechanics.readout_chain.element_force_resolution_N`), never a
fixed figure; the array's resolution at a K_obj is its best unit's.

:func:`verification_matrix` evaluates every requirement at one ladder level:
one record per requirement with ``requirement``, ``target``, ``predicted``,
``error_estimate_rel``, ``margin_rel``, ``model``, ``pass``, ``verdict``. A
record of several items (the rows' pairs of ``kr_over_km``) judges each item
on its own error and takes the worst item's verdict (:func:`deciding_item`).

Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace as _replaced
from typing import Any, Callable, Collection, Mapping, Sequence

import numpy as np

from tactcad.store import kept_per_process
from tactcad.vocabulary.rounding import clean as _clean, round_down, round_up
from tactcad.design.array_plan import ElementGeometry, Material, Plan
from tactcad.design.requirements_section import (REQUIREMENT_KEYS, cites_paper,
                                                 derived_requirements, requirements_source,
                                                 stated_footprint, stated_number,
                                                 stated_requirements)
from tactcad.mechanics.stack_crosstalk import crosstalk_records
from tactcad.mechanics.verdicts import (INFO, VERDICTS, deciding_item, judged,  # noqa: F401 (API)
                                        reported_not_judged, verdict)
from tactcad.studies.resonance import resonance_records, resonance_summary
from tactcad.mechanics.thermal_drift import thermal_record

#: The predicted readable range is searched this factor beyond the required one.
KOBJ_SEARCH_FACTOR = 100.0


#: How far below its target a row's K_r / K_m may lie when the file states no band
#: (``requirements.kr_over_km_tolerance_rel``): the paper's K_r/K_m "about 10".
KR_OVER_KM_BAND_REL = 0.1


@dataclass(frozen=True)
class Requirements:
    """The requirement values of a design and where each comes from.

    Attributes:
        full_scale_force_N (N), kobj_range_N_per_mm ((LO, HI) N/mm),
        kr_over_km, k_tolerance_rel, kobj_resolution_rel: the values.
        kr_over_km_tolerance_rel: how far below ``kr_over_km`` a row's K_r / K_m may lie
            (the requirement's own band; default :data:`KR_OVER_KM_BAND_REL`).
        reasons: per key, "stated in the design file" or the derivation.
        stated: the keys the lab states in the design file (not those the file marks as
            derived by ``tactcad design``, :func:`derived_requirements`).
        written: every key the design file gives a value, stated or so derived (the values
            judged as the file gives them).
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
    written: frozenset = frozenset()
    source: str | None = None
    cites_paper: bool = False
    footprint_mm: tuple[float, ...] | None = None
    kr_over_km_tolerance_rel: float = KR_OVER_KM_BAND_REL

    def as_json(self) -> dict:
        return {"full_scale_force_N": self.full_scale_force_N,
                "kobj_range_N_per_mm": list(self.kobj_range_N_per_mm),
                "kr_over_km": self.kr_over_km,
                "kr_over_km_tolerance_rel": self.kr_over_km_tolerance_rel,
                "k_tolerance_rel": self.k_tolerance_rel,
                "kobj_resolution_rel": self.kobj_resolution_rel, "reasons": dict(self.reasons),
                "stated": sorted(self.stated), "source": self.source,
                **({} if self.footprint_mm is None else
                   {"footprint_mm": list(self.footprint_mm)})}


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
    #: per part whose figures a lower level made (kept by :func:`verification_auto`), that
    #: level; a part not listed was solved at ``model``
    kept_from: dict[str, str] = field(default_factory=dict)
    #: the level every part's grid strain and force resolution are read at when no open
    #: requirement reads them (:func:`unread_stress`: the closed form's, so the level solves
    #: no face-strain sequence for them); None: each part's own level (:meth:`level_of`)
    grids_from: str | None = None
    #: per part whose K was solved at ``model`` while its stresses (its force limits) were
    #: kept from a lower level (listed in :attr:`kept_from`), that level's K error, which
    #: its limits carry (:func:`strengths_decided_below`)
    strength_k_error: dict[str, float] = field(default_factory=dict)

    def limit_k_errors(self) -> dict[str, float]:
        """Per part, the K error its force limits carry (relative): its own level's, or the
        lower level's whose stresses it keeps (:attr:`strength_k_error`)."""
        return {**self.k_error, **self.strength_k_error}

    def grid_level_of(self, part: str) -> str:
        """The level whose grid strain and force resolution part ``part`` reads."""
        return self.grids_from or self.level_of(part)

    def k_of(self, number: int) -> float:
        return self.k[self.by_element[number]]

    def level_of(self, part: str) -> str:
        """The level whose figures part ``part`` carries (``model`` unless kept from below)."""
        return self.kept_from.get(part, self.model)


def element_figures(plan: Plan, model: str = "closed-form",
                    progress: Callable[[str], None] | None = None,
                    stress: Callable | None = None, below: Figures | None = None,
                    keep: Collection[str] = (), keep_strength: Collection[str] = ()) -> Figures:
    """K (Richardson at FEM levels), its error estimate and the peak stress of
    every distinct element of ``plan`` at ``model``.

    Args:
        stress: (geometry, material, model) -> ElementStress; default the
            closed form's (closed form and beam). The FEM levels pass
            :func:`tactcad.studies.strength_studies.element_stress`.
        below: a lower level's figures; the parts named in ``keep`` take theirs (K in
            N/mm, its error, the stress) and are not solved at ``model``
            (:attr:`Figures.kept_from` says which level made them).
        keep: part names kept from ``below`` (empty: every part solved at ``model``).
        keep_strength: part names whose K (and its error) is solved at ``model`` while their
            stresses are taken from ``below`` (:func:`strengths_decided_below`): no
            peak-stress sequence is solved for them; their force limits are ``below``'s
            (listed in :attr:`Figures.kept_from`, their K error there in
            :attr:`Figures.strength_k_error`).

    Returns:
        The :class:`Figures` (K in N/mm, relative errors, stresses per N).

    Raises:
        ValueError: an FEM model without ``stress``.
    """
    from tactcad.mechanics.ladder import estimate
    from tactcad.mechanics.ladder import is_meshed
    from tactcad.mechanics.element_strength import at_the_grid, closed_form_stress
    from tactcad.mechanics.limits import limit_k_error

    if stress is None:
        if is_meshed(model):
            raise ValueError(f"model {model} runs the FEM: pass its stress "
                             "(tactcad.studies.strength_studies.element_stress)")
        stress = closed_form_stress
    element_stress = stress

    if (keep or keep_strength) and below is None:
        raise ValueError(f"keep {sorted({*keep, *keep_strength})}: pass the lower level's "
                         "figures (below)")
    k, k_err, st, kept_from, strength_err = {}, {}, {}, {}, {}
    for name, g in plan.distinct_elements.items():
        if name in keep:
            k[name], k_err[name], st[name] = below.k[name], below.k_error[name], \
                below.stresses[name]
            kept_from[name] = below.level_of(name)
            if name in below.strength_k_error:
                strength_err[name] = below.strength_k_error[name]
            continue
        if progress:
            progress(f"{model}: {name}")
        opts = {"progress": progress} if progress and is_meshed(model) else {}
        r = estimate(model, g, plan.material, **opts)
        # the K error the force limits carry: strength's rating reads the same function
        k[name], k_err[name] = r.stiffness_N_per_mm, limit_k_error(model, g, plan.material, r)
        if name in keep_strength:  # K at the level; the force limits the level below made
            st[name], kept_from[name] = below.stresses[name], below.level_of(name)
            strength_err[name] = below.limit_k_errors()[name]
            continue
        # the gauge strain the grid reads (strength, limits and read-out quote one); a level
        # whose stresses no open requirement reads solves no mesh sequence for it either
        es = element_stress(g, plan.material, model)
        st[name] = unread_at_the_grid(es, g, plan) if element_stress is unread_stress \
            else at_the_grid(es, g, plan)
    return Figures(model, k, k_err, st, {s.number: s.geometry.part_name for s in plan.slots},
                   kept_from, "closed-form" if element_stress is unread_stress else None,
                   strength_err)


def figures_limits(plan: Plan, fig: Figures) -> list:
    """Every force limit of every element (:func:`tactcad.mechanics.limits.plan_limits`),
    each part's at the level whose figures it carries (:meth:`Figures.level_of`: a part
    kept from a lower level keeps that level's limits and errors), in the plan's order; with
    :attr:`Figures.grids_from` set, every gauge limit on the grid strain read there.

    Args:
        plan: the design. fig: its figures (N/mm, relative errors, stresses per N).

    Returns:
        The :class:`~tactcad.mechanics.limits.ForceLimit` list (N).

    Raises:
        DesignError: the material has no yield strength.
    """
    from tactcad.mechanics.limits import plan_limits

    if fig.grids_from is not None:  # read by no open requirement: nothing solved, nor said
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return plan_limits(plan, fig.model, fig.stresses, fig.limit_k_errors(),
                               fig.grids_from)
    levels = {fig.level_of(part) for part in plan.distinct_elements}
    if levels == {fig.model}:
        return plan_limits(plan, fig.model, fig.stresses, fig.k_error)
    order = sorted(levels)
    by_level = [plan_limits(plan, lv, fig.stresses, fig.limit_k_errors()) for lv in order]
    # the same slots and kinds in the same order at every level: each from its part's level
    out = []
    for same in zip(*by_level):
        out.extend(lim for lv, lim in zip(order, same) if fig.level_of(lim.part_name) == lv)
    return out


def web_band_rel(plan: Plan) -> float:
    """Largest relative K change of any element over web +/- web tolerance
    (corrected closed form; a derivative of K, so the level hardly matters;
    :func:`tactcad.in_use.kobj_budget.web_tolerance_k_rel` per element)."""
    from tactcad.in_use.kobj_budget import web_tolerance_k_rel

    return max((web_tolerance_k_rel(g, plan.material) for g in plan.distinct_elements.values()),
               default=0.0)


def closed_form_k_error(plan: Plan) -> float:
    """Largest error estimate of the corrected closed-form K over the design's elements."""
    from tactcad.mechanics.ladder import estimate

    return max(estimate("closed-form", g, plan.material).error_estimate_rel
               for g in plan.distinct_elements.values())


#: The K spread over the web tolerance (relative, +/-) beyond which ``verify`` and ``design``
#: note it when the design file states no ``k_tolerance_rel``: the K_r/K_m band a sensing
#: unit's ratio is allowed by default (:data:`KR_OVER_KM_BAND_REL`, the paper's "about 10"):
#: a K moving further moves a unit's ratio off its target by more than that band, so one
#: nominal K per element no longer serves the array.
K_SPREAD_NOTE_REL = KR_OVER_KM_BAND_REL

#: The step a suggested web tolerance is rounded down to (mm).
WEB_TOLERANCE_STEP_MM = 0.005


def web_spread(plan: Plan, web_tolerance_mm: float | None = None) -> tuple[float, str]:
    """The largest relative K change of any element over its web +/- the web tolerance
    (corrected closed form, as :func:`web_band_rel`) and the element that has it.

    Args:
        plan: the design.
        web_tolerance_mm: the web tolerance to evaluate (mm, > 0); None: each element's own.

    Returns:
        (spread, part name): spread dimensionless (0.5 for +/-50 %).
    """
    import warnings

    from tactcad.in_use.kobj_budget import web_tolerance_k_rel

    with warnings.catch_warnings():
        if web_tolerance_mm is not None:  # a what-if's range warnings are not the design's
            warnings.simplefilter("ignore")
        spreads = [(web_tolerance_k_rel(g if web_tolerance_mm is None else
                                        _replaced(g, web_tolerance_mm=web_tolerance_mm),
                                        plan.material), name)
                   for name, g in plan.distinct_elements.items()]
    return max(spreads, default=(0.0, ""))


def tighter_web_tolerance(tolerance_mm: float, spread_rel: float,
                          limit_rel: float = K_SPREAD_NOTE_REL,
                          floor_mm: float = WEB_TOLERANCE_STEP_MM) -> float:
    """The web tolerance that brings a K spread to ``limit_rel``, K's change taken as
    proportional to the tolerance, rounded down to :data:`WEB_TOLERANCE_STEP_MM` and no
    tighter than ``floor_mm`` (what the element's cut process holds on its sheet,
    :func:`held_web_tolerance`).

    Args:
        tolerance_mm: the web tolerance now (mm, > 0). spread_rel: the K spread it gives
            (> 0). limit_rel: the spread to reach (> 0). floor_mm: the tightest (mm).

    Returns:
        The tolerance (mm), at most ``tolerance_mm``.
    """
    step = WEB_TOLERANCE_STEP_MM
    need = tolerance_mm * limit_rel / spread_rel
    return min(tolerance_mm, max(floor_mm, math.floor(need / step + 1e-9) * step))


@dataclass(frozen=True)
class HeldTolerance:
    """The tightest web tolerance a cut process holds on an element's sheet.

    Attributes:
        tolerance_mm: +/- on the web (mm). process: the cut process's name.
        sheet_mm: the sheet it is cut from (mm). rule: the process's rule for the figure.
    """

    tolerance_mm: float
    process: str
    sheet_mm: float
    rule: str

    @property
    def words(self) -> str:
        return f"what {self.process} holds on a {self.sheet_mm:g} mm sheet ({self.rule})"


def _held_by(process: str, g: ElementGeometry, plan: Plan) -> HeldTolerance:
    from tactcad.vocabulary.process import cut_process

    lim = cut_process(process).limits(g.sheet_thickness_mm, plan.edm,
                                      plan.material.grade or plan.material.name)
    return HeldTolerance(lim.tolerance_mm.value_mm, process, g.sheet_thickness_mm,
                         lim.tolerance_mm.rule)


def held_web_tolerance(plan: Plan) -> HeldTolerance:
    """The tightest web tolerance every element's own cut process holds on its sheet: the
    figure the design file's ``element.web_tolerance_mm`` is checked against (the loosest
    over the elements, so that one value serves all of them).

    Args:
        plan: the design.

    Returns:
        The :class:`HeldTolerance` (mm).
    """
    return max((_held_by(g.process, g, plan) for g in plan.distinct_elements.values()),
               key=lambda h: h.tolerance_mm)


def finer_process(plan: Plan, part: str) -> HeldTolerance | None:
    """A cut process other than the element's own that holds its web tighter on its sheet
    and takes that sheet for a flexure (the finest such), or None.

    Args:
        plan: the design. part: the element's part name.

    Returns:
        What that process holds (mm), or None.
    """
    from tactcad.vocabulary.process import CUT_PROCESSES

    g = plan.distinct_elements[part]
    own = _held_by(g.process, g, plan).tolerance_mm
    found = []
    for name, proc in CUT_PROCESSES.items():
        lo, hi, _ = proc.flexure_sheet()
        if name == g.process or not lo - 1e-12 <= g.sheet_thickness_mm <= hi + 1e-12:
            continue
        held = _held_by(name, g, plan)
        if held.tolerance_mm < own - 1e-12:
            found.append(held)
    return min(found, key=lambda h: h.tolerance_mm, default=None)


#: How far past its design web the search of a web whose K spread meets the band goes (x).
WEB_SEARCH_FACTOR = 10.0


def web_for_band(g: ElementGeometry, material: Material, tolerance_mm: float,
                 limit_rel: float = K_SPREAD_NOTE_REL) -> float | None:
    """The thinnest web, in steps of :data:`WEB_TOLERANCE_STEP_MM` above the element's own,
    whose K moves at most ``limit_rel`` over +/- ``tolerance_mm`` (corrected closed form,
    the rest of the element as drawn), or None within :data:`WEB_SEARCH_FACTOR` x its web.

    Args:
        g: the element (mm). material: its material (MPa). tolerance_mm: +/- on the web
            (mm, > 0). limit_rel: the spread to reach (dimensionless, > 0).

    Returns:
        The web (mm), or None.
    """
    import warnings

    from tactcad.in_use.kobj_budget import web_tolerance_k_rel

    step = WEB_TOLERANCE_STEP_MM
    first = math.floor(g.web_thickness_mm / step + 1e-9) + 1
    last = math.ceil(WEB_SEARCH_FACTOR * g.web_thickness_mm / step)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a what-if's range warnings are not the design's
        for n in range(first, last + 1):
            web = round(n * step, 6)
            at = _replaced(g, web_thickness_mm=web, web_tolerance_mm=tolerance_mm)
            if web_tolerance_k_rel(at, material) <= limit_rel:
                return web
    return None


def out_of_band_words(plan: Plan, part: str, held: HeldTolerance) -> str:
    """What would bring a K spread the process's best web tolerance leaves past
    :data:`K_SPREAD_NOTE_REL` within it: a thicker web, another cut process.

    Args:
        plan: the design. part: the element with the largest spread. held: the best
            tolerance its process holds (:func:`held_web_tolerance`).

    Returns:
        Words for the note.
    """
    g = plan.distinct_elements[part]
    band = f"+/-{100 * K_SPREAD_NOTE_REL:g} %"
    web = web_for_band(g, plan.material, held.tolerance_mm)
    thicker = (f"a thicker web ({part} reaches {band} at +/-{held.tolerance_mm:g} mm with a "
               f"web of {web:g} mm, not {g.web_thickness_mm:g} mm; its arm re-sized to keep K)"
               if web is not None else "a thicker web")
    other = finer_process(plan, part)
    if other is None:
        return f"{thicker}; no cut process tactcad knows holds the web tighter on this sheet"
    at, _ = web_spread(plan, other.tolerance_mm)
    return (f"{thicker}, or another cut process ({other.words}: K +/-{100 * at:.3g} %; "
            f"--set element.process={other.process} "
            f"--set element.web_tolerance_mm={other.tolerance_mm:g})")


def process_web_tolerance(plan: Plan, tolerance_mm: float, spread_rel: float,
                          held: HeldTolerance) -> tuple[float, float]:
    """The web tolerance a K spread note offers and the spread it gives: proportional
    (:func:`tighter_web_tolerance`), then a step tighter at a time while the spread it
    gives is still past :data:`K_SPREAD_NOTE_REL` and the process holds it.

    Args:
        plan: the design. tolerance_mm: the web tolerance now (mm). spread_rel: its K
            spread. held: what the process holds (:func:`held_web_tolerance`).

    Returns:
        (tolerance (mm), the K spread at it (dimensionless)); the tolerance now and its
        spread when the process holds none tighter.
    """
    tighter = tighter_web_tolerance(tolerance_mm, spread_rel, floor_mm=held.tolerance_mm)
    if tighter >= tolerance_mm - 1e-12:
        return tolerance_mm, spread_rel
    at, _ = web_spread(plan, tighter)
    while at > K_SPREAD_NOTE_REL and tighter - WEB_TOLERANCE_STEP_MM >= held.tolerance_mm - 1e-12:
        tighter = round(tighter - WEB_TOLERANCE_STEP_MM, 6)
        at, _ = web_spread(plan, tighter)
    return tighter, at


def k_spread_note(plan: Plan, requirements: "Requirements") -> str | None:
    """What ``verify`` and ``design`` say of the K spread over the web tolerance when the
    design file states no ``k_tolerance_rel`` and the spread exceeds
    :data:`K_SPREAD_NOTE_REL`: how far K moves, and the ways out (calibrate every element,
    or a tighter web tolerance no tighter than the element's process holds on its sheet
    (:func:`held_web_tolerance`), with the figure it gives and the line to paste; where
    even that leaves K past the band, says so and names what would reach it:
    :func:`out_of_band_words`).

    Args:
        plan: the design. requirements: its :func:`requirements_of`.

    Returns:
        One line, or None (a stated band, judged by its row, or a spread within the limit).
    """
    if "k_tolerance_rel" in requirements.stated:
        return None
    spread, part = web_spread(plan)
    if spread <= K_SPREAD_NOTE_REL:
        return None
    tol = max(g.web_tolerance_mm for g in plan.distinct_elements.values())
    held = held_web_tolerance(plan)
    text = (f"K moves up to +/-{100 * spread:.3g} % ({part}, closed form) with the "
            f"+/-{tol:g} mm web tolerance, more than +/-{100 * K_SPREAD_NOTE_REL:g} % (a "
            f"unit's K_r/K_m band), and the design states no requirements.k_tolerance_rel: "
            f"calibrate every element (eq. 4-6)")
    tighter, at = process_web_tolerance(plan, tol, spread, held)
    if tighter < tol:
        text += (f", or tighten the web tolerance to +/-{tighter:g} mm (K +/-{100 * at:.3g} %"
                 f"; --set element.web_tolerance_mm={tighter:g})")
    if at > K_SPREAD_NOTE_REL:
        band = f"+/-{100 * K_SPREAD_NOTE_REL:g} %"
        best = (f"even +/-{tighter:g} mm, {held.words}, leaves K past {band}" if tighter < tol
                else f"the +/-{tol:g} mm is already {held.words}, and K stays past {band}")
        text += f"; {best}: {out_of_band_words(plan, part, held)}"
    return text + "; state the band your use needs as requirements.k_tolerance_rel to judge it"


@dataclass(frozen=True)
class RowPair:
    """A row's reference and the softest measuring element of that row at one level.

    Attributes:
        row: 0-based row of the reference; reference, measuring: element numbers.
        ratio: K_r / K_m of the pair; *_error_rel: the level's K error estimates.
        column: with the plan's pairing "column" (each column's reference read by the
            element beside it in the other row), the pair's 0-based column; None with
            pairing "row".
    """

    row: int
    reference: int
    measuring: int
    ratio: float
    reference_error_rel: float
    measuring_error_rel: float
    column: int | None = None

    @property
    def error_rel(self) -> float:
        """The pair's K_r / K_m error estimate: its two K errors added."""
        return self.reference_error_rel + self.measuring_error_rel

    def as_json(self, target: float, threshold_rel: float = 0.0) -> dict:
        """The pair as an item of the ``kr_over_km`` record, judged on its own error
        (``threshold_rel``: the margin the requirement needs, :func:`verdict`)."""
        where = {} if self.column is None else {"column": self.column + 1}
        return judged({"row": self.row + 1, **where, "reference_element": self.reference,
                       "measuring_element": self.measuring, "kr_over_km": self.ratio,
                       "error_estimate_rel": self.error_rel,
                       "margin_rel": self.ratio / target - 1.0}, threshold_rel)


def row_pairs(plan: Plan, fig: Figures) -> list[RowPair]:
    """Per reference (:attr:`~tactcad.design.array_plan.Plan.references`: each row's, or
    each column's with pairing "column") over the softest element read against it (its
    smallest K_r / K_m); a reference read by no other element pairs with itself (ratio 1)."""
    out = []
    for number in plan.references:
        ref = plan.element(number)
        others = [s for s in plan.slots
                  if s.number != number and plan.reference_for(s).number == number] or [ref]
        soft = min(others, key=lambda s: (fig.k_of(s.number), s.number))
        out.append(RowPair(ref.row, ref.number, soft.number, fig.k_of(ref.number) / fig.k_of(soft.number),
                           fig.k_error[ref.geometry.part_name],
                           fig.k_error[soft.geometry.part_name],
                           ref.column if plan.pairing == "column" else None))
    return out


@dataclass(frozen=True)
class SensingUnits:
    """The design's sensing units at one level, each read through the design's read-out
    chain (:mod:`tactcad.mechanics.readout_chain`): every element softer than its row's
    reference measures against it (:func:`tactcad.mechanics.readout_chain.row_units`).

    Attributes:
        read: one :class:`~tactcad.mechanics.resolution.ReadUnit` per unit (K and force
            resolution of reference and measuring element; N/mm, N).
        errors: per unit, the level's K error estimate of (reference, measuring element).
        force_resolution_N: per element number, its force resolution (N, 1 sigma).
        strain_error_rel: the largest relative error of the grid strain any unit's element
            reads at the level (:func:`tactcad.mechanics.readout_chain.grid_strain_error_rel`):
            each force resolution is the reading's noise over that strain, so a strain
            read e low leaves it up to 1 / (1 - e) coarser.
    """

    read: tuple
    errors: tuple
    force_resolution_N: dict
    strain_error_rel: float = 0.0

    def noise_factors(self) -> tuple[float, ...]:
        """The factors the grid strains' error can scale every K_obj resolution of the units
        by, (1 / (1 + e), 1 / (1 - e)) for e = :attr:`strain_error_rel`: a unit's resolution
        is proportional to its two elements' force resolutions together (the hypot of their
        deflection resolutions, :func:`tactcad.mechanics.resolution.ratio_noise`) and rises
        with each, so each element's strain moved by at most e keeps it within these factors
        of the stated one. (inf,) when e >= 1 (a strain that may be nil bounds nothing)."""
        e = self.strain_error_rel
        if not e < 1.0:
            return (math.inf,)
        return (1.0 / (1.0 + e), 1.0 / (1.0 - e))

    def shifted_by_error(self, sign_r: int, sign_m: int) -> list:
        """The units with every reference's K moved by ``sign_r`` x its error and every
        measuring element's by ``sign_m`` x its error."""
        return [u._replace(k_r=u.k_r * (1 + sign_r * er), k_m=u.k_m * (1 + sign_m * em))
                for u, (er, em) in zip(self.read, self.errors)]


def sensing_units(plan: Plan, fig: Figures) -> SensingUnits:
    """The units of ``plan`` with the K of ``fig``'s level, each element's force
    resolution through the read-out chain at that level (a FEM level reads the gauge
    strain off its own solves) and the largest error of those grid strains. A part whose
    figures were kept from a lower level (:attr:`Figures.kept_from`) has its force
    resolution read at that level too, beside the K it carries from there: the level does
    not solve it (at fem3d two mesh sequences a part, the bare and the layered element);
    a level whose stresses no open requirement reads (:attr:`Figures.grids_from`) reads
    every part's at the closed form.

    Raises:
        UnknownModelError: ``fig.model`` is not a ladder level.
    """
    from tactcad.mechanics.readout_chain import force_resolution_reads, row_units
    from tactcad.mechanics.resolution import ReadUnit

    reads = {}
    for level in dict.fromkeys(fig.grid_level_of(part) for part in plan.distinct_elements):
        parts = [part for part in plan.distinct_elements if fig.grid_level_of(part) == level]
        reads.update(force_resolution_reads(plan, level, parts=parts))
    read, errors, strain_errors = [], [], [0.0]
    for ref, meas in row_units(plan, fig.k):
        r, m = ref.geometry.part_name, meas.geometry.part_name
        read.append(ReadUnit(fig.k[r], reads[r]["dF"], fig.k[m], reads[m]["dF"]))
        errors.append((fig.k_error[r], fig.k_error[m]))
        strain_errors += [reads[r]["strain_error_rel"], reads[m]["strain_error_rel"]]
    return SensingUnits(tuple(read), tuple(errors),
                        {s.number: reads[s.geometry.part_name]["dF"] for s in plan.slots},
                        max(strain_errors))


def worst_resolution(units: SensingUnits, rng, force_N: float) -> float:
    """The array's worst relative K_obj resolution over ``rng`` (N/mm) at ``force_N`` (N)."""
    from tactcad.mechanics.resolution import worst_resolution_rel

    return worst_resolution_rel(units.read, rng, force_N)


def resolution_error_rel(units: SensingUnits, rng, force_N: float) -> float:
    """The worst K_obj resolution's relative error (:func:`worst_and_error`'s second value).
    """
    return worst_and_error(units, rng, force_N)[1]


def readable_range(units: SensingUnits, rng, force_N, target_rel) -> tuple[float, float] | None:
    """The widest K_obj interval around the range's geometric mean where the
    resolution is at most ``target_rel`` (N/mm), or None when the mean is not."""
    from tactcad.mechanics.resolution import best_unit_resolution_rel, reads_within

    lo, hi = rng
    centre = math.sqrt(lo * hi)
    grid = np.geomspace(lo / KOBJ_SEARCH_FACTOR, hi * KOBJ_SEARCH_FACTOR, 801)
    grid = np.unique(np.append(grid, [lo, hi, centre]))
    ok = reads_within(best_unit_resolution_rel(units.read, grid, force_N), target_rel)
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


#: Derived requirement values are written this much beyond margin + error, so
#: that rounding cannot leave a margin a hair inside the error.
ROOM_BEYOND_ERROR = 1e-6

#: The K_obj resolution written when no element is softer than its reference (none can be
#: read): the largest ``requirements.kobj_resolution_rel`` allows.
UNREADABLE_RESOLUTION_REL = 10.0


def worst_and_error(units: SensingUnits, rng, force_N: float,
                    kept: dict | None = None) -> tuple[float, float]:
    """(:func:`worst_resolution`, :func:`resolution_error_rel`) of ``units`` over ``rng``
    (N/mm) at ``force_N`` (N), the worst worked out once for both; ``kept``: answers already
    found for these units (by range and force), where one verification matrix asks for the
    derived requirement and for its record.

    Args:
        units: the sensing units. rng: (low, high) K_obj (N/mm). force_N: the force (N).
        kept: a dict of answers for these same ``units``, filled here; None: none kept.

    Returns:
        (the worst relative resolution, its relative error: its largest change with each
        K moved by its own error, every sign combination, and every force resolution by
        the grid strains' error (:meth:`SensingUnits.noise_factors`); inf where a move by
        the K errors leaves a unit unreadable: its measuring element as stiff as its
        reference or stiffer, where eq. 2 has no answer).
    """
    from tactcad.mechanics.resolution import worst_resolution_rel

    key = (tuple(float(v) for v in rng), float(force_N))
    if kept is not None and key in kept:
        return kept[key]
    worst = worst_resolution(units, rng, force_N)
    moved = [worst] + [worst_resolution_rel(units.shifted_by_error(sr, sm), rng, force_N)
                       for sr in (-1, 1) for sm in (-1, 1)]
    factors = units.noise_factors()
    error = math.inf if not all(math.isfinite(w) for w in [*moved, *factors]) else \
        max(abs(w * f / worst - 1.0) for w in moved for f in (1.0, *factors))
    if kept is not None:
        kept[key] = (worst, error)
    return worst, error


def kobj_resolution_requirement(units: SensingUnits, rng, force_N: float,
                                kept: dict | None = None) -> tuple[float, float]:
    """(requirement, worst) of the K_obj resolution a design reaches: the worst over ``rng``
    (N/mm) at ``force_N`` (N), each element read through the design's own read-out chain,
    padded by its error estimate and rounded up, so that the level it was derived at
    decides it (its margin clears its error); :data:`UNREADABLE_RESOLUTION_REL` and inf
    without a unit. The value may exceed what a design may state (the search refuses it
    as the force that set it); ``kept``: as :func:`worst_and_error`'s."""
    if not units.read:
        return UNREADABLE_RESOLUTION_REL, math.inf
    worst, error = worst_and_error(units, rng, force_N, kept)
    padded = worst * (1.0 + error) * (1.0 + ROOM_BEYOND_ERROR)
    return round_up(padded), worst


#: The smallest K band a derived requirement states (a design without web tolerance).
MIN_K_BAND_REL = 1e-3


def k_band_requirement(plan: Plan) -> tuple[float, float]:
    """(requirement, band) of the K band over the web tolerance (:func:`web_band_rel`):
    :func:`padded_band_requirement` of it."""
    band = web_band_rel(plan)
    return padded_band_requirement(band, closed_form_k_error(plan)), band


def padded_band_requirement(band: float, error: float) -> float:
    """A K band requirement derived from a relative ``band``: at least
    :data:`MIN_K_BAND_REL`, padded by the K ``error`` and rounded up, so that the closed
    form decides it."""
    return round_up(max(band, MIN_K_BAND_REL) * (1.0 + error) * (1.0 + ROOM_BEYOND_ERROR))


def smallest_row_ratio(plan: Plan, fig: Figures) -> float:
    """The smallest K_r / K_m over the rows' pairs (:func:`row_pairs`): the rule the
    ``kr_over_km`` record checks, so a derived target is derived by it."""
    return min(q.ratio for q in row_pairs(plan, fig))


# ---------------------------------------------------------------------------
# The requirements
# ---------------------------------------------------------------------------
def requirements_of(plan: Plan, figures: Figures | None = None,
                    k_band: tuple[float, float] | None = None,
                    units: SensingUnits | None = None,
                    kept: dict | None = None) -> Requirements:
    """The design's requirements: stated values from ``[requirements]``,
    the rest derived from its nominal geometry (corrected closed form) with
    the reason (see the module docstring). Worked out once per plan when no
    ``figures`` are handed in (an export's manifest, drawings and budget all ask).

    Args:
        plan: the validated design.
        figures: the closed form's :func:`element_figures`, when the caller has them.
        k_band: (:func:`web_band_rel`, :func:`closed_form_k_error`) of ``plan``, when the
            caller has them (only read with ``figures``).
        units, kept: :func:`sensing_units` of ``plan`` at ``figures``' level and the
            resolutions found for them (:func:`worst_and_error`), where the caller has
            them (only read with closed-form ``figures``).

    Returns:
        the :class:`Requirements` (shared: read them, do not change them).

    Raises:
        DesignError: the material has no yield strength.
    """
    if figures is None:
        return _plan_requirements(plan)
    return _requirements_from(plan, figures, k_band, units, kept)


@kept_per_process(maxsize=8)
def _plan_requirements(plan: Plan) -> Requirements:
    """:func:`requirements_of` without figures, kept per plan (the plan's design hash is
    part of its equality, so an edited design is another entry)."""
    return _requirements_from(plan, None)


def _requirements_from(plan: Plan, figures: Figures | None,
                       k_band: tuple[float, float] | None = None,
                       units: SensingUnits | None = None,
                       kept: dict | None = None) -> Requirements:
    """:func:`requirements_of` worked out (``k_band``: the web band and the closed form's
    K error, ``units`` and ``kept``: the closed form's sensing units and their resolutions,
    where already worked out)."""
    from tactcad.mechanics.limits import LIMIT_WORDS, binding, plan_limits

    stated = stated_requirements(plan.raw)
    derived = derived_requirements(plan.raw)  # written by tactcad design, not the lab's
    if "k_tolerance_rel" in derived:
        # an earlier tactcad design wrote its own K band: not a requirement, read as unstated
        del stated["k_tolerance_rel"], derived["k_tolerance_rel"]
    fig = figures if figures is not None and figures.model == "closed-form" \
        else element_figures(plan, "closed-form")
    if fig is not figures:  # units read at another level are not the closed form's
        units, kept = None, None
    values: dict[str, Any] = dict(stated)
    reasons = {k: guards_later_edits(derived[k]) if k in derived else "stated in the design file"
               for k in stated}
    if "full_scale_force_N" not in values:
        b = binding(plan_limits(plan, "closed-form", fig.stresses, fig.k_error))
        values["full_scale_force_N"] = round_down(b.force_N)
        reasons["full_scale_force_N"] = (
            f"not stated: the largest force every element carries, {b.force_N:.4g} N, bound by "
            f"{LIMIT_WORDS[b.limit]} (element {b.element}, closed form), rounded down")
    if "kr_over_km" not in values:
        ratio = smallest_row_ratio(plan, fig)
        values["kr_over_km"] = round_down(ratio) if ratio > 1 else 1.0
        reasons["kr_over_km"] = (f"not stated: the smallest row's reference over its softest "
                                 f"measuring element, {ratio:.4g} (closed form), rounded down")
    if "kobj_range_N_per_mm" not in values:
        ks = [fig.k_of(s.number) for s in plan.slots]
        values["kobj_range_N_per_mm"] = (_clean(min(ks)), _clean(max(ks)))
        reasons["kobj_range_N_per_mm"] = (
            "not stated: the elements' own stiffness span (closed form); eq. 2 reads best "
            "where the elements straddle the object")
    if "k_tolerance_rel" not in values:
        values["k_tolerance_rel"], band = k_band_requirement(plan) if k_band is None else \
            (padded_band_requirement(*k_band), k_band[0])
        reasons["k_tolerance_rel"] = (f"not stated: reported, not judged: the largest K "
                                      f"change over the web tolerance is {100 * band:.3g} % "
                                      f"(closed form); the row's reference is that band "
                                      f"padded by its error and rounded up, so it cannot fail: "
                                      f"state the band your use needs to judge it")
    if "kobj_resolution_rel" not in values:
        values["kobj_resolution_rel"], reasons["kobj_resolution_rel"] = \
            derived_kobj_resolution(plan, fig, values["kobj_range_N_per_mm"],
                                    values["full_scale_force_N"], units, kept)
    band = stated_number(plan.raw, "kr_over_km_tolerance_rel")
    reasons["kr_over_km_tolerance_rel"] = "stated in the design file" if band is not None else (
        f"not stated: {100 * KR_OVER_KM_BAND_REL:g} %, a K_r/K_m 'about' its target, as a "
        f"sensing unit's ratio is specified")
    band = KR_OVER_KM_BAND_REL if band is None else band
    return Requirements(
        full_scale_force_N=float(values["full_scale_force_N"]),
        kr_over_km_tolerance_rel=float(band),
        kobj_range_N_per_mm=tuple(float(v) for v in values["kobj_range_N_per_mm"]),
        kr_over_km=float(values["kr_over_km"]), k_tolerance_rel=float(values["k_tolerance_rel"]),
        kobj_resolution_rel=float(values["kobj_resolution_rel"]),
        reasons={k: reasons[k] for k in (*REQUIREMENT_KEYS, "kr_over_km_tolerance_rel")},
        stated=frozenset(stated) - frozenset(derived), written=frozenset(stated),
        source=requirements_source(plan.raw), cites_paper=cites_paper(plan.raw),
        footprint_mm=stated_footprint(plan.raw))


#: What a reason a design file marks as ``tactcad design``'s own
#: (:data:`~tactcad.design.requirements_section.DERIVED_BY_DESIGN`) is followed by in
#: ``verify``: the value stays judged.
GUARDS_LATER_EDITS = ("judged as the design file gives it: it guards later edits of the "
                      "design against reaching less than the design reached")


def guards_later_edits(reason: str) -> str:
    """The reason ``verify`` gives a requirement value ``tactcad design`` wrote into the
    design file from its own prediction: the file's reason, then
    :data:`GUARDS_LATER_EDITS` (the value is judged, unlike one derived anew).

    Args:
        reason: the file's reason (under ``[assumptions]``).

    Returns:
        The reason, in words.
    """
    return f"{reason.rstrip().rstrip('.')}; {GUARDS_LATER_EDITS}"


def derived_kobj_resolution(plan: Plan, fig: Figures, rng, force_N: float,
                            units: SensingUnits | None = None,
                            kept: dict | None = None) -> tuple[float, str]:
    """The K_obj resolution requirement a design file leaves out and its reason: what the
    design's own read-out chain reaches (:func:`kobj_resolution_requirement`), at most
    :data:`UNREADABLE_RESOLUTION_REL`, the largest a design may state (a design that reads
    worse fails it: its full-scale force is too small for its read-out chain). ``units``:
    :func:`sensing_units` of ``plan`` and ``fig`` where already worked out; ``kept``: as
    :func:`worst_and_error`'s."""
    units = sensing_units(plan, fig) if units is None else units
    padded, worst = kobj_resolution_requirement(units, rng, force_N, kept)
    value = min(padded, UNREADABLE_RESOLUTION_REL)
    if not math.isfinite(worst):
        return value, ("not stated: no element is softer than its row's reference, so no K_obj "
                       "can be read")
    forces = units.force_resolution_N.values()
    why = ("a measuring element's K within its error may reach its reference's, where eq. 2 "
           "has no answer" if math.isinf(padded) else
           "the full-scale force is too small for the read-out chain")
    return value, (f"not stated: the worst K_obj resolution over the range at the full-scale "
                   f"force, {100 * worst:.3g} % ({fig.model}, each element read through the "
                   f"design's [readout] chain to {1e3 * min(forces):.3g}-{1e3 * max(forces):.3g} "
                   f"mN), padded by its error and rounded up"
                   + ("; reported, not judged: derived from the prediction it would be tested "
                      "against, it cannot fail: state the resolution your use needs to judge "
                      "it" if value < UNREADABLE_RESOLUTION_REL else
                      f", at most {UNREADABLE_RESOLUTION_REL:g} (the largest a design may state: "
                      f"{why})"))


#: The rows of the K band over the tolerances, reported, not judged, where the design file
#: states no ``k_tolerance_rel``.
K_BAND_ROWS = ("k_tolerance_rel", "k_tolerance_rel_toleranced")


def informational_requirements(req: Requirements) -> frozenset[str]:
    """The matrix rows reported, not judged (:func:`reported_not_judged`: verdict ``info``,
    no target, no margin): the design's own figures, which no prediction can fail.

    * the K band rows (:data:`K_BAND_ROWS`) where the design file gives no
      ``k_tolerance_rel`` (or an earlier ``tactcad design`` wrote its own band's, read as
      not stated): their reference is the design's own band, padded;
    * ``kobj_resolution_rel`` where the design file gives none: derived from the very
      prediction the row tests (:func:`derived_kobj_resolution`, padded by its error), unless
      the derivation stopped at :data:`UNREADABLE_RESOLUTION_REL`, the largest a design may
      state, which a design reading worse fails (judged).

    A value the design file carries is judged, even one ``tactcad design`` wrote from its
    own prediction (marked under ``[assumptions]``): it guards later edits.

    Args:
        req: the design's :func:`requirements_of`.

    Returns:
        The requirement names of the rows shown as INFO.
    """
    out = set()
    if "k_tolerance_rel" not in req.written:
        out.update(K_BAND_ROWS)
    if "kobj_resolution_rel" not in req.written \
            and req.kobj_resolution_rel < UNREADABLE_RESOLUTION_REL:
        out.add("kobj_resolution_rel")
    return frozenset(out)


#: The requirements on reading K_obj (eq. 3), which apply where a row has a measuring element.
KOBJ_KEYS = frozenset({"kobj_resolution_rel", "kobj_range_N_per_mm"})


def kobj_records(units: SensingUnits, req: Requirements, force_N: float, model: str,
                 kept: dict | None = None) -> list[dict]:
    """The records of :data:`KOBJ_KEYS`: the worst relative K_obj resolution over the
    required range and the range read within the required resolution, each element read
    through the design's read-out chain at ``force_N`` (N); none read (no measuring
    element) fails both. ``kept``: as :func:`worst_and_error`'s."""
    rng = req.kobj_range_N_per_mm
    if units.read:
        worst, res_err = worst_and_error(units, rng, force_N, kept)
        span = readable_range(units, rng, force_N, req.kobj_resolution_rel)
        span_err = readable_range_error_rel(units, rng, force_N, req.kobj_resolution_rel, span)
    else:
        worst, res_err, span, span_err = math.inf, 0.0, None, 0.0
    m_rng = min(rng[0] / span[0], span[1] / rng[1]) - 1.0 if span else -1.0
    return [_record("kobj_resolution_rel", req.kobj_resolution_rel, _finite_or_none(worst),
                    res_err, req.kobj_resolution_rel / worst - 1.0, model,
                    worst <= req.kobj_resolution_rel,
                    force_resolution_N={str(n): f for n, f in units.force_resolution_N.items()},
                    basis=READOUT_BASIS),
            _record("kobj_range_N_per_mm", list(rng), list(span) if span else None, span_err,
                    m_rng, model, m_rng >= 0)]


def readable_range_error_rel(units: SensingUnits, rng, force_N: float, target_rel: float,
                             span: tuple[float, float] | None) -> float:
    """How far the K errors of the references and the measuring elements and the grid
    strains' error can move the K_obj range record's margin towards its verdict's edge:
    each K moved by its own error, every sign combination (as :func:`worst_and_error`
    moves them), with every resolution scaled by the strains' factor that narrows the
    readable range where it is met and widens it where it is not
    (:meth:`SensingUnits.noise_factors`; a resolution scaled by f reads within the target
    where the stated one reads within the target over f); the largest fall of the margin
    (``min(lo / a, b / hi) - 1`` of the readable range ``(a, b)``) where it is met, the
    largest rise where it is not; inf when a move leaves the range's centre unread. The
    range's margin is then decided exactly where every such move keeps its sign.

    Args:
        units: the sensing units. rng: the required (low, high) K_obj (N/mm).
        force_N: the force (N). target_rel: the resolution the range is read within.
        span: :func:`readable_range` of ``units`` (None: none read, error 0: the record
            fails whatever the K).

    Returns:
        The relative error (dimensionless, >= 0, or inf).
    """
    if span is None:
        return 0.0
    lo, hi = rng
    margin = min(lo / span[0], span[1] / hi) - 1.0
    factors = units.noise_factors()
    if not all(math.isfinite(f) for f in factors):
        return math.inf
    adverse = max(factors) if margin >= 0 else min(factors)  # towards the verdict's edge
    moves = [units.read] + [tuple(units.shifted_by_error(sr, sm))
                            for sr in (-1, 1) for sm in (-1, 1)]
    worst = 0.0
    for read in moves:
        moved = readable_range(_replaced(units, read=read), rng, force_N, target_rel / adverse)
        if moved is None:
            return math.inf
        change = min(lo / moved[0], moved[1] / hi) - 1.0 - margin
        worst = max(worst, -change if margin >= 0 else change)
    return worst


def rated_full_scale_force(plan: Plan) -> float:
    """The design's rated full-scale force (N), the one force every command,
    drawing and page calls full scale: ``[requirements] full_scale_force_N``,
    derived from the elements' limits when absent (:func:`requirements_of`).

    Raises:
        DesignError: the material has no yield strength.
    """
    return requirements_of(plan).full_scale_force_N


def calibration_full_scale_force(plan: Plan) -> float | None:
    """The force (N) a static calibration's Z steps load each element to: None for the
    paper's own design (a design file citing the paper: the paper's 25 um steps to 150 um,
    :data:`tactcad.mechanics.calibration.CALIBRATION_STEPS_UM`), else the rated full-scale
    force (:func:`rated_full_scale_force`). ``calibrate`` and the K_obj budget both read it
    (:func:`calibration_gauge`).

    Raises:
        DesignError: the material has no yield strength.
    """
    return None if cites_paper(plan.raw) else rated_full_scale_force(plan)


def calibration_gauge(plan: Plan):
    """The calibration rig: the force gauge in series with each element, where it comes
    from, and the force its Z steps load each element to (:func:`calibration_full_scale_force`).
    The gauge is the project's rigs' own (``plan.rigs_force_gauge``, set where the project is
    loaded with its rigs), or, for a plan without rigs (a comb or a stacked array for a
    grasper's jaw, a plan made in code), the catalogue gauge that leaves the smallest
    expected calibration error (:func:`catalogue_calibration_gauge`). ``calibrate`` and every
    caller of the K_obj budget read this one rig, so the budget's calibration term is that
    of the steps ``calibrate`` drives.

    Args:
        plan: the design.

    Returns:
        :class:`tactcad.mechanics.calibration.CalibrationGauge`: ``gauge`` (``model``,
        ``range_N``, ``resolution_N`` (N), ``stiffness_N_per_mm`` (N/mm)), ``source`` (in
        words), ``full_scale_force_N`` (N, or None for the paper's steps).

    Raises:
        DesignError: the material has no yield strength.
    """
    from tactcad.mechanics.calibration import CalibrationGauge

    force = calibration_full_scale_force(plan)
    if plan.rigs_force_gauge is not None:
        return CalibrationGauge(plan.rigs_force_gauge, "the design's rigs ([force_gauge])", force)
    gauge, why = catalogue_calibration_gauge(plan)
    return CalibrationGauge(gauge, f"{why}: the project has no rigs; a data file's "
                                   f"k_sensor_N_per_mm overrides it", force)


@kept_per_process(maxsize=8)
def catalogue_calibration_gauge(plan: Plan) -> tuple[Any, str]:
    """The catalogue force gauge a design without rigs is calibrated on: of those whose range
    holds the largest force the calibration reads (the rated full-scale force, or the force
    the paper's steps reach), the one that leaves the smallest expected calibration error,
    the largest over the design's elements of σ_K/K and σ_K_v/|K_v| in quadrature
    (:func:`tactcad.in_use.kobj_budget.calibration_stderr_by_part` at the closed form, each
    at the steps a calibration on that gauge drives); of equal errors the smaller range.

    A gauge's resolution share of the rated force alone does not decide it: a stiff element
    on a soft gauge leaves the element a small share of the Z travel, so the force's
    resolution, amplified by 1 + K/K_s, dominates the fit (short full-scale travels of a
    stiff, low-force design), and a stiffer gauge of coarser resolution can leave less.
    Kept per plan (a plan's equality includes its design hash).

    Args:
        plan: the design (without rigs).

    Returns:
        (the gauge, why it, in words).

    Raises:
        DesignError: the material has no yield strength.
    """
    from tactcad.in_use.kobj_budget import calibration_stderr_by_part
    from tactcad.mechanics.calibration import CalibrationGauge, apparent_stiffness
    from tactcad.mechanics.ladder import estimate
    from tactcad.mechanics.readout_chain import element_force_resolution_N
    from tactcad.vocabulary.force_gauge_catalogue import (calibration_gauge_need,
                                                          choose_force_gauge, force_gauges)

    rated = rated_full_scale_force(plan)
    force = calibration_full_scale_force(plan)
    k = {n: estimate("closed-form", g, plan.material).stiffness_N_per_mm
         for n, g in plan.distinct_elements.items()}
    readout = element_force_resolution_N(plan, "closed-form")
    scored = []
    for gauge in force_gauges():
        rig = CalibrationGauge(gauge, "", force)
        reach = max(apparent_stiffness(kk, gauge.stiffness_N_per_mm) * rig.steps_um(kk)[-1]
                    * 1e-3 for kk in k.values())
        if gauge.range_N < max(rated, reach) * (1 - 1e-9):
            continue
        se = calibration_stderr_by_part(plan, "closed-form", k, rig, readout=readout)
        scored.append((max(math.hypot(*v) for v in se.values()), gauge.range_N, gauge))
    if not scored:
        gauge, _ = choose_force_gauge(calibration_gauge_need(rated))
        return gauge, (f"no catalogue gauge's range holds the calibration's force; the "
                       f"largest, {gauge.range_N:g} N")
    scored.sort(key=lambda t: (t[0], t[1]))
    error, _, gauge = scored[0]
    runner = (f"; the next best, {scored[1][2].model}, {100 * scored[1][0]:.3g} %"
              if len(scored) > 1 else "")
    return gauge, (f"of the catalogue gauges whose range holds the calibration's force, the one "
                   f"that leaves the least expected calibration error (sigma_K/K and "
                   f"sigma_Kv/|Kv| in quadrature, worst element): {100 * error:.3g} %{runner}")


# ---------------------------------------------------------------------------
# The verification matrix
# ---------------------------------------------------------------------------
def _finite_or_none(x: float | None) -> float | None:
    return float(x) if x is not None and math.isfinite(x) else None


def _record(requirement: str, target, predicted, error: float, margin: float, model: str,
            passed: bool, **extra) -> dict:
    return {"requirement": requirement, "target": target, "predicted": predicted,
            "error_estimate_rel": _finite_or_none(error), "margin_rel": _finite_or_none(margin),
            "model": model, "pass": bool(passed), **extra}


def verification_matrix(plan: Plan, model: str = "closed-form",
                        progress: Callable[[str], None] | None = None,
                        requirements: Requirements | None = None,
                        stress: Callable | None = None,
                        envelope_mm: Sequence[float] | None = None,
                        below: Figures | None = None, keep: Collection[str] = (),
                        figures_made: list | None = None, reported: bool = True,
                        keep_strength: Collection[str] = ()) -> list[dict]:
    """One record per requirement, evaluated at ``model``.

    margin_rel: predicted / target - 1 for a lower bound (full-scale force,
    K_r/K_m), target / predicted - 1 for an upper bound (K band, K_obj
    resolution), the smaller end ratio - 1 for the readable K_obj range;
    positive means met. K_r / K_m passes within the K band the requirements
    allow (margin >= -k_tolerance_rel); the others pass with margin >= 0.
    The full-scale-force record lists every limit (``limits``) and the one
    that binds (``binding_limit``). The rows of :func:`informational_requirements` (the two
    K band records where the design file gives no ``k_tolerance_rel``, the K_obj resolution
    where it gives none) are the design's own figures, not requirements:
    :func:`reported_not_judged` (verdict ``info``, ``pass``, ``target`` and ``margin_rel``
    None, shown as INFO), the web band's with a ``note`` (:func:`k_spread_note`) when K
    spreads beyond :data:`K_SPREAD_NOTE_REL`. ``stress``: as :func:`element_figures`
    (an FEM level needs :func:`tactcad.studies.strength_studies.element_stress`).
    ``below``, ``keep``: as :func:`element_figures`: the parts named in ``keep`` keep a lower
    level's figures and limits (with its errors); each listed limit then says its ``level``
    and the full-scale record its ``element_levels`` (part -> level). ``keep_strength``:
    as :func:`element_figures` (K at ``model``, the limits ``below``'s, said alike).
    ``figures_made``: a list the level's :class:`Figures` is appended to (for the next
    level's ``below``).
    ``reported`` False leaves out what is reported and never judged: where the design states
    no ``k_tolerance_rel``, the Monte Carlo K band record and the spread note (a search that
    reads the verdicts alone, as the comb's candidates and the atlas's points, needs
    neither; about two thirds of a closed-form matrix).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
        DesignError: the material has no yield strength.
    """
    from tactcad.mechanics.limits import LIMIT_WORDS, binding, per_kind_binding

    fig = element_figures(plan, model, progress, stress, below, keep, keep_strength)
    if figures_made is not None:
        figures_made.append(fig)
    # the web band and K error, read by the derived K band requirement as well: once
    band, error = web_band_rel(plan), closed_form_k_error(plan)
    # the units and their resolutions, read by the derived K_obj resolution as well: once
    units, kept = sensing_units(plan, fig), {}
    req = requirements or requirements_of(plan, fig, k_band=(band, error), units=units,
                                          kept=kept)
    out = []
    lims = figures_limits(plan, fig)
    b = binding(lims)
    kinds = per_kind_binding(lims)
    F = req.full_scale_force_N
    # a part kept from a lower level: each limit and the record say which level made it
    levels = ({part: fig.level_of(part) for part in plan.distinct_elements}
              if fig.kept_from else None)
    out.append(_record("full_scale_force_N", F, b.force_N, b.error_estimate_rel,
                       b.force_N / F - 1.0, model, b.force_N >= F,
                       binding_limit=b.limit, binding_words=LIMIT_WORDS[b.limit],
                       binding_element=b.element,
                       limits=[{**lim.as_json(lim is b),
                                **({"level": levels[lim.part_name]} if levels else {})}
                               for lim in kinds.values()],
                       **({"element_levels": levels} if levels else {})))
    out.append(kr_over_km_record(row_pairs(plan, fig), req, model))
    out.append(_record("k_tolerance_rel", req.k_tolerance_rel, band, error,
                       req.k_tolerance_rel / band - 1.0 if band > 0 else math.inf,
                       "closed-form", band <= req.k_tolerance_rel))
    if units.read or KOBJ_KEYS & req.written:
        out.extend(kobj_records(units, req, F, model, kept))
    # else: no row has an element softer than its reference, so the design reads no K_obj
    # and states no K_obj target: there is nothing of K_obj to verify (derived, none applies)
    from tactcad.studies.tolerance_budget import toleranced_band_record

    derive = None if "k_tolerance_rel" in req.written else \
        (lambda band: padded_band_requirement(band, error))
    if reported or derive is None:
        out.append(toleranced_band_record(plan, req.k_tolerance_rel, error, derive))
    # not stated: the design's own figures, reported, never judged (verdict info)
    unjudged = informational_requirements(req)
    out = [reported_not_judged(r) if r["requirement"] in unjudged else r for r in out]
    if derive is not None:
        note = k_spread_note(plan, req) if reported else None
        if note:  # once, on the web band's row
            next(r for r in out if r["requirement"] == "k_tolerance_rel")["note"] = note
    if req.footprint_mm is not None:
        if envelope_mm is None:
            raise ValueError("the design states requirements.footprint_mm: pass the array's "
                             "envelope (tactcad.assembly.inventory.array_envelope_mm)")
        from tactcad.design.tolerances import tolerances_of

        out.append(footprint_record(req.footprint_mm, envelope_mm, tolerances_of(plan.raw).general))
    out.extend(resonance_records(plan, model, progress))
    out.extend(r for r in [thermal_record(plan, fig, req)] if r is not None)
    out.append(grid_power_density_record(plan))
    out += crosstalk_records(plan, F, units.force_resolution_N)
    budget = accuracy_budget(plan, fig, req)
    out.extend(r for r in [kobj_accuracy_record(plan, fig, req, budget),
                           tip_height_tolerance_record(plan, fig, budget)] if r is not None)
    out.extend(r for r in [max_grasp_force_record(plan, fig, req)] if r is not None)
    for r in out:
        r["stated"] = r["requirement"] in req.stated
        # the K band is the closed form's derivative at every level: no level decides it anew
        r["level_fixed"] = r["model"] != model or r["requirement"] in LEVEL_FIXED
        if "verdict" not in r:  # a record with a rule of its own states its verdict
            r["verdict"] = verdict(r["margin_rel"], r["error_estimate_rel"],
                                   r.get("allowed_margin_rel", 0.0), r["pass"])
        r["pass"] = passed_flag(r["verdict"])
    return out


def passed_flag(said: str) -> bool | None:
    """The ``pass`` (and ``met``) key of a judged record: True only for the verdict ``pass``,
    False for ``fail`` and ``undecided`` (a margin inside the level's error is not a pass),
    None for a row reported, not judged (verdict ``info``). One rule for every output with
    such a key (verify's records, the manifest's ``closed_form_matrix`` and
    ``full_scale_force.met``, ``strength --json``'s ``met``); ``verdict`` says which.

    Args:
        said: the record's verdict (:data:`tactcad.mechanics.verdicts.VERDICTS` or ``info``).

    Returns:
        True, False or None.
    """
    return None if said == INFO else said == "pass"


#: The verification row of the gauge grid's power density (TN-502).
GRID_POWER_REQUIREMENT = "grid_power_density_W_per_mm2"


def grid_power_density_verdict(density_W_per_mm2: float, grid_rise_K: float,
                               accepted_W_per_mm2: float | None = None) -> str:
    """The verdict on a gauge's excitation by Micro-Measurements TN-502.

    TN-502's power densities are guidance on self-heating (an offset that warms up and is
    tared, zero stability spent), not a strength limit: a lab may accept more
    (``requirements.grid_power_density_W_per_mm2``); the grid's rise past the backing's
    derating fails whatever it accepts.

    Args:
        density_W_per_mm2: the grid's power density (W/mm^2).
        grid_rise_K: the grid's temperature rise above the element (K).
        accepted_W_per_mm2: the density the design states it accepts (W/mm^2), or None.

    Returns:
        ``fail`` when the grid runs more than
        :data:`~tactcad.design.readout_section.TN502_HIGH_EXCITATION_DERATING_K` above the
        element (past the largest backing derating TN-502 names for high excitation) or above
        the density the design accepts; ``pass`` within that density, or, when the design
        states none, within TN-502's thin-section guidance (at most 2 W/in^2, the sections
        these webs are); otherwise ``undecided`` (above the guidance, which the design has
        not said it accepts; whether the element sinks the heat as a heavier section would is
        not modelled).
    """
    from tactcad.design.readout_section import (TN502_HIGH_EXCITATION_DERATING_K,
                                                TN502_THIN_SECTION_W_PER_MM2)

    if grid_rise_K > TN502_HIGH_EXCITATION_DERATING_K:
        return "fail"
    if accepted_W_per_mm2 is not None:
        return "pass" if density_W_per_mm2 <= accepted_W_per_mm2 * (1 + 1e-9) else "fail"
    if density_W_per_mm2 <= TN502_THIN_SECTION_W_PER_MM2[1] * (1 + 1e-9):
        return "pass"
    return "undecided"


def grid_power_density_record(plan: Plan) -> dict:
    """The gauge's excitation against Micro-Measurements TN-502 ("Optimizing Strain Gage
    Excitation Levels"), for every design read through a bonded foil gauge.

    The quarter-bridge grid dissipates V_ex^2 / (4 R_g) over its area and warms above the
    element by that power over the grid-to-element heat transfer
    (:func:`tactcad.mechanics.thermal_drift.self_heating_K`, what ``tactcad thermal`` prints).
    Target: the density the design accepts (``requirements.grid_power_density_W_per_mm2``),
    else TN-502's top for thin sections, 2 W/in^2; margin target / density - 1; the verdict
    is :func:`grid_power_density_verdict`'s (the rise decides a failure). Exact in the chain's
    values and the same at every level: no error estimate (None); an ``undecided`` verdict is
    the band between the guidance and the failure, not a margin inside an error.

    Args:
        plan: the design.

    Returns:
        The record: ``predicted`` the grid's power density (W/mm^2), ``grid_rise_K`` and its
        limit ``grid_rise_limit_K`` (K), ``excitation_V`` (V), ``guidance_W_per_mm2``
        (TN-502's), ``basis`` the sources.
    """
    from tactcad.design.readout_section import (TN502_HIGH_EXCITATION_DERATING_K,
                                                TN502_THIN_SECTION_W_PER_MM2)
    from tactcad.design.requirements_section import stated_grid_power_density
    from tactcad.mechanics.readout_chain import readout_chain
    from tactcad.mechanics.thermal_drift import self_heating_K

    chain = readout_chain(plan)
    density = chain.grid_power_density_W_per_mm2
    _, rise = self_heating_K(chain)
    guidance = TN502_THIN_SECTION_W_PER_MM2[1]
    accepted = stated_grid_power_density(plan.raw)
    target = guidance if accepted is None else accepted
    said = grid_power_density_verdict(density, rise, accepted)
    why = (f"the design accepts {645.16 * accepted:.3g} W/in^2 "
           f"(requirements.grid_power_density_W_per_mm2), TN-502's thin-section guidance "
           f"(1-2 W/in^2) being on self-heating, not a limit" if accepted is not None else
           "thin sections 1-2 W/in^2, guidance on self-heating: above it undecided short of "
           "the failure, until the design states the density it accepts "
           "(requirements.grid_power_density_W_per_mm2)")
    # no error estimate: the figures are exact in the chain's values, and the band between
    # the guidance and the failure is the rule's own (how well the element sinks the heat is
    # not modelled), not a margin inside a model's error
    rec = _record(GRID_POWER_REQUIREMENT, target, density, None, target / density - 1.0,
                  "closed-form", density <= target * (1 + 1e-9),
                  excitation_V=chain.excitation_V, grid_rise_K=rise,
                  grid_rise_limit_K=TN502_HIGH_EXCITATION_DERATING_K,
                  guidance_W_per_mm2=guidance, verdict=said,
                  basis=(f"Micro-Measurements TN-502: {645.16 * density:.3g} W/in^2 in the grid at "
                         f"{chain.excitation_V:g} V ({why}); the grid "
                         f"{rise:.3g} K above the element (tactcad thermal), fails past "
                         f"{TN502_HIGH_EXCITATION_DERATING_K:g} K, the largest backing derating "
                         f"TN-502 names for high excitation"))
    return rec


#: How the K_obj resolution records read each force.
READOUT_BASIS = ("each element read through the design's [readout] chain: noise of one "
                 "averaged reading / sensitivity (tactcad readout)")


def design_kobj_budget(plan: Plan, fig: Figures, req: Requirements):
    """The design's K_obj error budget (:func:`tactcad.in_use.kobj_budget.kobj_budget`) at
    ``fig``'s level over the required K_obj range, at the full-scale force and the default
    temperature step."""
    from tactcad.in_use.kobj_budget import DEFAULT_DELTA_T_K, kobj_budget

    return kobj_budget(plan, req.kobj_range_N_per_mm, req.full_scale_force_N,
                       DEFAULT_DELTA_T_K, fig.model, fig.k, fig.k_error,
                       force_gauge=calibration_gauge(plan),
                       readable_within_rel=req.kobj_resolution_rel)


def accuracy_budget(plan: Plan, fig: Figures, req: Requirements):
    """The budget the accuracy's records read (one for both).

    Args:
        plan: the design. fig: the level's figures. req: its requirements.

    Returns:
        :func:`design_kobj_budget` when the design states ``kobj_accuracy_rel``, else None.

    Raises:
        DesignError: a source of the budget cannot be evaluated (unknown CTE).
    """
    from tactcad.design.requirements_section import stated_kobj_accuracy

    return design_kobj_budget(plan, fig, req) if stated_kobj_accuracy(plan.raw) is not None \
        else None


def kobj_accuracy_record(plan: Plan, fig: Figures, req: Requirements,
                         budget=None) -> dict | None:
    """``kobj_accuracy_rel`` when the design states it (None otherwise): at each K_obj of
    the budget's grid the RSS after correction of the unit that reads it best, margin
    target / RSS - 1, error the budget's own uncertainty (gauge model plus K error of the
    level), judged on its own (``points``); the record shows the point with the worst
    verdict (:func:`deciding_item`)."""
    from tactcad.design.requirements_section import stated_kobj_accuracy

    target = stated_kobj_accuracy(plan.raw)
    if target is None:
        return None
    budget = budget or design_kobj_budget(plan, fig, req)
    a = budget.array
    items = [undecided_reading(judged(
                {"K_obj_N_per_mm": k, "unit": u, "rss_rel": rss, "dominant": dom,
                 "error_estimate_rel": unc, "reads_undecided": open_,
                 "margin_rel": -1.0 if rss is None  # no unit reads it
                 else target / rss - 1.0 if rss > 0 and math.isfinite(rss)
                 else (None if rss == 0 else -1.0)}))
             for k, u, rss, dom, unc, open_ in zip(budget.k_obj, a["unit"], a["rss_rel"],
                                                   a["dominant"], a["uncertainty_rel"],
                                                   a["reads_undecided"])]
    if not items:  # no unit: nothing reads K_obj, so the accuracy cannot be met
        return _record("kobj_accuracy_rel", target, None, math.inf, -1.0, fig.model, False,
                       basis="no element is softer than its row's reference")
    w = deciding_item(items)
    return _record("kobj_accuracy_rel", target, w["rss_rel"], w["error_estimate_rel"],
                   w["margin_rel"], fig.model,
                   all(it["rss_rel"] is not None and it["rss_rel"] <= target for it in items),
                   binding_kobj_N_per_mm=w["K_obj_N_per_mm"], binding_unit=w["unit"],
                   dominant=w["dominant"], points=items, force_N=budget.force_N,
                   verdict=w["verdict"],
                   delta_T_K=budget.delta_T_K,
                   basis="RSS of the K_obj error budget after correction (tactcad budget), "
                         "each K_obj read by its best unit")


def undecided_reading(item: dict) -> dict:
    """An accuracy point whose unit reads K_obj within the required resolution only inside
    the level's error (``reads_undecided``: the budget's
    :func:`tactcad.in_use.kobj_budget.unit_reads_undecided`) cannot pass: its RSS holds
    where the unit reads, and none is read where it does not; a pass becomes
    ``undecided`` (a failure beyond the error stays one, read or not)."""
    if item.get("reads_undecided") and item["verdict"] == "pass":
        return {**item, "verdict": "undecided"}
    return item


#: The verification matrix's name of the tip-height row.
TIP_HEIGHT_REQUIREMENT = "tip_height_tolerance_mm"


def tip_height_tolerance_record(plan: Plan, fig: Figures, budget) -> dict | None:
    """"tip height: tolerance drawn vs tolerance needed", when the design states
    ``kobj_accuracy_rel`` (None otherwise, or without a budget).

    The drawings' tip-height decision
    (:func:`tactcad.in_use.tip_height_drawing.tip_height_from_budget`, the one the export
    hands the drawings) against the budget's coplanarity allowance (+/- mm). It passes when
    the drawn tolerance holds the allowance (margin allowance / drawn - 1), or when the
    drawing names the zeroing on a rigid flat and the mismatch that procedure leaves fits
    the twice-the-allowance mismatch the accuracy permits (margin 2 allowance / residual -
    1); ``binding_words`` names which. It fails where the other terms leave no room. The
    allowance reads each K_obj in the unit :func:`kobj_accuracy_record` reads it with (the
    array's best), so the two rows judge one budget: an accuracy that passes leaves room
    for the tips, and a looser one a looser allowance.
    Error: the budget's largest own uncertainty (the allowance scales with the room).

    Args:
        plan: the design. fig: the level's figures. budget: :func:`accuracy_budget`'s.

    Returns:
        The record, or None.
    """
    from tactcad.in_use.tip_height_drawing import tip_height_from_budget

    tip = tip_height_from_budget(plan, budget) if budget is not None else None
    if tip is None:
        return None
    error = max((u["uncertainty_rel"] for u in budget.units), default=0.0)
    needed = tip.allowance_mm
    if needed is None:
        return _record(TIP_HEIGHT_REQUIREMENT, None, tip.drawn_mm, error, -1.0, fig.model,
                       False, verdict="fail", tip_height=tip.as_json(),
                       binding_words="no tolerance fits: the other terms fill the accuracy",
                       basis="the K_obj budget's coplanarity allowance (tactcad budget)")
    if tip.holds_allowance:
        margin = needed / tip.drawn_mm - 1.0 if tip.drawn_mm > 0 else math.inf
        predicted, passed = tip.drawn_mm, True
        words = f"drawn +/-{tip.drawn_mm:.3g} mm holds it"
    else:
        margin = 2 * needed / tip.residual_mm - 1.0
        predicted, passed = tip.residual_mm / 2, tip.residual_fits
        words = (f"zeroed on a rigid flat (tactcad calibrate --flat): "
                 f"{1e3 * tip.residual_mm:.2g} um mismatch left; drawn +/-{tip.drawn_mm:g} mm, "
                 f"machining holds +/-{tip.floor_mm:g} mm")
    return _record(TIP_HEIGHT_REQUIREMENT, needed, predicted, error, margin, fig.model, passed,
                   tip_height=tip.as_json(), binding_words=words,
                   basis="tip height: tolerance drawn vs tolerance needed (the K_obj budget's "
                         "coplanarity allowance, +/- mm); with the zeroing, half the mismatch "
                         "it leaves")


def grasp_error_rel(fig: Figures) -> float:
    """The grasp model's relative error on an element's force: the level's largest K error
    and the tissue model's (:data:`TISSUE_MODEL_ERROR_REL`), root-sum-square."""
    return math.hypot(max(fig.k_error.values(), default=0.0), TISSUE_MODEL_ERROR_REL)


#: The limits a grasp's one-off overload must stay within: the web's yield (with the
#: design's safety factor) and the gauge's largest strain; fatigue and the rated reading
#: range are the sensor's duty, not a grasp's (the hard stop exists to exceed the rating).
OVERLOAD_LIMITS = ("yield", "gauge_max")
#: The limits a load repeated at every grasp is held to.
FATIGUE_LIMITS = ("fatigue", "gauge_fatigue")


def element_overload_limits_N(plan: Plan, fig: Figures,
                              names: Sequence[str] = OVERLOAD_LIMITS) -> dict[int, float]:
    """Each element's least force limit (N) of ``names`` (default :data:`OVERLOAD_LIMITS`) at
    ``fig``'s level (:func:`tactcad.mechanics.limits.plan_limits`); an element with none of
    them is left out."""
    from tactcad.mechanics.limits import plan_limits

    out: dict[int, float] = {}
    for lim in plan_limits(plan, fig.model, fig.stresses, fig.k_error):
        if lim.limit in names:
            out[lim.element] = min(out.get(lim.element, math.inf), lim.force_N)
    return out


def grasp_force_columns(target_N: float, margin_rel: float, on_stop: bool) -> dict:
    """The ``predicted`` and ``margin_rel`` of a ``max_grasp_force_N`` row in the target's
    own quantity, the grasp force (N): the grasp at which the deciding element reaches its
    overload limit, its force in proportion to the grasp (``target_N`` x limit / force),
    so margin = predicted / target - 1 = limit / force - 1. Both None when that element
    rests on its stop: the stop holds its force whatever the grasp, so the springs set no
    largest grasp (each element's own margin stays in the record's items).

    Args:
        target_N: the stated grasp force (N). margin_rel: the deciding element's overload
            limit over its force at that grasp, less one. on_stop: whether it rests on
            its stop.

    Returns:
        ``{"predicted": N or None, "margin_rel": relative}``.
    """
    if on_stop:
        return {"predicted": None, "margin_rel": None}
    return {"predicted": target_N * (1.0 + margin_rel), "margin_rel": margin_rel}


def max_grasp_force_record(plan: Plan, fig: Figures, req: Requirements) -> dict | None:
    """``max_grasp_force_N`` when the design states it (None otherwise): the grasp's force
    mode at that grasp force (:func:`tactcad.in_use.grasp_experiment.design_grasp_at_force`:
    the design's stated jaw and tissue or the defaults, the design's layout, the elements' K at ``fig``'s level);
    each element's force on its spring against its overload limit
    (:func:`element_overload_limits_N`: yield with the safety factor, the gauge's largest
    strain), margin limit / force - 1, error :func:`grasp_error_rel`, judged on its own
    (``elements``), a hard stop taking the force beyond its engagement; the record shows
    the element that decides it (:func:`deciding_item`) and the elements past the rated
    full-scale force (on their stops or not). A grasp force the jaw cannot reach fails.
    ``predicted`` is a grasp force, as the target is (:func:`grasp_force_columns`); the
    deciding element's force and overload limit, which the margin is taken on, are
    ``element_force_N`` and ``overload_limit_N``."""
    from tactcad.design.requirements_section import stated_max_grasp_force
    from tactcad.errors import DesignError
    from tactcad.in_use.grasp_experiment import (default_assumptions, design_grasp_at_force,
                                                 grasp_summary)

    target = stated_max_grasp_force(plan.raw)
    if target is None:
        return None
    rated, basis = req.full_scale_force_N, default_assumptions(req.kobj_range_N_per_mm, plan)
    try:
        result = design_grasp_at_force(plan, target, rated, req.kobj_range_N_per_mm, fig.model)
    except DesignError as exc:
        return _record("max_grasp_force_N", target, None, math.inf, -1.0, fig.model, False,
                       verdict="fail", basis=f"{basis}; the grasp is out of reach: {exc}")
    error = grasp_error_rel(fig)
    limit = element_overload_limits_N(plan, fig)
    items = [judged({"element": t["site"], "element_force_N": t["element_force_N"],
                     "stop_force_N": t["stop_force_N"], "on_stop": t["on_stop"],
                     "rated_force_N": rated, "overload_limit_N": limit[t["site"]],
                     "error_estimate_rel": error,
                     "margin_rel": limit[t["site"]] / t["element_force_N"] - 1.0
                     if t["element_force_N"] > 0 else None})
             for t in result.as_laid_out.tips]
    w = deciding_item(items)
    over = [it for it in items if it["element_force_N"] > it["overload_limit_N"]]
    past_rating = [it for it in items if it["element_force_N"] > rated]
    # not an overload, yet a grasp is repeated: each one past a fatigue limit is a cycle
    # beyond it, which the overload verdict does not judge; said beside it
    fatigue = element_overload_limits_N(plan, fig, FATIGUE_LIMITS)
    past_fatigue = [f"element {it['element']}: {it['element_force_N']:.4g} N over its fatigue "
                    f"limit {fatigue[it['element']]:.4g} N"
                    + (" (on its stop)" if it["on_stop"] else "")
                    for it in items if it["element"] in fatigue
                    and it["element_force_N"] > fatigue[it["element"]]]
    # the predicted figure is an element's force, not the grasp's: said where it binds
    words = (f"the {target:g} N grasp ({result.jaw.slab_thickness_mm:g} mm {result.profile} "
             f"on a {result.tissue_base} base, jaw at {result.as_laid_out.angle_deg:.3g} "
             "degrees) puts "
             f"{w['element_force_N']:.4g} N on the spring, overload limit "
             f"{w['overload_limit_N']:.4g} N"
             + ("" if w["on_stop"] else
                f" (predicted: the grasp at which element {w['element']} reaches it, its "
                "force in proportion to the grasp)")
             + (f"; {len(past_fatigue)} of {len(items)} elements past their fatigue limits, "
                "each such grasp a cycle beyond them (not judged here: fatigue_at_max_grasp "
                "lists them)" if past_fatigue else ""))
    columns = grasp_force_columns(target, w["margin_rel"], w["on_stop"]) \
        if w["margin_rel"] is not None else {"predicted": None, "margin_rel": None}
    # no grasp force predicted (the deciding element on its stop): say what is predicted
    stop_words = {"predicted_words": f"on its stop: element {w['element']} carries "
                                     f"{w['element_force_N']:.4g} N (limit "
                                     f"{w['overload_limit_N']:.4g} N)"} \
        if columns["predicted"] is None and w["on_stop"] else {}
    return _record("max_grasp_force_N", target, columns["predicted"], error,
                   columns["margin_rel"], fig.model, not over, verdict=w["verdict"],
                   binding_element=w["element"], element_force_N=w["element_force_N"],
                   overload_limit_N=w["overload_limit_N"], binding_words=words,
                   rated_force_N=rated, elements=items, grasp=grasp_summary(result),
                   **stop_words,
                   over_limit=[f"element {it['element']}: {it['element_force_N']:.4g} N over "
                               f"its overload limit {it['overload_limit_N']:.4g} N"
                               for it in over],
                   fatigue_at_max_grasp=past_fatigue,
                   past_rating=[f"element {it['element']}: {it['element_force_N']:.4g} N "
                                f"(rated {rated:.4g} N{', on its stop' if it['on_stop'] else ''})"
                                for it in past_rating],
                   basis=f"{basis}; each element's force on its spring against its overload "
                         f"limit (yield with the safety factor, the gauge's largest strain), "
                         f"a hard stop taking the rest")


def kr_over_km_record(pairs: Sequence[RowPair], req: Requirements, model: str) -> dict:
    """``kr_over_km``: every row's pair judged on its own error (:meth:`RowPair.as_json`);
    the record shows the pair that decides it (:func:`deciding_item`), so one pair that
    fails beyond its error fails the record whatever the others do. A pair passes within
    the requirement's own band (margin >= -kr_over_km_tolerance_rel), never the
    manufacturing band (``k_tolerance_rel``: what the tolerance study answers)."""
    threshold = -req.kr_over_km_tolerance_rel
    items = [q.as_json(req.kr_over_km, threshold) for q in pairs]
    worst = deciding_item(items)
    return _record("kr_over_km", req.kr_over_km, worst["kr_over_km"],
                   worst["error_estimate_rel"], worst["margin_rel"], model,
                   all(it["margin_rel"] >= threshold for it in items),
                   reference_element=worst["reference_element"],
                   measuring_element=worst["measuring_element"], row=worst["row"],
                   **({"column": worst["column"]} if "column" in worst else {}),
                   allowed_margin_rel=threshold, pairs=items)


def footprint_record(footprint_mm: Sequence[float], envelope_mm: Sequence[float],
                     general: str = "f") -> dict:
    """``footprint_mm``: the array's envelope (X, Y and, when the footprint
    states it, Z; mm) against the footprint, one item per axis (``axes``),
    margin footprint / envelope - 1. Geometry, not a model: each axis's error
    is the envelope's ISO 2768-1 deviation in the design's general class
    ``general`` (:func:`tactcad.design.tolerances.general_linear_tolerance_mm`)
    over its size, so an envelope that fills the footprint exactly is
    undecided, not met. The record shows the axis with the worst verdict
    (:func:`deciding_item`)."""
    from tactcad.design.tolerances import general_linear_tolerance_mm

    env = [float(e) for e in envelope_mm[:len(footprint_mm)]]
    axes = []
    for axis, f, e in zip("XYZ", footprint_mm, env):
        axes.append(judged({"axis": axis, "footprint_mm": float(f), "envelope_mm": e,
                            "error_estimate_rel": general_linear_tolerance_mm(e, general) / e,
                            "margin_rel": f / e - 1.0}))
    worst = deciding_item(axes)
    return {"requirement": "footprint_mm", "target": list(footprint_mm), "predicted": env,
            "error_estimate_rel": worst["error_estimate_rel"], "margin_rel": worst["margin_rel"],
            "model": "geometry", "pass": all(a["margin_rel"] >= 0 for a in axes),
            "binding_axis": worst["axis"], "axes": axes,
            "basis": f"the assembly STEP's box from the parts' expected boxes, each axis to "
                     f"ISO 2768-{general}"}


#: The step (mm) a least footprint is rounded up to.
FOOTPRINT_STEP_MM = 0.1


def footprint_met(envelope_mm: Sequence[float], footprint_mm: Sequence[float],
                  general: str = "f") -> bool:
    """True when :func:`footprint_record` passes every axis the footprint states: each
    holds the envelope plus its ISO 2768-1 deviation in class ``general`` (mm); the rule
    ``design --footprint`` designs to, so its design passes its own requirement."""
    return all(a["verdict"] == "pass"
               for a in footprint_record(footprint_mm, envelope_mm, general)["axes"])


def least_footprint_mm(envelope_mm: Sequence[float], axes: int = 2,
                       general: str = "f") -> list[float]:
    """The smallest footprint (first ``axes`` of X, Y, Z; mm) an envelope meets
    (:func:`footprint_met`): each axis plus its deviation, rounded up to
    :data:`FOOTPRINT_STEP_MM`, so that it can be pasted as ``--footprint``."""
    from tactcad.design.tolerances import general_linear_tolerance_mm

    out = []
    for e in envelope_mm[:axes]:
        need = float(e) + general_linear_tolerance_mm(float(e), general)
        out.append(round(math.ceil(need / FOOTPRINT_STEP_MM - 1e-9) * FOOTPRINT_STEP_MM, 6))
    return out


#: Requirements computed the same way at every level (the K band over the web tolerance).
LEVEL_FIXED = ("k_tolerance_rel", "k_tolerance_rel_toleranced", "footprint_mm",
               "max_crosstalk_rel", GRID_POWER_REQUIREMENT)

def prefetch_top_level(plan: Plan, model: str, progress: Callable[[str], None] | None = None,
                       peak_stress: bool = False, parts: Collection[str] | None = None,
                       stress_parts: Collection[str] | None = None) -> int:
    """At the ladder's dearest level, the distinct elements not yet kept in the store solved
    side by side, one process each (:mod:`tactcad.studies.parallel_solves`), for the matrix
    to read back; with ``peak_stress`` their peak-stress sequences too (a matrix given its
    ``stress`` reads them); the processes used (0 at any other level, or when nothing is
    to solve). ``parts``: the part names the level solves (default every distinct element;
    :func:`elements_decided_below` keeps the others' lower-level figures). ``stress_parts``:
    of those, the ones whose peak-stress sequence is solved (default all of them;
    :func:`strengths_decided_below` keeps the others' lower-level stresses)."""
    from tactcad.studies.parallel_solves import solve_side_by_side, top_of_the_ladder

    if not top_of_the_ladder(model):
        return 0
    solved = [g for name, g in plan.distinct_elements.items() if parts is None or name in parts]
    stressed = None if stress_parts is None else \
        [g for g in solved if g.part_name in stress_parts]
    return solve_side_by_side(model, solved, plan.material, progress, peak_stress=peak_stress,
                              stress_geometries=stressed)


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

    A level decides a requirement a cheaper level left undecided only when it is at least
    as accurate on it (its record's error estimate no larger, :func:`less_accurate`): the
    ladder's middle levels can be less accurate than the fem3d-corrected closed form (fem2d's
    plane model), so a verdict inside the closed form's error is not settled by one outside
    a wider error. Such a verdict is kept beside the undecided record
    (``less_accurate_levels``) and the ladder climbs on. A requirement no level decides
    stays undecided with the most accurate level's record (the smallest error estimate,
    :func:`ladder_undecided`: its figures and its ``model``), every other level tried
    listed beside it (``less_accurate_levels``), whichever level the ladder stopped at.

    A level above the first whose open requirements all read K alone (:func:`reads_k_alone`:
    K_r/K_m, the K band, the footprint, the grid's power density) solves no peak stress
    (:func:`unread_stress` stands for ``stress``): what reads one was decided below it, so the
    records returned are those the full matrix of every level gives.

    A level climbed for a per-element strength requirement alone (:data:`PER_ELEMENT_STRENGTH`,
    the others still open fixed alike at every level) solves only the elements whose figures
    below do not clear it by their error (:func:`elements_decided_below`); the others keep
    the lower level's figures and errors, the record saying each part's level
    (``element_levels``; each listed limit its ``level``). The verdict is still the margin
    against the error of the figure that binds. With a requirement that reads K open
    (K_r/K_m, the K_obj rows, ...) every element's K is solved; when those read K alone
    (:data:`K_ALONE`), the elements cleared below keep their stresses and limits
    (:func:`strengths_decided_below`: no peak-stress sequence of theirs is solved).

    Args:
        stress: as :func:`verification_matrix` (needed once a FEM level runs).
        levels: the ladder to climb; default every level, cheapest first.

    Returns:
        (records in the matrix's order, [{"model", "seconds", "undecided_before",
        "elements_kept", "stresses_kept"}] per level run; ``elements_kept`` the part names
        whose lower-level figures the level kept, empty when it solved every element;
        ``stresses_kept`` those whose K it solved and whose lower-level stresses it kept,
        :func:`strengths_decided_below`).

    Outside a :func:`tactcad.store.keeping_results` block the climb keeps its solves in
    memory for its length (``Store(None)``, as ``--no-cache`` does): each level's K, grid
    strain and peak-stress sequences are solved once, not once per figure that reads them.
    """
    import contextlib

    from tactcad.store import Store, active_store, keeping_results

    kept = contextlib.nullcontext() if active_store() is not None else keeping_results(Store(None))
    with kept:
        return _climbed(plan, progress, requirements, stress, levels, envelope_mm)


def _climbed(plan: Plan, progress: Callable[[str], None] | None,
             requirements: Requirements | None, stress: Callable | None,
             levels: tuple[str, ...] | None,
             envelope_mm: Sequence[float] | None) -> tuple[list[dict], list[dict]]:
    """:func:`verification_auto`'s climb, within a block keeping its solves."""
    import time

    from tactcad.mechanics.ladder import models

    ladder = tuple(levels or models())
    req = requirements or requirements_of(plan)
    chosen: dict[str, dict] = {}
    order: list[str] = []
    spent: list[dict] = []
    # per requirement left undecided, its most accurate undecided record so far with every
    # other level tried listed beside it: a level less accurate than it (a larger error
    # estimate) does not decide it, and it is the row shown when no level decides it
    open_at: dict[str, dict] = {}
    below: Figures | None = None  # the last level's figures
    records_below: dict[str, dict] = {}  # and its records
    for i, level in enumerate(ladder):
        open_before = [k for k in order if k not in chosen] if order else None
        t0 = time.perf_counter()
        # a level whose open requirements read K alone solves no peak stress: the records
        # that read one were decided below it, and its own are not kept
        read = stress if stress is None or not reads_k_alone(open_before) else unread_stress
        # climbed for a per-element strength alone: the elements decided below are kept
        keep = elements_decided_below(plan, below, records_below, open_before, req)
        # climbed for it with K_r/K_m (K alone) open too: every K solved, the stresses of
        # the elements decided below kept
        strong = frozenset() if keep else strengths_decided_below(
            plan, below, records_below, open_before, req)
        solve = None if not keep else [name for name in plan.distinct_elements
                                       if name not in keep]
        prefetch_top_level(plan, level, progress,
                           peak_stress=stress is not None and read is stress, parts=solve,
                           stress_parts=None if not strong else
                           [name for name in plan.distinct_elements if name not in strong])
        made: list[Figures] = []
        records = verification_matrix(plan, level, progress, req, read, envelope_mm,
                                      below=below, keep=keep, figures_made=made,
                                      keep_strength=strong)
        below = made[0] if made else None
        records_below = {r["requirement"]: r for r in records}
        spent.append({"model": level, "seconds": time.perf_counter() - t0,
                      "undecided_before": open_before, "elements_kept": sorted(keep),
                      "stresses_kept": sorted(strong)})
        order = order or [r["requirement"] for r in records]
        top = i == len(ladder) - 1
        for r in records:
            before = open_at.get(r["requirement"])
            # a figure kept from below that binds clears the requirement by its own error
            if r["verdict"] != "undecided" and before is not None \
                    and less_accurate(r, before) and not binds_below(r):
                r["less_accurate_than"] = before["model"]
        # a record another level computes the same way (the K band is always the
        # closed form's) cannot be decided by climbing: it stays undecided
        climbable = [r for r in records if r["requirement"] not in chosen
                     and (r["verdict"] == "undecided" or "less_accurate_than" in r)
                     and not r["level_fixed"]]
        last = top or not climbable
        for r in records:
            key = r["requirement"]
            if key in chosen:
                continue
            if r["verdict"] == "undecided" or "less_accurate_than" in r:
                # the same record at every level (level fixed) is not merged with itself
                open_at[key] = r if r["level_fixed"] else ladder_undecided(open_at.get(key), r)
                if not last:
                    continue
                r = open_at[key]
            r["decided_by"] = None if r["verdict"] == "undecided" else level
            r["levels_tried"] = list(ladder[:i + 1])
            chosen[key] = r
        if len(chosen) == len(order):
            break
    return [chosen[k] for k in order], spent


#: Requirements whose figure is the least over the elements of each one's own figures, read
#: from that element's K and stress alone (the full-scale force: every limit of every
#: element), so a level may solve only the elements a lower level left undecided.
PER_ELEMENT_STRENGTH = ("full_scale_force_N",)


def elements_decided_below(plan: Plan, below: Figures | None, records_below: Mapping[str, dict],
                           open_requirements: Sequence[str] | None,
                           requirements: Requirements, reading_k: Collection[str] = ()
                           ) -> frozenset[str]:
    """The parts the next level need not solve: when every requirement still open is a
    per-element strength (:data:`PER_ELEMENT_STRENGTH`) or one computed alike at every level
    (``level_fixed``), and the last level left each such strength undecided, the parts all
    of whose force limits there (:func:`figures_limits`) clear the full-scale force by their
    own error (margin >= error, :func:`tactcad.mechanics.verdicts.verdict` ``pass``).
    Otherwise none (a requirement reading K, or one a less accurate level decided, is not
    judged from a partly solved level), nor when no part clears.

    Args:
        plan: the design. below: the last level's figures (None before the first level).
        records_below: its records by requirement. open_requirements: those no level
            decided (None before the first). requirements: the design's (the force, N).
        reading_k: requirements that may be open beside the strength too (those reading
            K alone, :func:`strengths_decided_below`); default none.

    Returns:
        The part names kept from ``below`` (empty: every element is solved).
    """
    if below is None or not open_requirements:
        return frozenset()
    strength = [k for k in open_requirements if k in PER_ELEMENT_STRENGTH]
    if not strength:
        return frozenset()
    for key in open_requirements:
        r = records_below.get(key)
        if r is None:
            return frozenset()
        if key in PER_ELEMENT_STRENGTH:
            if r["verdict"] != "undecided" or "less_accurate_than" in r:
                return frozenset()
        elif not r.get("level_fixed") and key not in reading_k:
            return frozenset()
    force = requirements.full_scale_force_N
    parts = set(plan.distinct_elements)
    cleared = set(parts)
    for lim in figures_limits(plan, below):
        if verdict(lim.force_N / force - 1.0, lim.error_estimate_rel, 0.0,
                   lim.force_N >= force) != "pass":
            cleared.discard(lim.part_name)
    return frozenset(cleared) if cleared != parts else frozenset()


def strengths_decided_below(plan: Plan, below: Figures | None,
                            records_below: Mapping[str, dict],
                            open_requirements: Sequence[str] | None,
                            requirements: Requirements) -> frozenset[str]:
    """The parts whose stresses the next level need not solve though it solves their K: as
    :func:`elements_decided_below`, with requirements reading K alone (:data:`K_ALONE`:
    K_r/K_m, ...) open beside the per-element strength. Such a requirement reads every
    element's K at the level (all solved there), none of its stresses; the strength of a
    part whose force limits below clear the full-scale force by their own error is decided,
    so its peak-stress sequence (at fem3d the bare element's, a mesh sequence as dear as its
    K's) is not solved: its limits are the lower level's.

    Args:
        plan: the design. below: the last level's figures (None before the first level).
        records_below: its records by requirement. open_requirements: those no level
            decided (None before the first). requirements: the design's (the force, N).

    Returns:
        The part names whose stresses are kept from ``below`` (empty: every stress solved).
    """
    return elements_decided_below(plan, below, records_below, open_requirements,
                                  requirements, reading_k=K_ALONE)


def binds_below(record: dict) -> bool:
    """Whether ``record``'s binding limit was kept from a level below the record's own
    (``limits`` with their ``level``, :func:`verification_auto`).

    Args:
        record: a verification record.

    Returns:
        True for a binding limit whose ``level`` is not the record's ``model``.
    """
    if not record.get("element_levels"):  # every element solved at the record's level
        return False
    bound = next((lim for lim in record.get("limits", ()) if lim.get("binding")), None)
    return bound is not None and bound.get("level", record["model"]) != record["model"]


#: Requirements whose record at a level reads no stress of that level: K_r/K_m (the rows'
#: K alone) and those computed alike at every level without the elements' figures.
K_ALONE = ("kr_over_km", "k_tolerance_rel", "k_tolerance_rel_toleranced", "footprint_mm",
           GRID_POWER_REQUIREMENT)


def reads_k_alone(open_requirements: Sequence[str] | None) -> bool:
    """Whether every requirement still open reads no stress of the next level (all in
    :data:`K_ALONE`), so :func:`verification_auto` solves that level's K and no peak stress.

    Args:
        open_requirements: the requirements no lower level decided; None before the first
            level (nothing decided yet: every requirement is open).

    Returns:
        True when none of them reads a stress (False for None).
    """
    return open_requirements is not None and all(k in K_ALONE for k in open_requirements)


def unread_stress(g: ElementGeometry, material: Material, model: str) -> Any:
    """The stress :func:`verification_auto` hands a level whose stresses no open requirement
    reads (:func:`reads_k_alone`): the closed form's formula on the level's K
    (:func:`tactcad.mechanics.element_strength.closed_form_stress`), so no peak-stress
    sequence is solved; the records made from it were decided below and are not kept, so
    its warnings (a K_t fit range) are not said. :func:`element_figures` reads its grid
    strain at the closed form too (:func:`unread_at_the_grid`): no face-strain sequence
    is solved at the level.

    Args:
        g: the element (mm). material: its material. model: the level (its K is read).

    Returns:
        The :class:`~tactcad.mechanics.element_strength.ElementStress`.
    """
    import warnings

    from tactcad.mechanics.element_strength import closed_form_stress

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return closed_form_stress(g, material, model)


def unread_at_the_grid(es: Any, g: ElementGeometry, plan: Plan) -> Any:
    """:func:`unread_stress`'s figures with the grid strain the closed form reads
    (:func:`tactcad.mechanics.element_strength.at_the_grid` at "closed-form"): no
    face-strain mesh sequence is solved for a level whose stresses no open requirement
    reads, and, as :func:`unread_stress`, its warnings are not said (the closed form's
    level said them).

    Args:
        es: :func:`unread_stress`'s figures (MPa/N, N/mm). g: the element (mm).
        plan: the design (its read-out chain).

    Returns:
        The :class:`~tactcad.mechanics.element_strength.ElementStress` with its
        ``grid_strain_per_N`` (1/N).
    """
    import warnings

    from tactcad.mechanics.element_strength import at_the_grid

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return at_the_grid(es, g, plan, "closed-form")


def less_accurate(record: dict, than: dict) -> bool:
    """Whether ``record``'s error estimate is larger than ``than``'s (both finite): the
    level that made it is less accurate on that requirement than the one that made
    ``than``, so its verdict cannot settle what ``than`` left undecided. A record without a
    finite error estimate (exact, or none) is not compared (False).

    Args:
        record, than: verification records (``error_estimate_rel``, relative or None).

    Returns:
        True when both errors are finite and ``record``'s is the larger.
    """
    a, b = record.get("error_estimate_rel"), than.get("error_estimate_rel")
    return a is not None and b is not None and math.isfinite(a) and math.isfinite(b) and a > b


def accuracy_key(record: dict) -> float:
    """How a record's level ranks on its requirement, the smaller the more accurate: its
    error estimate (relative), or infinity when it has no finite one (none stated, or an
    infinite one), so that any level with a finite estimate ranks above it.

    Args:
        record: a verification record (``error_estimate_rel``, relative or None).

    Returns:
        The error estimate (relative, >= 0) or ``math.inf``.
    """
    error = record.get("error_estimate_rel")
    return float(error) if error is not None and math.isfinite(error) else math.inf


def _level_position(model: str) -> int:
    """``model``'s place on the ladder (:func:`tactcad.mechanics.ladder.models`), cheapest
    first; a level not on it after every one that is."""
    from tactcad.mechanics.ladder import models

    ladder = tuple(models())
    return ladder.index(model) if model in ladder else len(ladder)


def _beside(record: dict) -> dict:
    """A level's record as :func:`ladder_undecided` lists it beside the row shown."""
    return {"model": record["model"], "verdict": record["verdict"],
            "margin_rel": record.get("margin_rel"),
            "error_estimate_rel": record.get("error_estimate_rel")}


def ladder_undecided(open_record: dict | None, later: dict) -> dict:
    """The record :func:`verification_auto` keeps for a requirement no level has decided
    so far: the most accurate level's record (the smallest error estimate,
    :func:`accuracy_key`; of equal ones the later level's), verdict ``undecided``, with
    every other level tried on it said beside it, cheapest first (``less_accurate_levels``:
    each one's ``model``, ``verdict``, ``margin_rel`` and ``error_estimate_rel``). A level
    that decided the requirement with a larger error than an undecided one is listed
    there, never shown.

    Args:
        open_record: the record kept so far (None: no level has left it undecided yet).
        later: the next level's record: undecided, or decided by a level less accurate
            than ``open_record``'s (:func:`less_accurate`).

    Returns:
        A new record (``open_record`` and ``later`` unchanged): a copy of the more
        accurate undecided one, with ``less_accurate_levels``.
    """
    if open_record is None:
        return dict(later)
    if later["verdict"] != "undecided" or accuracy_key(later) > accuracy_key(open_record):
        shown, other = open_record, later
    else:
        shown, other = later, open_record
    listed = [*open_record.get("less_accurate_levels", []), _beside(other)]
    out = dict(shown)
    out["less_accurate_levels"] = sorted(listed, key=lambda b: _level_position(b["model"]))
    return out


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


def matrix_table(records: list[dict]) -> str:
    """The matrix as a Markdown table (one row per requirement, the level
    that decided it and the pair or element that binds; the limits of the
    full-scale force below it)."""
    rows = ["| requirement | target | predicted | error est. | margin | model | verdict | "
            "binds |",
            "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in records:
        rows.append(f"| {r['requirement']} | {target_text(r)} | "
                    f"{predicted_text(r)} | "
                    f"{percent_text(r['error_estimate_rel'], sign=False)} | "
                    f"{margin_text(r)} | {r['model']} | {r['verdict'].upper()} | "
                    f"{binding_text(r)} |")
        rows += limit_rows(r)  # under the requirement they belong to
    return "\n".join(rows)


def limit_rows(record: dict) -> list[str]:
    """The table rows of a record's force limits (the full-scale force's: yield, fatigue,
    the gauge's strains, ...; ``binds`` on the one that binds), each named ``limit:``, to
    follow that record's own row; none for a record without limits.

    Args:
        record: a verification record (``limits``: N, relative errors).

    Returns:
        Markdown table rows.
    """
    return [f"|   limit: {lim['words']} (element {lim['element']}) | | "
            f"{lim['force_N']:.4g} N | {100 * lim['error_estimate_rel']:.2f} % | | | "
            f"{'binds' if lim['binding'] else ''} | |"
            for lim in record.get("limits", ())]


def predicted_text(record: dict) -> str:
    """A record's prediction as verify, check and the review page show it:
    :func:`value_text` of ``predicted``, or, where the record predicts no figure in the
    target's quantity, the words saying what it predicts instead (``predicted_words``: a
    grasp whose deciding element rests on its stop, with the force that element carries).

    Args:
        record: a verification record.

    Returns:
        The text.
    """
    if record.get("predicted") is None and record.get("predicted_words"):
        return record["predicted_words"]
    return value_text(record.get("predicted"))


def target_text(record: dict) -> str:
    """A record's target as verify, check and the review page show it: ``not stated`` for
    a row reported, not judged (verdict ``info``: it has none), else :func:`value_text`."""
    return "not stated" if record.get("verdict") == INFO else value_text(record.get("target"))


def margin_text(record: dict) -> str:
    """A record's margin in percent, with the margin it is allowed when that is not 0
    (K_r / K_m within the K band: ``-20.2 % (allowed -24.0 %)``); ``n/a`` for a row
    reported, not judged (verdict ``info``) or without a finite margin."""
    if record.get("verdict") == INFO:
        return "n/a"
    allowed = record.get("allowed_margin_rel")
    text = percent_text(record.get("margin_rel"))
    return text if not allowed else f"{text} (allowed {percent_text(allowed)})"


def binding_text(record: dict) -> str:
    """What a record's figure comes from: the row's pair for K_r/K_m
    (``row 1: element 2 / 1``; ``column 3: element 3 / 8`` where each column pairs its two
    rows), the binding limit and its element for the full-scale force, the tightest axis
    for the footprint, the element with the lowest first resonance; empty otherwise."""
    if "measuring_element" in record:
        where = f"column {record['column']}" if record.get("column") is not None else \
            f"row {record['row']}"
        return (f"{where}: element {record['reference_element']} / "
                f"{record['measuring_element']}")
    if "binding_words" in record:
        element = record.get("binding_element")
        return record["binding_words"] + ("" if element is None else f" (element {element})")
    if "binding_unit" in record:
        return (f"unit {record['binding_unit']} at K_obj {record['binding_kobj_N_per_mm']:.3g} "
                f"N/mm ({record['dominant'].replace('_', ' ')} dominates)")
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
                                 "met": passed_flag(force["verdict"]),
                                 # met alone cannot tell undecided from failed
                                 "verdict": force["verdict"], "model": force["model"]}}


#: The tissue model's relative error on a bias: its agreement with the independent
#: elastic-block model (tests/in_use/test_tissue_coupling_fem.py, within 5 %).
TISSUE_MODEL_ERROR_REL = 0.05
#: K_obj points per unit of the tissue-coupling record (log-spaced, ends included).
TISSUE_POINTS = 5


def bias_verdict(bias_rel: float, error_rel: float, target_rel: float) -> str:
    """A K_obj bias's verdict against the resolution: ``pass`` when even the bias
    moved by its error estimate stays within the target (|bias| + error <= target),
    ``fail`` when it leaves it whatever the error (|bias| - error > target), else
    ``undecided`` (:mod:`tactcad.mechanics.verdicts`).

    Args:
        bias_rel: the K_obj bias (relative, signed).
        error_rel: its error estimate (relative, >= 0).
        target_rel: the K_obj resolution required (relative, > 0).
    """
    if abs(bias_rel) + error_rel <= target_rel:
        return "pass"
    return "fail" if abs(bias_rel) - error_rel > target_rel else "undecided"


def _cross_level_items(working, level, k, units, points) -> list[dict]:
    """Per unit, the coupled inversion's bias read on the check ``level`` and the bias's
    error estimate there: the largest change of the bias, over ``points``, between the
    level's extrapolation and the one a step coarser, with the tissue model's
    :data:`TISSUE_MODEL_ERROR_REL` of the bias, root-sum-square."""
    from tactcad.in_use.tissue_coupling import cross_level_bias

    out = []
    for unit in units:
        bias = cross_level_bias(working, level.sample, k, unit, points)
        coarser = cross_level_bias(working, level.coarser, k, unit, points)
        finite = bool(np.all(np.isfinite(bias)) and np.all(np.isfinite(coarser)))
        worst = float(max(bias, key=abs)) if finite else None
        level_error = float(np.max(np.abs(bias - coarser))) if finite else None
        out.append({"bias": [float(b) if np.isfinite(b) else None for b in bias],
                    "worst": worst, "level_error": level_error,
                    "error": None if worst is None else
                    float(np.hypot(level_error, TISSUE_MODEL_ERROR_REL * worst))})
    return out


def tissue_coupling_record(plan: Plan, req: Requirements, tissue=None) -> dict:
    """The K_obj bias the tissue coupling causes, per unit, worst over the K_obj range, read by
    eq. 3 and by the coupled inversion (eq. 3 corrected), each judged against the K_obj
    resolution the design requires (margin = target / |bias| - 1, error estimate
    :data:`TISSUE_MODEL_ERROR_REL`; :func:`tactcad.mechanics.verdicts.judged`; a reading eq. 3
    cannot answer fails). Not a requirement of the matrix: how K_obj must be read.

    The coupled inversion is judged against another level, as the stiffness ladder is: R
    made on the check model of another discretisation
    (:func:`tactcad.in_use.tissue_coupling.check_level`) read back by the working model's
    inversion; its bias is the two levels' disagreement, judged with the check level's own
    error on it (:func:`bias_verdict`: undecided while the bias is within it). Where a unit
    is undecided and the cell budget allows, the check is refined (cells halved) and the
    finest check judges. A layer has no check level: the inversion is then read against its
    own R, which cannot fail, and says so.

    Args:
        tissue: :class:`tactcad.in_use.tissue_coupling.Tissue` (default: half-space, ν 0.5).
    """
    from tactcad.in_use.tissue_coupling import (Tissue, check_level, coupled_sample,
                                                coupling_report, design_units)
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element
    from tactcad.mechanics.verdicts import deciding_item, judged

    tissue = tissue or Tissue()
    k = ladder_stiffness_by_element(plan)
    points = np.geomspace(*req.kobj_range_N_per_mm, TISSUE_POINTS)
    units = design_units(plan, k)
    rep = coupling_report(plan, k, units, points, tissue)
    target = req.kobj_resolution_rel
    working, level = coupled_sample(plan, tissue), check_level(plan, tissue)
    cross: list[dict] = []
    while level is not None:
        cross = _cross_level_items(working, level, k, units, points)
        open_ = any(c["worst"] is not None and bias_verdict(c["worst"], c["error"], target)
                    == "undecided" for c in cross)
        if not (open_ and level.finer_fits):
            break
        level = check_level(plan, tissue, level.refinement + 1)
    for record, c in zip(rep["units"], cross):
        record["bias_corrected_rel"] = c["bias"]
        record["worst_corrected_rel"] = c["worst"]
        record["corrected_error_rel"] = c["error"]

    def item(unit: dict, key: str) -> dict:
        bias = unit[key]
        margin = None if bias is None else (target / abs(bias) - 1.0 if bias else None)
        if key == "worst_corrected_rel" and bias is not None:
            error = unit["corrected_error_rel"]
            return {"unit": unit["unit"], "bias_rel": bias, "margin_rel": margin,
                    "error_estimate_rel": error / abs(bias) if bias else None,
                    "bias_error_rel": error, "pass": True,
                    "verdict": bias_verdict(bias, error, target)}
        return judged({"unit": unit["unit"], "bias_rel": bias, "margin_rel": margin,
                       "error_estimate_rel": TISSUE_MODEL_ERROR_REL, "pass": bias is not None})

    out = {"tissue": rep["tissue"], "target_rel": target, "units": rep["units"],
           "check_level": _check_level_words(working, level)}
    for key, name in (("worst_eq3_rel", "eq3"), ("worst_corrected_rel", "coupled")):
        items = [item(u, key) for u in rep["units"]]
        for it in items:
            if it["bias_rel"] is None:
                it["verdict"] = "fail"  # no answer for the coupled R there
        out[name] = {"items": items, "verdict": deciding_item(items)["verdict"] if items else "pass"}
    return out


def _check_level_words(working, level) -> str:
    """What the tissue row's coupled inversion was judged against."""
    if level is None:
        return "none for a layer: the inversion read against its own R (it cannot fail)"
    finer = f", cells halved {level.refinement} time(s) to decide" if level.refinement else ""
    return ("R made on a boundary-element model of another discretisation (uniform cells of "
            f"{level.cell_mm:.3g} and {level.cell_mm / 2:.3g} mm{finer}, point-load quadrature, "
            f"first-order extrapolation; mesh error {level.sample.error_rel:.2g} on the "
            "compliance; a bias's error is its change from the extrapolation a mesh coarser) "
            "read by the working model's inversion (graded cells, mesh error "
            f"{working.error_rel:.2g})")
