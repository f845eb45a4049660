"""Inverse design over the layout the targets leave free, and refusals that
name the asked targets.

``tactcad design`` asks for sensing targets (K_r/K_m, a K_obj range, a
full-scale force, optionally a footprint) on a grid and a material. The base
design's other values are where the search starts, not constraints: the sheet
thickness (:data:`STOCK_SHEETS_MM`), the clamp bolt (the ISO table,
:data:`tactcad.vocabulary.standards.BOLTS`), the pitch and the tip width are
free within the design domain unless the user fixes them (an option or a
``--set`` of the field, :data:`FREE_FIELDS`).

Method (closed form throughout; the caller verifies only the design chosen):

1. Candidate layouts, nearest the start first: fewest values changed, then the
   smallest change (log distance). The pitch is the start's, or the sheet plus
   the start's spacer, or the sheet plus the least spacer; the tip the start's,
   narrowed to the pitch's tip gap where it must be.
2. Each layout's stack must fit the longest stock of its bolt with both clamp
   plates and the rigs' bracket ear (:func:`tactcad.design.domain.longest_grip_mm`).
3. Each (sheet, tip) pair's web search (:func:`tactcad.studies.inverse_design.search_webs`,
   about 25 ms) gives the largest full-scale force its elements carry at the
   asked K_r and K_m; the layouts that cannot carry the asked force are skipped.
4. The rest get a whole inverse design (within the footprint when one is
   asked, :mod:`tactcad.studies.footprint_fit`), validated as the written
   project will be (the caller's ``validate``); the first that passes is the
   design, with the reason for each changed value under ``[assumptions]``.

When none passes, the refusal (:class:`InverseDesignError`, a
:class:`~tactcad.errors.DesignError`) names each asked target that binds, with
the limit behind it, and the nearest feasible targets as options to paste,
each judged as pasted, by the search itself (:func:`paste_judge`): the largest force the
search designs at (the figure a design then reports as its largest across the layouts),
layouts and validation included (:func:`searched_force`; bound by yield / safety
factor, fatigue or the gauge's strain), the smallest footprint
(with the force its layout carries where the asked one is out of reach), the
most columns any bolt's stack holds, the K_r/K_m and K_obj range nearest the
asked ones, and a derived requirement the targets break (e.g. the K_obj
resolution a small force gives) as the force that meets it.

Units: mm, N, N/mm.
"""

from __future__ import annotations

import copy
import math
import warnings
from dataclasses import dataclass, field as default_of, replace
from typing import Any, Callable, Iterator, Mapping, Sequence

import numpy as np

from tactcad.design.array_plan import (ARM_RANGE_MM, BOLTS, MIN_SPACER_MM, MIN_TIP_GAP_MM, Plan,
                                       plan_from_dict)
from tactcad.design.domain import longest_grip_mm
from tactcad.design.requirements_section import MAX_FULL_SCALE_FORCE_N, MIN_FULL_SCALE_FORCE_N
from tactcad.errors import DesignError, DesignErrors, RequirementFailure
from tactcad.mechanics.correction import range_warnings_unsaid
from tactcad.vocabulary.process import DEFAULT_CUT_PROCESS, cut_process
from tactcad.vocabulary.rounding import round_down, round_up
from tactcad.studies.design_alternatives import (evaluations_kept, nearest_on_scan,
                                                 largest_feasible_force, nearest_targets,
                                                 relaxing_changes)
from tactcad.studies.footprint_fit import design_in_footprint, fits, stated_footprint
from tactcad.studies.inverse_design import (STIFFNESS_LIMITS, InverseDesign, InverseDesignError,
                                            Targets, binding_limits, centred_for_tissue, design_from_tables,
                                            design_variant, grid_fitted_to_sheet, held_to_process,
                                            max_full_scale_force_N,
                                            mounting_min_arm_mm,
                                            required_overall_length_mm, search_webs,
                                            tip_root_min_arm_mm)

#: Fields the search may change unless the user fixes them.
FREE_FIELDS = ("sheet.thickness_mm", "clamp.bolt_size", "array.pitch_mm", "element.tip_width_mm")
#: Sheet thicknesses searched (mm): stock plate and sheet gauges over the
#: domain's 0.5-10 mm, the start's own added.
STOCK_SHEETS_MM = (0.5, 0.8, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0)
#: Foil gauges searched (mm) where the element's process cuts a flexure thinner than
#: plate (etching, laser cutting): common precision strip thicknesses.
FOIL_SHEETS_MM = (0.05, 0.075, 0.1, 0.125, 0.15, 0.2, 0.25, 0.3, 0.4)
#: The narrowest contact face the domain allows (mm, ``element.tip_width_mm``).
MIN_TIP_WIDTH_MM = 0.5
#: Whole designs tried before the search refuses (each 0.1-1 s on the closed form).
MAX_DESIGNS = 10
#: A layout whose web search carries less than this share of the asked force
#: is skipped (the whole design, with its taller arm, differs a little).
FORCE_SCREEN = 0.95
#: Footprints offered are rounded up to this step (mm).
FOOTPRINT_STEP_MM = 1.0

Envelope = Callable[[Plan], Sequence[float]]
Validate = Callable[[Mapping[str, Any]], Any]


@dataclass(frozen=True)
class FreeLayout:
    """The values the search may change (mm; the bolt by ISO size)."""

    sheet_mm: float
    pitch_mm: float
    tip_width_mm: float
    bolt: str

    def values(self) -> dict[str, Any]:
        return dict(zip(FREE_FIELDS, (self.sheet_mm, self.bolt, self.pitch_mm, self.tip_width_mm)))

    def changed(self, start: "FreeLayout") -> tuple[str, ...]:
        """The fields whose value differs from ``start``'s."""
        mine, theirs = self.values(), start.values()
        return tuple(f for f in FREE_FIELDS if not _same(mine[f], theirs[f]))

    def distance(self, start: "FreeLayout") -> float:
        """Log distance of the numbers plus the bolt's steps in the ISO table."""
        sizes = list(BOLTS)
        steps = abs(sizes.index(self.bolt) - sizes.index(start.bolt)) \
            if self.bolt in BOLTS and start.bolt in BOLTS else 0
        return (abs(math.log(self.sheet_mm / start.sheet_mm))
                + abs(math.log(self.pitch_mm / start.pitch_mm))
                + abs(math.log(self.tip_width_mm / start.tip_width_mm)) + 0.5 * steps)

    def words(self) -> str:
        return (f"sheet {self.sheet_mm:g} mm, pitch {self.pitch_mm:g} mm, tip {self.tip_width_mm:g}"
                f" mm, {self.bolt} bolts")


def _same(a: Any, b: Any) -> bool:
    return math.isclose(a, b, abs_tol=1e-9) if isinstance(a, float) and isinstance(b, float) \
        else a == b


