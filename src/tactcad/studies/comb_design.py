"""Designing an insert to a grasper's jaw: the monolithic comb searched over the sheet, its
pitch, arms, webs and hard stops for a stiffness ratio, an object-stiffness range and a
full-scale force, inside the room the jaw leaves.

The room (:func:`tactcad.partlib.grasper_jaw.jaw_room`) is the jaw part's own derivation
rules on a trocar class's default jaw or on a lab's ``[grasper_jaw]`` table: its stated
pocket, else the pocket between the pin's steel and the distal wall along and between the
side walls across, and the insert no taller than the jaw's thickness plus the tips' proud
height. The comb's fixed details (tip, arm height, notch radius, post, spacer, wire) are
the base comb's (the construction's ``jaw_template``, the shipped
``examples/grasper_jaw_10mm``), each marked as not searched (the template's own reasons
name its sizes); what the search sets:

* the pitch: the jaw's pocket length over the columns, to 0.1 mm;
* the arms: the references' the fitted range's shortest (the stiffest), the measuring
  elements' the longest the pitch leaves with the wire's slot;
* the webs: each solved at the closed form for K_m = s sqrt(K_lo K_hi / X) and K_r = X K_m
  (eq. 2's centre, each tip on its own object spring, scaled by s of :data:`KM_SCALES`: a
  stiffer pair carries more force while verify still reads the K_obj range), to 1 µm;
* the hard stops: engaging at :data:`STOP_MULTIPLE` x the rated deflection, or midway to
  the element's lowest fatigue limit where that comes first
  (:func:`tactcad.mechanics.hard_stops.engagement_force_N`), a shim no thinner than the
  comb's thinnest;
* the pairing: by column, each reference beside its measuring element (one radius);
* the fasteners, once the sheet and K_m are chosen: of the miniature screws
  (:data:`tactcad.vocabulary.standards.MINIATURE_SCREWS`) and ISO 8734 dowels, the largest
  screw, then the largest dowel, that the row and the jaw's height hold
  (:func:`with_fasteners`; a larger screw clamps the rows harder and is set by hand with a
  common key; the stiffness does not depend on them).

Asked for a grasp the insert must survive (``max_grasp_force_N``), the candidates that count
are grasped in that order in the jaw they are for, and the first that survives is chosen
(:func:`surviving`). Every sheet of :data:`SHEETS_MM` is tried at every scale; a candidate counts when its design
validates, stands no taller than the jaw's room, its verification matrix at the closed form
fails nothing and every stop engages between its rated and its yield-limited deflection. Of those, the softest pair that carries the force
with :data:`FORCE_MARGIN_REL` to spare is chosen (:func:`chosen`). When none counts, the refusal names each sheet's binding limit and the largest
full-scale force any sheet carries, as an option to paste; where no comb of the grade carries
any force at any column count, the other grade of the library whose comb carries the most
of the asked force (:func:`nearest_grade`). Units: mm, N, N/mm.
"""

from __future__ import annotations

import functools
import math
import shlex
import threading
from collections import OrderedDict
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field, replace
from pathlib import PurePath
from typing import Any, Callable, Iterator, Mapping, NamedTuple

from tactcad.vocabulary.schema import copy_tables
from tactcad.design.array_plan import plan_from_dict
from tactcad.errors import DesignError, DesignErrors
from tactcad.studies.inverse_design import (InverseDesignError, Targets, grid_fitted_to_sheet,
                                            held_to_process)

#: Sheet thicknesses searched (mm): Ti-6Al-4V and steel sheet of common stock.
SHEETS_MM = (0.5, 0.6, 0.8, 1.0, 1.2, 1.5)
#: A hard stop engages at this multiple of its element's rated deflection.
STOP_MULTIPLE = 1.3
#: Webs are solved to this step (mm): below wire EDM's tolerance.
WEB_STEP_MM = 0.001
#: The slot the search leaves after the longest element (mm): wider than a 0.1 mm wire's.
SLOT_MM = 0.2
#: K_m over eq. 2's centre sqrt(K_lo K_hi / X) searched: a stiffer pair carries more force
#: and reads the range's low end with less resolution (verify's K_obj range decides).
KM_SCALES = (1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0)
#: The force margin a chosen comb keeps, where one can (the softest pair that keeps it is
#: chosen; a stiffer one trades K_obj resolution for force).
FORCE_MARGIN_REL = 0.2
#: How near a refusal's force lies under the search's frontier (relative): its bracket is
#: bisected until its ends are this close (the stacked search's rule,
#: :func:`tactcad.studies.design_alternatives.largest_feasible_force`: seven bisections of
#: a 1.25 x bracket, 0.17 %), then rounded down to three digits, so the force pasted
#: designs and one 1 % above it is refused; each bisection judges again only the sheets
#: and K_m scales whose :class:`ForceBound` does not already fail the force.
FRONTIER_TOLERANCE_REL = 0.002


@dataclass(frozen=True)
class CombCandidate:
    """One sheet's comb at one K_m scale: its tables, plan (None when refused) and what
    binds it."""

    sheet_mm: float
    km_scale: float
    data: dict | None
    plan: Any
    failures: tuple[str, ...]
    force_margin_rel: float
    rated_force_N: float | None
    #: the code of each failure's limit (:mod:`tactcad.vocabulary.binding_limits`), in
    #: the failures' order
    limits: tuple[str, ...] = ()
    #: what fails this sheet and K_m scale at any full-scale force (:class:`ForceBound`);
    #: None when nothing is known beyond the force it was judged at
    force_bound: "ForceBound | None" = None
    #: recorded from its limits alone, its verification matrix left out
    #: (:func:`sketched_candidate`): its margin and rating are its judgement's, its
    #: failures only the force
    sketched: bool = False
    #: requirement -> its predicted figure in the candidate's closed-form verification
    #: matrix (:func:`judge_recorded`), where it was judged in full; None otherwise
    predicted: Mapping[str, Any] | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class ForceBound:
    """What a sheet's comb at one K_m scale fails at whatever full-scale force its stops
    are set for: its webs and plan do not depend on the force asked, only its stop gaps
    do (and through the widest, the arms' underside: the limits' error estimates move by
    a few parts in 1e9), so a refusal before the stops, its full-scale-force record and
    its gauge limits' clearances judge another force without judging the comb again,
    where they fail it by more than :data:`BOUND_SLACK_REL`.

    Attributes:
        refused: refused before any force was read (the pitch, a web, the plan): fails at
            every force.
        binding_force_N: the force (N) of the binding limit (the full-scale-force record's
            prediction, closed form); None when refused.
        binding_error_rel: its relative error estimate (None: infinite).
        gauge_limits: (force N, error estimate) of each gauge limit
            (:func:`tactcad.mechanics.limits.uncleared_gauge_limits`' rule).
    """

    refused: bool = False
    binding_force_N: float | None = None
    binding_error_rel: float | None = None
    gauge_limits: tuple[tuple[float, float], ...] = ()

    def fails_at(self, force_N: float) -> bool:
        """True when the comb fails at a full-scale force of ``force_N`` (N) by what this
        bound holds (a False says only that the comb must be judged at that force).

        The full-scale-force record's rule (the force it carries below the force asked:
        failed, or undecided but :func:`nominally_short`) and the gauge rule
        F_limit < F (1 + e), as :func:`judge_limits` applies them.
        """
        if self.refused:
            return True
        slack = 1.0 + BOUND_SLACK_REL
        if any(f * slack < force_N * (1.0 + e) for f, e in self.gauge_limits):
            return True
        if self.binding_force_N is None:
            return False
        # the record fails, or is short of the force in its prediction
        # (:func:`nominally_short`), either way below the force asked
        return self.binding_force_N * slack < force_N


#: How far (relative) a :class:`ForceBound` must fail a force to skip judging the comb:
#: a thousand times the drift of its figures with the stop gaps.
BOUND_SLACK_REL = 1e-6
#: The bound of a comb refused before any force was read.
REFUSED_AT_ANY_FORCE = ForceBound(refused=True)


@dataclass(frozen=True)
class CombDesign:
    """The search's answer: the chosen comb and every candidate tried."""

    data: dict
    plan: Any
    room: Any
    candidates: tuple[CombCandidate, ...]
    fasteners: tuple[FastenerTry, ...] = ()
    #: the candidate written (its fasteners chosen), before its name and reasons
    chosen: CombCandidate | None = None
    #: the largest full-scale force (N) a comb of this jaw, columns and grade counts at
    #: for these stiffness targets (:func:`largest_comb_force`, the frontier a refusal
    #: offers), or None where not sought
    max_full_scale_force_N: float | None = None


@dataclass(frozen=True)
class FastenerTry:
    """One screw and dowel pair tried on the chosen comb: what binds it (empty: it counts)."""

    screw_size: str
    dowel_diameter_mm: float
    failures: tuple[str, ...]

    @property
    def label(self) -> str:
        return f"{self.screw_size} screws, {self.dowel_diameter_mm:g} mm dowels"


#: The words of a comb's misfit in a size that does not depend on its columns.
COLUMN_FREE_MISFITS = ("height", "width")

def sheets_of(base: Mapping[str, Any]) -> tuple[float, ...]:
    """The sheets (mm) the comb is searched over: :data:`SHEETS_MM` for wire EDM; for
    another process of the base's ``[element] process``, the foil and stock gauges its
    flexure range holds (:func:`tactcad.studies.layout_search.process_sheets_mm`)."""
    from tactcad.studies.layout_search import process_sheets_mm
    from tactcad.vocabulary.process import DEFAULT_CUT_PROCESS

    process = (base.get("element") or {}).get("process") or DEFAULT_CUT_PROCESS
    if process == DEFAULT_CUT_PROCESS:
        return SHEETS_MM
    return tuple(process_sheets_mm(process))


def slot_of(d: Mapping[str, Any]) -> float:
    """The slot the search leaves after the longest element (mm): :data:`SLOT_MM`, or the
    narrowest the rows' process cuts on the sheet where that is wider."""
    from tactcad.design.array_plan import element_process_limits

    return max(SLOT_MM, element_process_limits(d).min_slot_mm.value_mm)


def _floor(x: float, step: float) -> float:
    return math.floor(x / step + 1e-9) * step


#: Web solves already made inside :func:`web_solves_kept` (None outside it): a refusal's
#: searches meet the same element, sheet and K target again (the reference's arm does not
#: change with the column count; the atlas judges a point's candidates twice).
_KEPT_WEBS: ContextVar[dict | None] = ContextVar("kept_web_solves", default=None)


@contextmanager
def candidates_weighed() -> Iterator[None]:
    """Where the search weighs its candidates: no range warning is said (they are not the
    design asked about, :func:`tactcad.mechanics.correction.range_warnings_unsaid`), so each
    element's closed-form estimate is kept and read again
    (:func:`tactcad.mechanics.ladder.closed_form_estimates_kept`).

    Returns:
        A context manager.
    """
    from tactcad.mechanics.correction import range_warnings_unsaid
    from tactcad.mechanics.ladder import closed_form_estimates_kept

    with range_warnings_unsaid(), closed_form_estimates_kept():
        yield


@contextmanager
def web_solves_kept() -> Iterator[None]:
    """Keep every :func:`solve_web` answer while inside (one command's search): the same
    geometry, material, K target (N/mm) and bracket (mm) give the same web, so each is
    solved once. Nested uses share the outer one's answers.

    Returns:
        A context manager; the answers are dropped on leaving the outermost.
    """
    from tactcad.store import memo_scope

    with memo_scope(_KEPT_WEBS):
        yield


def solve_web(geometry, material, k_target: float, lo: float, hi: float) -> float | None:
    """The web (mm, to :data:`WEB_STEP_MM`) giving ``geometry`` the closed form's K
    ``k_target`` (N/mm), or None when no web in [lo, hi] does; inside
    :func:`web_solves_kept`, an answer already found is reused.

    Args:
        geometry: the element (:class:`~tactcad.partlib.array.element.ElementGeometry`, mm).
        material: its material. k_target: the stiffness sought (N/mm). lo, hi: the webs
            searched (mm).

    Returns:
        The web (mm) or None.
    """
    kept = _KEPT_WEBS.get()
    key = (geometry, material, k_target, lo, hi)
    if kept is not None and key in kept:
        return kept[key]
    web = solved_web(geometry, material, k_target, lo, hi)
    if kept is not None:
        kept[key] = web
    return web


def solved_web(geometry, material, k_target: float, lo: float, hi: float) -> float | None:
    """:func:`solve_web` without the kept answers: the web of the :data:`WEB_STEP_MM` grid
    nearest the closed form's root of K = ``k_target`` (N/mm) on [lo, hi] (mm), found
    exactly: K rises with the web, so the root's grid web is the count of the half-steps
    between grid webs whose K falls short of the target, all worked out in one vectorised
    call (:func:`tactcad.mechanics.closed_form_batch.corrected_stiffness_batch`, K to
    within 1e-14 of :func:`closed_form_k`'s) rather than a root finder's dozen scalar ones.
    The K of the bracket's ends and half-steps does not depend on the target, so it is
    worked out once per element, material and bracket in a process (:func:`web_k_grid`):
    every point of an atlas and every K_m scale solve the same elements' webs again.

    Args:
        geometry: the element (mm; its web is the one sought). material: its material.
        k_target: the stiffness sought (N/mm). lo, hi: the webs searched (mm).

    Returns:
        The web (mm), or None when K - ``k_target`` has one sign at both ends.
    """
    import numpy as np

    grid = web_k_grid(geometry, material, lo, hi)
    if (grid.k_lo - k_target) * (grid.k_hi - k_target) > 0:
        return None
    k = grid.half_steps()
    return (grid.first + int(np.count_nonzero(k < k_target))) * WEB_STEP_MM


@dataclass
class WebKGrid:
    """An element's closed-form K over a web bracket (:func:`web_k_grid`), kept per
    process.

    Attributes:
        geometry, material, lo, hi: the element (mm), its material and the bracket (mm).
        correction: the fitted correction the K are worked out with.
        k_lo, k_hi: K (N/mm) at the bracket's ends (:func:`closed_form_k`).
        first, last: the bracket's ends in :data:`WEB_STEP_MM` steps.
    """

    geometry: Any
    material: Any
    lo: float
    hi: float
    correction: Any
    k_lo: float
    k_hi: float
    first: int
    last: int
    _k_half_steps: Any = None

    def half_steps(self):
        """K (N/mm, a read-only array) at every half-step between grid webs of the bracket,
        worked out on the first call (a bracket whose ends do not straddle a target needs
        none): one call of
        :func:`tactcad.mechanics.closed_form_batch.corrected_stiffness_batch`."""
        import numpy as np

        from tactcad.mechanics.closed_form_batch import corrected_stiffness_batch

        if self._k_half_steps is None:
            g, m = self.geometry, self.material
            steps = (np.arange(self.first, self.last) + 0.5) * WEB_STEP_MM
            k = np.atleast_1d(corrected_stiffness_batch(
                steps, g.notch_radius_mm, g.arm_length_mm, m.youngs_modulus_MPa, g,
                m.poisson_ratio, self.correction))
            k.setflags(write=False)
            self._k_half_steps = k
        return self._k_half_steps


#: Most :class:`WebKGrid` kept in a process (least recently used dropped first): an atlas
#: of one jaw meets a few hundred (sheets x column counts x grades), each at most a few
#: thousand floats.
WEB_K_GRIDS_KEPT = 1024
_WEB_K_GRIDS: "OrderedDict[tuple, WebKGrid]" = OrderedDict()
_WEB_K_GRIDS_LOCK = threading.Lock()  # a Dask worker may run tasks on several threads


def web_k_grid(geometry, material, lo: float, hi: float) -> WebKGrid:
    """The closed form's K of ``geometry`` in ``material`` at the web bracket's ends
    [``lo``, ``hi``] (mm) and, on demand, at every half-step between :data:`WEB_STEP_MM`
    grid webs in it: what :func:`solved_web` reads, the same numbers for any K target. A
    pure function of the element (every field but its web), the material, the bracket and
    the fitted correction (:func:`tactcad.mechanics.correction.load_correction`, read
    again when its file changes), so kept per process by those (:data:`WEB_K_GRIDS_KEPT`
    at most): every point of an atlas and every K_m scale of a search solve the same few
    hundred elements' webs.

    Args:
        geometry: the element (mm). material: its material. lo, hi: the bracket (mm).

    Returns:
        :class:`WebKGrid`.
    """
    from tactcad.mechanics.correction import load_correction

    correction = load_correction()
    key = (geometry, material, lo, hi)
    with _WEB_K_GRIDS_LOCK:
        kept = _WEB_K_GRIDS.get(key)
        if kept is not None and kept.correction is correction:
            _WEB_K_GRIDS.move_to_end(key)
            return kept
    grid = WebKGrid(geometry, material, lo, hi, correction,
                    closed_form_k(replace(geometry, web_thickness_mm=lo), material),
                    closed_form_k(replace(geometry, web_thickness_mm=hi), material),
                    round(lo / WEB_STEP_MM), round(hi / WEB_STEP_MM))
    with _WEB_K_GRIDS_LOCK:
        _WEB_K_GRIDS[key] = grid
        while len(_WEB_K_GRIDS) > WEB_K_GRIDS_KEPT:
            _WEB_K_GRIDS.popitem(last=False)
    return grid


def closed_form_k(geometry, material) -> float:
    """The closed form's K (N/mm) of ``geometry`` (mm) in ``material``
    (:func:`tactcad.mechanics.closed_form.corrected_element_k`: the K of
    :func:`~tactcad.mechanics.closed_form.estimate_closed_form` to the bit, without its
    gauge strain and range warning, which a trial web does not need); inside
    :func:`web_solves_kept`, a K already found is reused: every web solve of one element
    and sheet starts at the same bracket ends, and Brent's method reads them once more.

    Args:
        geometry: the element (:class:`~tactcad.partlib.array.element.ElementGeometry`, mm).
        material: its material.

    Returns:
        K (N/mm).
    """
    from tactcad.mechanics.closed_form import corrected_element_k

    kept = _KEPT_WEBS.get()
    key = ("K", geometry, material)
    if kept is not None and key in kept:
        return kept[key]
    k = corrected_element_k(geometry, material)
    if kept is not None:
        kept[key] = k
    return k


