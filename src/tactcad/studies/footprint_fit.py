"""Inverse design within a footprint: shorter elements, thinner webs, another sheet.

``tactcad design --footprint X Y`` asks for a clamped array whose envelope
(plan view X by Y, the assembly STEP's box) fits. The envelope follows three
things the inverse design can change:

* X, the two facing rows' overall element length: the longest arm plus the
  notch, half the tip, the arm clearance and the clamped base's bolt pattern
  (:func:`tactcad.studies.inverse_design.required_overall_length_mm`). A
  shorter element caps the arms; the web search then takes a thinner web,
  whose shorter arms reach the same K_m and K_r (and carry less force);
* Y, the stack across the columns: the pitch (sheet + spacer) times the
  columns, the clamp plates and the bolts through them. A thinner sheet
  (:data:`tactcad.studies.design_alternatives.SHEET_THICKNESSES_MM`) with the
  base design's spacer gives a smaller pitch;
* Z, the element's height, kept.

The design as asked is tried first (and kept when it fits; its own refusals
are reported as without a footprint). The search then takes the base sheet,
then each thinner one; for each, the
longest element whose envelope fits (0.5 mm steps), then the inverse design
with the arms capped to it. The first design that meets the targets and fits
is taken (the thickest sheet and longest element that fit: the most room for
the arms). When none fits, the refusal names the footprint and the nearest
feasible one: over the sheets, the smallest envelope of a design that meets
the targets (found by bisection on the element length), the one that needs
the footprint enlarged least.

The envelope is measured by the caller's ``envelope_of(plan)`` (the assembly's
:func:`tactcad.assembly.inventory.array_envelope_mm`): studies read plans and
never the parts' catalogue. Units: mm, N, N/mm.
"""

from __future__ import annotations

import copy
import math
import warnings
from dataclasses import dataclass, replace
from typing import Any, Callable, Mapping, Sequence

from tactcad.design.array_plan import (ARM_RANGE_MM, MIN_SPACER_MM, MIN_TIP_GAP_MM, Plan,
                                       plan_from_dict)
from tactcad.errors import DesignError
from tactcad.studies.design_alternatives import SHEET_THICKNESSES_MM, refusal_with_alternatives
from tactcad.studies.inverse_design import (LENGTH_STEP_MM, InverseDesign, InverseDesignError,
                                            Targets, design_from_tables, design_tables,
                                            required_overall_length_mm, tip_root_min_arm_mm)

#: (X, Y, Z) of a plan's clamped array, mm.
Envelope = Callable[[Plan], Sequence[float]]
#: Bisection steps on the element length for the nearest feasible footprint.
LENGTH_STEPS = 8
#: How far (mm) an element's envelope at its longest arm may exceed the
#: footprint and still be tried, and how many lengths are tried per sheet.
ENVELOPE_SLACK_MM = 1.0
FIT_TRIES = 4


@dataclass(frozen=True)
class Layout:
    """One candidate: a sheet, its pitch and the element length (mm)."""

    sheet_mm: float
    pitch_mm: float
    overall_length_mm: float

    def words(self) -> str:
        return (f"sheet {self.sheet_mm:g} mm, pitch {self.pitch_mm:g} mm, elements "
                f"{self.overall_length_mm:g} mm long")


def fits(envelope_mm: Sequence[float], footprint_mm: Sequence[float]) -> bool:
    """True when every axis the footprint states holds the envelope with room for its
    ISO 2768-f deviation (mm): the rule ``verify`` judges the footprint by
    (:func:`tactcad.studies.verification.footprint_met`), so a design that fits passes."""
    from tactcad.studies.verification import footprint_met

    return footprint_met(envelope_mm, footprint_mm)


def _sheet_tables(data: Mapping[str, Any], sheet_mm: float) -> dict[str, Any] | None:
    """``data`` on another sheet, the base design's spacer kept (the pitch at
    least the tip width plus the tip gap), or None when that breaks the tip rule."""
    out = copy.deepcopy(dict(data))
    spacer = max(float(out["array"]["pitch_mm"]) - float(out["sheet"]["thickness_mm"]),
                 MIN_SPACER_MM)
    pitch = round(max(sheet_mm + spacer, float(out["element"]["tip_width_mm"]) + MIN_TIP_GAP_MM), 6)
    out["sheet"] = {**out["sheet"], "thickness_mm": float(sheet_mm)}
    out["array"] = {**out["array"], "pitch_mm": pitch}
    return out


def _shortest_arm_mm(data: Mapping[str, Any]) -> float:
    el = data["element"]
    return max(ARM_RANGE_MM[0], float(tip_root_min_arm_mm(
        el["tip_width_mm"], el["inside_corner_radius_mm"], el["notch_radius_mm"])))