def layout_of(data: Mapping[str, Any]) -> FreeLayout:
    """The free values of raw design tables."""
    return FreeLayout(float(data["sheet"]["thickness_mm"]), float(data["array"]["pitch_mm"]),
                      float(data["element"]["tip_width_mm"]), str(data["clamp"]["bolt_size"]))


def with_layout(data: Mapping[str, Any], layout: FreeLayout) -> dict[str, Any]:
    """``data`` with the layout's values, the dimensions that hold the bolt
    raised where it needs them (:func:`tactcad.studies.inverse_design.fit_to_bolt`)."""
    out = copy.deepcopy(dict(data))
    out["sheet"] = {**out["sheet"], "thickness_mm": layout.sheet_mm}
    out["array"] = {**out["array"], "pitch_mm": layout.pitch_mm}
    out["element"] = {**out["element"], "tip_width_mm": layout.tip_width_mm}
    out["clamp"] = {**out["clamp"], "bolt_size": layout.bolt}
    el, arms = out["element"], out["arms"]["lengths_mm"]
    R = max(float(el["notch_radius_mm"]), float(el["web_thickness_mm"]))
    shortest = max(ARM_RANGE_MM[0], layout.tip_width_mm + 0.01,
                   float(tip_root_min_arm_mm(layout.tip_width_mm, el["inside_corner_radius_mm"], R)),
                   float(mounting_min_arm_mm(BOLTS[layout.bolt],
                                             float(out["clamp"]["arm_clearance_mm"]),
                                             layout.pitch_mm, R)))
    # the arms are the design's to choose: until then each at least the shortest the
    # layout allows, so that the tables are a design to start from
    start_arm = max(shortest, max(arms)) if arms else shortest
    return grid_fitted_to_sheet(held_to_process(design_variant(
        out, arms_mm=[math.ceil(start_arm * 100 - 1e-9) / 100] * len(arms))))


def process_sheets_mm(process: str | None) -> list[float]:
    """The stock and foil sheets (mm) a flexure cut by ``process`` may be
    (:meth:`~tactcad.vocabulary.process.CutProcess.flexure_sheet`; None: the default process)."""
    lo, hi, _ = cut_process(process or DEFAULT_CUT_PROCESS).flexure_sheet()
    return [t for t in (*FOIL_SHEETS_MM, *STOCK_SHEETS_MM) if lo - 1e-9 <= t <= hi + 1e-9]


def candidate_layouts(start: FreeLayout, fixed: frozenset[str],
                      process: str | None = None) -> list[FreeLayout]:
    """Every layout the search tries (module docstring, step 1), nearest ``start`` first;
    the sheets those a flexure of the element's ``process`` may be."""
    def free(f: str) -> bool:
        return f not in fixed

    sheets = sorted({start.sheet_mm, *process_sheets_mm(process)}) if free(FREE_FIELDS[0]) \
        else [start.sheet_mm]
    bolts = list(BOLTS) if free(FREE_FIELDS[1]) else [start.bolt]
    spacer = max(start.pitch_mm - start.sheet_mm, MIN_SPACER_MM)
    out = set()
    for sheet in sheets:
        pitches = {start.pitch_mm} if not free(FREE_FIELDS[2]) else \
            {p for p in (start.pitch_mm, sheet + spacer, sheet + MIN_SPACER_MM)
             if p >= sheet + MIN_SPACER_MM - 1e-9}
        for pitch in pitches:
            tip = start.tip_width_mm
            if tip > pitch - MIN_TIP_GAP_MM + 1e-9:
                if free(FREE_FIELDS[3]):
                    tip = pitch - MIN_TIP_GAP_MM
                elif free(FREE_FIELDS[2]):
                    pitch = tip + MIN_TIP_GAP_MM
            if tip < MIN_TIP_WIDTH_MM - 1e-9 or pitch < sheet + MIN_SPACER_MM - 1e-9:
                continue
            out |= {FreeLayout(round(sheet, 6), round(pitch, 6), round(tip, 6), b) for b in bolts}
    return sorted(out, key=lambda c: (len(c.changed(start)), c.distance(start), c.sheet_mm,
                                      c.pitch_mm, c.tip_width_mm, c.bolt))


def stack_grip_mm(data: Mapping[str, Any], layout: FreeLayout) -> float:
    """The grip the layout's clamp bolts need (mm): the element/spacer stack and
    both clamp plates (:func:`tactcad.design.array_plan.stack_length`)."""
    columns = int(data["array"]["columns"])
    return ((columns - 1) * layout.pitch_mm + layout.sheet_mm
            + 2 * float(data["clamp"]["plate_thickness_mm"]))


def stack_fits(data: Mapping[str, Any], layout: FreeLayout) -> bool:
    """The layout's stack fits its bolt's longest stock (module docstring, step 2)."""
    return stack_grip_mm(data, layout) <= longest_grip_mm(BOLTS[layout.bolt]) + 1e-9


def most_columns(data: Mapping[str, Any], layouts: Sequence[FreeLayout]) -> int:
    """The most columns some layout's stack holds (0: none holds one)."""
    best = 0
    plate = 2 * float(data["clamp"]["plate_thickness_mm"])
    for c in layouts:
        room = longest_grip_mm(BOLTS[c.bolt]) - plate - c.sheet_mm
        if room >= -1e-9:
            best = max(best, 1 + int(math.floor(room / c.pitch_mm + 1e-9)))
    return best


# ---------------------------------------------------------------------------
# The elements' mechanics of a (sheet, tip) pair
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Mechanics:
    """A web search on one layout's elements (step 3)."""

    tables: dict[str, Any]
    search: Any  # WebSearch
    largest_force_N: float


def mechanics_of(data: Mapping[str, Any], layout: FreeLayout, targets: Targets,
                 correction=None) -> Mechanics | None:
    """The web search on ``layout``'s elements; None where its tables break a
    rule that does not depend on the clamp. The elements' stiffness and limits
    do not depend on the bolt or the columns, so the search runs on one column
    held by the smallest bolt, with every arm at the shortest the tip allows."""
    smallest = min(BOLTS.values(), key=lambda b: b.nominal_diameter_mm).size
    tables = with_layout(data, replace(layout, bolt=smallest))
    tables["array"] = {**tables["array"], "columns": 1}
    tables["arms"] = {"lengths_mm": tables["arms"]["lengths_mm"][:int(tables["array"]["rows"])]}
    tables.pop("requirements", None)
    try:
        plan = plan_from_dict(tables, source="<layout search>")
        with range_warnings_unsaid():
            searches = [search_webs(plan, t, correction)
                        for t in centrings(with_layout(data, layout), targets)]
    except DesignError:
        return None
    forces = [max_full_scale_force_N(s, targets.full_scale_force_N) for s in searches]
    best = int(np.argmax(forces))  # the centring a whole design would fall back to, if it must
    return Mechanics(tables, searches[best], forces[best])