def usable_length_mm(d: Mapping[str, Any], along_mm: float) -> float:
    """The length (mm) a comb may fill of a pocket ``along_mm`` long: less the ISO 2768-1
    deviation of the design's general class on that length, so that the comb's length plus
    its deviation stays within the pocket and its own footprint requirement passes, not
    undecided (:func:`tactcad.studies.verification.footprint_record`)."""
    from tactcad.design.tolerances import general_linear_tolerance_mm, tolerances_of

    return along_mm - general_linear_tolerance_mm(along_mm, tolerances_of(d).general)


def pocket_for_length_mm(d: Mapping[str, Any], length_mm: float) -> float:
    """The shortest pocket (mm) whose usable length (:func:`usable_length_mm`) holds a comb
    ``length_mm`` long: the length plus its ISO 2768-1 deviation (that of the longer size
    where the sum crosses into the standard's next range)."""
    pocket = length_mm
    for _ in range(4):  # the deviation steps at a range's end: settles in one or two steps
        if usable_length_mm(d, pocket) >= length_mm - 1e-9:
            return pocket
        pocket = length_mm + (pocket - usable_length_mm(d, pocket))
    return pocket


#: The reference elements' arm (mm): the fitted range's shortest (row 1, every column).
REFERENCE_ARM_MM = 2.0
#: How much longer (mm) the measuring arm must be than the reference's for a comb to be
#: searched: a pitch that leaves less gives no pair whose K ratio the arms set.
MEASURING_ARM_EXCESS_MM = 0.5


def comb_tables(base: dict, sheet_mm: float, columns: int, room: Any,
                targets: Targets, grade: str | None) -> tuple[dict, list[str]]:
    """The comb's tables for one sheet, before its webs and stops (see the module doc), and
    the limits already binding (none when it can go on): :func:`target_free_tables` with
    the requirements the targets write (:func:`with_target_requirements`).

    Args:
        base: the tables searched. sheet_mm: the sheet (mm). columns: the comb's columns.
        room: the jaw's room (mm). targets: the targets (N/mm, N). grade: the material's
            grade, or None for the base's.

    Returns:
        (the tables, sharing nothing mutable with ``base``; the limits already binding).
    """
    d, binding = target_free_tables(base, sheet_mm, columns, room, grade)
    return with_target_requirements(d, targets), binding


def with_target_requirements(d: dict, targets: Targets) -> dict:
    """``d`` (:func:`target_free_tables`' tables) with the requirements the search writes
    from its targets (:data:`TARGET_REQUIREMENTS`: the full-scale force, N; the K_obj
    range, N/mm; K_r/K_m) before its own: a new top table and a new ``[requirements]``,
    every other table ``d``'s own (shared, not copied).

    Args:
        d: the target-free tables. targets: the targets.

    Returns:
        The tables, their keys in :func:`target_free_tables`' order.
    """
    lo, hi = targets.k_obj_range_N_per_mm
    return {**d, "requirements": {"full_scale_force_N": targets.full_scale_force_N,
                                  "kobj_range_N_per_mm": [lo, hi],
                                  "kr_over_km": targets.kr_over_km, **d["requirements"]}}


def target_free_tables(base: dict, sheet_mm: float, columns: int, room: Any,
                       grade: str | None) -> tuple[dict, list[str]]:
    """:func:`comb_tables` less the requirements its targets write: none of its tables but
    ``[requirements]``' force, K_obj range and K_r/K_m reads the targets.

    Args:
        base, sheet_mm, columns, room, grade: as :func:`comb_tables` (mm).

    Returns:
        (the tables, their ``[requirements]`` the footprint and any asked grasp alone; the
        limits already binding).
    """
    d = copy_tables(base)
    e, comb = d["element"], d["comb"]
    if grade is not None:
        d["material"] = {"name": grade, "grade": grade}
    d["sheet"] = {"thickness_mm": sheet_mm}
    if e.get("process"):  # the process's tolerance, notch and corner radii on this sheet
        d = held_to_process(d)
    d = grid_fitted_to_sheet(d)
    e, comb = d["element"], d["comb"]
    # a starting web the process leaves (each is solved next): the base's shared web, else
    # its thinnest; the notch keeps t/R <= 1
    base_web = e.pop("web_thickness_mm", None) or min(comb.get("web_thicknesses_mm") or [0.0])
    start_web = max(base_web, round(web_floor(d).value_mm, 6))
    e["notch_radius_mm"] = max(e["notch_radius_mm"], start_web)
    pitch = _floor(min(usable_length_mm(d, room.along_mm) / columns, 20.0), 0.1)
    arm_r = REFERENCE_ARM_MM
    arm_m = _floor(pitch - slot_of(d) - comb["post_length_mm"] - e["notch_radius_mm"]
                   - e["tip_width_mm"] / 2, 0.1)
    n = 2 * columns
    d["array"] = {"construction": "monolithic-comb", "pairing": "column", "rows": 2,
                  "columns": columns, "pitch_mm": round(pitch, 6)}
    d["arms"] = {"lengths_mm": [arm_r] * columns + [round(arm_m, 6)] * columns,
                 "reference_elements": list(range(1, columns + 1))}
    # each element's web from here on (the file gives webs one way, not both)
    comb["web_thicknesses_mm"] = [start_web] * n
    comb["stop_gaps_mm"] = [0.05] * n
    grasp = (base.get("requirements") or {}).get("max_grasp_force_N")  # asked, else none
    d["requirements"] = {"footprint_mm": [round(room.across_mm, 6), round(room.along_mm, 6)],
                         **({} if grasp is None else {"max_grasp_force_N": grasp})}
    d.pop("files", None)
    if room.table:  # the jaw's own checks judge every candidate, as they judge the design
        d["grasper_jaw"] = dict(room.table)
    binding = []
    if arm_m < arm_r + MEASURING_ARM_EXCESS_MM:
        binding.append(f"the pitch {pitch:g} mm ({columns} columns in the jaw's {room.along_mm:g} mm) "
                       f"leaves a measuring arm of {arm_m:g} mm, short of the "
                       f"{arm_r + MEASURING_ARM_EXCESS_MM:g} mm it needs "
                       f"({MEASURING_ARM_EXCESS_MM:g} mm longer than the reference's {arm_r:g} mm)")
    return d, binding


def sheet_tables(base: dict, sheet_mm: float, columns: int, room: Any, targets: Targets,
                 grade: str | None) -> tuple[dict, list[str]]:
    """:func:`comb_tables`, which no K_m scale changes: inside :func:`web_solves_kept`, the
    tables of one ``base``, sheet (mm), column count, ``room``, ``targets`` and grade are
    made once and shared by every scale, so they are read, never changed (:func:`with_webs`
    changes a copy). Their target-free part is kept per process by value
    (:func:`kept_target_free_tables`): every point of an atlas makes the same few.

    Args:
        base, sheet_mm, columns, room, targets, grade: as :func:`comb_tables`.

    Returns:
        (the tables, the limits already binding), as :func:`comb_tables`.
    """
    kept = _KEPT_WEBS.get()
    if kept is None:
        return comb_tables(base, sheet_mm, columns, room, targets, grade)
    # by identity: the entry holds base, room and targets, so no other object takes their ids
    key = ("tables", id(base), id(room), id(targets), sheet_mm, columns, grade)
    hit = kept.get(key)
    if hit is not None and hit[0] is base and hit[1] is room and hit[2] is targets:
        return hit[3]
    free = kept_target_free_tables(base, sheet_mm, columns, room, grade, kept)
    if free is None:  # tables no exact key tells apart: made afresh
        made = comb_tables(base, sheet_mm, columns, room, targets, grade)
    else:
        made = (with_target_requirements(free[0], targets), list(free[1]))
        kept[("target-free key", id(made[0]))] = free[2]
    kept[key] = (base, room, targets, made)
    kept[("shared tables", id(made[0]))] = made[0]  # never changed: starting_plan's by id
    return made


#: Most target-free tables :func:`kept_target_free_tables` keeps in a process (least
#: recently used dropped first): a jaw's atlas makes grades x sheets x column counts.
TARGET_FREE_TABLES_KEPT = 1024
_TARGET_FREE_TABLES: "OrderedDict[tuple, tuple[dict, tuple[str, ...], tuple]]" = OrderedDict()
_TARGET_FREE_TABLES_LOCK = threading.Lock()


def kept_target_free_tables(base: dict, sheet_mm: float, columns: int, room: Any,
                            grade: str | None, kept: dict | None = None
                            ) -> tuple[dict, tuple[str, ...], tuple] | None:
    """:func:`target_free_tables`, kept per process by the value of what it reads: the
    base's tables (:func:`exact_key`), the sheet (mm), the columns, the room's length,
    width (mm) and ``[grasper_jaw]`` table, and the grade; so tables built anew with equal
    contents (each point's ``base`` copy, an outline's room narrowed anew) are made once.
    The tables kept are shared by every caller: read, never changed.

    Args:
        base, sheet_mm, columns, room, grade: as :func:`target_free_tables`.
        kept: a search's kept answers (:func:`web_solves_kept`), where the base's key is
            worked out once per ``base`` object.

    Returns:
        (the tables, the limits already binding, :func:`exact_key` of the tables: that of
        :func:`target_free_plan` for them with any targets' requirements); None when a
        table's keys do not sort (no exact key).
    """
    try:
        key = (base_key(base, kept), exact_key(sheet_mm), exact_key(columns), exact_key(grade),
               exact_key((room.across_mm, room.along_mm,
                          None if not room.table else dict(room.table))))
    except TypeError:
        return None
    with _TARGET_FREE_TABLES_LOCK:
        hit = _TARGET_FREE_TABLES.get(key)
        if hit is not None:
            _TARGET_FREE_TABLES.move_to_end(key)
            return hit
    d, binding = target_free_tables(base, sheet_mm, columns, room, grade)
    try:
        made = (d, tuple(binding), exact_key(d))
    except TypeError:
        return None
    with _TARGET_FREE_TABLES_LOCK:
        _TARGET_FREE_TABLES[key] = made
        while len(_TARGET_FREE_TABLES) > TARGET_FREE_TABLES_KEPT:
            _TARGET_FREE_TABLES.popitem(last=False)
    return made


def base_key(base: dict, kept: dict | None = None) -> tuple:
    """:func:`exact_key` of the base's tables; inside a search's kept answers, worked out
    once per ``base`` object (the entry holds it, so no other object takes its id).

    Args:
        base: the tables searched. kept: the search's kept answers, or None.

    Returns:
        The key.

    Raises:
        TypeError: a table whose keys do not sort.
    """
    if kept is None:
        return exact_key(base)
    hit = kept.get(("base key", id(base)))
    if hit is not None and hit[0] is base:
        return hit[1]
    key = exact_key(base)
    kept[("base key", id(base))] = (base, key)
    return key


def with_webs_and_stops(d: dict, targets: Targets, km_scale: float = 1.0) -> tuple[dict, list[str]]:
    """``d`` with every web solved for its K target and every stop gap set (see the module
    doc); the binding limits when a web or the plan is refused."""
    d, plan, binding = with_webs(d, targets, km_scale)
    return (d, binding) if binding else (with_stops(d, plan, targets), [])


def with_webs(d: dict, targets: Targets, km_scale: float = 1.0) -> tuple[dict, Any, list[str]]:
    """``d`` with every web solved for its K target (K_m = ``km_scale`` x eq. 2's centre,
    K_r = K_r/K_m x K_m, at the closed form), its plan at the default stop gaps, and the
    binding limits when a web is out of reach: nothing here reads the full-scale force
    (its stops are :func:`with_stops`').

    Raises:
        DesignErrors: the plan with its webs is refused.
    """
    start, webs, binding = solved_webs(d, targets, km_scale)
    if binding:
        return d, None, binding
    d = webbed_tables(d, webs, start.columns)
    return d, plan_from_dict(d), []


def solved_webs(d: dict, targets: Targets, km_scale: float = 1.0
                ) -> tuple[Any, tuple[float, float] | None, list[str]]:
    """:func:`with_webs`' web solves, before the tables take them: the reference's web for
    K_r and the measuring element's for K_m (mm), each on the sheet's starting plan
    (:func:`starting_plan`).

    Args:
        d: a sheet's comb tables at their starting webs (:func:`sheet_tables`).
        targets: the targets. km_scale: K_m over eq. 2's centre.

    Returns:
        (the starting plan, (reference web, measuring web) or None, the binding limits
        when a web is out of reach or thinner than the process cuts).

    Raises:
        DesignErrors: the starting tables are refused.
    """
    plan = starting_plan(d)
    columns = plan.columns
    k_m = km_scale * centred_km(targets)
    k_r = targets.kr_over_km * k_m
    r = d["element"]["notch_radius_mm"]
    webs = []
    for number, k in ((1, k_r), (columns + 1, k_m)):
        g = plan.element(number).geometry
        web = solve_web(g, plan.material, k, 0.02, min(2 * r, d["sheet"]["thickness_mm"] * 2))
        if web is None:
            return plan, None, [f"no web of element {number} ({g.arm_length_mm:g} mm arm) "
                                f"reaches K = {k:.4g} N/mm at the closed form"]
        thinnest = tables_web_floor(d)
        if web < thinnest.value_mm - 1e-9:
            return plan, None, [f"web {web:g} mm of element {number} (K = {k:.4g} N/mm), "
                                f"below the {thinnest.value_mm:g} mm {process_name(d)} holds "
                                f"in a {d['sheet']['thickness_mm']:g} mm sheet "
                                f"({thinnest.rule})"]
        webs.append(web)
    return plan, (webs[0], webs[1]), []


def webbed_tables(d: dict, webs: tuple[float, float], columns: int) -> dict:
    """A copy of ``d`` whose references (row 1) take the first of ``webs`` and measuring
    elements (row 2) the second (mm)."""
    d = copy_tables(d)
    d["comb"]["web_thicknesses_mm"] = [webs[0]] * columns + [webs[1]] * columns
    return d


def starting_plan(d: dict) -> Any:
    """The plan of a sheet's comb tables before its webs are solved
    (:func:`comb_tables`' ``d``, which no K_m scale changes); inside
    :func:`web_solves_kept` each distinct table is planned once, its refusal kept as well,
    so the scales of one sheet share it (tables :func:`sheet_tables` shares are known by
    their identity, others by their content).

    Args:
        d: the comb's tables at their starting webs.

    Returns:
        The plan.

    Raises:
        DesignErrors: the tables are refused (the same refusal each time).
    """
    import json

    kept = _KEPT_WEBS.get()
    if kept is None:
        key = None
    elif kept.get(("shared tables", id(d))) is d:  # sheet_tables' own: never changed
        key = ("plan of shared tables", id(d))
    else:
        key = ("plan", json.dumps(d, sort_keys=True, default=repr))
    if key is not None and key in kept:
        plan, refused = kept[key]
    else:
        free_key = None if key is None or key[0] == "plan" else \
            kept.get(("target-free key", id(d)))
        try:
            plan, refused = target_free_plan(d, free_key), None
        except DesignErrors as exc:
            plan, refused = None, exc
        if key is not None:
            kept[key] = (plan, refused)
    if refused is not None:
        raise refused
    return plan


#: The requirements a comb's tables take from the search's targets (:func:`comb_tables`).
TARGET_REQUIREMENTS = ("full_scale_force_N", "kobj_range_N_per_mm", "kr_over_km")
#: Most plans :func:`target_free_plan` keeps in a process (least recently used dropped
#: first): a jaw's atlas plans a few hundred sheets' starting combs (grades x sheets x
#: column counts).
TARGET_FREE_PLANS_KEPT = 512
_TARGET_FREE_PLANS: "OrderedDict[tuple, tuple[Any, DesignErrors | None]]" = OrderedDict()
_TARGET_FREE_PLANS_LOCK = threading.Lock()


def target_free_plan(d: dict, key: tuple | None = None) -> Any:
    """``plan_from_dict(d)`` for a reader of the plan's elements, material, strength,
    columns and envelope only, not of its requirements, raw tables or hash (a sheet's
    starting plan, a comb's envelope): kept per process by the tables less the
    requirements the search writes from its targets (:data:`TARGET_REQUIREMENTS`), so the
    atlas's points plan each sheet's starting comb once, not once a point.

    Exact where it is kept: the tables' validation reads those requirements in their own
    section's fields and its K_obj range rule alone (:class:`RequirementsSection`,
    :func:`~tactcad.design.requirements_section.check_requirements`), and the plan's
    elements, material and envelope not at all, so tables that differ in them alone, each
    passing those checks on its own (:func:`targets_validate`), are refused alike or
    planned alike but for the requirements and hash. Tables whose requirements fail them
    are planned afresh.

    Args:
        d: a comb's tables.
        key: where known, :func:`exact_key` of ``d`` less the requirements the targets
            write (:func:`kept_target_free_tables`' third value for the tables
            :func:`with_target_requirements` made of it); None: worked out here.

    Returns:
        The plan: where kept, the first such tables' (their requirements and hash).

    Raises:
        DesignErrors: the tables are refused (where kept, the first such tables' refusal).
    """
    req = d.get("requirements")
    if not isinstance(req, dict) or not targets_validate(req):
        return plan_from_dict(d)
    try:
        if key is None:
            key = exact_key({**d, "requirements": {k: v for k, v in req.items()
                                                   if k not in TARGET_REQUIREMENTS}})
    except TypeError:  # keys that do not sort: not a TOML file's tables
        return plan_from_dict(d)
    with _TARGET_FREE_PLANS_LOCK:
        kept = _TARGET_FREE_PLANS.get(key)
        if kept is not None:
            _TARGET_FREE_PLANS.move_to_end(key)
    if kept is None:
        try:
            kept = (plan_from_dict(d), None)
        except DesignErrors as exc:
            kept = (None, exc)
        with _TARGET_FREE_PLANS_LOCK:
            _TARGET_FREE_PLANS[key] = kept
            while len(_TARGET_FREE_PLANS) > TARGET_FREE_PLANS_KEPT:
                _TARGET_FREE_PLANS.popitem(last=False)
    plan, refused = kept
    if refused is not None:
        raise refused
    return plan


def targets_validate(requirements: Mapping[str, Any]) -> bool:
    """Whether a ``[requirements]`` table passes, on its own, every check a design file's
    validation makes of it alone: its section's fields
    (:class:`~tactcad.design.requirements_section.RequirementsSection`) and the K_obj
    range's LO < HI (:func:`~tactcad.design.requirements_section.check_requirements`).

    Args:
        requirements: the table.

    Returns:
        True when neither refuses it.
    """
    from tactcad.design.requirements_section import RequirementsSection, check_requirements
    from tactcad.vocabulary.schema import Problems, validate

    p = Problems()
    model = validate(_requirements_file(RequirementsSection),
                     {"requirements": dict(requirements)}, p)
    if model is not None:
        check_requirements(model, p)
    return model is not None and not p


