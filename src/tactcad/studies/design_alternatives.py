"""What to ask instead when the inverse design refuses its targets.

A refusal of :func:`tactcad.studies.inverse_design.design_for_targets` names
the limits that bind. This module adds what a designer needs next:

* the nearest feasible targets, one target moved at a time with the others
  kept: the largest full-scale force at the asked ratio and range, the
  K_r / K_m nearest the asked one (log scale) at the asked force and range,
  and the K_obj range moved (its width kept) nearest the asked one;
* the changes that relax the limits, each tried with all targets as asked:
  every other material grade of the library, the common sheet thicknesses
  (:data:`SHEET_THICKNESSES_MM`) and every other strain gauge of the library,
  with the largest full-scale force each allows at the asked ratio and range
  and whether it meets every target.

Each candidate is a whole inverse design on the changed tables (0.1 s each on
the closed form), so what it reports is what ``tactcad design`` with that
change would do on that layout; given a judge of the pasted command (:data:`Designs`,
the layout search's), each offer is also one the pasted command designs with.
Units: mm, N, N/mm.
"""

from __future__ import annotations

import copy
import math
import warnings
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, replace
from typing import Any, Callable, Mapping

import numpy as np

from tactcad.vocabulary.rounding import round_down, round_up
from tactcad.errors import DesignError
from tactcad.studies.inverse_design import (InverseDesign, InverseDesignError, Targets,
                                            design_from_tables, design_tables,
                                            max_full_scale_force_N, search_webs,
                                            web_searches_kept)

#: Sheet thicknesses tried as an alternative (mm): plate and sheet gauges
#: commonly stocked for wire EDM of flexures (0.5 mm steps to 3 mm, then 1 mm).
SHEET_THICKNESSES_MM = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0)
#: Points of the scans over K_r / K_m and over the K_obj range's position.
SCAN_POINTS = 41
#: Bisection steps refining a scan's nearest feasible point, and the largest force.
REFINE_STEPS = 7
FORCE_STEPS = 7


@dataclass(frozen=True)
class Alternative:
    """One way out of a refusal.

    Attributes:
        kind: ``"target"`` (one target moved) or ``"change"`` (a design value changed).
        field: the option or design field it moves (``--full-scale-force``,
            ``material.grade``, ``sheet.thickness_mm``, ``strength.gauge``, ...).
        value: its value (N, a ratio, [LO, HI] N/mm, a grade or gauge name, mm).
        meets_targets: the inverse design succeeds with it.
        largest_force_N: the largest full-scale force at the asked ratio and
            range with the change (0: the stiffness targets cannot be met); for a change
            that meets every target, at least the asked force (not searched beyond it).
    """

    kind: str
    field: str
    value: Any
    meets_targets: bool
    largest_force_N: float

    def words(self) -> str:
        value = (f"{self.value[0]:.3g}-{self.value[1]:.3g} N/mm" if isinstance(self.value, tuple)
                 else f"{self.value:.4g}" if isinstance(self.value, float) else str(self.value))
        if self.kind == "target":
            return f"{self.field} {value}"
        if self.meets_targets:  # its force estimate is of the base layout, not the search's
            return f"{self.field} = {value}: meets every target"
        force = (f"largest full-scale force {self.largest_force_N:.3g} N"
                 if self.largest_force_N > 0 else "the stiffness targets still out of reach")
        return f"{self.field} = {value}: {force}"

    def as_json(self) -> dict:
        return {"kind": self.kind, "field": self.field,
                "value": list(self.value) if isinstance(self.value, tuple) else self.value,
                "meets_targets": self.meets_targets, "largest_force_N": self.largest_force_N}


def design_or_alternatives(base, targets: Targets, *, correction=None, name: str = "inverse_design",
                           **layout) -> InverseDesign:
    """:func:`tactcad.studies.inverse_design.design_for_targets`, whose refusal
    also lists the nearest feasible targets and the relaxing changes
    (:func:`refusal_with_alternatives`).

    Args:
        layout: ``grade``, ``pitch_mm``, ``rows``, ``columns`` as there.

    Raises:
        InverseDesignError: the targets cannot be met, with ``.alternatives``.
        DesignError: a bad grade, pitch or grid, naming the field.
    """
    data = design_tables(base, **layout)
    try:
        return design_from_tables(copy.deepcopy(data), targets, name=name, correction=correction)
    except InverseDesignError as exc:
        raise refusal_with_alternatives(exc, data, targets, correction) from None