def centrings(tables: Mapping[str, Any], targets: Targets) -> list[Targets]:
    """The stiffness centrings a whole design on ``tables`` may take: with a tissue, the
    coupled one (:func:`tactcad.studies.inverse_design.centred_for_tissue`, on the whole
    array's tips) and eq. 2's it falls back to; without, eq. 2's alone."""
    if targets.tissue is None:
        return [targets]
    try:
        plan = plan_from_dict(copy.deepcopy(dict(tables)), source="<layout search>")
    except DesignError:  # the whole array breaks a rule: its design is refused on its own
        return [targets]
    return [centred_for_tissue(plan, targets), targets]


def smallest_length_mm(data: Mapping[str, Any], mech: Mechanics, force_N: float) -> float | None:
    """The shortest overall element length (mm) whose bolt pattern holds the
    longest arm of some web that meets the stiffness targets and carries
    ``force_N`` (None: no web does), on ``data``'s bolt."""
    s = mech.search
    ok = np.ones(s.webs_mm.shape, bool)
    for lim in s.limits[:STIFFNESS_LIMITS]:
        ok &= lim.allowed
    ok &= s.margin * s.force_N >= force_N * (1 - 1e-9)
    if not ok.any():
        return None
    longest = np.fmax(s.arm_r_mm, s.arm_m_mm)[ok]
    radii = s.radii_mm[ok]
    need = min(required_overall_length_mm(data, float(a), float(r)) for a, r in zip(longest, radii))
    return math.ceil(need * 2 - 1e-9) / 2


# ---------------------------------------------------------------------------
# The search
# ---------------------------------------------------------------------------
@dataclass
class Attempts:
    """What the search met, for its refusal."""

    stack_fit: list[FreeLayout]
    mechanics: dict[tuple[float, float], Mechanics | None]
    derived: list[DesignError]
    other: list[DesignError]
    #: The least full-scale force (N) at which each layout's whole design was refused.
    refused_at: dict[FreeLayout, float] = default_of(default_factory=dict)


def searched_design(data: Mapping[str, Any], targets: Targets, *, fixed: Sequence[str] = (),
                    validate: Validate | None = None, footprint_mm: Sequence[float] | None = None,
                    envelope_of: Envelope | None = None, name: str = "inverse_design",
                    correction=None) -> InverseDesign:
    """The inverse design nearest the start tables that meets ``targets`` (and
    fits ``footprint_mm``), searched over the free layout (module docstring).

    Args:
        data: the start's raw tables (material, grid and the user's values set,
            :func:`tactcad.studies.inverse_design.start_tables`); not modified.
        fixed: fields of :data:`FREE_FIELDS` the user fixed.
        validate: raw tables -> anything, raising :class:`DesignError` where
            the written project would be refused (e.g. its rigs); None: the
            design's own rules only.
        footprint_mm: [X, Y] or [X, Y, Z] the clamped array must fit, or None.
        envelope_of: plan -> its clamped array's (X, Y, Z), mm (with a footprint).

    Returns:
        The design, its changed values' reasons under ``[assumptions]``.

    Raises:
        InverseDesignError: no layout meets the targets; the binding limits of
            the asked targets and the nearest feasible ones (``alternatives``).
    """
    start = layout_of(data)
    fixed = frozenset(fixed)
    layouts = candidate_layouts(start, fixed, data["element"].get("process"))
    seen = Attempts([c for c in layouts if stack_fits(data, c)], {}, [], [])
    found = first_design(data, targets, seen, footprint_mm, envelope_of, validate, name,
                         correction)
    if found is not None:
        d, layout = found
        d = _with_reasons(d, start, layout, footprint_mm)
        across = None if footprint_mm is not None else across_layouts_force(
            data, targets, seen, start, layout, validate, name, correction)
        return replace(d, layout_words=layout.words(), **({} if across is None else dict(
            across_layouts_force_N=across[0], across_layouts_layout=across[1].words())))
    raise refusal(data, targets, start, seen, fixed, footprint_mm, envelope_of, validate, name,
                  correction)


def first_design(data: Mapping[str, Any], targets: Targets, seen: Attempts,
                 footprint_mm: Sequence[float] | None, envelope_of: Envelope | None,
                 validate: Validate | None, name: str, correction
                 ) -> tuple[InverseDesign, FreeLayout] | None:
    """The first whole design the search finds at ``targets`` (module docstring, steps
    3-4): of the layouts in ``seen.stack_fit`` (nearest the start first) whose elements
    carry the asked force, at most :data:`MAX_DESIGNS` are tried.

    A layout refused at a force no larger than the one asked (``seen.refused_at``) is
    counted as tried without judging it again: its whole design only gets harder as the
    force grows, so a refusal's search for the force it offers skips it.

    Args:
        data: the start's raw tables. targets: the asked targets. seen: what the search
            met (filled in). footprint_mm, envelope_of, validate, name, correction: as
            :func:`searched_design`.

    Returns:
        (the design, its layout), or None when no layout tried passes.
    """
    F = targets.full_scale_force_N
    tried = 0
    with warnings.catch_warnings():  # the candidates, not the design written (its own warn)
        warnings.simplefilter("ignore")
        for layout in seen.stack_fit:
            mech = _mechanics(seen, data, layout, targets, correction)
            if mech is None or mech.largest_force_N < FORCE_SCREEN * F:
                continue
            if footprint_mm is not None and not _may_fit(data, layout, mech, F, footprint_mm,
                                                         envelope_of):
                continue
            tried += 1
            d = None if seen.refused_at.get(layout, math.inf) <= F else _attempt(
                with_layout(data, layout), targets, name, correction, footprint_mm,
                envelope_of, validate, seen)
            if d is not None:
                return d, layout
            seen.refused_at[layout] = min(F, seen.refused_at.get(layout, math.inf))
            if tried >= MAX_DESIGNS:
                break
    return None


def _mechanics(seen: Attempts, data, layout: FreeLayout, targets: Targets, correction
               ) -> Mechanics | None:
    key = (layout.sheet_mm, layout.tip_width_mm)
    if key not in seen.mechanics:
        seen.mechanics[key] = mechanics_of(data, layout, targets, correction)
    return seen.mechanics[key]