def exact_key(tables: Any) -> tuple:
    """A key of a design file's tables that tells apart every two a validation may tell
    apart: tables by their sorted keys, arrays and tuples apart, every scalar by its type
    and its repr (so -0.0 is not 0.0, and 1 is not 1.0).

    Args:
        tables: a table, an array or a scalar.

    Returns:
        A hashable key.

    Raises:
        TypeError: a table whose keys do not sort.
    """
    kind = type(tables)
    if kind is dict:
        return ("table", tuple(sorted((k, exact_key(v)) for k, v in tables.items())))
    if kind is list or kind is tuple:
        return (kind.__name__, tuple(exact_key(v) for v in tables))
    return (kind.__name__, repr(tables))


@functools.lru_cache(maxsize=1)
def _requirements_file(section: type) -> type:
    # a file model holding [requirements] alone (pydantic builds a model in milliseconds)
    from pydantic import create_model

    from tactcad.vocabulary.schema import Section

    return create_model("RequirementsFile", __base__=Section, requirements=(section, ...))


def with_stops(d: dict, plan: Any, targets: Targets) -> dict:
    """``d`` (webs solved, ``plan`` its plan) with every stop gap set for the full-scale
    force: engaging at :data:`STOP_MULTIPLE` x the rated deflection, or midway to the
    element's lowest fatigue limit where that comes first, no smaller than the least gap
    set by hand (mm)."""
    from tactcad.design.comb_plan import MIN_SET_GAP_MM
    from tactcad.mechanics.element_strength import part_strength
    from tactcad.mechanics.hard_stops import engagement_force_N, fatigue_limit_N, stop_gap_for

    gaps = []
    force = targets.full_scale_force_N
    # a stop reads its element's K and fatigue limits: the same for every element of a part
    strength = part_strength(plan, force)
    for stop in plan.hard_stops:
        g = plan.element(stop.element).geometry
        r = strength[g.part_name]
        k = r.stiffness_N_per_mm
        engage_N = engagement_force_N(STOP_MULTIPLE, force, fatigue_limit_N(r)[0])
        gap = stop_gap_for(engage_N / force, force / k, stop, g.arm_length_mm)
        gaps.append(max(math.ceil(gap / WEB_STEP_MM - 1e-9) * WEB_STEP_MM, MIN_SET_GAP_MM))
    d["comb"]["stop_gaps_mm"] = [round(x, 6) for x in gaps]
    return d


def process_name(d: Mapping[str, Any]) -> str:
    """The rows' cut process of raw comb tables (wire EDM when not stated)."""
    from tactcad.vocabulary.process import DEFAULT_CUT_PROCESS

    return (d.get("element") or {}).get("process") or DEFAULT_CUT_PROCESS


def web_floor(d: Mapping[str, Any]):
    """The thinnest web the rows' process leaves on the sheet (a
    :class:`~tactcad.vocabulary.process.Figure`, mm)."""
    from tactcad.design.array_plan import element_process_limits

    return element_process_limits(d).min_web_mm


def tables_web_floor(d: Mapping[str, Any]):
    """:func:`web_floor` of ``d``; inside :func:`web_solves_kept`, worked out once for the
    tables :func:`sheet_tables` shares (never changed: known by their identity), which every
    K_m scale's web solve reads.

    Args:
        d: a comb's tables.

    Returns:
        The thinnest web the rows' process leaves (a
        :class:`~tactcad.vocabulary.process.Figure`, mm).
    """
    kept = _KEPT_WEBS.get()
    if kept is None or kept.get(("shared tables", id(d))) is not d:
        return web_floor(d)
    key = ("web floor", id(d))
    if key not in kept:
        kept[key] = web_floor(d)
    return kept[key]


def _short(value: Any) -> str:
    """A record's value in 4 significant digits (lists item by item)."""
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_short(v) for v in value) + "]"
    return f"{value:.4g}" if isinstance(value, float) else str(value)


def failure_line(record: dict) -> str:
    """A failed verification record in one line: its prediction against its target, or, where
    it has none, why (its basis's last clause: a grasp out of the jaw's reach, say)."""
    head = f"{record['requirement']}: "
    if record.get("predicted") is None and record.get("basis"):
        return head + str(record["basis"]).rsplit("; ", 1)[-1]
    return head + f"predicted {_short(record['predicted'])}, target {_short(record['target'])}"


def judge(d: dict, envelope_of: Callable | None, room: Any = None
          ) -> tuple[Any, tuple[str, ...], float, float | None]:
    """(plan, failures, full-scale-force margin, rated force) of a candidate's tables
    (:func:`judge_limits` without the failures' limit codes)."""
    plan, fails, _, margin, rated = judge_limits(d, envelope_of, room)
    return plan, fails, margin, rated


def judge_unless_too_tall(d: dict, envelope_of: Callable | None, room: Any = None
                          ) -> tuple[Any, tuple[str, ...], float, float | None]:
    """:func:`judge`, except that a plan standing taller than the jaw's ``room``
    (:func:`too_tall`) is refused by its height alone, without its verification matrix:
    such a plan fails :func:`judge` too, which lists the matrix's failures before it.

    Args:
        d, envelope_of, room: as :func:`judge`.

    Returns:
        (plan, failures, full-scale-force margin, rated force N); for a plan too tall,
        (the plan, the height's failure, -inf, None).
    """
    return pair_judged(d, envelope_of, room, first_failure=False)[:4]


def pair_judged(d: dict, envelope_of: Callable | None, room: Any = None,
                first_failure: bool = True
                ) -> tuple[Any, tuple[str, ...], float, float | None,
                           Mapping[str, Any] | None]:
    """:func:`judge` (``first_failure``) or :func:`judge_unless_too_tall` (not), with what
    the plan's verification matrix predicts where it was worked out.

    Args:
        d, envelope_of, room: as :func:`judge`. first_failure: False: a plan taller than
            ``room`` is refused by its height alone (:func:`judge_unless_too_tall`).

    Returns:
        (plan, failures, full-scale-force margin, rated force N, predicted figures by
        requirement or None: as :func:`judge_recorded`).
    """
    plan = None
    if not first_failure:
        try:
            plan = plan_from_dict(d)
        except DesignErrors as exc:
            return None, refused_fields(exc)[0], -math.inf, None, None
        tall = too_tall(plan, room) if room is not None else ()
        if tall:
            return plan, tall, -math.inf, None, None
    plan, fails, _, margin, rated, _, predicted = judge_recorded(d, envelope_of, room, plan)
    return plan, fails, margin, rated, predicted


def refused_fields(exc: DesignErrors) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """A validation's refusal as failures and their limit codes
    (:func:`tactcad.vocabulary.binding_limits.field_limit` of each field)."""
    from tactcad.vocabulary.binding_limits import field_limit

    return (tuple(f"{e.field} = {e.value}: allowed {e.allowed}" for e in exc.errors),
            tuple(e.limit or field_limit(e.field) for e in exc.errors))


def judge_limits(d: dict, envelope_of: Callable | None, room: Any = None
                 ) -> tuple[Any, tuple[str, ...], tuple[str, ...], float, float | None]:
    """(plan, failures, each failure's limit code, full-scale-force margin, rated force) of
    a candidate's tables: the design's validation, its verification matrix at the closed
    form, its gauge limits clearing the closed form's strain error (as the stacked search's
    webs do), its hard stops and, given the jaw's ``room``, its height (:func:`too_tall`).
    The codes are :mod:`tactcad.vocabulary.binding_limits`', set by the check that fails."""
    return judge_bounded(d, envelope_of, room)[:5]


def judge_bounded(d: dict, envelope_of: Callable | None, room: Any = None,
                  plan: Any = None, limits: list | None = None,
                  refusal: DesignErrors | None = None
                  ) -> tuple[Any, tuple[str, ...], tuple[str, ...], float, float | None,
                             ForceBound | None]:
    """:func:`judge_limits`' answer and the candidate's :class:`ForceBound` (None when the
    plan or its matrix is refused: a refusal after the stops are set may hang on them).

    Args:
        d: the candidate's tables (webs and stops set). envelope_of, room: as
            :func:`judge_limits`. plan, limits: ``d``'s plan and its closed-form limits
            where already worked out (:func:`planned_limits`), else worked out here.
        refusal: where ``plan`` is None, the refusal :func:`plan_from_dict` gave ``d``
            already (:func:`planned`): read, not worked out again.

    Returns:
        (plan, failures, limit codes, full-scale-force margin, rated force N, bound).
    """
    return judge_recorded(d, envelope_of, room, plan, limits, refusal)[:6]


def judge_recorded(d: dict, envelope_of: Callable | None, room: Any = None,
                   plan: Any = None, limits: list | None = None,
                   refusal: DesignErrors | None = None
                   ) -> tuple[Any, tuple[str, ...], tuple[str, ...], float, float | None,
                              ForceBound | None, dict[str, Any] | None]:
    """:func:`judge_bounded`'s answer and what the plan's closed-form verification matrix
    predicts (requirement -> its ``predicted``), so that the comb written from these
    tables (their name and reasons alone changed: no figure reads them) reads its figures
    rather than working the matrix out again.

    Args:
        d, envelope_of, room, plan, limits, refusal: as :func:`judge_bounded`.

    Returns:
        (plan, failures, limit codes, full-scale-force margin, rated force N, bound,
        predicted figures by requirement; None where the plan or its matrix is refused).
    """
    if plan is None and refusal is not None:
        return (None, *refused_fields(refusal), -math.inf, None, None, None)
    from tactcad.mechanics.hard_stops import stop_verdicts
    from tactcad.mechanics.limits import LIMIT_WORDS, plan_limits, uncleared_gauge_limits
    from tactcad.studies.verification import verification_matrix
    from tactcad.vocabulary.binding_limits import (HEIGHT, MECHANICS_LIMITS, STOP,
                                                   requirement_limit)

    try:
        plan = plan if plan is not None else plan_from_dict(d)
    except DesignErrors as exc:
        return (None, *refused_fields(exc), -math.inf, None, None, None)
    env = envelope_of(plan) if envelope_of is not None else None
    try:
        # the verdicts alone: the K band a candidate states none of is reported, not judged
        records = verification_matrix(plan, "closed-form", envelope_mm=env, reported=False)
    except DesignErrors as exc:  # a table the plan holds refuses it (the jaw's, say)
        return (None, *refused_fields(exc), -math.inf, None, None, None)
    failed = [r for r in records if r["verdict"] == "fail" or nominally_short(r)]
    fails = [failure_line(r) for r in failed]
    codes = [requirement_limit(r["requirement"]) for r in failed]
    force = d["requirements"]["full_scale_force_N"]
    stops = [v for v in stop_verdicts(plan, force) if not v.engages_between]
    fails += [f"hard stop of element {v.element}: engages at {v.multiple_of_rated:.2f} x the rated "
              f"deflection, yield-limited at {v.yield_tip_mm:.4f} mm" for v in stops]
    codes += [STOP] * len(stops)
    tall = too_tall(plan, room) if room is not None else ()
    fails += tall
    codes += [HEIGHT] * len(tall)
    limits = limits if limits is not None else plan_limits(plan, "closed-form")
    gauges = uncleared_gauge_limits(limits, force)
    fails += [f"{LIMIT_WORDS[lim.limit]} of element {lim.element}: {lim.force_N:.4g} N does not "
              f"clear {force:g} N by the closed form's {100 * lim.error_estimate_rel:.2g} % "
              "error on the grid's strain" for lim in gauges]
    codes += [MECHANICS_LIMITS.get(lim.limit, "other") for lim in gauges]
    margin = next((r["margin_rel"] for r in records if r["requirement"] == "full_scale_force_N"),
                  0.0)
    bound = force_bound(records, limits)
    return (plan, tuple(fails), tuple(codes), float(margin if margin is not None else 0.0),
            rated_force_N(d, bound), bound, {r["requirement"]: r["predicted"] for r in records})


def nominally_short(record: dict) -> bool:
    """Whether a verification record is the full-scale force's, undecided at its level but
    short of the force asked in its prediction (margin below 0 within its error): a comb
    rated above what its binding limit carries, which a higher level may only fail, so no
    candidate counts with it and no refusal offers such a force to paste."""
    return (record["requirement"] == "full_scale_force_N" and record["verdict"] == "undecided"
            and record["margin_rel"] is not None and record["margin_rel"] < 0.0)


def rated_force_N(d: dict, bound: ForceBound) -> float | None:
    """The full-scale force (N) a candidate's tables ``d`` are rated for when they state
    none (:func:`tactcad.studies.verification.rated_full_scale_force`: the binding limit's
    force rounded down); None when the tables without the force are refused.

    The binding limit is the full-scale-force record's (``bound``): the rating derives it
    again from the same plan less its stated force, so it is read from there rather than
    worked out a second time with every other derived requirement.
    """
    from tactcad.studies.verification import rated_full_scale_force, round_down

    if bound.binding_force_N is not None and math.isfinite(bound.binding_force_N):
        return float(round_down(bound.binding_force_N))
    probe = copy_tables(d)
    probe["requirements"].pop("full_scale_force_N")
    try:
        return rated_full_scale_force(plan_from_dict(probe))
    except DesignErrors:
        return None


def force_bound(records: list[dict], limits: list) -> ForceBound:
    """A judged candidate's :class:`ForceBound`: its full-scale-force record's binding
    force and error, and its gauge limits (``limits``: :func:`plan_limits` at the closed
    form), none of which depend on the force its stops were set for."""
    full = next((r for r in records if r["requirement"] == "full_scale_force_N"), None)
    return ForceBound(binding_force_N=None if full is None else full["predicted"],
                      binding_error_rel=None if full is None else full["error_estimate_rel"],
                      gauge_limits=gauge_bounds(limits))


def gauge_bounds(limits: list) -> tuple[tuple[float, float], ...]:
    """(force N, error estimate) of each gauge limit among ``limits`` (:func:`plan_limits`
    at the closed form): a :class:`ForceBound`'s ``gauge_limits``."""
    from tactcad.mechanics.limits import GAUGE_LIMITS

    return tuple((lim.force_N, lim.error_estimate_rel) for lim in limits
                 if lim.limit in GAUGE_LIMITS)


def comb_for_jaw(targets: Targets, room: Any, columns: int, base: Mapping[str, Any], *,
                 grade: str | None = None, name: str = "grasper_insert",
                 envelope_of: Callable | None = None,
                 progress: Callable[[str], None] | None = None,
                 other_rooms: Mapping[str, Any] | None = None,
                 max_grasp_force_N: float | None = None,
                 process: str | None = None) -> CombDesign:
    """The monolithic comb that fits ``room`` and meets ``targets``.

    Args:
        targets: K_r/K_m, the K_obj range (N/mm) and the full-scale force (N).
        room: the jaw's room (:class:`tactcad.partlib.grasper_jaw.JawRoom`: ``across_mm``,
            ``along_mm``, ``height_mm``, ``shaft_class_mm``).
        columns: columns of the 2-row comb (1 ... 12).
        base: the comb whose fixed details the design takes (a shipped comb's tables).
        grade: material grade of the library (default the base's).
        name: the design's name.
        envelope_of: plan -> its footprint envelope (mm) for the footprint requirement.
        other_rooms: ``--jaw`` value -> room of the jaws a refusal may offer instead (the
            nearest that holds a comb the pocket is too small for).
        max_grasp_force_N: the largest grasp the insert must survive (N): every candidate
            is judged on it (``requirements.max_grasp_force_N``); None: not judged.
        process: the rows' cut process (a name of
            :data:`~tactcad.vocabulary.process.CUT_PROCESSES`; None: the base's): the sheets
            searched are those its flexure range holds (:func:`sheets_of`), and every
            web, slot, radius and tolerance is held to its rules on each sheet.

    Returns:
        :class:`CombDesign`.

    Raises:
        DesignError: ``--columns`` out of range.
        InverseDesignError: no sheet gives a comb that counts; names each sheet's binding
            limit, the largest full-scale force any carries (``--full-scale-force``) and,
            where the pocket is too small for every sheet's comb, the pocket the smallest
            needs and a jaw of ``other_rooms`` that holds it (``--jaw``); where no comb of
            the grade carries any force at any column count, the grade of the library
            whose comb of ``columns`` carries the most (``--material``,
            :func:`nearest_grade`), its option still ``--full-scale-force``.
    """
    with web_solves_kept():  # the refusal's searches meet the same webs again
        base, tried = comb_candidates(targets, room, columns, base, grade=grade,
                                      envelope_of=envelope_of, progress=progress,
                                      process=process)
        good = counting(tried)
        if not good:
            rated = [c.rated_force_N for c in tried if c.rated_force_N]
            fewer = None if rated else \
                nearest_columns(base, columns, room, targets, grade, envelope_of)
            jaw = nearest_jaw(base, columns, room, targets, grade, other_rooms or {})
            rating = tried
            if not rated and fewer is None and not jaw[0]:
                # every candidate refused at this force, some by a limit the force sets
                # (stop gaps a lighter rating closes): a lighter force may carry
                rating = rated_at_a_lighter_force(base, columns, room, targets, grade,
                                                  envelope_of)
                rated = [c.rated_force_N for c in rating if c.rated_force_N]
            frontier = None if not rated or jaw[0] else frontier_of(
                rating, base, columns, room, targets, grade, envelope_of)
            other = None
            if not rated and fewer is None and not jaw[0]:
                # nothing of this grade to paste: the other grade whose comb of these
                # columns carries the most of the force (the refusal's option stays the
                # force's)
                other = nearest_grade(base, columns, room, targets, grade, envelope_of)
            refused = refusal(tried, targets, room, columns, jaw, fewer, frontier,
                              other_grade=other, grade_asked=asked_grade(base, grade))
            refused.candidates = tuple(tried)  # what binds, read by the design atlas
            nearest = nearest_failure(tried)
            refused.limit = nearest.limits[0] if nearest and nearest.limits else ""
            raise refused
        made = comb_of_candidates(tried, targets, room, columns, name=name,
                                  envelope_of=envelope_of, max_grasp_force_N=max_grasp_force_N)
        return replace(made, max_full_scale_force_N=frontier_of(
            tried, base, columns, room, targets, grade, envelope_of))