def refusal_with_alternatives(exc: InverseDesignError, data: Mapping[str, Any],
                              targets: Targets, correction=None) -> InverseDesignError:
    """``exc`` (the binding limits) with the nearest feasible targets and the
    relaxing changes appended to its text and kept in ``.alternatives``."""
    with warnings.catch_warnings(), evaluations_kept():  # the candidates are explored, not
        warnings.simplefilter("ignore")  # the user's design: their range warnings would mislead
        nearest = nearest_targets(data, targets, correction)
        now = max((a.largest_force_N for a in nearest if a.field == "--full-scale-force"),
                  default=0.0)
        changes = relaxing_changes(data, targets, correction, better_than_N=now)
    text = str(exc)
    if nearest:
        text += ". Nearest feasible targets, one at a time: " + "; ".join(
            a.words() for a in nearest)
    else:
        text += ". No single target moved alone makes the design feasible"
    if changes:
        text += (". Changes that relax the limits (at the asked K_r/K_m and K_obj range): "
                 + "; ".join(a.words() for a in changes))
    else:
        text += ". No other grade, sheet or gauge of the library relaxes them"
    out = InverseDesignError(text)
    out.alternatives = [a.as_json() for a in (*nearest, *changes)]
    return out


#: The whole designs judged inside :func:`evaluations_kept`: (kind, tables, targets,
#: correction) -> answer; None outside it.
_KEPT: ContextVar[dict | None] = ContextVar("tactcad_alternative_evaluations", default=None)


@contextmanager
def evaluations_kept():
    """Within it, each whole design a refusal's alternatives judge (:func:`_feasible`,
    :func:`_largest_force`) on the same tables and targets is judged once: a scan's
    neighbour already tried, or the largest force sought again on the same layout, is
    read back; the web searches of one plan are worked out once for every force asked
    (:func:`~tactcad.studies.inverse_design.web_searches_kept`). Nested uses share the
    outer one's answers."""
    if _KEPT.get() is not None:
        yield
        return
    token = _KEPT.set({})
    try:
        with web_searches_kept():
            yield
    finally:
        _KEPT.reset(token)


def _frozen(value: Any) -> Any:
    """``value`` (nested tables) as a hashable key: tables by sorted key, lists and
    tuples told apart, leaves as they are (their repr when unhashable)."""
    if isinstance(value, Mapping):
        return ("table", tuple(sorted((str(k), _frozen(v)) for k, v in value.items())))
    if isinstance(value, (list, tuple)):
        return (type(value).__name__, tuple(_frozen(v) for v in value))
    try:
        hash(value)
    except TypeError:
        return ("repr", repr(value))
    return value


def _kept(kind: str, data: Mapping[str, Any], targets: Targets, correction,
          judge: Callable[[], Any]) -> Any:
    """``judge()``, or its answer already kept for the same tables, targets and correction
    inside :func:`evaluations_kept` (the correction by identity: it is one object there)."""
    kept = _KEPT.get()
    if kept is None:
        return judge()
    key = (kind, _frozen(data), repr(targets), id(correction))
    if key not in kept:
        kept[key] = judge()
    return kept[key]


def _feasible(data: Mapping[str, Any], targets: Targets, correction) -> bool:
    """Whether the whole inverse design meets ``targets`` on ``data``."""
    def judge() -> bool:
        try:
            design_from_tables(copy.deepcopy(dict(data)), targets, correction=correction)
        except (InverseDesignError, DesignError):
            return False
        return True

    return _kept("feasible", data, targets, correction, judge)


def _feasible_range(data: Mapping[str, Any], targets: Targets, rng: tuple[float, float],
                    correction) -> bool:
    """:func:`_feasible` with the K_obj range ``rng`` (N/mm); False for a range the targets
    refuse (a shifted range past the K_obj bounds a design takes)."""
    try:
        shifted = replace(targets, k_obj_range_N_per_mm=rng)
    except DesignError:
        return False
    return _feasible(data, shifted, correction)