def _envelope(tables: Mapping[str, Any], envelope_of: Envelope, length_mm: float
              ) -> tuple[float, ...] | None:
    """The envelope of ``tables`` with elements ``length_mm`` long (its Y and Z do
    not depend on the arms; X grows with the length)."""
    out = copy.deepcopy(dict(tables))
    out["element"] = {**out["element"], "overall_length_mm": float(length_mm)}
    R = float(out["element"]["notch_radius_mm"])
    arm = min(ARM_RANGE_MM[1], max(ARM_RANGE_MM[0],
                                   length_mm - required_overall_length_mm(out, 0.0, R)))
    out["arms"] = {"lengths_mm": [round(arm, 3)] * len(out["arms"]["lengths_mm"])}
    out.pop("requirements", None)
    try:
        return tuple(float(e) for e in envelope_of(plan_from_dict(out, source="<footprint>")))
    except DesignError:
        return None


def _may_fit(data, layout, mech, force_N, footprint_mm, envelope_of) -> bool:
    """The smallest envelope the layout's web search allows at ``force_N`` fits."""
    tables = with_layout(data, layout)
    length = smallest_length_mm(tables, mech, force_N)
    if length is None:
        return False
    env = _envelope(tables, envelope_of, length)
    return env is not None and fits(env, [f + FOOTPRINT_STEP_MM for f in footprint_mm])


def _attempt(tables, targets, name, correction, footprint_mm, envelope_of, validate,
             seen: Attempts) -> InverseDesign | None:
    """A whole design on ``tables`` (within the footprint), validated; None
    when refused (the refusal kept in ``seen``)."""
    try:
        if footprint_mm is None:
            d = design_from_tables(copy.deepcopy(tables), targets, name=name,
                                   correction=correction)
        else:
            d = _within_footprint(tables, targets, footprint_mm, envelope_of, name, correction)
            if d is None:
                return None
        if validate is not None:
            validate(d.data)
        return d
    except InverseDesignError:
        return None
    except DesignError as exc:
        errors = getattr(exc, "errors", (exc,))
        derived = [e for e in errors if e.field.startswith("requirements.")
                   and not isinstance(e, RequirementFailure)]
        (seen.derived if derived else seen.other).extend(derived or errors)
        return None


def _within_footprint(tables, targets, footprint_mm, envelope_of, name, correction
                      ) -> InverseDesign | None:
    """The design on ``tables`` as asked when it fits, else with the longest
    element that fits (:func:`tactcad.studies.footprint_fit.design_in_footprint`),
    the footprint stated."""
    try:
        plain = design_from_tables(copy.deepcopy(tables), targets, name=name,
                                   correction=correction)
    except DesignError:
        plain = None
    if plain is not None and fits(envelope_of(plain.plan), footprint_mm):
        return stated_footprint(plain, footprint_mm)
    return design_in_footprint(tables, targets, footprint_mm, envelope_of,
                               correction=correction, name=name)


def _with_reasons(d: InverseDesign, start: FreeLayout, layout: FreeLayout,
                  footprint_mm) -> InverseDesign:
    """``d`` with the reason of each free value it changed from the start."""
    changed = layout.changed(start)
    if not changed:
        return d
    data = copy.deepcopy(d.data)
    why = data.setdefault("assumptions", {})
    before, after = start.values(), layout.values()
    asked = "the footprint and targets" if footprint_mm is not None else "the targets"
    for field in changed:
        why[field] = (f"tactcad design: {after[field]:g}" if isinstance(after[field], float)
                      else f"tactcad design: {after[field]}") + (
            f" instead of the base design's {before[field]:g}" if isinstance(before[field], float)
            else f" instead of the base design's {before[field]}") + (
            f"; the layout nearest the base design that meets {asked} ({layout.words()}).")
    return replace(d, data=data, plan=plan_from_dict(data, source="<inverse design>"),
                   layout_changes=tuple((f, before[f], after[f]) for f in changed))


# ---------------------------------------------------------------------------
# The refusal
# ---------------------------------------------------------------------------
def _fmt(x: float, digits: int = 3) -> str:
    return f"{float(f'{x:.{digits}g}'):g}"


def _ceil_step(x: float, step: float) -> float:
    return math.ceil(x / step - 1e-9) * step


def force_refusal(asked_N: float, whole_N: float, estimate_N: float, asked: str,
                  why: str) -> DesignError | None:
    """The refusal of ``--full-scale-force`` as the force that binds, or None when it does
    not: whole designs meet the force asked (``whole_N`` >= ``asked_N``), so another rule
    refused the layouts, and an "at most" the asked force itself would contradict itself.

    Args:
        asked_N: the force asked (N).
        whole_N: the largest force whole designs meet (N, rounded down; 0 when none).
        estimate_N: the web search's estimate of it (N), said when no whole design meets one.
        asked: the targets in words. why: what binds, in words.

    Returns:
        The :class:`DesignError` naming ``--full-scale-force``, or None.
    """
    if whole_N >= asked_N:
        return None
    most = whole_N or estimate_N
    # rounded down: an "at most" rounded to the nearest digit can name a force above the
    # limit (0.004826 N said as 0.00483 N, which pasted is refused again)
    shown = next((f"{round_down(most, d):g}" for d in (3, 4) if round_down(most, d) < asked_N),
                 f"{round_down(most, 6):g}")
    if float(shown) >= asked_N:  # no digits show it below the force asked: say so
        return DesignError("--full-scale-force", asked_N, f"less than {asked_N:g} N for "
                           f"{asked}", why)
    return DesignError("--full-scale-force", asked_N, f"at most {shown} N for {asked}", why)