def comb_candidates(targets: Targets, room: Any, columns: int, base: Mapping[str, Any], *,
                    grade: str | None = None, envelope_of: Callable | None = None,
                    progress: Callable[[str], None] | None = None,
                    process: str | None = None) -> tuple[dict, list[CombCandidate]]:
    """Every sheet's comb at every K_m scale, judged: the search's verdict before any
    refusal's alternatives are sought (:func:`comb_for_jaw`'s first step; its arguments).

    Returns:
        (the base tables as searched, the candidates in the order tried).

    Raises:
        DesignError: ``--columns`` out of 1 ... 12.
    """

    check_comb_columns(columns, room, base, targets, grade, process)
    base = searched_base(base, columns, process)
    with candidates_weighed():  # the candidates are not the design asked about
        tried = [candidate(base, sheet, scale, columns, room, targets, grade, envelope_of,
                           progress) for sheet in sheets_of(base) for scale in KM_SCALES]
    return base, tried


#: Why a comb's column count is bounded, as its refusal says it.
COMB_COLUMNS_WHY = "the grid's range (array.columns)"


def most_comb_columns(room: Any, base: Mapping[str, Any], targets: Targets,
                      grade: str | None = None, process: str | None = None) -> dict:
    """The column count to paste for a comb asked more columns than any comb takes: the
    most of the grid's range where the jaw's pocket holds that comb's length, else the
    most the pocket holds (:func:`comb_misfit`'s own paste, at the least pitch).

    Args:
        room: the jaw's room (:class:`tactcad.partlib.grasper_jaw.JawRoom`, mm).
        base: the comb template's tables. targets: the targets (N/mm, N).
        grade: the material grade (None: the base's). process: the rows' cut process
            (None: the base's).

    Returns:
        An alternative: ``option`` (``--columns N``) and ``words`` (why that count).
    """
    from tactcad.design.array_plan import COLUMNS_RANGE
    from tactcad.vocabulary.binding_limits import SHEET

    hi = COLUMNS_RANGE[1]
    misses = comb_misfit(room, hi, base, targets, grade, process)
    fewer = [m["option"] for m in misses if m.get("limit") == SHEET and m.get("option")]
    if fewer and len(misses) == 1:
        return {"option": fewer[0],
                "words": "the most columns of the monolithic comb the pocket holds"}
    if not misses:
        return {"option": f"--columns {hi}",
                "words": "the most columns a monolithic comb takes, which the pocket holds"}
    return {"option": f"--columns {hi}", "words": "the nearest count a monolithic comb takes"}


def check_comb_columns(columns: int, room: Any, base: Mapping[str, Any], targets: Targets,
                       grade: str | None = None, process: str | None = None) -> None:
    """Refuse ``--columns`` outside :data:`tactcad.design.array_plan.COLUMNS_RANGE` for a
    comb to the jaw's ``room``, offering the count to paste: too many, the most the pocket
    holds (:func:`most_comb_columns`); too few, the fewest a comb takes.

    Args:
        columns: the columns asked. room, base, targets, grade, process: as
            :func:`most_comb_columns`.

    Raises:
        DesignError: ``--columns`` out of range, with its ``--columns`` to paste.
    """
    from tactcad.design.array_plan import COLUMNS_RANGE

    lo, hi = COLUMNS_RANGE
    if lo <= columns <= hi:
        return
    paste = (most_comb_columns(room, base, targets, grade, process) if columns > hi else
             {"option": f"--columns {lo}", "words": "the nearest count a monolithic comb takes"})
    held = int(paste["option"].removeprefix("--columns "))
    if columns > hi and held < hi:  # the pocket binds before the grid's range: its count
        raise DesignError("--columns", columns,
                          f"{lo} ... {held} for a monolithic comb in this jaw's pocket",
                          f"the pocket holds no longer comb; {COMB_COLUMNS_WHY} is {lo} ... "
                          f"{hi}", alternatives=[paste])
    raise DesignError("--columns", columns, f"{lo} ... {hi} for a monolithic comb",
                      COMB_COLUMNS_WHY, alternatives=[paste])


def searched_base(base: Mapping[str, Any], columns: int, process: str | None = None) -> dict:
    """The base tables as the search takes them: a copy without the template's own
    requirements, on ``process`` where one is given.

    Raises:
        DesignError: ``--columns`` out of :data:`tactcad.design.array_plan.COLUMNS_RANGE`.
    """
    from tactcad.design.array_plan import COLUMNS_RANGE

    lo, hi = COLUMNS_RANGE
    if not lo <= columns <= hi:
        nearest = min(max(columns, lo), hi)
        raise DesignError("--columns", columns, f"{lo} ... {hi} for a monolithic comb",
                          COMB_COLUMNS_WHY,
                          alternatives=[{"option": f"--columns {nearest}",
                                         "words": "the nearest count a monolithic comb takes"}])
    base = copy_tables(dict(base))
    base["requirements"] = {}  # the template's own grasp is its jaw's, not this design's
    if process is not None:
        base["element"]["process"] = process
    return base


def first_preferred(targets: Targets, room: Any, columns: int, base: Mapping[str, Any], *,
                    grade: str | None = None, envelope_of: Callable | None = None,
                    judged: list[CombCandidate] | None = None,
                    scales: tuple[float, ...] = KM_SCALES,
                    only_what_decides: bool = False) -> CombCandidate | None:
    """The candidate :func:`chosen` picks, found by judging the candidates in its order of
    preference (the softest pair first, the thicker sheet on a tie) and stopping at the
    first that counts with :data:`FORCE_MARGIN_REL` to spare: none softer or thicker can
    come before it, so it is ``chosen(counting(comb_candidates(...)))`` without judging the
    rest. A candidate whose binding limit already falls short of the margin
    (:func:`short_of_margin`) cannot be that one, so its verification matrix waits until
    no candidate has the margin; one whose yield or fatigue limit alone falls short of it
    (:func:`short_by_strength`) waits with its stops, plan and limits as well. None when
    no candidate has the margin (then only the whole search decides: the one with the
    most margin, or a refusal).

    Args:
        targets, room, columns, base, grade, envelope_of: as :func:`comb_candidates`.
        judged: where given, every candidate judged is appended to it (all of them when
            the answer is None: :func:`in_search_order` makes them the full search's). A
            candidate :func:`short_of_margin` is judged only then, after the others, and
            only where its judgement can change the search's answer
            (:func:`settled_short`; the others are sketched from their limits).
        scales: the K_m scales walked (default :data:`KM_SCALES`); a caller leaves out only
            scales none of whose candidates can count (:func:`atlas_scales`).
        only_what_decides: True: when none has the margin, a candidate
            :func:`short_by_strength` is weighed only where it can change what the design
            atlas reads of the search (:func:`settled_walk`), else left out of ``judged``.

    Returns:
        The chosen candidate, or None.

    Raises:
        DesignError: ``--columns`` out of 1 ... 12.
    """

    base = searched_base(base, columns)
    judged = [] if judged is None else judged
    walked: list = []  # each candidate walked, or its webs while its stops wait
    with candidates_weighed():
        for scale in scales:
            for sheet in sorted(sheets_of(base), reverse=True):
                c, webbed, _ = webbed_candidate(base, sheet, scale, columns, room, targets,
                                                grade)
                aside = short_by_strength(webbed) if c is None else None
                if aside is not None:
                    walked.append(aside)  # not the answer: weighed if none is
                    continue
                c = weighed_candidate(c, webbed, envelope_of)
                walked.append(c)
                if isinstance(c, CombCandidate) and c.plan is not None and not c.failures \
                        and c.force_margin_rel >= FORCE_MARGIN_REL:
                    judged += [w for w in walked if isinstance(w, CombCandidate)]
                    return c
        # none has the margin: every candidate as the walk would have weighed it in turn
        judged += settled_walk(walked, envelope_of, only_what_decides)
    return None


def settled_walk(walked: list, envelope_of: Callable | None,
                 only_what_decides: bool = False) -> list[CombCandidate]:
    """:func:`first_preferred`'s candidates when none has the margin, each as the walk
    weighs it (:func:`weighed_candidate`), those set aside short of the margin settled
    (:func:`settled_short`).

    Args:
        walked: the walk's candidates, short ones set aside (tuples) and those waiting
            with their webs (:class:`Waiting`), in its order.
        envelope_of: as :func:`judge_limits`.
        only_what_decides: True: a :class:`Waiting` candidate is weighed only where it can
            change whether some candidate counts (none can: its margin is short of the
            force), the nearest failure (:func:`nearest_failure`) or its judgement
            (:func:`settled_short`: its margin bound within the slack of the nearest's),
            or whether any candidate is rated (none of the others is); the waiting ones
            with the most margin first, until none of the rest can. The others are left
            out of the answer: what the design atlas reads of it is the whole walk's.

    Returns:
        The candidates (with ``only_what_decides``, less those left out).
    """
    if not only_what_decides:
        walked = [weighed_candidate(None, w.webbed, envelope_of) if isinstance(w, Waiting)
                  else w for w in walked]
        judged = [w for w in walked if isinstance(w, CombCandidate)]
        return judged + settled_short([w for w in walked if isinstance(w, tuple)], judged,
                                      envelope_of)
    waits = sorted((w for w in walked if isinstance(w, Waiting)),
                   key=lambda w: -w.margin_bound_rel)
    weighed = [w for w in walked if not isinstance(w, Waiting)]
    in_full: dict = {}  # (sheet, scale) -> judged in full by settled_short, kept
    while True:
        judged = [w for w in weighed if isinstance(w, CombCandidate)]
        tried = judged + settled_short([w for w in weighed if isinstance(w, tuple)], judged,
                                       envelope_of, in_full)
        if not waits or counting(tried):
            return tried
        nearest = nearest_failure(tried)
        if nearest is None:
            pick = 0
        else:
            # settled_short judges a sketch within 2 x the slack of the nearest's margin
            m = nearest.force_margin_rel
            least = m - 4 * BOUND_SLACK_REL * (1.0 + abs(m))
            pick = next((i for i, w in enumerate(waits) if w.margin_bound_rel >= least), None)
        if pick is None and not any(c.rated_force_N for c in tried):
            pick = 0  # whether any is rated decides the refusal's option
        if pick is None:
            return tried
        weighed.append(weighed_candidate(None, waits.pop(pick).webbed, envelope_of))


def weighed_candidate(refused: CombCandidate | None, webbed: WebbedCandidate | None,
                      envelope_of: Callable | None) -> CombCandidate | tuple:
    """A candidate of :func:`first_preferred`'s walk weighed: refused before its webs
    (``refused``, as it is), refused by its plan, judged (:func:`judged_candidate`), or,
    where its closed-form limits already fall short of the force margin
    (:func:`short_of_margin`), set aside unjudged for :func:`settled_short`.

    Args:
        refused: the candidate refused before its webs, or None. webbed: else its webs
            (:func:`webbed_candidate`). envelope_of: as :func:`judge_limits`.

    Returns:
        The candidate, or (tables, sheet mm, K_m scale, room, plan, limits) set aside.
    """
    if refused is not None:
        return refused
    c, d = stopped_candidate(webbed)
    if c is not None:
        return c
    plan, limits, refusal = planned(d)
    if limits is not None and short_of_margin(d, limits):
        return (d, webbed.sheet_mm, webbed.km_scale, webbed.room, plan, limits)
    return judged_candidate(d, webbed.sheet_mm, webbed.km_scale, envelope_of, webbed.room,
                            plan, limits, refusal)


def limits_bound(limits: list) -> ForceBound:
    """A candidate's :class:`ForceBound` read from its closed-form limits alone
    (:func:`planned_limits`): the binding limit's force and error, which its verification
    matrix's full-scale-force record takes from the same limits, and its gauge limits.

    Args:
        limits: the candidate's limits at the closed form (not empty).

    Returns:
        The bound.
    """
    from tactcad.mechanics.limits import binding

    b = binding(limits)
    return ForceBound(binding_force_N=b.force_N, binding_error_rel=b.error_estimate_rel,
                      gauge_limits=gauge_bounds(limits))


def sketched_candidate(d: dict, sheet: float, km_scale: float, plan: Any, bound: ForceBound
                       ) -> CombCandidate:
    """A candidate its limits already fail at its full-scale force (``bound.fails_at``),
    recorded without its verification matrix: its force margin and rating are the ones
    its judgement would give (both read from the binding limit), its one failure the
    force. It is never the nearest failure of :func:`settled_short`'s answer.

    Args:
        d: the tables (webs and stops set). sheet: mm. km_scale: K_m over eq. 2's centre.
        plan: ``d``'s plan. bound: :func:`limits_bound` of its limits.

    Returns:
        The candidate (``sketched`` True).
    """
    from tactcad.vocabulary.binding_limits import FORCE

    force = d["requirements"]["full_scale_force_N"]
    allowed = float(bound.binding_force_N or 0.0)
    return CombCandidate(sheet, km_scale, d, plan,
                         (f"full-scale force: the binding limit allows {allowed:.4g} N, "
                          f"{force:g} N asked (closed form)",),
                         allowed / force - 1.0, rated_force_N(d, bound), (FORCE,), bound,
                         sketched=True)


def settled_short(short: list[tuple], judged: list[CombCandidate],
                  envelope_of: Callable | None, in_full: dict | None = None
                  ) -> list[CombCandidate]:
    """The candidates :func:`first_preferred` set aside as short of the force margin, each
    judged where its judgement can change what the search answers: whether some candidate
    counts (which, and with what margin) or, where none does, the nearest failure
    (:func:`nearest_failure`: the most force margin, the stiffer pair on a tie) and its
    first failure. A candidate whose limits fail its force (:meth:`ForceBound.fails_at`,
    the judgement's own rule with :data:`BOUND_SLACK_REL` to spare) cannot count; unless
    its margin comes within the slack of the nearest's it is sketched
    (:func:`sketched_candidate`), its verification matrix, most of a judgement's cost,
    left out.

    Args:
        short: (tables, sheet mm, K_m scale, room, plan, limits) of each candidate set
            aside. judged: the candidates judged already (none counting with the margin).
        envelope_of: as :func:`judge_limits`.
        in_full: where given, each candidate judged in full is kept in it by (sheet,
            K_m scale) and read from it again (the same entries of ``short`` settled
            again with more candidates beside them, :func:`settled_walk`).

    Returns:
        One candidate per entry of ``short``, in its order.
    """
    kept = {} if in_full is None else in_full

    def in_full_of(entry: tuple) -> CombCandidate:
        d, sheet, scale, at, plan, limits = entry
        if (sheet, scale) not in kept:
            kept[(sheet, scale)] = judged_candidate(d, sheet, scale, envelope_of, at, plan,
                                                    limits)
        return kept[(sheet, scale)]

    out: list[CombCandidate] = []
    for entry in short:
        d, sheet, scale, at, plan, limits = entry
        bound = limits_bound(limits)
        if bound.fails_at(d["requirements"]["full_scale_force_N"]):
            out.append(sketched_candidate(d, sheet, scale, plan, bound))
        else:
            out.append(in_full_of(entry))
    while True:
        nearest = nearest_failure(judged + out)
        close = [i for i, c in enumerate(out) if c.sketched and nearest is not None
                 and c.force_margin_rel >= nearest.force_margin_rel - 2 * BOUND_SLACK_REL
                 * (1.0 + abs(nearest.force_margin_rel))]
        if not close:
            return out
        for i in close:  # judged in full: the nearest's first failure is its own
            out[i] = in_full_of(short[i])


def in_search_order(judged: list[CombCandidate], base: Mapping[str, Any]
                    ) -> list[CombCandidate]:
    """Candidates of every sheet and K_m scale in :func:`comb_candidates`' order (sheet by
    sheet of :func:`sheets_of`, each at every scale of :data:`KM_SCALES`): the refusal's
    ties go to the first, so the order of the full search is kept.

    Args:
        judged: the candidates, one per sheet (mm) and scale. base: the tables searched.

    Returns:
        The same candidates, reordered.
    """
    sheets = list(sheets_of(base))
    return sorted(judged, key=lambda c: (sheets.index(c.sheet_mm), KM_SCALES.index(c.km_scale)))


def counting(tried: list[CombCandidate]) -> list[CombCandidate]:
    """The candidates that count: a plan and no failure."""
    return [c for c in tried if c.plan is not None and not c.failures]


def comb_of_candidates(tried: list[CombCandidate], targets: Targets, room: Any, columns: int,
                       *, name: str = "grasper_insert", envelope_of: Callable | None = None,
                       max_grasp_force_N: float | None = None,
                       fastener_reasons: bool = True) -> CombDesign:
    """The comb :func:`comb_for_jaw` writes from candidates some of which count: the one
    :func:`chosen` (or the first :func:`surviving` the grasp), with its fasteners and reasons.

    Args:
        fastener_reasons: False where only the comb's plan is read, not the reasons of the
            screws and dowels tried before its own (the design atlas's figures): a pair
            too tall for the jaw is then refused by its height alone
            (:func:`with_fasteners`), the same pair is chosen and the plan is the same
            but for those reasons' words.

    Raises:
        InverseDesignError: with ``max_grasp_force_N``, no candidate survives the grasp.
    """

    good = counting(tried)
    with candidates_weighed():
        first = chosen(good) if max_grasp_force_N is None else \
            surviving(good, max_grasp_force_N, room, envelope_of, targets, columns)
        best, fasteners = with_fasteners(first, room, envelope_of,
                                         first_failure=fastener_reasons)
    data = named(best.data, name, targets, room, best, columns, fasteners)
    return CombDesign(data, plan_from_dict(data), room, tuple(tried), fasteners, best)