def _largest_force(data: Mapping[str, Any], targets: Targets, correction) -> float:
    """The largest full-scale force some web carries at the targets' ratio and
    range on ``data`` (0 when the stiffness targets are out of reach or the
    tables break a rule)."""
    from tactcad.design.array_plan import plan_from_dict

    def judge() -> float:
        try:
            plan = plan_from_dict(copy.deepcopy(dict(data)), source="<alternative>")
            search = search_webs(plan, targets, correction)
        except DesignError:
            return 0.0
        return max_full_scale_force_N(search, targets.full_scale_force_N)

    return _kept("largest force", data, targets, correction, judge)


#: Factor by which the bracket above a feasible force grows until a force fails.
BRACKET_STEP = 1.25


def largest_feasible_force(data: Mapping[str, Any], targets: Targets, correction=None) -> float:
    """The largest full-scale force (N, 3 significant digits, rounded down) the
    inverse design meets at the targets' ratio and range on ``data``; 0 when
    none. The web search's estimate (:func:`_largest_force`) is refined by
    whole designs, which also raise the arm height with the arms: a bracket grown from
    the estimate by :data:`BRACKET_STEP` until a force fails (below the asked force, which
    is refused), then bisection in it, so the answer does not move with the force asked."""
    est = _largest_force(data, targets, correction)
    if est <= 0:
        return 0.0

    def ok(force: float) -> bool:
        return _feasible(data, replace(targets, full_scale_force_N=force), correction)

    lo = min(est, targets.full_scale_force_N)
    while not ok(lo):  # the estimate is near: step down from it
        lo *= 0.95
        if lo < est * 1e-3:
            return 0.0
    asked = targets.full_scale_force_N
    hi = min(asked, est * 1.05)  # a bracket as tight as the estimate
    while hi > lo and ok(hi):  # grow it by steps, never to the asked force at once: the
        lo, hi = hi, min(asked, hi * BRACKET_STEP)  # frontier is the same whatever was asked
    if lo >= hi:
        return _round_down(lo)
    for _ in range(FORCE_STEPS):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return _round_down(lo)


def _round_down(x: float) -> float:
    """``x`` to three significant digits, down (a force or ratio to paste)."""
    return round_down(x, 3)


def _round_up(x: float) -> float:
    """``x`` to three significant digits, up."""
    return round_up(x, 3)


def nearest_on_scan(values: np.ndarray, asked: float, ok: Callable[[float], bool],
                    steps: int = REFINE_STEPS) -> float | None:
    """The value nearest ``asked`` (log distance) where ``ok`` holds: the scan's
    points tried nearest first until one holds, then ``steps`` bisections between it and
    its neighbour towards ``asked`` (which does not hold)."""
    order = sorted(range(len(values)), key=lambda k: abs(math.log(values[k] / asked)))
    i = next((k for k in order if ok(float(values[k]))), None)
    if i is None:
        return None
    j = i + (1 if values[i] < asked else -1)
    if not 0 <= j < len(values) or abs(math.log(values[j] / asked)) > abs(
            math.log(values[i] / asked)) or ok(float(values[j])):
        return float(values[i])
    lo, hi = float(values[i]), float(values[j])  # lo holds, hi not
    for _ in range(steps):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return lo


#: Judge of an option pasted into ``tactcad design``: (the targets, a change of the start's
#: tables as (field, value) or None) -> whether the command designs with it (its layout
#: search and validation included, :func:`tactcad.studies.layout_search.paste_judge`).
Designs = Callable[..., bool]
#: Bisection steps refining the nearest value a pasted command designs with, where the
#: scan's own layout's value is refused when pasted (each step a whole layout search).
PASTE_REFINE_STEPS = 3


def pasted_nearest(values: np.ndarray, found: float, asked: float,
                   offered: Callable[[float], Any], designs: Callable[[Any], bool]
                   ) -> Any | None:
    """The offer nearest ``asked`` that the pasted command designs with: ``found`` (the
    nearest feasible value on one layout) where it does, else the scan ``values`` judged
    by the pasted command itself (:func:`nearest_on_scan`, on either side of ``asked``:
    the layout the command reaches may need the value moved the other way).

    Args:
        values: the scan's points. found: the value the scan found on one layout (a
            ratio, or a factor on the K_obj range). asked: the asked value (the ratio, or
            1 for the range). offered: value -> the offer to paste (rounded away from
            ``asked``). designs: offer -> whether the pasted command designs.

    Returns:
        The offer, never equal to the asked one's (which is refused), or None when no
        point of the scan designs.
    """
    def ok(x: float) -> bool:
        return offered(x) != offered(asked) and designs(offered(x))

    if ok(found):
        return offered(found)
    near = nearest_on_scan(values, asked, ok, steps=PASTE_REFINE_STEPS)
    return None if near is None else offered(near)