def refusal(data, targets: Targets, start: FreeLayout, seen: Attempts, fixed, footprint_mm,
            envelope_of, validate, name, correction) -> InverseDesignError:
    """The error of a search that found no design: each asked target that
    binds, its limit, and the nearest feasible targets (module docstring)."""
    F = targets.full_scale_force_N
    lo, hi = targets.k_obj_range_N_per_mm
    asked = (f"K_r/K_m {targets.kr_over_km:g} over K_obj {lo:g}-{hi:g} N/mm"
             f"{' (with the tissue coupling)' if targets.tissue is not None else ''} in "
             f"{data['material'].get('grade') or data['material'].get('name')}")
    errors: list[DesignError] = []
    alternatives: list[dict] = []
    columns = int(data["array"]["columns"])
    designs = paste_judge(data, frozenset(fixed), validate, name, correction)
    with warnings.catch_warnings(), evaluations_kept():  # one layout's force is sought twice
        warnings.simplefilter("ignore")
        if not seen.stack_fit:
            most = most_columns(data, candidate_layouts(start, fixed))
            free = "" if FREE_FIELDS[1] in fixed else " of the ISO table"
            errors.append(DesignError(
                "--columns", columns, f"at most {most}" if most else "none",
                f"no bolt{free} holds a stack of {columns} elements with both clamp plates and "
                f"the rigs' bracket ear, in any layout searched"))
            if most:
                alternatives.append(_alt(f"--columns {most}", f"{most} columns: the longest "
                                         "stack a stock bolt holds", "target"))
            return _error(errors, alternatives, targets)
        mechs = [(c, _mechanics(seen, data, c, targets, correction)) for c in seen.stack_fit]
        mechs = [(c, m) for c, m in mechs if m is not None]
        if not mechs:  # the values the user fixed break a rule no free value mends
            unseen = tissue_centring_error(data, seen.stack_fit, targets)
            if unseen is not None:  # or no rule is broken: the tissue hides K_obj from R
                return _error([unseen], [], targets)
            return fewest_rule_errors(data, seen.stack_fit)
        stiff = [(c, m) for c, m in mechs if m.largest_force_N > 0]
        if not stiff:
            errors.append(_stiffness_error(data, targets, mechs))
            alternatives += _stiffness_alternatives(data, targets, mechs, correction, designs)
            return _error(errors, alternatives, targets)
        best_c, best_m = max(stiff, key=lambda cm: (cm[1].largest_force_N, -cm[0].distance(start)))
        # the force binds where the best elements fall short of it, or where every layout
        # tried was refused by the targets alone (none by a rule or a derived requirement)
        refused_by_targets = footprint_mm is None and not seen.other and not seen.derived
        short = best_m.largest_force_N < F
        force_binds = short or refused_by_targets
        if force_binds:
            # sought from the domain's largest force, not the asked one: the same whatever
            # force was asked above it
            f_best = largest_feasible_force(with_layout(data, best_c), replace(
                targets, full_scale_force_N=MAX_FULL_SCALE_FORCE_N), correction)
            offer = None if footprint_mm is not None else frontier_force(
                data, targets, seen, best_c, validate, name, correction)
            where = (f"{offer[1].words()}, the layout the search designs at {offer[0]:g} N"
                     if offer else f"{best_c.words()}, the layout whose elements carry most")
            # elements that carry the force asked: named only with a force the search designs
            error = None if not short and not offer else force_refusal(
                F, offer[0] if offer else f_best, best_m.largest_force_N, asked,
                f"bound by {_force_limits(best_m, targets)}; at {where}")
            force_binds = error is not None
            errors += [error] if force_binds else []
            if force_binds and offer:
                alternatives.append(_alt(
                    f"--full-scale-force {_fmt(offer[0])}",
                    f"the largest full-scale force the search designs ({offer[1].words()})",
                    "target", largest_force_N=offer[0]))
        if footprint_mm is not None:
            errors_fp, alts_fp = _footprint_refusal(data, targets, stiff, footprint_mm,
                                                    envelope_of, validate, name, correction, start)
            errors += errors_fp
            alternatives += alts_fp
        if not errors and seen.derived:
            e, alt = _derived_refusal(with_layout(data, best_c), targets, seen.derived, best_m,
                                      validate, name, correction)
            errors.append(e)
            alternatives += alt
        if not errors:
            errors.append(_other_error(seen, targets, asked))
        if footprint_mm is None and (force_binds or not alternatives):
            tables = with_layout(data, best_c)
            # each judged as pasted: by the search from the start, not on this one layout
            near = nearest_targets(tables, targets, correction, designs=designs)
            alternatives += [_alt(_option(a), TARGET_WORDS[a.field], "target")
                             for a in near if a.field != "--full-scale-force"]
            alternatives += [_alt(_option(a), a.words(), "change", meets_targets=a.meets_targets,
                                  largest_force_N=a.largest_force_N)
                             for a in relaxing_changes(tables, targets, correction,
                                                       better_than_N=best_m.largest_force_N,
                                                       designs=designs)
                             if a.field != "sheet.thickness_mm"]
    return _error(errors, alternatives, targets)


def across_layouts_force(data: Mapping[str, Any], targets: Targets, seen: Attempts,
                         start: FreeLayout, chosen: FreeLayout, validate: Validate | None,
                         name: str, correction
                         ) -> tuple[float, FreeLayout]:
    """The largest full-scale force (N) the search designs at across the layouts it searches
    and its layout, as its refusal names it (:func:`refusal`: the frontier sought from the
    layout whose elements carry most, :func:`searched_force`), for a search that designed
    on ``chosen`` at ``targets``: a lab reading a design's largest force must not miss a
    larger one another sheet gives, and must read the figure a refusal of a larger force
    offers, not a layout's own estimate of it. Never less than the force designed.

    Args:
        data: the start's raw tables. targets: the asked targets. seen: the asked search's
            attempts (its layouts' mechanics are reused). start: the start's layout (of
            layouts alike, the nearest it is taken). chosen: the layout designed on.
        validate, name, correction: as :func:`searched_design`.

    Returns:
        (force N, its layout); (the asked force, ``chosen``) where the frontier is not
        above it (a force asked between two forces of the 3-digit grid).
    """
    F = targets.full_scale_force_N
    with warnings.catch_warnings(), evaluations_kept():
        warnings.simplefilter("ignore")
        mechs = [(c, _mechanics(seen, data, c, targets, correction)) for c in seen.stack_fit]
        stiff = [(c, m) for c, m in mechs if m is not None and m.largest_force_N > 0]
        offer = None
        if stiff:
            best_c, _ = max(stiff, key=lambda cm: (cm[1].largest_force_N,
                                                   -cm[0].distance(start)))
            offer = frontier_force(data, targets, seen, best_c, validate, name, correction)
    return (F, chosen) if offer is None or offer[0] < F else offer


def frontier_force(data: Mapping[str, Any], targets: Targets, seen: Attempts,
                   best: FreeLayout, validate: Validate | None, name: str, correction
                   ) -> tuple[float, FreeLayout] | None:
    """The largest full-scale force (N, on the 3-digit grid) the search designs at, and its
    layout: sought from ``best``'s own largest force (whole designs on that layout, sought
    from the domain's largest force, so the same whatever force was asked), then by the
    search itself (:func:`searched_force`). One figure for a refusal and a design's report.

    Args:
        data: the start's raw tables. targets: the asked targets (their force unused).
        seen: the search's attempts. best: the layout whose elements carry most.
        validate, name, correction: as :func:`searched_design`.

    Returns:
        (force N, layout), or None when the search designs at no force tried.
    """
    f_best = largest_feasible_force(with_layout(data, best), replace(
        targets, full_scale_force_N=MAX_FULL_SCALE_FORCE_N), correction)
    return None if f_best <= 0 else searched_force(data, targets, seen, f_best, validate,
                                                   name, correction)