def designs_in_preference(result: CombDesign, targets: Targets, room: Any, columns: int, *,
                          name: str = "grasper_insert", envelope_of: Callable | None = None,
                          max_grasp_force_N: float | None = None) -> Iterator[CombDesign]:
    """The search's design, then the comb of each other candidate that counts, in the order
    the search prefers them (:func:`in_preference`), each made as :func:`comb_of_candidates`
    makes the chosen one (its fasteners, its reasons, the grasp where asked): so that a
    requirement judged after the search (``--kobj-accuracy``) takes the first that meets it.

    Args:
        result: the search's answer (:func:`comb_for_jaw`).
        targets: the targets searched (N/mm, N). room: the jaw's room (mm).
        columns: the comb's columns. name, envelope_of, max_grasp_force_N: as
            :func:`comb_for_jaw` takes them (N for the grasp).

    Returns:
        An iterator of :class:`CombDesign`, each with every candidate tried; a candidate
        its fasteners or the grasp refuse is passed over.
    """
    yield result
    first = result.chosen
    for c in in_preference(counting(list(result.candidates))):
        if first is not None and (c.sheet_mm, c.km_scale) == (first.sheet_mm, first.km_scale):
            continue
        try:
            made = comb_of_candidates([c], targets, room, columns, name=name,
                                      envelope_of=envelope_of,
                                      max_grasp_force_N=max_grasp_force_N)
        except DesignError:
            continue
        yield replace(made, candidates=result.candidates)


def refusal_option(base: dict, tried: list[CombCandidate], targets: Targets, room: Any,
                   columns: int, grade: str | None, envelope_of: Callable | None) -> str:
    """The option :func:`comb_for_jaw`'s refusal names when no candidate of ``tried``
    counts, found as it finds it but without the force it offers to paste: ``--jaw`` where
    the pocket holds no sheet's comb (:func:`nearest_jaw`), ``--full-scale-force`` where some
    candidate carries a force, ``--columns`` where another column count counts or carries
    one (:func:`fewer_columns_carry`), else ``--full-scale-force``.

    Args:
        base: the tables as searched (:func:`comb_candidates`' first value).
        tried: the candidates, none counting. targets, room, columns, grade, envelope_of:
            as :func:`comb_for_jaw` takes them.

    Returns:
        The option's name.
    """
    if nearest_jaw(base, columns, room, targets, grade, {})[0]:
        return "--jaw"
    if any(c.rated_force_N for c in tried):
        return "--full-scale-force"
    fewer = fewer_columns_carry(base, columns, room, targets, grade, envelope_of)
    return "--columns" if fewer else "--full-scale-force"


def fewer_columns_carry(base: dict, columns: int, room: Any, targets: Targets,
                        grade: str | None, envelope_of: Callable | None) -> bool:
    """Whether :func:`nearest_columns` finds an answer (it is not None): some count other
    than ``columns`` (fewer first, then more: :func:`other_column_counts`) has a candidate
    that counts or carries some force. Stops at the first such candidate instead of
    bisecting the force it would carry: the refusal's option alone.

    Args:
        base, columns, room, targets, grade, envelope_of: as :func:`nearest_columns`.

    Returns:
        True when a comb of another column count counts or is rated for some force.
    """

    scales = stop_fitting_scales(targets)  # the others carry at no column count
    with candidates_weighed():
        for count in sum(other_column_counts(columns), ()):
            for sheet in sheets_of(base):
                for scale in scales:
                    if candidate_carries(base, sheet, scale, count, room, targets, grade,
                                         envelope_of):
                        return True
    return False


def candidate_carries(base: dict, sheet: float, km_scale: float, columns: int, room: Any,
                      targets: Targets, grade: str | None, envelope_of: Callable | None
                      ) -> bool:
    """Whether :func:`candidate` counts or is rated for some force, as
    :func:`fewer_columns_carry` asks it, its verification matrix left out where its
    closed-form limits already rate it: the rating is the binding limit's force rounded
    down (:func:`rated_force_N`), and the matrix's full-scale-force record takes that force
    from the same limits (as :func:`sketched_candidate` reads it), so a candidate whose
    limits rate it is rated by its judgement.

    Args:
        base, sheet, km_scale, columns, room, targets, grade, envelope_of: as
            :func:`candidate` (sheet mm; no progress lines).

    Returns:
        True when the candidate counts or carries some force (N).
    """
    refused, webbed, at = webbed_candidate(base, sheet, km_scale, columns, room, targets,
                                           grade)
    d = None
    if refused is None:
        if notch_below_a_web(webbed.tables, webbed.webs) or stops_past_the_tables(webbed):
            return False  # its plan refused before or with its stops: no plan, no rating
        refused, d = stopped_candidate(webbed)
    if refused is not None:
        return bool((refused.plan is not None and not refused.failures)
                    or refused.rated_force_N)
    if stop_gap_too_wide(d):
        return False  # refused with its stops set, as judged: no plan, no rating
    plan, limits, _ = planned(d)
    if plan is None:
        return False  # judged, the same refusal: no plan, no rating
    if limits and rated_by_limits(d, limits):
        return True
    c = judged_candidate(d, sheet, km_scale, envelope_of, at, plan, limits)
    return bool((c.plan is not None and not c.failures) or c.rated_force_N)


def notch_below_a_web(tables: Mapping[str, Any], webs: tuple[float, float]) -> bool:
    """Whether a comb's tables with ``webs`` (:func:`webbed_tables`) are surely refused by
    their notch: the comb's rule R >= every web (t/R <= 1,
    :func:`tactcad.design.comb_plan.validate_tables`' element check, whose least R is at
    least the thickest web, less its tolerance
    :data:`~tactcad.vocabulary.schema.LIMIT_TOLERANCE_MM`). Where the tables pass no
    further (their types, web source or lists), they are refused before it: refused
    either way. A necessary condition of the refusal, not its words.

    Args:
        tables: the sheet's comb tables (their ``[element] notch_radius_mm``, mm).
        webs: (the references' web, the measuring elements' web) (mm).

    Returns:
        True only when the tables with those webs are refused.
    """
    from tactcad.vocabulary.schema import LIMIT_TOLERANCE_MM

    radius = (tables.get("element") or {}).get("notch_radius_mm")
    if isinstance(radius, bool) or not isinstance(radius, (int, float)) \
            or not math.isfinite(radius):
        return False  # judged as the search judges it
    return radius < max(webs) - LIMIT_TOLERANCE_MM


def stops_past_the_tables(w: WebbedCandidate) -> bool:
    """Whether a candidate with its webs solved surely sets a stop gap past
    :data:`~tactcad.design.comb_plan.MAX_STOP_GAP_MM` (:func:`with_stops`), before its
    tables are planned: the gap it sets is at least the rated tip deflection F / K times
    the stop's lever over the arm (:func:`tactcad.mechanics.hard_stops.stop_gap_for` at an
    engagement of at least the rating,
    :func:`~tactcad.mechanics.hard_stops.engagement_force_N`, rounded up; of
    :data:`STOP_MULTIPLE` x the rating where the element's notch fatigue limit is at or
    below it, :func:`least_engagement_multiple`), K the element's closed-form K with its
    solved web (:func:`closed_form_k`, the strength record's to the bit) and the lever the
    starting plan's (the arm plus half the tip: no web or gap moves it). Such tables are
    refused with their stops set, or before if their webs are: either way no plan and no
    rating. Past the range by :data:`STOP_BOUND_SLACK_REL` at least.

    Args:
        w: the candidate (:func:`webbed_candidate`; its full-scale force in N).

    Returns:
        True only when some element's gap surely exceeds the tables' range.
    """
    from tactcad.design.comb_plan import MAX_STOP_GAP_MM
    from tactcad.mechanics.element_strength import notch_fatigue_strength

    plan, force = w.start, w.targets.full_scale_force_N
    if plan.material.yield_strength_MPa is None:
        return False  # setting its stops refuses the material: as the search does
    levers = {stop.element: stop.lever_mm for stop in plan.hard_stops}
    notch = notch_fatigue_strength(plan.material)
    for number, web in ((1, w.webs[0]), (plan.columns + 1, w.webs[1])):
        g = replace(plan.element(number).geometry, web_thickness_mm=web)
        try:
            k = closed_form_k(g, plan.material)
        except ValueError:
            return False  # judged as the search judges it
        if number not in levers or not (math.isfinite(k) and k > 0):
            return False
        multiple = least_engagement_multiple(
            None if notch is None else notch_fatigue_force_N(g, notch.strength_MPa), force)
        least = multiple * force / k * levers[number] / g.arm_length_mm
        if least > MAX_STOP_GAP_MM * (1.0 + STOP_BOUND_SLACK_REL):
            return True
    return False


def notch_fatigue_force_N(g: Any, notch_strength_MPa: float) -> float | None:
    """An element's notch fatigue limit (N) at the closed form: the notch fatigue strength
    over the peak stress per N (:func:`tactcad.mechanics.element_strength.closed_form_stress`'s,
    a function of the web, notch radius, arm and sheet alone), the strength record's
    ``fatigue_force_N`` to the bit (as :func:`strength_bound_N` reads it).

    Args:
        g: the element's geometry (its solved web, mm). notch_strength_MPa: the material's
            fatigue strength at the notch (MPa).

    Returns:
        The force (N); None without a finite positive stress.
    """
    from tactcad.mechanics.element_strength import peak_stress_per_newton

    s = float(peak_stress_per_newton(g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm,
                                     g.sheet_thickness_mm))
    return notch_strength_MPa / s if math.isfinite(s) and s > 0 else None


def least_engagement_multiple(notch_fatigue_N: float | None, rated_N: float) -> float:
    """The least multiple of the rating a stop can be set to engage at
    (:func:`tactcad.mechanics.hard_stops.engagement_force_N` over the rating), knowing only
    the element's notch fatigue limit: its lowest fatigue limit is at most that one (the
    gauge's may be lower), so where the notch's is at or below the rating (by
    :data:`STOP_BOUND_SLACK_REL`) so is the lowest, and the stop engages at
    :data:`STOP_MULTIPLE` x the rating; else the lowest limit may lie just above the
    rating, and the stop engages just above it (1).

    Args:
        notch_fatigue_N: the element's notch fatigue limit (N; None: unknown).
        rated_N: the rated full-scale force (N), > 0.

    Returns:
        The multiple (>= 1).
    """
    if notch_fatigue_N is not None and notch_fatigue_N <= rated_N * (1.0 - STOP_BOUND_SLACK_REL):
        return STOP_MULTIPLE
    return 1.0


#: How far (relative) :func:`stops_past_the_tables`' least gap must pass the tables' range:
#: a thousand times the drift of a closed-form K between its two ways of working it out.
STOP_BOUND_SLACK_REL = 1e-6


def stop_gap_too_wide(d: Mapping[str, Any]) -> bool:
    """Whether a candidate's tables with their stops set (:func:`with_stops`) are surely
    refused by a stop gap: one above :data:`~tactcad.design.comb_plan.MAX_STOP_GAP_MM`,
    the most ``[comb] stop_gaps_mm`` takes (its field's closed upper bound).

    Args:
        d: the tables (their stop gaps, mm).

    Returns:
        True only when a gap is wider than the tables take.
    """
    from tactcad.design.comb_plan import MAX_STOP_GAP_MM

    gaps = (d.get("comb") or {}).get("stop_gaps_mm") or ()
    return any(isinstance(g, float) and g > MAX_STOP_GAP_MM for g in gaps)


def rated_by_limits(d: dict, limits: list) -> bool:
    """Whether a candidate's closed-form limits (:func:`planned_limits`, not empty) rate it
    for some force: the rating :func:`rated_force_N` gives their binding force, where that
    force is finite (else the rating is worked out from the tables: False here).

    Args:
        d: the candidate's tables (webs and stops set). limits: its limits (N).

    Returns:
        True when the rating is a force other than zero.
    """
    bound = limits_bound(limits)
    force = bound.binding_force_N
    return force is not None and math.isfinite(force) and bool(rated_force_N(d, bound))


#: How far above its K target (N/mm) a solved web may leave an element's closed-form K in
#: :func:`stops_can_fit`: a web rounded to :data:`WEB_STEP_MM` in a bracket from 0.02 mm
#: moves K (at most as t^3) by under 8 % (1.025^3 = 1.077); the 3385 solved candidates of
#: the 10 mm jaw atlas's first 24 points in two grades came within 1.7 % of their targets.
#: 1.25 keeps three times the rounding's worst case as margin. (At 2, a refusal judged
#: every sheet of every fewer column count whose gaps then came out 1.3 to 2.7 mm.)
STOP_BOUND_K_SLACK = 1.25


def least_stop_gap_mm(full_scale_force_N: float, stiffness_N_per_mm: float) -> float:
    """A lower bound (mm) of the stop gap :func:`with_stops` sets for an element of closed-
    form K ``stiffness_N_per_mm`` (N/mm) at a full-scale force ``full_scale_force_N`` (N):
    the rated tip deflection F / K, since a stop engages above the rating
    (:func:`tactcad.mechanics.hard_stops.engagement_force_N` exceeds F) and its lever, the
    arm plus half the tip, is longer than the arm
    (:func:`tactcad.mechanics.hard_stops.stop_gap_for`).

    Args:
        full_scale_force_N: the rated force (N). stiffness_N_per_mm: the element's K (N/mm).

    Returns:
        The gap's lower bound (mm).
    """
    return full_scale_force_N / stiffness_N_per_mm


def stops_can_fit(targets: Targets, km_scale: float) -> bool:
    """Whether a comb at K_m scale ``km_scale`` can have stop gaps the tables take
    (:data:`~tactcad.design.comb_plan.MAX_STOP_GAP_MM`) on some sheet at some column
    count: False when the softer element's gap, at :data:`STOP_BOUND_K_SLACK` x its K target
    (K_m or K_r = K_r/K_m x K_m), already exceeds it. Then every such candidate is refused
    with its stops set and carries no force, whatever its sheet, pitch or material, so a
    refusal's search for fewer columns skips it (a necessary condition, not a judgement).

    Args:
        targets: K_r/K_m, the K_obj range (N/mm) and the full-scale force (N).
        km_scale: K_m over eq. 2's centre (:data:`KM_SCALES`).

    Returns:
        False only when no candidate at that scale can carry.
    """
    from tactcad.design.comb_plan import MAX_STOP_GAP_MM

    k_m = km_scale * centred_km(targets)
    softest = min(k_m, targets.kr_over_km * k_m)
    gap = least_stop_gap_mm(targets.full_scale_force_N, STOP_BOUND_K_SLACK * softest)
    return gap <= MAX_STOP_GAP_MM


def stop_fitting_scales(targets: Targets) -> tuple[float, ...]:
    """The K_m scales of :data:`KM_SCALES` whose stops can fit (:func:`stops_can_fit`), in
    their order."""
    return tuple(s for s in KM_SCALES if stops_can_fit(targets, s))


def atlas_scales(targets: Targets) -> tuple[float, ...]:
    """The K_m scales whose candidates can change a verdict, its binding limit or its option:
    those whose stops can fit (:func:`stop_fitting_scales`), else the stiffest alone.

    A scale whose stops cannot fit is refused on every sheet (force margin -inf, no rating),
    so it neither counts nor rates, and :func:`nearest_failure` (most margin, then the
    stiffer pair) takes it only when no scale fits: then the stiffest scale's first sheet,
    which judging the stiffest scale alone finds as well.

    Args:
        targets: K_r/K_m, the K_obj range (N/mm) and the full-scale force (N).

    Returns:
        The scales, in :data:`KM_SCALES`' order.
    """
    return stop_fitting_scales(targets) or KM_SCALES[-1:]


def nearest_failure(tried: list[CombCandidate]) -> CombCandidate | None:
    """Of the candidates that fail, the nearest to counting (the most force margin, the
    stiffer pair on a tie: the refusal's rule for each sheet's line); None when none fails."""
    failing = [c for c in tried if c.failures]
    return max(failing, key=lambda c: (c.force_margin_rel, c.km_scale), default=None)


def comb_counts(base: dict, force_N: float, columns: int, room: Any, targets: Targets,
                grade: str | None, envelope_of: Callable | None,
                order: list[tuple[float, float]] | None = None,
                bounds: dict[tuple[float, float], ForceBound | None] | None = None) -> bool:
    """True when some sheet's comb at some K_m scale counts at a full-scale force of
    ``force_N`` (N) and carries it as the closed form decides it (:func:`carries_decided`:
    the force a refusal offers to paste designs a comb that passes); tried in ``order``
    ((sheet mm, K_m scale) pairs; default every sheet of :func:`sheets_of` at every scale),
    stopping at the first that counts.

    ``bounds`` ((sheet, scale) -> :class:`ForceBound`, kept over one refusal's calls):
    a pair whose bound fails at ``force_N`` is not judged again (the answer is the same,
    its webs and limits do not depend on the force); each pair judged adds its bound."""

    at = replace(targets, full_scale_force_N=force_N)
    pairs = order or [(sheet, scale) for sheet in sheets_of(base) for scale in KM_SCALES]
    known = {} if bounds is None else bounds
    with candidates_weighed():
        for sheet, scale in pairs:
            bound = known.get((sheet, scale))
            if bound is not None and bound.fails_at(force_N):
                continue
            c = candidate(base, sheet, scale, columns, room, at, grade, envelope_of, None)
            known[(sheet, scale)] = c.force_bound
            if c.plan is not None and not c.failures and carries_decided(c):
                return True
    return False


def carries_decided(c: CombCandidate) -> bool:
    """Whether a candidate's full-scale-force record passes at the closed form, beyond its
    error (margin >= error estimate): a force offered to paste is one the comb it designs
    carries as ``verify`` decides it, not one a higher level may yet fail.

    Args:
        c: a judged candidate.

    Returns:
        True when its margin clears the binding limit's error (an unknown error: when the
        margin is not negative).
    """
    bound = c.force_bound
    error = bound.binding_error_rel if bound is not None else None
    return c.force_margin_rel >= (error if error is not None and math.isfinite(error) else 0.0)


def bounds_of(tried: list[CombCandidate]) -> dict[tuple[float, float], ForceBound | None]:
    """(sheet mm, K_m scale) -> :class:`ForceBound` of candidates judged (one column
    count): what :func:`comb_counts` need not judge again."""
    return {(c.sheet_mm, c.km_scale): c.force_bound for c in tried}


#: The lightest full-scale force (N) a refusal's search for a lighter rating tries: the
#: least ``design --full-scale-force`` and the atlas take.
LIGHTEST_SEARCHED_FORCE_N = 1e-4