def nearest_targets(data: Mapping[str, Any], targets: Targets, correction=None,
                    designs: Designs | None = None) -> list[Alternative]:
    """Each target moved alone to the nearest value the design meets, the
    others as asked (see the module docstring); those with no feasible value
    are left out.

    Args:
        data: the tables the scans design on (mm, N, N/mm). targets: the asked targets.
        correction: the closed form's correction, or None.
        designs: the judge of a pasted option (:data:`Designs`), or None: the scans'
            own design on ``data``. Given, each ratio and range offered is one the pasted
            command designs with (moved further from the asked value where the scan's
            layout is not the one the command reaches), and the force is left to the
            caller's own search (not offered here).

    Returns:
        The :class:`Alternative` of each target that has one.
    """
    out = []
    if designs is None:
        force = largest_feasible_force(data, targets, correction)
        if force > 0:
            out.append(Alternative("target", "--full-scale-force", float(f"{force:.3g}"), True,
                                   force))
    ratios = np.geomspace(1.05, 1000.0, SCAN_POINTS)
    ratio = nearest_on_scan(ratios, targets.kr_over_km, lambda x: _feasible(
        data, replace(targets, kr_over_km=x), correction))
    if ratio is not None:
        # three digits, rounded away from the asked ratio (it does not hold): the rounded
        # value stays on the feasible side of the edge the scan found
        asked = targets.kr_over_km

        def ratio_offer(x: float) -> float:
            return _round_down(x) if x < asked else _round_up(x)

        if designs is None:
            ratio = ratio_offer(ratio) if _feasible(
                data, replace(targets, kr_over_km=ratio_offer(ratio)), correction) else None
        else:
            ratio = pasted_nearest(ratios, ratio, asked, ratio_offer, lambda x: designs(
                replace(targets, kr_over_km=x)))
        if ratio is not None:
            out.append(Alternative("target", "--kr-over-km", ratio, True, 0.0))
    lo, hi = targets.k_obj_range_N_per_mm
    shifts = np.geomspace(1e-2, 1e2, SCAN_POINTS)
    shift = nearest_on_scan(shifts, 1.0, lambda c: _feasible_range(
        data, targets, (lo * c, hi * c), correction))
    if shift is not None:
        rng = _range_offer(data, targets, lo, hi, shift, correction) if designs is None else \
            pasted_nearest(shifts, shift, 1.0, lambda c: _away_range(lo, hi, c), lambda r: (
                _range_allowed(targets, r) and designs(replace(targets, k_obj_range_N_per_mm=r))))
        if rng is not None:
            out.append(Alternative("target", "--kobj-range", rng, True, 0.0))
    return out


def _away_range(lo: float, hi: float, shift: float) -> tuple[float, float]:
    """The K_obj range (N/mm) ``lo``-``hi`` moved by ``shift``, each end to three digits
    rounded away from the asked range (up when moved up, down when moved down)."""
    away = _round_up if shift > 1.0 else _round_down
    return (float(f"{away(lo * shift):.12g}"), float(f"{away(hi * shift):.12g}"))


def _range_allowed(targets: Targets, rng: tuple[float, float]) -> bool:
    """Whether the targets take the K_obj range ``rng`` (N/mm) at all."""
    try:
        replace(targets, k_obj_range_N_per_mm=rng)
    except DesignError:
        return False
    return True


def _range_offer(data, targets: Targets, lo: float, hi: float, shift: float, correction
                 ) -> tuple[float, float] | None:
    """The range offered on one layout's designs: three digits, the nearest first, then
    rounded away from the asked range (it does not hold), so that the rounded range stays
    on the feasible side of the edge; never the asked range itself; None when neither
    designs."""
    for rng in ((float(f"{lo * shift:.3g}"), float(f"{hi * shift:.3g}")),
                _away_range(lo, hi, shift)):
        if rng != (lo, hi) and _feasible_range(data, targets, rng, correction):
            return rng
    return None