#: A refusal's offered force: the search is asked again at forces this factor apart,
#: down from the best layout's largest force, at most :data:`OFFER_STEPS_DOWN` times,
#: then a decade (:data:`OFFER_DECADE`) at a time down to the domain's least force
#: (:data:`~tactcad.design.requirements_section.MIN_FULL_SCALE_FORCE_N`), then the
#: interval between the force that designs and the one refused above it is halved on a
#: log scale, at most :data:`OFFER_HALVINGS` times, until the grid has no force inside it.
OFFER_STEP = 0.97
OFFER_STEPS_DOWN = 6
OFFER_DECADE = 0.1
OFFER_HALVINGS = 16
#: Steps up from a start force that designs: the first by 1 / :data:`OFFER_STEP`, each
#: next the last one squared (x1.03, x1.06, x1.13, x1.28, ...), to the domain's largest force.
OFFER_STEPS_UP = 12


def searched_force(data: Mapping[str, Any], targets: Targets, seen: Attempts, start_N: float,
                   validate: Validate | None, name: str, correction
                   ) -> tuple[float, FreeLayout] | None:
    """The largest full-scale force (N, 3 significant digits, rounded down) at which the
    search itself designs (:func:`first_design`, layout and validation included), sought
    from ``start_N`` (:func:`force_frontier`): the force a refusal offers to paste.

    A layout's elements may carry more than the search reaches: only the
    :data:`MAX_DESIGNS` layouts nearest the start that pass the force screen are tried,
    so the best layout's own largest force may be refused when pasted.

    Args:
        data: the start's raw tables. targets: the asked targets (their force unused).
        seen: the asked search's attempts (its layouts' mechanics and refusals are reused).
        start_N: where the search for the force starts (N): the best layout's largest force.
        validate, name, correction: as :func:`searched_design`.

    Returns:
        (force N, the layout the search designs there), or None when the search designs
        at none of the forces tried.
    """
    def designed_layout(force_N: float) -> FreeLayout | None:
        again = Attempts(seen.stack_fit, seen.mechanics, [], [], seen.refused_at)
        found = first_design(data, replace(targets, full_scale_force_N=force_N), again, None,
                             None, validate, name, correction)
        return None if found is None else found[1]

    return force_frontier(designed_layout, start_N)


def force_frontier(designed: Callable[[float], Any], start_N: float,
                   floor_N: float = MIN_FULL_SCALE_FORCE_N,
                   ceiling_N: float = MAX_FULL_SCALE_FORCE_N) -> tuple[float, Any] | None:
    """The largest force on the 3-significant-digit grid at which ``designed`` answers
    (not None), found from ``start_N`` alone, so the same for any force asked above it:
    ``start_N`` rounded down, then steps of :data:`OFFER_STEP` down, then decades down
    (:data:`OFFER_DECADE`) to ``floor_N`` until one designs, then the interval up to the
    force refused above it bisected on a log scale on the grid (a soft K_obj range's
    layouts may design only far below the best layout's own largest force). Where
    ``start_N`` itself designs, the search steps up (:data:`OFFER_STEPS_UP`, to
    ``ceiling_N``) until a force is refused, then bisects:
    the start is one layout's estimate, and the layout the search reaches may carry more
    (a 0.281 N start on a 6 mm sheet that designs up to 0.284 N), so the answer does not
    depend on where it started. Every force returned was itself judged.

    Args:
        designed: force (N) -> what designs there (e.g. its layout), or None.
        start_N: the force to start from (N, > 0).
        floor_N: the least force tried (N): the domain's least full-scale force.
        ceiling_N: the largest force tried (N): the domain's largest full-scale force.

    Returns:
        (force N, ``designed``'s answer there), or None when none of the forces tried,
        down to ``floor_N``, designs.
    """
    def tried() -> Iterator[float]:
        force = round_down(start_N, 3)
        for _ in range(OFFER_STEPS_DOWN):
            yield force
            force = round_down(force * OFFER_STEP, 3)
        while force >= floor_N:
            yield force
            force = round_down(force * OFFER_DECADE, 3)

    refused = None
    for force in tried():
        got = designed(force)
        if got is not None:
            break
        refused = force
    else:
        return None
    best = (force, got)
    factor = 1.0 / OFFER_STEP
    for _ in range(OFFER_STEPS_UP if refused is None else 0):  # the start designs: go up,
        up = min(round_up(best[0] * factor, 3), round_down(ceiling_N, 3))  # the step squared
        if up <= best[0]:  # each time it designs again
            break
        got = designed(up)
        if got is None:
            refused = up
            break
        best, factor = (up, got), factor * factor
    for _ in range(OFFER_HALVINGS if refused is not None else 0):
        # the geometric mean (a decade's interval), else the arithmetic one, which falls
        # on a grid force inside the interval whenever there is one
        mid = round_down(math.sqrt(best[0] * refused), 3)
        if mid <= best[0]:
            mid = round_down(0.5 * (best[0] + refused), 3)
        if mid <= best[0] or mid >= refused:
            break  # the grid has no force between them
        got = designed(mid)
        if got is not None:
            best = (mid, got)
        else:
            refused = mid
    return best


#: What each nearest target of :func:`tactcad.studies.design_alternatives.nearest_targets` is.
TARGET_WORDS = {"--full-scale-force": "the largest full-scale force",
                "--kr-over-km": "the nearest feasible K_r/K_m",
                "--kobj-range": "the K_obj range moved to the nearest feasible, its width kept"}


def _alt(option: str, words: str, kind: str, **more) -> dict:
    return {"option": option, "words": words, "kind": kind, **more}


def _option(a) -> str:
    """An :class:`~tactcad.studies.design_alternatives.Alternative` as options to paste; a
    change that does not meet every target with the force (N) it designs at."""
    if a.field.startswith("--"):
        value = " ".join(_fmt(v) for v in a.value) if isinstance(a.value, tuple) else _fmt(a.value)
        return f"{a.field} {value}"
    force = "" if a.kind != "change" or a.meets_targets or a.largest_force_N <= 0 else \
        f" --full-scale-force {a.largest_force_N:g}"
    if a.field == "material.grade":
        return f"--material {a.value}{force}"
    return (f"--set '{a.field}=\"{a.value}\"'" if isinstance(a.value, str)
            else f"--set {a.field}={a.value:g}") + force


def paste_judge(data: Mapping[str, Any], fixed: frozenset[str], validate: Validate | None,
                name: str, correction) -> Callable[..., bool]:
    """The judge of an option a refusal offers to paste
    (:data:`tactcad.studies.design_alternatives.Designs`): whether ``tactcad design`` with
    it designs, by the search itself (the layouts nearest the start, the force screen,
    whole designs and validation: :func:`first_design`), not by one layout's design.

    Args:
        data: the start's raw tables. fixed: the fields of :data:`FREE_FIELDS` the user
            fixed. validate, name, correction: as :func:`searched_design`.

    Returns:
        (targets, change) -> bool, each answer kept for the same targets and change;
        ``change`` is None or (``material.grade`` or a ``section.field``, its value).
    """
    kept: dict[tuple[str, str], bool] = {}

    def designs(targets: Targets, change: tuple[str, Any] | None = None) -> bool:
        key = (repr(targets), repr(change))
        if key not in kept:
            tables = changed_start(data, change)
            layouts = candidate_layouts(layout_of(tables), fixed, tables["element"].get("process"))
            seen = Attempts([c for c in layouts if stack_fits(tables, c)], {}, [], [])
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                kept[key] = first_design(tables, targets, seen, None, None, validate, name,
                                         correction) is not None
        return kept[key]

    return designs