def rated_at_a_lighter_force(base: dict, columns: int, room: Any, targets: Targets,
                             grade: str | None, envelope_of: Callable | None
                             ) -> list[CombCandidate]:
    """Every sheet's comb at every K_m scale judged at the first of a tenth, a hundredth
    ... of the asked force (down to :data:`LIGHTEST_SEARCHED_FORCE_N`) at which one is rated
    for some force: what a refusal's frontier starts from when every candidate at the asked
    force was refused by a limit that force sets (the stop gaps grow with it).

    Args:
        base, columns, room, targets, grade, envelope_of: as :func:`comb_counts`.

    Returns:
        The candidates at that force (each with its rating), or [] when none is rated at
        any force tried.
    """

    force = targets.full_scale_force_N / 10.0
    with candidates_weighed():
        while force >= LIGHTEST_SEARCHED_FORCE_N:
            at = replace(targets, full_scale_force_N=force)
            tried = [candidate(base, sheet, scale, columns, room, at, grade, envelope_of, None)
                     for sheet in sheets_of(base) for scale in KM_SCALES]
            if any(c.rated_force_N for c in tried):
                return tried
            force /= 10.0
    return []


def frontier_of(rating: list[CombCandidate], base: dict, columns: int, room: Any,
                targets: Targets, grade: str | None,
                envelope_of: Callable | None) -> float | None:
    """The largest full-scale force (N) a comb counts at for ``targets``' stiffnesses
    (:func:`largest_comb_force`), from the best rating of ``rating``, its best-rated pairs
    judged first and their bounds kept (:func:`comb_counts`): the force a refusal offers
    and a design reports.

    Args:
        rating: candidates judged at one force (their ``rated_force_N``, N).
        base, columns, room, targets, grade, envelope_of: as :func:`comb_counts`.

    Returns:
        The force (N, three digits, rounded down), or None where no candidate is rated.
    """
    rated = [c.rated_force_N for c in rating if c.rated_force_N]
    if not rated:
        return None
    # the best-rated candidates first: the one that counts is found soonest
    order = [(c.sheet_mm, c.km_scale) for c in
             sorted(rating, key=lambda c: -(c.rated_force_N or 0.0))]
    bounds = bounds_of(rating)
    return largest_comb_force(max(rated) * 0.99, lambda force: comb_counts(
        base, force, columns, room, targets, grade, envelope_of, order, bounds))


def largest_comb_force(estimate_N: float, counts: Callable[[float], bool]) -> float:
    """The largest full-scale force (N, 3 significant digits, rounded down) at which a comb
    counts (``counts``), from the candidates' own rating ``estimate_N``: a candidate's
    stops and webs are set for the force asked, so its rating is only an estimate. Stepped
    down from it until one counts, then a bracket grown by
    :data:`~tactcad.studies.design_alternatives.BRACKET_STEP` until a force fails and
    bisected to within :data:`FRONTIER_TOLERANCE_REL`, so the answer is the search's
    frontier whatever force was asked.

    Args:
        estimate_N: the candidates' best rating (N).
        counts: whether a comb counts at a full-scale force (N).

    Returns:
        The force (N).
    """
    from tactcad.studies.design_alternatives import BRACKET_STEP, _round_down

    lo = estimate_N
    while not counts(lo):
        lo *= 0.9
        if lo < estimate_N * 0.3:
            return _round_down(estimate_N)  # nothing near counts: the estimate as it is
    hi = lo * 1.05
    while counts(hi):
        lo, hi = hi, hi * BRACKET_STEP
    while hi > lo * (1.0 + FRONTIER_TOLERANCE_REL):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if counts(mid) else (lo, mid)
    return _round_down(lo)


def chosen(good: list[CombCandidate]) -> CombCandidate:
    """Of the candidates that count, the softest pair (the K_obj range read finest) that
    carries the force with :data:`FORCE_MARGIN_REL` to spare, the thicker sheet on a tie;
    when none has that margin, the one with the most."""
    return in_preference(good)[0]


def in_preference(good: list[CombCandidate]) -> list[CombCandidate]:
    """The candidates that count in the order they are preferred (:func:`chosen`'s rule):
    those with the force margin, softest pair first, thicker sheet on a tie; then the rest,
    most margin first."""
    spare = sorted((c for c in good if c.force_margin_rel >= FORCE_MARGIN_REL),
                   key=lambda c: (c.km_scale, -c.sheet_mm))
    short = sorted((c for c in good if c.force_margin_rel < FORCE_MARGIN_REL),
                   key=lambda c: (-c.force_margin_rel, -c.sheet_mm))
    return spare + short


def surviving(good: list[CombCandidate], grasp_N: float, room: Any,
              envelope_of: Callable | None, targets: Targets, columns: int) -> CombCandidate:
    """The first candidate in :func:`in_preference`'s order that also survives a grasp of
    ``grasp_N`` (N) in the jaw it is for (``requirements.max_grasp_force_N``, judged by
    :func:`judge` with the jaw's ``[grasper_jaw]`` table): a grasp costs a contact solve, so
    only the candidates that count otherwise are grasped.

    Raises:
        InverseDesignError: none survives; names the nearest one's binding limit and its
            code (``limit``), and, where the grasp is out of the jaw's reach, the nearest
            grasp in reach that a candidate survives (:func:`grasp_in_reach`).
    """
    nearest = None
    for c in in_preference(good):
        d = grasped_tables(c.data, grasp_N, room)
        plan, fails, codes, margin, rated = judge_limits(d, envelope_of, room)
        if plan is not None and not fails:
            # the grasp's tables: not those its figures were predicted for
            return replace(c, data=d, plan=plan, force_margin_rel=margin, rated_force_N=rated,
                           predicted=None)
        nearest = nearest or (fails, codes)
    fails, codes = nearest or (("?",), ())
    lo, hi = targets.k_obj_range_N_per_mm
    text = (f"no monolithic comb of 2 x {columns} for the {room.label} (K_r/K_m "
            f"{targets.kr_over_km:g}, K_obj {lo:g} ... {hi:g} N/mm at "
            f"{targets.full_scale_force_N:g} N) survives a {grasp_N:g} N grasp "
            f"(--max-grasp-force): of the "
            f"{len(good)} that count, the first binds on {fails[0]}")
    pasted = grasp_in_reach(good, grasp_N, room, envelope_of, targets)
    if pasted is None:
        text += "\n  none to paste: no comb that counts survives a grasp in its jaw's reach"
    refused = InverseDesignError(
        text + (f"\n  nearest: --max-grasp-force {pasted:.3g}" if pasted else ""),
        "--max-grasp-force", grasp_N, "a grasp the comb's hard stops hold",
        alternatives=[{"option": f"--max-grasp-force {pasted:.3g}",
                       "words": "the nearest grasp in the jaw's reach that the comb "
                                "survives"}] if pasted else [])
    refused.limit = codes[0] if codes else ""
    raise refused


def grasped_tables(data: Mapping[str, Any] | None, grasp_N: float, room: Any) -> dict:
    """A candidate's tables (``data``: a counting candidate's, never None) asked to survive a
    grasp of ``grasp_N`` (N) in the jaw of ``room`` (its ``[grasper_jaw]`` table)."""
    d = copy_tables(data)
    d["requirements"]["max_grasp_force_N"] = float(grasp_N)
    d["grasper_jaw"] = dict(room.table or {})
    return d


#: How many candidates :func:`grasp_in_reach` judges at the grasp it would offer before it
#: offers none: each is a grasp's contact solve, and the first in reach nearly always holds.
GRASP_REACH_TRIES = 3


def grasp_in_reach(good: list[CombCandidate], grasp_N: float, room: Any,
                   envelope_of: Callable | None, targets: Targets) -> float | None:
    """The grasp (N) a refusal of ``grasp_N`` offers when that grasp is out of the jaw's
    reach: for the candidates in :func:`in_preference`'s order whose reach
    (:func:`tactcad.in_use.grasp_experiment.design_grasp_reach_N`, the jaw open to closed
    flat on its slab) leaves ``grasp_N`` out, the end of that reach nearest it, to three
    significant digits inward (down from above, up from below) so that it is in reach; the
    first such grasp the candidate then survives (:func:`judge_limits`), after at most
    :data:`GRASP_REACH_TRIES` tries.

    Args:
        good: the candidates that count. grasp_N: the grasp asked (N). room, envelope_of,
            targets: as :func:`surviving` takes them.

    Returns:
        The grasp to paste (N), or None when the asked one is in every candidate's reach
        (an overload binds, not the reach) or none tried survives its own.
    """
    from tactcad.in_use.grasp_experiment import design_grasp_reach_N
    from tactcad.vocabulary.rounding import round_down, round_up

    tries = 0
    for c in in_preference(good):
        # the jaw's own table in the plan: its grasp is in this jaw, not a default one
        plan = plan_from_dict(grasped_tables(c.data, grasp_N, room))
        least, largest = design_grasp_reach_N(plan, targets.full_scale_force_N,
                                              targets.k_obj_range_N_per_mm)
        if least <= grasp_N <= largest:
            continue
        paste = round_down(largest, 3) if grasp_N > largest else round_up(least, 3)
        if not least <= paste <= largest:
            continue
        plan, fails, _, _, _ = judge_limits(grasped_tables(c.data, paste, room), envelope_of,
                                            room)
        if plan is not None and not fails:
            return paste
        tries += 1
        if tries >= GRASP_REACH_TRIES:
            break
    return None


def centred_km(targets: Targets) -> float:
    """Eq. 2's centre of the K_obj range for K_m (N/mm): sqrt(K_lo K_hi / X)."""
    lo, hi = targets.k_obj_range_N_per_mm
    return math.sqrt(lo * hi / targets.kr_over_km)


def candidate(base: dict, sheet: float, km_scale: float, columns: int, room: Any,
              targets: Targets, grade: str | None, envelope_of: Callable | None,
              progress: Callable[[str], None] | None) -> CombCandidate:
    """One sheet's comb at one K_m scale, judged (:func:`judge`), or the limit that binds
    it first."""
    if progress:
        progress(f"comb on a {sheet:g} mm sheet, K_m {km_scale:g} x eq. 2's centre")
    refused, d, room = prepared_candidate(base, sheet, km_scale, columns, room, targets, grade)
    return refused if refused is not None else \
        judged_candidate(d, sheet, km_scale, envelope_of, room)


def judged_candidate(d: dict, sheet: float, km_scale: float, envelope_of: Callable | None,
                     room: Any, plan: Any = None, limits: list | None = None,
                     refusal: DesignErrors | None = None) -> CombCandidate:
    """A candidate whose tables ``d`` (webs and stops set, :func:`prepared_candidate`) are
    judged (:func:`judge_bounded`) on a ``sheet`` (mm) at ``km_scale``.

    Args:
        d: the tables. sheet: the sheet (mm). km_scale: K_m over eq. 2's centre.
        envelope_of, room: as :func:`judge_limits`. plan, limits, refusal: ``d``'s plan,
            closed-form limits and plan's refusal where already worked out
            (:func:`planned`).

    Returns:
        The :class:`CombCandidate`.
    """
    plan, fails, codes, margin, rated, bound, predicted = judge_recorded(
        d, envelope_of, room, plan, limits, refusal)
    return CombCandidate(sheet, km_scale, d, plan, fails, margin, rated, codes, bound,
                         predicted=predicted)


def prepared_candidate(base: dict, sheet: float, km_scale: float, columns: int, room: Any,
                       targets: Targets, grade: str | None
                       ) -> tuple[CombCandidate | None, dict | None, Any]:
    """One sheet's comb at one K_m scale up to its judgement: its tables with the webs
    solved and the stops set, or the candidate refused before (the pitch, a web, the plan).

    Args:
        base, sheet, km_scale, columns, room, targets, grade: as :func:`candidate`.

    Returns:
        (the refused candidate or None, the tables or None, the room it is judged in: an
        outline's room narrowed to the sheet's comb).
    """
    refused, webbed, room = webbed_candidate(base, sheet, km_scale, columns, room, targets,
                                             grade)
    if refused is not None:
        return refused, None, room
    refused, d = stopped_candidate(webbed)
    return refused, d, room


@dataclass(frozen=True)
class WebbedCandidate:
    """One sheet's comb at one K_m scale with its webs solved, before its tables take them
    and its stops are set (:func:`webbed_candidate`; :func:`stopped_candidate` goes on).

    Attributes:
        sheet_mm: the sheet (mm). km_scale: K_m over eq. 2's centre.
        tables: the sheet's comb tables at their starting webs (:func:`sheet_tables`'s:
            shared, read only). start: their plan (:func:`starting_plan`).
        webs: (the references' web, the measuring elements' web) (mm).
        targets: the targets. room: the room it is judged in.
    """

    sheet_mm: float
    km_scale: float
    tables: dict
    start: Any
    webs: tuple[float, float]
    targets: Targets
    room: Any


def webbed_candidate(base: dict, sheet: float, km_scale: float, columns: int, room: Any,
                     targets: Targets, grade: str | None
                     ) -> tuple[CombCandidate | None, WebbedCandidate | None, Any]:
    """:func:`prepared_candidate`'s first half: the sheet's tables and their webs solved,
    or the candidate refused before (the pitch, the starting plan, a web).

    Args:
        base, sheet, km_scale, columns, room, targets, grade: as :func:`candidate`.

    Returns:
        (the refused candidate or None, the :class:`WebbedCandidate` or None, the room it
        is judged in: an outline's room narrowed to the sheet's comb).
    """
    from tactcad.vocabulary.binding_limits import FOOTPRINT, SHEET

    if getattr(room, "outline", None) is not None:
        room, why = room_of_outline(base, sheet, columns, room, targets, grade)
        if why:
            return CombCandidate(sheet, km_scale, None, None, (why,), -math.inf, None,
                                 (FOOTPRINT,), REFUSED_AT_ANY_FORCE), None, room
    d, binding = sheet_tables(base, sheet, columns, room, targets, grade)
    codes: tuple[str, ...] = (SHEET,) * len(binding)  # the pitch leaves no arm
    bound: ForceBound | None = REFUSED_AT_ANY_FORCE  # until the stops read the force
    if not binding:
        try:
            start, webs, binding = solved_webs(d, targets, km_scale)
            codes = (SHEET,) * len(binding)  # no web the sheet's process cuts reaches K
        except DesignErrors as exc:
            binding, codes = refused_fields(exc)
            if not force_free(exc):
                bound = None
    if binding:
        return CombCandidate(sheet, km_scale, None, None, tuple(binding), -math.inf, None,
                             tuple(codes), bound), None, room
    return None, WebbedCandidate(sheet, km_scale, d, start, webs, targets, room), room


def stopped_candidate(w: WebbedCandidate) -> tuple[CombCandidate | None, dict | None]:
    """:func:`prepared_candidate`'s second half: the tables with ``w``'s webs, planned, and
    their stops set (:func:`with_stops`), or the candidate refused by its plan.

    Args:
        w: the candidate with its webs solved (:func:`webbed_candidate`).

    Returns:
        (the refused candidate or None, the tables or None).
    """
    d = webbed_tables(w.tables, w.webs, w.start.columns)
    bound: ForceBound | None = REFUSED_AT_ANY_FORCE  # until the stops read the force
    try:
        plan = plan_from_dict(d)
        bound = None
        d = with_stops(d, plan, w.targets)
    except DesignErrors as exc:
        binding, codes = refused_fields(exc)
        if not force_free(exc):
            bound = None
        return CombCandidate(w.sheet_mm, w.km_scale, None, None, tuple(binding), -math.inf,
                             None, tuple(codes), bound), None
    return None, d


def strength_bound_N(w: WebbedCandidate) -> float | None:
    """The least of the yield and fatigue limits (N) of a candidate's references and
    measuring elements, with its webs solved and before its stops are set: at least the
    force its binding limit allows once they are.

    Those limits are yield / (peak stress per N x safety factor) and the notch fatigue
    strength / peak stress per N (:func:`tactcad.mechanics.limits.element_limits`), the
    peak stress a function of the web, notch radius, arm and sheet alone
    (:func:`tactcad.mechanics.element_strength.closed_form_stress`), none of which the
    stop gaps change: each is, to the bit, a limit :func:`planned_limits` and the
    verification matrix give the plan with its stops, whose binding limit (the least of
    all) allows no more.

    Args:
        w: the candidate (:func:`webbed_candidate`).

    Returns:
        The force (N); None without a yield strength or a finite positive stress.
    """
    from tactcad.mechanics.element_strength import (notch_fatigue_strength,
                                                    peak_stress_per_newton)

    plan = w.start
    y = plan.material.yield_strength_MPa
    if y is None or not math.isfinite(y) or y <= 0:
        return None  # the plan's limits refuse it: judged as the search judges it
    notch = notch_fatigue_strength(plan.material)
    least = math.inf
    for number, web in ((1, w.webs[0]), (plan.columns + 1, w.webs[1])):
        g = plan.element(number).geometry
        s = float(peak_stress_per_newton(web, g.notch_radius_mm, g.arm_length_mm,
                                         g.sheet_thickness_mm))
        if not (math.isfinite(s) and s > 0):
            return None
        least = min(least, y / (s * plan.strength.safety_factor))
        if notch is not None:
            least = min(least, notch.strength_MPa / s)
    return least if math.isfinite(least) else None


def short_by_strength(w: WebbedCandidate) -> "Waiting | None":
    """Whether a candidate with its webs solved surely lacks :data:`FORCE_MARGIN_REL`
    before its stops are set: its :func:`strength_bound_N` falls short of (1 + margin) x
    the full-scale force by :data:`MARGIN_BOUND_SLACK_REL` (the rule of
    :func:`short_of_margin`, which then holds for it once its stops are set, unless its
    plan is refused), so it is not :func:`first_preferred`'s answer.

    Args:
        w: the candidate (:func:`webbed_candidate`).

    Returns:
        The candidate set aside (:class:`Waiting`) when it is short; None when it is not
        or has no bound.
    """
    bound = strength_bound_N(w)
    force = w.tables["requirements"]["full_scale_force_N"]
    if bound is None or not bound * (1.0 + MARGIN_BOUND_SLACK_REL) \
            < (1.0 + FORCE_MARGIN_REL) * force:
        return None
    return Waiting(w, bound / force - 1.0)


@dataclass(frozen=True)
class Waiting:
    """A candidate of :func:`first_preferred`'s walk set aside with its webs solved
    (:func:`short_by_strength`): its stops, plan and limits wait until no candidate has
    the margin.

    Attributes:
        webbed: the candidate (:func:`webbed_candidate`).
        margin_bound_rel: the most force margin it can have, its
            :func:`strength_bound_N` over the full-scale force less 1 (its judgement's,
            its sketch's or -inf when its plan is refused: none is above it).
    """

    webbed: WebbedCandidate
    margin_bound_rel: float