def _with_length(data: Mapping[str, Any], length_mm: float, arm_mm: float) -> dict[str, Any]:
    out = copy.deepcopy(dict(data))
    out["element"] = {**out["element"], "overall_length_mm": float(length_mm)}
    out["arms"] = {**out["arms"], "lengths_mm": [float(arm_mm)] * len(out["arms"]["lengths_mm"])}
    return out


def _envelope(data: Mapping[str, Any], envelope_of: Envelope) -> tuple[float, ...] | None:
    try:
        return tuple(float(e) for e in envelope_of(plan_from_dict(copy.deepcopy(dict(data)),
                                                                   source="<footprint>")))
    except DesignError:
        return None


def _length_grid(data: Mapping[str, Any]) -> list[float]:
    """Element lengths (mm, 0.5 mm steps) from the shortest that holds the
    shortest arm's bolt pattern up to the longest the arm range needs."""
    R = float(data["element"]["notch_radius_mm"])
    lo = required_overall_length_mm(data, _shortest_arm_mm(data), R)
    hi = required_overall_length_mm(data, ARM_RANGE_MM[1], R)
    first = math.ceil(lo / LENGTH_STEP_MM - 1e-9)
    last = math.ceil(hi / LENGTH_STEP_MM - 1e-9)
    return [k * LENGTH_STEP_MM for k in range(first, last + 1)]


def _arm_cap(data: Mapping[str, Any], length_mm: float) -> float:
    """The longest arm (mm) an element of ``length_mm`` holds with its bolt pattern."""
    R = float(data["element"]["notch_radius_mm"])
    return min(length_mm - required_overall_length_mm(data, 0.0, R), ARM_RANGE_MM[1])


def _fitting_design(data, footprint_mm, envelope_of, targets, correction, name, grid
                    ) -> float | None:
    """The longest element length of ``grid`` whose design's envelope fits, or
    None. An element's envelope with its arm at the longest the length holds
    (cheap, no design) is within :data:`ENVELOPE_SLACK_MM` of a design's, whose
    arms may be shorter: the lengths that come that close are tried, longest first."""
    near = [f + ENVELOPE_SLACK_MM for f in footprint_mm]
    lengths = [L for L in reversed(grid)
               if (e := _envelope(_with_length(data, L, _arm_cap(data, L)), envelope_of))
               is not None and fits(e, near)]
    for L in lengths[:FIT_TRIES]:
        d = _design_at(data, L, targets, correction, name)
        if d is not None and fits(envelope_of(d.plan), footprint_mm):
            return L
    return None


def _design_at(data, length_mm, targets, correction, name) -> InverseDesign | None:
    """The inverse design with arms up to the longest ``length_mm`` holds, its
    element then shortened to its longest arm, or None when refused."""
    cap = _arm_cap(data, length_mm)
    tables = _with_length(data, length_mm, cap)
    try:
        return design_from_tables(tables, targets, name=name, correction=correction,
                                  arm_max_mm=cap, shortest_element=True)
    except (InverseDesignError, DesignError):
        return None


def design_in_footprint(tables: Mapping[str, Any], targets: Targets,
                        footprint_mm: Sequence[float], envelope_of: Envelope, *,
                        correction=None, name: str = "inverse_design",
                        sheet0_mm: float | None = None) -> InverseDesign | None:
    """The inverse design on ``tables`` with the longest element whose clamped
    array fits ``footprint_mm`` (arms capped to it), the footprint stated and
    the element length's reason written (and the sheet's, where it differs from
    ``sheet0_mm``); None when no element length fits."""
    length = _fitting_design(tables, footprint_mm, envelope_of, targets, correction, name,
                             _length_grid(tables))
    d = None if length is None else _design_at(tables, length, targets, correction, name)
    if d is None:
        return None
    sheet = float(tables["sheet"]["thickness_mm"])
    return _stated(d, footprint_mm, sheet if sheet0_mm is None else sheet0_mm, Layout(
        sheet, float(tables["array"]["pitch_mm"]),
        float(d.plan.element(1).geometry.overall_length_mm)))


def _shortest_design(data, targets, correction, name, grid) -> InverseDesign | None:
    """The design with the shortest element of ``grid`` that meets the targets
    (bisection: a longer element allows every arm a shorter one does)."""
    lo, hi = 0, len(grid) - 1  # grid[hi] feasible, grid[lo - 1] not
    best = _design_at(data, grid[hi], targets, correction, name)
    if best is None:
        return None
    for _ in range(LENGTH_STEPS):
        if lo >= hi:
            break
        mid = (lo + hi) // 2
        d = _design_at(data, grid[mid], targets, correction, name)
        if d is None:
            lo = mid + 1
        else:
            hi, best = mid, d
    return best