def changed_start(data: Mapping[str, Any], change: tuple[str, Any] | None) -> dict[str, Any]:
    """The start's tables with ``change`` pasted as ``tactcad design`` takes it: a grade
    (``--material``) replaces the material table, any other ``section.field`` (``--set``)
    sets that value.

    Args:
        data: the start's raw tables. change: None, or (field, value).

    Returns:
        A copy of the tables.
    """
    out = copy.deepcopy(dict(data))
    if change is None:
        return out
    field, value = change
    if field == "material.grade":
        out["material"] = {"name": value, "grade": value}
        return out
    section, key = field.split(".", 1)
    out[section] = {**out.get(section, {}), key: value}
    return out


def _error(errors: list[DesignError], alternatives: list[dict], targets: Targets
           ) -> InverseDesignError:
    """One error naming every binding target, then the options to paste."""
    lines = [e.line() for e in errors]
    text = "the targets cannot be met" + (": " if len(lines) == 1 else ":\n  ") + \
        "\n  ".join(lines)
    if alternatives:
        text += "\nnearest feasible, to paste: " + "; ".join(
            f"{a['option']} ({a['words']})" for a in alternatives)
    first = errors[0]
    out = InverseDesignError(text, first.field, first.value, first.allowed, alternatives)
    out.errors = tuple(errors)
    out.why = first.why
    return out


def _force_limits(mech: Mechanics, targets: Targets) -> str:
    """The limits that bind just above the layout's largest force, in words."""
    s = mech.search
    above = replace(targets, full_scale_force_N=mech.largest_force_N * 1.001)
    plan = plan_from_dict(copy.deepcopy(mech.tables), source="<layout search>")
    with range_warnings_unsaid():
        probe = search_webs(plan, above, webs_mm=s.webs_mm)
    return "; ".join(lim.name for lim in binding_limits(probe))


def _stiffness_error(data, targets: Targets, mechs) -> DesignError:
    """No layout meets K_r and K_m within the arm range: the ratio is refused."""
    c, m = mechs[0]
    words = "; ".join(f"{lim.name}: {lim.detail}" for lim in binding_limits(m.search)
                      if lim in m.search.limits[:STIFFNESS_LIMITS])
    return DesignError("--kr-over-km", targets.kr_over_km,
                       f"a ratio whose K_r = {targets.k_r:.4g} and K_m = {targets.k_m:.4g} N/mm "
                       f"arms within {ARM_RANGE_MM[0]:g}-{ARM_RANGE_MM[1]:g} mm reach",
                       f"{words} (with --kobj-range {' '.join(f'{k:g}' for k in targets.k_obj_range_N_per_mm)})")


def _stiffness_alternatives(data, targets, mechs, correction, designs=None) -> list[dict]:
    if not mechs:
        return []
    tables = with_layout(data, mechs[0][0])
    return [_alt(_option(a), TARGET_WORDS[a.field], "target")
            for a in nearest_targets(tables, targets, correction, designs=designs)]


def _footprint_refusal(data, targets: Targets, stiff, footprint_mm, envelope_of, validate,
                       name, correction, start) -> tuple[list[DesignError], list[dict]]:
    """The footprint's limit: the smallest envelope any layout meets, at the
    asked force or, where its elements cannot carry it, the largest they do.
    Where some layout fits at the force its elements carry, the footprint does
    not bind: no error, and the largest such force is offered instead."""
    F = targets.full_scale_force_N
    weighed = []  # (need, force, distance, layout, envelope)
    for c, m in stiff:
        force = min(F, m.largest_force_N)
        tables = with_layout(data, c)
        length = smallest_length_mm(tables, m, force)
        env = None if length is None else _envelope(tables, envelope_of, length)
        if env is not None:
            weighed.append((max(e / f for e, f in zip(env, footprint_mm)), force,
                            c.distance(start), c, env))
    if not weighed:
        return [DesignError("--footprint", list(footprint_mm), "none for these targets",
                            "no layout's elements meet the stiffness targets")], []
    fitting = [w for w in weighed if w[0] <= 1.0 + 1e-9]
    if fitting:  # the force binds, not the footprint
        _, force, _, c, _ = max(fitting, key=lambda w: (w[1], -w[2]))
        force = _offered_force(with_layout(data, c), targets, force, correction)
        d = _checked(with_layout(data, c), replace(targets, full_scale_force_N=force),
                     footprint_mm, envelope_of, validate, name, correction)
        return [], [] if d is None else [_alt(
            f"--full-scale-force {force:g}",
            f"the largest full-scale force within the footprint ({c.words()})", "target",
            full_scale_force_N=force)]
    from tactcad.studies.verification import least_footprint_mm

    need, force, _, c, env = min(weighed, key=lambda w: (w[0], -w[1], w[2]))
    axes = len(footprint_mm)
    tables = with_layout(data, c)
    if force < F:  # the force the layout carries, by whole designs
        force = _offered_force(tables, targets, force, correction)
    offer = [_ceil_step(e, FOOTPRINT_STEP_MM) for e in env[:axes]]
    for _ in range(4):  # a whole design within the offer; grown a step where it is not
        d = _checked(tables, replace(targets, full_scale_force_N=force), offer, envelope_of,
                     validate, name, correction)
        if d is not None:
            break
        offer = [o + FOOTPRINT_STEP_MM for o in offer]
    err = DesignError("--footprint", list(footprint_mm),
                      f"at least {' x '.join(f'{e:g}' for e in least_footprint_mm(env, axes))} mm"
                      + ("" if force >= F else f" at {force:g} N"),
                      f"the smallest clamped array of any layout ({c.words()}); the soft arm for "
                      f"K_m = {targets.k_m:.4g} N/mm and the bolt pattern behind it set X, the "
                      "stack of sheets and spacers across the columns Y"
                      + ("" if d is not None else
                         "; none to paste: no whole design of that layout validates within it "
                         f"or {FOOTPRINT_STEP_MM * 4:g} mm more each way"))
    if d is None:
        return [err], []
    option = " ".join(_fmt(o) for o in offer)
    words = f"the smallest footprint ({c.words()})"
    return [err], [_alt(f"--footprint {option}" if force >= F else
                        f"--full-scale-force {force:g} --footprint {option}",
                        words if force >= F else words + ", at the force it carries", "target",
                        full_scale_force_N=force)]