#: How far (relative) a candidate's closed-form binding force, worked out before its
#: verification matrix, must fall short of the margin's force to be judged last in
#: :func:`first_preferred`: a thousand times the drift of the limits with the stop gaps.
MARGIN_BOUND_SLACK_REL = 1e-6


def planned_limits(d: dict) -> tuple[Any, list | None]:
    """A candidate's plan and its closed-form limits
    (:func:`tactcad.mechanics.limits.plan_limits`), as :func:`judge_bounded` works them out,
    so that a bound read first and the judgement share them.

    Args:
        d: the candidate's tables (webs and stops set).

    Returns:
        (plan, limits); (None, None) when the plan is refused, (plan, None) when its
        limits are (the judgement says why).
    """
    return planned(d)[:2]


def planned(d: dict) -> tuple[Any, list | None, DesignErrors | None]:
    """:func:`planned_limits` with the plan's refusal, so that a judgement of the same
    tables (:func:`judge_bounded`) reads it rather than validating them again.

    Args:
        d: the candidate's tables (webs and stops set).

    Returns:
        (plan, limits, refusal): (None, None, the refusal) when the plan is refused;
        else as :func:`planned_limits` with None.
    """
    from tactcad.mechanics.limits import plan_limits

    try:
        plan = plan_from_dict(d)
    except DesignErrors as exc:
        return None, None, exc
    try:
        return plan, plan_limits(plan, "closed-form"), None
    except DesignError:
        return plan, None, None


def short_of_margin(d: dict, limits: list) -> bool:
    """Whether a candidate's tables ``d`` (webs and stops set) surely lack
    :data:`FORCE_MARGIN_REL`: the force its binding limit allows at the closed form
    (``limits``, :func:`planned_limits`'; the verification matrix's full-scale-force
    record takes the least of these) falls short of (1 + margin) x the full-scale force by
    more than :data:`MARGIN_BOUND_SLACK_REL`. The candidate's force margin is that force
    over the full-scale force less 1, so such a candidate cannot be
    :func:`first_preferred`'s answer.

    Args:
        d: the candidate's tables (N for the full-scale force). limits: its limits.

    Returns:
        True only when the candidate cannot count with the margin.
    """
    from tactcad.mechanics.limits import binding

    force = d["requirements"]["full_scale_force_N"]
    allowed = binding(limits).force_N * (1.0 + MARGIN_BOUND_SLACK_REL)
    return allowed < (1.0 + FORCE_MARGIN_REL) * force


def force_free(exc: DesignErrors) -> bool:
    """Whether a plan's refusal (its webs solved, its stops not yet set) holds at any
    full-scale force: some refused field is not the force (every field is validated, and
    the force is read only as ``requirements.full_scale_force_N``)."""
    return any(not str(e.field).startswith("requirements.full_scale_force_N")
               for e in exc.errors)


def too_tall(plan: Any, room: Any) -> tuple[str, ...]:
    """The failure of a comb taller than the jaw's room (its thickness and the tips' proud
    height; mm), else none."""
    height = float(plan.comb.envelope_mm[2])
    if height <= room.height_mm + 1e-9:
        return ()
    return (f"the comb's height: {height:.4g} mm, the {room.label} holds "
            f"{room.height_mm:.4g} mm (its thickness and the tips' proud height)",)


def fastener_pairs() -> list[tuple[str, float]]:
    """Every (screw size, dowel diameter mm) of the miniature tables, in the order tried:
    the largest screw first, then the largest dowel."""
    from tactcad.vocabulary.standards import DOWEL_PINS, MINIATURE_SCREWS

    screws = sorted(MINIATURE_SCREWS, key=lambda k: -MINIATURE_SCREWS[k].nominal_diameter_mm)
    return [(sc, dw) for sc in screws for dw in sorted(DOWEL_PINS, reverse=True)]


def with_fasteners(best: CombCandidate, room: Any, envelope_of: Callable | None,
                   first_failure: bool = True
                   ) -> tuple[CombCandidate, tuple[FastenerTry, ...]]:
    """The chosen comb with the first screw and dowel pair of :func:`fastener_pairs` that
    counts (validates, passes :func:`judge` and stands in the room), and every pair tried up
    to it. The chosen comb's own pair counts, so one always does.

    Args:
        best: the chosen comb. room: the jaw's room. envelope_of: as :func:`judge`.
        first_failure: False: a pair whose plan stands taller than ``room``
            (:func:`too_tall`) is refused by that alone, its verification matrix left
            out (it counts no more than when judged in full); its failures are then the
            height's, where a full judgement lists the matrix's failures first.

    Returns:
        (the comb with the pair that counts, every pair tried in order).
    """
    tried = []
    for screw, dowel in fastener_pairs():
        d = copy_tables(best.data)
        d["comb"]["screw_size"] = screw
        d["comb"]["dowel_diameter_mm"] = f"{dowel:g}"
        own = (screw, f"{dowel:g}") == (best.data["comb"]["screw_size"],
                                         str(best.data["comb"]["dowel_diameter_mm"]))
        if own:
            tried.append(FastenerTry(screw, dowel, ()))
            return best, tuple(tried)
        plan, fails, margin, rated, predicted = pair_judged(d, envelope_of, room,
                                                            first_failure)
        tried.append(FastenerTry(screw, dowel, fails))
        if plan is not None and not fails:
            return replace(best, data=d, plan=plan, force_margin_rel=margin,
                           rated_force_N=rated, predicted=predicted), tuple(tried)
    return best, tuple(tried)


def room_of_outline(base: dict, sheet: float, columns: int, room: Any, targets: Targets,
                    grade: str | None) -> tuple[Any, str]:
    """The room a jaw's pocket outline leaves one sheet's comb: as wide as the comb and as
    long as the outline's longest stretch that holds it (``room.along_for``), and why there
    is none."""
    env = comb_envelope_mm(base, sheet, columns, room, targets, grade)
    if env is None:
        return room, f"the {sheet:g} mm sheet's comb has no plan"
    along = room.along_for(env[0])
    if along <= 0:
        return room, (f"requirements.footprint_mm[1]: the pocket outline holds no stretch "
                      f"{env[0]:.4g} mm wide (the comb across its rows) on the jaw's axis")
    return replace(room, across_mm=env[0], along_mm=along), ""


def comb_envelope_mm(base: dict, sheet: float, columns: int, room: Any, targets: Targets,
                     grade: str | None) -> tuple[float, float, float] | None:
    """The envelope (across, along, height; mm) of one sheet's comb at the base's webs,
    whatever the pocket (its footprint requirement left out); None when it has no plan."""
    d, binding = comb_tables(base, sheet, columns, room, targets, grade)
    if binding:
        return None
    d["requirements"].pop("footprint_mm", None)
    try:
        plan = target_free_plan(d)  # its envelope does not depend on the targets
    except DesignErrors:
        return None
    return tuple(float(v) for v in plan.comb.envelope_mm)


def least_pitch_mm(base: dict, sheet: float, columns: int, room: Any, targets: Targets,
                   grade: str | None) -> float:
    """The least pitch at which one sheet's comb has a measuring arm 0.5 mm longer than the
    reference's (:func:`comb_tables`' rule: reference arm 2 mm, the measuring arm the pitch
    less the slot, post, notch and half the tip).

    Args:
        base: the comb template's tables. sheet: the sheet (mm). columns: the columns.
        room: the jaw's room (mm). targets: the targets. grade: the grade, or None.

    Returns:
        The pitch (mm, rounded up to 0.1 mm).
    """
    d, _ = comb_tables(base, sheet, columns, room, targets, grade)
    e, comb = d["element"], d["comb"]
    need = REFERENCE_ARM_MM + MEASURING_ARM_EXCESS_MM + slot_of(d) + comb["post_length_mm"] \
        + e["notch_radius_mm"] \
        + e["tip_width_mm"] / 2
    return math.ceil(round(need * 10, 6)) / 10


def comb_misfit(room: Any, columns: int, base: Mapping[str, Any], targets: Targets,
                grade: str | None = None, process: str | None = None) -> list[dict]:
    """The dimensions in which the smallest comb of ``columns`` (of every sheet, at its
    least pitch) cannot fit the jaw's ``room``, before any search: its height against the
    jaw's thickness and the tips' proud height, its width across the rows against the
    pocket's width, its length against the pocket's length (mm). Each a dict: ``words``
    (the comb's size against the jaw's, naming the jaw file's key), ``option`` (what to
    paste: fewer columns where they fit the length, or "") and ``limit`` (the code the
    search's own check sets for it, :mod:`tactcad.vocabulary.binding_limits`: the height,
    the footprint across, the sheet for the length, whose pitch leaves no measuring arm).
    Empty when some sheet's smallest comb fits every dimension (the search then decides).

    Args:
        room: the jaw's room (:class:`tactcad.partlib.grasper_jaw.JawRoom`, mm).
        columns: columns of the 2-row comb.
        base: the comb template's tables.
        targets: the targets (the comb's tables carry them; its size does not depend on them).
        grade: the material grade, or None for the base's.
        process: the rows' cut process (None: the base's): its sheets are the ones held.

    Returns:
        The misfits (see above); ``[]`` when some sheet's smallest comb fits, or when no
        sheet's comb has a plan (the search then says why).
    """
    tables: dict = copy_tables(dict(base))
    tables["requirements"] = {}
    if process is not None:
        tables["element"]["process"] = process
    roomy = replace(room, across_mm=1e3, along_mm=1e3, height_mm=1e3, outline=None, table=None)
    smallest = None
    for sheet in sheets_of(tables):
        pitch = least_pitch_mm(tables, sheet, columns, roomy, targets, grade)
        pocket = pocket_for_length_mm(tables, pitch * columns)  # the length, its deviation
        env = comb_envelope_mm(tables, sheet, columns, replace(roomy, along_mm=pocket),
                               targets, grade)
        if env is None:
            continue
        misses = _misses(env, pocket, room)
        if not misses:
            return []
        if smallest is None or (len(misses), env[0]) < (len(smallest[2]), smallest[1][0]):
            smallest = (sheet, env, misses, pitch)
    if smallest is None:
        return []  # no sheet's comb has a plan: the search says why
    from tactcad.vocabulary.binding_limits import FOOTPRINT, HEIGHT, SHEET

    sheet, env, misses, pitch = smallest
    out = []
    keys = room_keys(room)
    edit, why_not = room.file_paste(env)  # a lab's own jaw: the keys that would hold it
    paste = (f"{' and '.join(k for k, _ in edit)} in {PurePath(room.option).name}"
             if edit and ("height" in misses or "across" in misses) else "")
    # where no key of the file holds it, why (said once, on the first size that binds)
    why_not = f"; {why_not}" if why_not and ("height" in misses or "across" in misses) else ""
    for dim in misses:
        if dim == "height":
            out.append({"words": f"height {env[2]:.3g} mm (the {sheet:g} mm sheet's comb, "
                                 f"its rows on edge) vs the jaw's {room.height_mm:.3g} mm "
                                 f"({keys['height']}){why_not}", "option": paste,
                        "limit": HEIGHT})
            paste = why_not = ""
        elif dim == "across":
            out.append({"words": f"width {env[0]:.3g} mm across its two rows (the {sheet:g} "
                                 f"mm sheet's) vs the pocket's {room.across_mm:.3g} mm "
                                 f"({keys['across']}){why_not}", "option": paste,
                        "limit": FOOTPRINT})
            paste = why_not = ""
        else:
            fit = next((n for n in range(columns - 1, 0, -1)
                        if pocket_for_length_mm(tables, n * pitch) <= room.along_mm + 1e-9), 0)
            deviation = pocket_for_length_mm(tables, pitch * columns) - pitch * columns
            out.append({"words": f"length {pitch * columns:.3g} mm ({columns} columns at its "
                                 f"least pitch {pitch:g} mm) vs the pocket's "
                                 f"{room.along_mm:.3g} mm ({keys['along']}), which must also hold the "
                                 f"length's ISO 2768-1 deviation (+/-{deviation:.3g} mm)",
                        "option": f"--columns {fit}" if fit >= 1 and len(misses) == 1 else "",
                        "limit": SHEET})
    return out


def _misses(env: tuple[float, float, float], along: float, room: Any) -> list[str]:
    """Which of a comb's height, width across its rows and length (``env``; ``along``: the
    pocket length it needs, its deviation included; mm) the jaw's ``room`` does not hold (an
    outline's room: its height alone)."""
    misses = ["height"] if env[2] > room.height_mm + 1e-9 else []
    if room.outline is None:
        misses += ["across"] if env[0] > room.across_mm + 1e-9 else []
        misses += ["along"] if along > room.along_mm + 1e-9 else []
    return misses


def room_keys(room: Any) -> dict[str, str]:
    """The jaw file's keys behind a room's height, width and length, in words.

    Args:
        room: the jaw's room (:class:`tactcad.partlib.grasper_jaw.JawRoom`, mm).

    Returns:
        ``{"height", "across", "along"}`` -> the keys (and clearances, mm) behind each.
    """
    t = dict(room.table or {})
    c = room.clearance_mm
    height = "thickness_mm + tip_proud_mm"
    across = (f"pocket_width_mm {t['pocket_width_mm']:g} less {c:g} mm clearance each side"
              if "pocket_width_mm" in t else
              f"the jaw's width less its side walls and {c:g} mm clearance each side")
    along = (f"pocket_length_mm {t['pocket_length_mm']:g} less {c:g} mm clearance each end"
             if "pocket_length_mm" in t else
             "length_mm between the pin's steel and the distal wall")
    return {"height": height, "across": across, "along": along}


def nearest_jaw(base: dict, columns: int, room: Any, targets: Targets, grade: str | None,
                other_rooms: Mapping[str, Any]) -> tuple[str, list[dict]]:
    """A line for a refusal when the pocket is too small across or too shallow for every
    sheet's comb: the smallest comb's pocket, the jaw-file keys that would hold it (a lab's
    own jaw) and the first jaw of ``other_rooms`` that holds it, with those as pasteable
    alternatives (empty when some sheet's comb fits the pocket: something else binds; the
    sheets after the first that fits are not planned)."""
    needs = []
    for sheet in sheets_of(base):
        env = comb_envelope_mm(base, sheet, columns, room, targets, grade)
        if env and env[0] <= room.across_mm and env[2] <= room.height_mm:
            return "", []
        if env:
            needs.append((sheet, env))
    if not needs:
        return "", []
    sheet, env = min(needs, key=lambda n: (n[1][0], n[1][2]))
    holds = [option for option, other in other_rooms.items()
             if other.across_mm >= env[0] and other.height_mm >= env[2]
             and other.along_mm >= env[1]]
    keys, why_not = room.file_paste(env)
    edit = [f"{' and '.join(k for k, _ in keys)} in {PurePath(room.option).name}"] if keys else []
    alternatives = [{"option": e, "words": "; ".join(w for _, w in keys)} for e in edit]
    alternatives += [{"option": f"--jaw {h}", "words": f"the {h} mm class's default jaw holds "
                      f"the {sheet:g} mm sheet's comb"} for h in holds[:1]]
    where = " or ".join(edit + [f"--jaw {h}" for h in holds[:1]]) \
        or "a jaw whose [grasper_jaw] pocket holds it"
    where += f" ({why_not})" if why_not else ""
    return (f"nearest jaw: a pocket of {env[0]:.3g} mm across and {env[2]:.3g} mm high inside "
            f"its clearances (the {sheet:g} mm sheet's comb, the smallest; this jaw's is "
            f"{room.across_mm:.3g} x {room.height_mm:.3g} mm): {where}", alternatives)