def _with(data: Mapping[str, Any], section: str, values: Mapping[str, Any]) -> dict[str, Any]:
    out = copy.deepcopy(dict(data))
    out[section] = {**out.get(section, {}), **values}
    return out


#: Steps down (each x0.97 on the 3-digit grid) from a change's largest force on one layout
#: until the pasted command designs with the change at that force.
PASTE_FORCE_STEPS = 3


def relaxing_changes(data: Mapping[str, Any], targets: Targets, correction=None,
                     better_than_N: float = 0.0, designs: Designs | None = None
                     ) -> list[Alternative]:
    """Every other library grade, common sheet thickness and library gauge,
    tried with all targets as asked; the one that relaxes most of each kind
    (grade, sheet, gauge): those meeting every target first, then by the
    largest full-scale force they allow; a change that allows no more than
    ``better_than_N`` (the design as it is) and meets no target is left out.

    Args:
        data: the tables the changes are tried on. targets: the asked targets.
        correction: the closed form's correction, or None.
        better_than_N: the force (N) a change must beat when it meets no target.
        designs: the judge of a pasted option (:data:`Designs`), or None: the design on
            ``data``. Given, a change is said to meet every target only where the pasted
            command designs with it, and a change that does not carries the force (N, 3
            digits, rounded down) at which the pasted command designs with it, or is left
            out; the sheet is not tried (the pasted command's layout search varies it).

    Returns:
        The changes, those meeting every target first.
    """
    from tactcad.vocabulary.material_library import material_grades, strain_gauges

    grade = dict(data.get("material", {})).get("grade")
    sheet = float(data.get("sheet", {}).get("thickness_mm", math.nan))
    gauge = data.get("strength", {}).get("gauge")
    # a grade brings its own values: the base material's table is replaced, not merged
    candidates = [("material.grade", g, {**copy.deepcopy(dict(data)),
                                         "material": {"name": g, "grade": g}})
                  for g in material_grades() if g != grade]
    candidates += [("sheet.thickness_mm", t, _with(data, "sheet", {"thickness_mm": t}))
                   for t in SHEET_THICKNESSES_MM if not math.isclose(t, sheet)
                   and designs is None]  # a pasted command searches the sheet itself
    candidates += [("strength.gauge", g, _with(data, "strength", {"gauge": g}))
                   for g in strain_gauges() if g != gauge]
    best: dict[str, tuple[Alternative, dict]] = {}
    for field, value, tables in candidates:
        force = _largest_force(tables, targets, correction)  # the web search's estimate
        if force <= 0:
            continue
        alt = Alternative("change", field, value, _feasible(tables, targets, correction), force)
        if field not in best or _rank(alt) < _rank(best[field][0]):
            best[field] = (alt, tables)
    out = []
    for alt, tables in best.values():  # the force each best change allows, by whole designs
        if alt.meets_targets and designs is not None and not designs(
                targets, (alt.field, alt.value)):  # one layout meets them, the search does not
            alt = replace(alt, meets_targets=False)
        if not alt.meets_targets:
            force = largest_feasible_force(tables, targets, correction)
            if designs is not None:
                force = _pasted_force(force, targets, (alt.field, alt.value), designs)
            alt = replace(alt, largest_force_N=force)
        else:  # the whole design carries the asked force, whatever the base layout's estimate
            alt = replace(alt, largest_force_N=max(alt.largest_force_N,
                                                   targets.full_scale_force_N))
        if alt.meets_targets or alt.largest_force_N > better_than_N:
            out.append(alt)
    return sorted(out, key=_rank)


def _pasted_force(force_N: float, targets: Targets, change: tuple[str, Any],
                  designs: Designs) -> float:
    """The largest of ``force_N`` (below the asked force, which the search refused) and
    :data:`PASTE_FORCE_STEPS` steps of x0.97 below it (N, 3 digits, rounded down) at which
    the pasted command designs with ``change``; 0 when none does (or ``force_N`` is 0)."""
    force = _round_down(min(force_N, targets.full_scale_force_N * 0.999))
    for _ in range(PASTE_FORCE_STEPS + 1):
        if force <= 0:
            return 0.0
        if designs(replace(targets, full_scale_force_N=force), change):
            return force
        force = _round_down(force * 0.97)
    return 0.0


def _rank(a: Alternative) -> tuple[bool, float]:
    return (not a.meets_targets, -a.largest_force_N)