def _offered_force(tables, targets: Targets, estimate_N: float, correction) -> float:
    """The largest force (N, 3 digits, rounded down) whole designs on ``tables``
    meet at the asked ratio and range, at most ``estimate_N``."""
    whole = largest_feasible_force(tables, targets, correction)
    return _round_away(min(estimate_N, whole) if whole > 0 else estimate_N, math.inf)


def _checked(tables, targets: Targets, footprint_mm, envelope_of, validate, name, correction
             ) -> InverseDesign | None:
    """The design within ``footprint_mm``, validated as written, or None."""
    d = _within_footprint(tables, targets, footprint_mm, envelope_of, name, correction)
    if d is not None and validate is not None:
        try:
            validate(d.data)
        except DesignError:
            return None
    return d


def _derived_refusal(tables, targets: Targets, derived: Sequence[DesignError], mech: Mechanics,
                     validate, name, correction) -> tuple[DesignError, list[dict]]:
    """A requirement the design derives from the targets breaks its range (e.g.
    the K_obj resolution a small force reaches): refused as the force that set
    it, with the nearest force that meets it."""
    e = derived[0]
    F = targets.full_scale_force_N

    def ok(force: float) -> bool:
        try:
            d = design_from_tables(copy.deepcopy(tables),
                                   replace(targets, full_scale_force_N=force), name=name,
                                   correction=correction)
            if validate is not None:
                validate(d.data)
        except DesignError:
            return False
        return True

    top = max(mech.largest_force_N, F)
    scan = np.geomspace(F / 100, top, 25)
    near = nearest_on_scan(scan, F, ok)
    if near is not None:  # offered to 3 digits, rounded away from the asked force
        offer = _round_away(near, F)
        near = offer if ok(offer) else None
    what = e.why or "a requirement the design derives"
    side = "at least" if near is not None and near > F else "at most"
    err = DesignError("--full-scale-force", F,
                      f"{side} {near:g} N, where the design's {what} is within {e.allowed}"
                      if near is not None else f"a force whose design's {what} is within "
                      f"{e.allowed}", f"at {F:g} N it is {e.value!r}")
    if near is None:
        return err, []
    return err, [_alt(f"--full-scale-force {near:g}",
                      f"the nearest full-scale force whose design's {what} is within range",
                      "target", full_scale_force_N=near)]


def _round_away(x: float, asked: float) -> float:
    """``x`` to 3 significant digits, rounded away from ``asked`` (so the
    offer stays on the feasible side of the edge between them)."""
    e = 10.0 ** (math.floor(math.log10(x)) - 2)
    return (math.ceil(x / e - 1e-9) if x > asked else math.floor(x / e + 1e-9)) * e


def tissue_centring_error(data: Mapping[str, Any], layouts: Sequence[FreeLayout],
                          targets: Targets) -> DesignError | None:
    """``--kr-over-km`` refused where the tissue-coupled centring of K_r and K_m
    (:func:`centrings`) refuses the first layout's tips: near K_r/K_m = 1 the unit's R
    barely changes with K_obj, and the K_obj factor the centring asks runs out of its
    range (2e-9 at K_r/K_m 1.0000001 over 1-10 N/mm), so no layout's elements are weighed.

    Args:
        data: the start's raw tables. layouts: the layouts searched, nearest first.
        targets: the targets asked.

    Returns:
        The error naming ``--kr-over-km`` and the factor asked, or None where the targets
        carry no tissue, no layout was searched or the centring is not what refuses.
    """
    if targets.tissue is None or not layouts:
        return None
    try:
        centrings(with_layout(data, layouts[0]), targets)
    except DesignError as exc:
        if exc.field != "--tissue-coupling":
            return None
        factor = exc.value if isinstance(exc.value, float) else math.nan
        return DesignError(
            "--kr-over-km", targets.kr_over_km,
            "a ratio at which the unit's R = e_m/e_r changes with K_obj through the tissue",
            f"centring K_r and K_m on the range through the tissue asks a K_obj factor of "
            f"{factor:.3g}, outside 0.01 ... 100: near K_r/K_m = 1 a unit reads nearly the "
            "same R at every K_obj")
    return None


def fewest_rule_errors(data: Mapping[str, Any], layouts: Sequence[FreeLayout]) -> DesignError:
    """Every rule that bars the sheets searched, each as the nearest sheet breaks it.

    When every layout breaks a rule, the start's own refusal may name only what a sheet the
    process cannot cut breaks (a notch too large for it), not the rule that bars every
    sheet it can cut (a gauge grid wider than the sheet). Of the layouts that break fewest
    rules (the nearest of each sheet), each rule broken is named once, with its sheet.

    Args:
        data: the start's raw tables. layouts: the candidates, nearest the start first.

    Returns:
        The :class:`DesignError` (or :class:`~tactcad.errors.DesignErrors`) to raise.
    """
    first_per_sheet: dict[float, FreeLayout] = {}
    for layout in layouts:
        first_per_sheet.setdefault(layout.sheet_mm, layout)
    broken = [(sheet, getattr(e, "errors", (e,))) for sheet, e in
              ((s, _rule_error(with_layout(data, c))) for s, c in first_per_sheet.items())]
    fewest = min(len(errs) for _, errs in broken)
    named: dict[str, DesignError] = {}
    for sheet, errs in broken:
        for e in errs if len(errs) == fewest else ():
            named.setdefault(e.field, DesignError(
                e.field, e.value, e.allowed,
                f"{e.why}; on the {sheet:g} mm sheet" if e.why else f"on the {sheet:g} mm sheet",
                e.file))
    found = list(named.values())
    return found[0] if len(found) == 1 else DesignErrors(
        found, what=f"every sheet searched ({', '.join(f'{t:g}' for t in sorted(first_per_sheet))} mm)")


def _rule_error(tables: Mapping[str, Any]) -> DesignError:
    """The design rules ``tables`` break (every one), or a plain error when none."""
    try:
        plan_from_dict(copy.deepcopy(dict(tables)), source="<layout search>")
    except DesignError as exc:
        return exc
    return DesignError("--full-scale-force", None, "targets some layout meets",
                       "no layout's elements could be weighed")


def _other_error(seen: Attempts, targets: Targets, asked: str) -> DesignError:
    """No layout passed for a reason the targets do not name: the first rule broken."""
    if seen.other:
        e = seen.other[0]
        return DesignError(e.field, e.value, e.allowed, e.why)
    return DesignError("--full-scale-force", targets.full_scale_force_N,
                       f"a force the searched layouts carry for {asked}",
                       f"none of the first {MAX_DESIGNS} layouts tried met every rule")