def other_column_counts(columns: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """The column counts a refusal offers instead of ``columns``, in the order it tries
    them: (fewer, most first; more, fewest first), each within
    :data:`tactcad.design.array_plan.COLUMNS_RANGE`. A shorter pitch leaves shorter arms,
    so a comb too soft at its longest arms counts with more columns.

    Args:
        columns: the columns asked (1 ... 12).

    Returns:
        (the counts below ``columns``, the counts above it).
    """
    from tactcad.design.array_plan import COLUMNS_RANGE

    lo, hi = COLUMNS_RANGE
    return tuple(range(columns - 1, lo - 1, -1)), tuple(range(columns + 1, hi + 1))


def nearest_columns(base: dict, columns: int, room: Any, targets: Targets, grade: str | None,
                    envelope_of: Callable | None) -> tuple[int, float | None] | None:
    """The most columns below ``columns`` whose comb counts in ``room``: (columns, None);
    else the most whose comb carries some smaller force, with that force (N: the search's
    frontier from the candidates' best rating, :func:`largest_comb_force`, over the sheets
    and K_m scales that rated, so that the force pasted designs). Where no count below
    ``columns`` carries any force, the fewest columns above it that count or carry one
    (:func:`other_column_counts`), found the same way; None when no count does. Asked
    when no sheet's comb of ``columns`` has a plan or a rating (the pitch, the arms or the
    webs bind before any force is judged)."""

    carrying: tuple[int, float, list, dict] | None = None
    scales = stop_fitting_scales(targets)  # the others neither count nor rate: not judged
    fewer_counts, more_counts = other_column_counts(columns)
    with candidates_weighed():
        for count in fewer_counts + more_counts:
            if carrying is not None and count > columns:
                break  # fewer columns carry a force: the nearer change is offered
            rated, judged = [], []
            for sheet in sheets_of(base):
                for scale in scales:
                    c = candidate(base, sheet, scale, count, room, targets, grade,
                                  envelope_of, None)
                    if c.plan is not None and not c.failures:
                        return count, None
                    judged.append(c)
                    rated += [(c.rated_force_N, sheet, scale)] if c.rated_force_N else []
            if rated and carrying is None:
                best = sorted(rated, reverse=True)
                carrying = (count, best[0][0], [(sheet, scale) for _, sheet, scale in best],
                            bounds_of(judged))
    if carrying is None:
        return None
    count, estimate, order, bounds = carrying
    return count, largest_comb_force(estimate, lambda force: comb_counts(
        base, force, count, room, targets, grade, envelope_of, order, bounds))


def asked_grade(base: Mapping[str, Any], grade: str | None) -> str:
    """The grade a comb is searched in: ``grade``, else the base tables' own.

    Args:
        base: the tables searched. grade: the grade asked, or None.

    Returns:
        The grade's name (the base's material name where it states no grade).
    """
    material = base.get("material", {})
    return str(grade or material.get("grade") or material.get("name"))


def grade_carried(base: dict, columns: int, room: Any, targets: Targets, grade: str,
                  envelope_of: Callable | None) -> tuple[float, float | None] | None:
    """What one grade's comb of ``columns`` carries in ``room``, as its margin on the asked
    full-scale force (the limit a grade with nothing to paste is refused at): its
    candidates judged at the asked force on every sheet at the K_m scales whose stops can
    fit (:func:`stop_fitting_scales`), then, where none is rated, at a lighter force
    (:func:`rated_at_a_lighter_force`).

    Args:
        base, columns, room, targets, envelope_of: as :func:`nearest_grade`.
        grade: the library grade judged.

    Returns:
        (margin_rel, None) where a comb counts at the asked force (its largest
        ``force_margin_rel``, >= 0); (margin_rel, force N) where it carries only a lighter
        force (:func:`largest_comb_force`, so that the force pasted designs; margin_rel
        that force over the asked one, minus 1, < 0); None when it carries no force.
    """
    asked_N = targets.full_scale_force_N
    judged = [candidate(base, sheet, scale, columns, room, targets, grade, envelope_of, None)
              for sheet in sheets_of(base) for scale in stop_fitting_scales(targets)]
    counting = [c.force_margin_rel for c in judged if c.plan is not None and not c.failures]
    if counting:
        return max(0.0, max(counting)), None
    if not any(c.rated_force_N for c in judged):
        judged = rated_at_a_lighter_force(base, columns, room, targets, grade, envelope_of)
    rated = sorted(((c.rated_force_N, c.sheet_mm, c.km_scale) for c in judged
                    if c.rated_force_N), reverse=True)
    if not rated:
        return None
    order, bounds = [(sheet, scale) for _, sheet, scale in rated], bounds_of(judged)
    force = largest_comb_force(rated[0][0], lambda f: comb_counts(
        base, f, columns, room, targets, grade, envelope_of, order, bounds))
    return force / asked_N - 1.0, force


class GradeOffer(NamedTuple):
    """Another grade a comb refusal offers (:func:`nearest_grade`).

    Attributes:
        grade: the library grade (None: no other grade carries any force).
        force_N: None where its comb counts at the asked force; else the largest
            full-scale force it carries (N).
        why: why this grade of those that carry ("" when none was compared).
    """

    grade: str | None
    force_N: float | None = None
    why: str = ""


def best_grade(carried: Mapping[str, tuple[float, float | None]]) -> GradeOffer:
    """Of the grades that carry, the one with the largest margin on the asked full-scale
    force (the library's order on a tie), and why it was chosen.

    Args:
        carried: grade -> (margin_rel, force N or None), :func:`grade_carried`'s, in the
            library's order.

    Returns:
        The offer; ``GradeOffer(None)`` when ``carried`` is empty.
    """
    if not carried:
        return GradeOffer(None)
    ranked = sorted(carried.items(), key=lambda item: -item[1][0])  # stable: library order
    grade, (margin, force) = ranked[0]
    others = ", ".join(f"{g} {m:+.1%}" for g, (m, _) in ranked[1:])
    why = (f"{grade} has the largest margin on the full-scale force of the grades that carry "
           f"({margin:+.1%}" + (f"; {others}" if others else "") + ")")
    return GradeOffer(grade, force, why)


def nearest_grade(base: dict, columns: int, room: Any, targets: Targets, grade: str | None,
                  envelope_of: Callable | None) -> GradeOffer:
    """The other grade of the library whose comb of ``columns`` carries the most of the
    asked full-scale force in ``room`` (its margin on it, :func:`grade_carried`), for a
    refusal with nothing else to paste (no comb of ``grade`` carries any force at any
    column count): every other grade is judged and the largest margin offered
    (:func:`best_grade`), not the first in the library's order.

    Args:
        base: the tables as searched (their ``[material]`` is the grade asked when
            ``grade`` is None). columns: the columns asked. room: the jaw's room (mm).
        targets: K_r/K_m, the K_obj range (N/mm) and the full-scale force (N).
        grade: the grade asked, or None for the base's. envelope_of: as
            :func:`comb_for_jaw`.

    Returns:
        :class:`GradeOffer`: (grade, None, why) where that grade's comb counts at the asked
        force; (grade, force N, why) where it carries only a lighter one; (None, None, "")
        when no other grade carries any force.
    """
    from tactcad.vocabulary.material_library import material_grades

    asked = asked_grade(base, grade)
    carried = {}
    with candidates_weighed():
        for other in material_grades():
            if other != asked:
                found = grade_carried(base, columns, room, targets, other, envelope_of)
                if found is not None:
                    carried[other] = found
    return best_grade(carried)


def refusal(tried: list[CombCandidate], targets: Targets, room: Any,
            columns: int, jaw: tuple[str, list[dict]] = ("", []),
            fewer_columns: tuple[int, float | None] | None = None,
            frontier_N: float | None = None,
            other_grade: "GradeOffer | tuple[str | None, float | None] | None" = None,
            grade_asked: str = "") -> InverseDesignError:
    """Why no sheet counts, the largest force any carries (a pasteable option:
    ``frontier_N``, :func:`largest_comb_force`, else the candidates' best rating less 1 %)
    or, when the pocket binds every sheet, the nearest jaw (``jaw``, :func:`nearest_jaw`'s
    line and alternatives: no force helps then); when the grid binds before any force, the
    nearest column count that counts or carries a force (``fewer_columns``, fewer first,
    then more: :func:`nearest_columns`); when no column count carries one either, another
    grade whose comb of ``columns`` counts or carries a force (``other_grade``,
    :func:`nearest_grade`'s :class:`GradeOffer`: (grade, None) where it counts, (grade,
    force N) where it carries that force, with why that grade (said in the text and the
    alternative's words), (None, None) where no other grade carries any; None: not
    searched), offered
    as ``--material`` while the option named stays ``--full-scale-force`` (the design
    atlas's :func:`refusal_option` names the same).

    Args:
        tried: the candidates, none counting. targets: the targets (N/mm, N). room: the
            jaw's room (mm). columns: the columns asked. jaw, fewer_columns, frontier_N,
            other_grade: as above. grade_asked: the grade searched (named beside
            ``other_grade``).

    Returns:
        The :class:`InverseDesignError`, with its pasteable ``alternatives``.
    """
    jaw_line, jaw_alternatives = jaw
    lines = []
    for sheet in sorted({c.sheet_mm for c in tried}):  # each sheet's nearest: most margin
        c = nearest_failure([c for c in tried if c.sheet_mm == sheet])
        if c is not None:
            lines.append(f"{sheet:g} mm sheet (nearest at K_m {c.km_scale:g} x eq. 2's centre): "
                         f"{c.failures[0]}")
    rated = [c.rated_force_N for c in tried if c.rated_force_N]
    text = (f"no monolithic comb of 2 x {columns} fits the {room.label} "
            f"({room.across_mm:g} x {room.along_mm:g} mm pocket, {room.height_mm:g} mm high) for "
            f"K_r/K_m {targets.kr_over_km:g}, K_obj {targets.k_obj_range_N_per_mm[0]:g} ... "
            f"{targets.k_obj_range_N_per_mm[1]:g} N/mm at {targets.full_scale_force_N:g} N:\n  "
            + "\n  ".join(lines))
    if jaw_line:  # the pocket holds no sheet's comb: no force or column count helps
        first = (jaw_alternatives or [{"option": "--jaw"}])[0]["option"]
        return InverseDesignError(text + f"\n  {jaw_line}", "--jaw", room.option,
                                  "a jaw whose pocket holds the comb: " + first,
                                  alternatives=jaw_alternatives)
    largest = frontier_N if frontier_N else (max(rated) * 0.99 if rated else None)
    nearest = f"--full-scale-force {largest:.3g}" if largest else ""
    option, value = "--full-scale-force", targets.full_scale_force_N
    words = "the largest full-scale force a comb of this jaw carries"
    if not nearest and fewer_columns is not None:
        fewer, force = fewer_columns
        nearest, option, value = f"--columns {fewer}", "--columns", columns
        which = "most" if fewer < columns else "fewest"
        words = f"the {which} columns whose comb counts in this jaw"
        if force is not None:
            nearest += f" --full-scale-force {force:.3g}"
            words = (f"the {which} columns whose comb carries a force in this jaw, and the "
                     "largest force it carries")
    if not nearest and other_grade is not None and other_grade[0] is not None:
        other, force, why = GradeOffer(*other_grade)
        text += (f"\n  no comb of {grade_asked or 'this grade'} at any column count on these "
                 "sheets carries any force in this jaw (each sheet's binding limit above)")
        nearest = f"--material {other}"
        words = f"another grade of the library whose comb of 2 x {columns} counts in this jaw"
        if force is not None:
            nearest += f" --full-scale-force {force:.3g}"
            words = (f"another grade of the library whose comb of 2 x {columns} carries a "
                     "force in this jaw, and the largest force it carries")
        if why:
            text += f"\n  {why}"
            words += f": {why}"
    if not nearest:  # say why there is nothing to paste
        text += ("\n  none to paste: no comb of any column count on these sheets "
                 "carries any force in this jaw"
                 + (", nor in any other grade of the library" if other_grade is not None
                    else "") + " (each sheet's binding limit above)")
    return InverseDesignError(text + (f"\n  nearest: {nearest}" if nearest else ""),
                              option, value, nearest or "a design the jaw holds",
                              alternatives=[{"option": nearest, "words": words}] if nearest
                              else [])


def sheet_rule_words(margin_rel: float) -> str:
    """How the sheet was chosen, as :func:`chosen`'s rule took it: the softest pair with
    :data:`FORCE_MARGIN_REL` to spare, or, none having it, the one with the most."""
    if margin_rel >= FORCE_MARGIN_REL:
        return (f"the sheet of the softest pair that carries the full-scale force with "
                f"{FORCE_MARGIN_REL:.0%} to spare ({margin_rel:+.1%})")
    return (f"the sheet of the pair with the most force to spare ({margin_rel:+.1%}): none "
            f"that counts has {FORCE_MARGIN_REL:.0%}")


def stop_reason(plan: Any, force_N: float) -> str:
    """Why the stop gaps are what they are, with where each kind of stop engages: the rule
    (:func:`tactcad.mechanics.hard_stops.engagement_force_N`), the least gap a shim sets, and
    any stop that still engages past a fatigue limit (which binds)."""
    from tactcad.design.comb_plan import MIN_SET_GAP_MM
    from tactcad.mechanics.hard_stops import stop_verdicts

    verdicts = stop_verdicts(plan, force_N)
    # in element order, as the arms and webs are listed, not sorted apart from them
    multiples = list(dict.fromkeys(round(v.multiple_of_rated, 2) for v in verdicts))
    over = [v for v in verdicts if not v.below_fatigue]
    words = (f"Each stop engages at {STOP_MULTIPLE:g} x its element's rated deflection, or "
             f"midway to the element's lowest fatigue limit where that comes first, rounded up "
             f"to 1 µm and no thinner than the {MIN_SET_GAP_MM:g} mm a shim sets: "
             f"{', '.join(f'{m:g}' for m in multiples)} x the rating as built (in element "
             f"order).")
    if over:
        words += (" Past a fatigue limit (the least gap binds): " + "; ".join(
            f"element {v.element} at {v.engage_force_N:.4g} N ({v.fatigue_limit} "
            f"{v.fatigue_tip_mm * v.stiffness_N_per_mm:.4g} N)" for v in over) + ".")
    return words


def built_stiffness_words(plan) -> str:
    """What the webs as written give at the closed form, the figure every command reports
    (rounding the webs to :data:`WEB_STEP_MM` moves K_m by about 2 % a step from the
    solved one): ``as written K_m = 3.754 N/mm, K_r/K_m = 8.025`` (a range where the units
    differ).

    Args:
        plan: the written design's plan.

    Returns:
        The words (no final full stop).
    """
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element

    k = ladder_stiffness_by_element(plan)
    k_m = sorted({round(k[m], 12) for _, m in plan.unit_pairs})
    ratio = sorted({round(k[r] / k[m], 12) for r, m in plan.unit_pairs})

    def span(values: list[float]) -> str:
        return f"{values[0]:.4g}" if len(values) == 1 else f"{values[0]:.4g}-{values[-1]:.4g}"

    return f"as written K_m = {span(k_m)} N/mm, K_r/K_m = {span(ratio)} (closed form)"


def resolution_written(d: dict, plan: Any, targets: Targets) -> dict[str, str]:
    """Write into ``d``'s ``[requirements]`` the K_obj resolution the comb reaches, as a
    stacked array's design writes it
    (:func:`tactcad.studies.inverse_design.written_kobj_resolution`: the rule is the
    construction's neither), where it is one a design file may state (at most
    :data:`~tactcad.studies.verification.UNREADABLE_RESOLUTION_REL`; a comb that reads
    worse is left to verify's derivation, which fails it).

    Args:
        d: the chosen tables (changed in place). plan: their plan. targets: the targets.

    Returns:
        ``{"requirements.kobj_resolution_rel": reason}``, or ``{}`` where nothing is written.
    """
    from tactcad.studies.inverse_design import written_kobj_resolution
    from tactcad.studies.verification import UNREADABLE_RESOLUTION_REL

    value, why = written_kobj_resolution(plan, targets)
    if not value <= UNREADABLE_RESOLUTION_REL:  # inf or NaN: none a file may state
        return {}
    d["requirements"]["kobj_resolution_rel"] = value
    return {"requirements.kobj_resolution_rel": why}


def named(d: dict, name: str, targets: Targets, room: Any, best: CombCandidate,
          columns: int, fasteners: tuple[FastenerTry, ...] = ()) -> dict:
    """The chosen tables with their name, description and every reason."""
    d = copy_tables(d)
    template = d.get("design", {}).get("name", "the template")
    lo, hi = targets.k_obj_range_N_per_mm
    d["design"] = {"name": name, "description": (
        f"2 x {columns} monolithic comb for a grasper's {room.label}: "
        f"K_r/K_m = {targets.kr_over_km:g} for K_obj {lo:g}-{hi:g} N/mm, full-scale force "
        f"{targets.full_scale_force_N:g} N")}
    comb, arms = d["comb"], d["arms"]["lengths_mm"]
    # the template's own reasons name its sizes (its jaw, its spine): not this design's
    why = {k: f"Not searched: the comb template's value ({template}); check it for this jaw."
           for k in d.get("assumptions", {}) if k != "element.web_thickness_mm"  # solved
           and (k.split(".")[0] in ("strength", "element", "edm") or k in (
               "comb.post_length_mm", "comb.spacer_thickness_mm")
           or (not fasteners and k in ("comb.screw_size", "comb.dowel_diameter_mm")))}
    if fasteners:
        why.update(fastener_reasons(fasteners))
    if "readout.grid_width_mm" in d.get("assumptions", {}):  # the grid fitted to the sheet
        why["readout.grid_width_mm"] = d["assumptions"]["readout.grid_width_mm"]
    searched = sheets_of(d)
    others = [c for c in searched if c != best.sheet_mm]
    why.update({
        "sheet.thickness_mm": (f"tactcad design --jaw {shlex.quote(PurePath(room.option).name)}"
                               ": of "
                               f"{', '.join(f'{s:g}' for s in searched)} mm ({process_name(d)}), "
                               + sheet_rule_words(best.force_margin_rel)
                               + f"; tried also {', '.join(f'{s:g}' for s in others)} mm."),
        "array.pairing": "Column pairing: each reference (row 1) beside its measuring element "
                         "(row 2), both tips at one radius from the jaw's pin.",
        "array.pitch_mm": (f"{columns} columns in the {room.along_mm:g} mm the jaw's pocket "
                           f"leaves (to 0.1 mm)."),
        "arms.lengths_mm": (f"References {arms[0]:g} mm (the fitted range's shortest), measuring "
                            f"elements {arms[-1]:g} mm: the longest the pitch leaves with a "
                            f"{slot_of(d):g} mm slot."),
        "arms.reference_elements": "Row 1: every column's reference.",
        "comb.web_thicknesses_mm": (
            f"Solved at the closed form for K_r = {targets.kr_over_km:g} K_m and K_m = "
            f"{best.km_scale:g} x sqrt(K_lo K_hi / X) = {best.km_scale * centred_km(targets):.4g} "
            f"N/mm (eq. 2's centre scaled by the least of {', '.join(f'{k:g}' for k in KM_SCALES)} "
            f"that carries the force with {FORCE_MARGIN_REL:.0%} to spare while verify reads the "
            f"K_obj range), to {WEB_STEP_MM * 1000:g} µm; "
            f"{built_stiffness_words(best.plan)}."),
        "comb.stop_gaps_mm": stop_reason(best.plan, targets.full_scale_force_N),
        "requirements.full_scale_force_N": "Asked (--full-scale-force).",
        "requirements.kobj_range_N_per_mm": "Asked (--kobj-range).",
        "requirements.kr_over_km": "Asked (--kr-over-km).",
        "requirements.footprint_mm": (f"The pocket of the {room.label} less its "
                                      "clearances (across, along)."),
        **({"requirements.max_grasp_force_N": "Asked (--max-grasp-force)."}
           if "max_grasp_force_N" in d["requirements"] else {}),
    })
    why.update(resolution_written(d, best.plan, targets))
    grade = d.get("material", {}).get("grade")
    if grade and "material.grade" not in why:  # the library's grade, with its sources
        from tactcad.vocabulary.material_library import material_grade

        why["material.grade"] = f"The comb's material: {material_grade(grade).cited()}."
    d["assumptions"] = why
    return d


def fastener_reasons(fasteners: tuple[FastenerTry, ...]) -> dict[str, str]:
    """The reasons of the searched screw and dowel: the pair chosen and why each larger
    one tried first does not count."""
    got = fasteners[-1]
    refused = "; ".join(f"{f.label}: {f.failures[0]}" for f in fasteners[:-1])
    head = ("Searched (the largest screw, then dowel, of the miniature tables that the row and "
            "the jaw's height hold: a harder clamp, a common key)")
    tail = f"; tried first {refused}." if refused else ": the largest of the tables."
    return {"comb.screw_size": f"{head}: {got.screw_size}{tail}",
            "comb.dowel_diameter_mm": (f"Searched with the screw (comb.screw_size's reason): "
                                       f"{got.dowel_diameter_mm:g} mm.")}