def design_within_footprint(base: Plan, targets: Targets, footprint_mm: Sequence[float],
                            envelope_of: Envelope, *, correction=None,
                            name: str = "inverse_design", **layout) -> InverseDesign:
    """An inverse design whose clamped array fits ``footprint_mm`` ([X, Y] or
    [X, Y, Z], mm), with ``requirements.footprint_mm`` stated and the changes'
    reasons under ``[assumptions]`` (see the module docstring).

    Args:
        envelope_of: plan -> (X, Y, Z) of its clamped array (mm).
        layout: ``grade``, ``pitch_mm``, ``rows``, ``columns`` as
            :func:`tactcad.studies.inverse_design.design_for_targets`.

    Raises:
        DesignError: ``--footprint`` naming the footprint and the nearest one a
            design meeting the targets fits; a bad value of the design itself
            (its name), naming the field.
        InverseDesignError: the targets cannot be met at any size (with the
            alternatives of :func:`tactcad.studies.design_alternatives.refusal_with_alternatives`).
    """
    data = design_tables(base, **layout)
    sheet0 = float(data["sheet"]["thickness_mm"])
    # the design as asked first: its own refusals (the targets, a bad name) are the
    # user's to read, not a candidate's to skip; when it fits, it is the answer
    try:
        plain = design_from_tables(copy.deepcopy(data), targets, name=name, correction=correction)
    except InverseDesignError as exc:
        raise refusal_with_alternatives(exc, data, targets, correction) from None
    if fits(envelope_of(plain.plan), footprint_mm):
        return stated_footprint(plain, footprint_mm)
    sheets = [sheet0] + [t for t in sorted(SHEET_THICKNESSES_MM, reverse=True) if t < sheet0]
    nearest: list[tuple[float, tuple[float, ...], Layout]] = []
    for sheet in sheets:
        tables = data if sheet == sheet0 else _sheet_tables(data, sheet)
        grid = _length_grid(tables)
        with warnings.catch_warnings():  # candidates explored, not the design written
            warnings.simplefilter("ignore")
            length = _fitting_design(tables, footprint_mm, envelope_of, targets, correction,
                                     name, grid)
            smallest = None if length is not None else \
                _shortest_design(tables, targets, correction, name, grid)
        if length is not None:  # designed again, its own warnings shown
            return design_in_footprint(tables, targets, footprint_mm, envelope_of,
                                       correction=correction, name=name, sheet0_mm=sheet0)
        if smallest is not None:
            env = tuple(float(e) for e in envelope_of(smallest.plan))
            need = max(e / f for e, f in zip(env, footprint_mm))
            nearest.append((need, env, Layout(sheet, float(tables["array"]["pitch_mm"]),
                                              smallest.plan.element(1).geometry
                                              .overall_length_mm)))
    if not nearest:
        raise InverseDesignError(
            f"--footprint {' x '.join(f'{f:g}' for f in footprint_mm)} mm: no design meets the "
            "targets on any sheet tried, whatever its size")
    from tactcad.studies.verification import least_footprint_mm

    _, env, where = min(nearest, key=lambda n: n[0])
    axes = len(footprint_mm)
    raise DesignError("--footprint", list(footprint_mm),
                      f"at least {' x '.join(f'{f:g}' for f in least_footprint_mm(env, axes))} "
                      "mm for these "
                      f"targets (the nearest feasible footprint: {where.words()})",
                      "shorter elements need thinner webs, which carry less force, and a "
                      f"thinner sheet (down to {min(SHEET_THICKNESSES_MM):g} mm) a smaller pitch; "
                      "a smaller full-scale force, a stiffer K_m or fewer columns shrink it "
                      "further")


def stated_footprint(d: InverseDesign, footprint_mm: Sequence[float]) -> InverseDesign:
    """``d`` as designed, with the footprint it fits stated as ``requirements.footprint_mm``."""
    return _stated(d, footprint_mm, d.plan.sheet_thickness_mm, None)


def _stated(d: InverseDesign, footprint_mm: Sequence[float], sheet0: float,
            where: Layout | None) -> InverseDesign:
    """``d`` with the footprint stated and the reasons of what it changed
    (``where`` None: the design as asked fits, nothing changed)."""
    data = copy.deepcopy(d.data)
    data["requirements"] = {**data.get("requirements", {}), "footprint_mm": list(footprint_mm)}
    if where is None:
        return replace(d, data=data, plan=plan_from_dict(data, source="<inverse design>"))
    fp = " x ".join(f"{f:g}" for f in footprint_mm)
    why = data.setdefault("assumptions", {})
    why["element.overall_length_mm"] = (
        f"tactcad design --footprint {fp}: {where.overall_length_mm:g} mm, the longest element "
        "whose clamped array fits the footprint; the arms are capped to it.")
    if not math.isclose(where.sheet_mm, sheet0):
        why["sheet.thickness_mm"] = (
            f"tactcad design --footprint {fp}: {where.sheet_mm:g} mm, the thickest common sheet "
            f"below {sheet0:g} mm whose stack (pitch {where.pitch_mm:g} mm, the spacer kept) fits "
            "the footprint.")
    return replace(d, data=data, plan=plan_from_dict(data, source="<inverse design>"))
