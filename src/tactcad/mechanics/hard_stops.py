"""Overload protection: where each element's hard stop engages, against its
rating and its yield.

A hard stop is a gap under the arm's free end (:class:`~tactcad.design.array_plan.HardStop`,
from the plan's construction) that closes on a fixed face before the notch
yields. The arm turns about the notch as a rigid lever (the notch carries
nearly all the compliance: Paros and Weisbord 1965), so the tip's travel at
engagement is the gap scaled by arm length over the gap's lever. The stop
must engage after the rated full-scale deflection (the element measures its
whole range) and before the deflection at its yield-limited force
(:func:`tactcad.mechanics.element_strength.plan_strength`, with the design's
safety factor). Units: mm, N, N/mm.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # annotations only: the design model costs a second to import
    from tactcad.design.array_plan import HardStop, Plan


@dataclass(frozen=True)
class StopVerdict:
    """One element's hard stop against its rating and its yield.

    Attributes:
        element: the element's number.
        kind: ``cut`` or ``set`` (:class:`~tactcad.design.array_plan.HardStop`).
        gap_mm: the stop's gap at the arm's free end.
        cut_mm: the gap the process cuts there.
        engage_tip_mm: the tip's travel when the stop engages.
        rated_tip_mm: the tip's deflection at the rated full-scale force.
        yield_tip_mm: the tip's deflection at the yield-limited force.
        stiffness_N_per_mm: the element's stiffness at the model.
        engages_between: True when rated < engagement < yield.
        fatigue_tip_mm: the tip's deflection at the element's lowest fatigue limit (the
            material's at the notch, the gauge's fatigue strain), inf without one.
        fatigue_limit: which fatigue limit that is (``material fatigue``, ``gauge
            fatigue``; "" without one).
    """

    element: int
    kind: str
    gap_mm: float
    cut_mm: float
    engage_tip_mm: float
    rated_tip_mm: float
    yield_tip_mm: float
    stiffness_N_per_mm: float
    engages_between: bool
    fatigue_tip_mm: float = math.inf
    fatigue_limit: str = ""

    @property
    def multiple_of_rated(self) -> float:
        """Engagement travel over the rated deflection."""
        return self.engage_tip_mm / self.rated_tip_mm

    @property
    def engage_force_N(self) -> float:
        """The force on the element (N) when its stop engages."""
        return self.engage_tip_mm * self.stiffness_N_per_mm

    @property
    def below_fatigue(self) -> bool:
        """True when the stop engages below the element's every fatigue limit: an overload
        it stops never cycles the element past them."""
        return self.engage_tip_mm < self.fatigue_tip_mm

    def as_json(self) -> dict:
        return {**asdict(self), "fatigue_tip_mm": _finite(self.fatigue_tip_mm),
                "multiple_of_rated": self.multiple_of_rated,
                "engage_force_N": self.engage_force_N, "below_fatigue": self.below_fatigue}


def _finite(x: float) -> float | None:
    return x if math.isfinite(x) else None


def fatigue_limit_N(record) -> tuple[float, str]:
    """(the element's lowest fatigue-limited force (N), which limit) of a strength record
    (:class:`tactcad.mechanics.element_strength.ElementStrength`): the material's fatigue
    strength at the notch or the gauge's fatigue strain; (inf, "") without either."""
    limits = [(f, w) for f, w in ((record.fatigue_force_N, "material fatigue"),
                                  (record.gauge_fatigue_force_N, "gauge fatigue"))
              if f is not None and math.isfinite(f)]
    return min(limits, default=(math.inf, ""))


def engagement_travel_mm(stop: HardStop, arm_length_mm: float) -> float:
    """The tip's travel (mm) when the stop's gap closes: gap x arm / lever.

    Raises:
        ValueError: a non-positive gap, arm or lever.
    """
    if min(stop.gap_mm, stop.lever_mm, arm_length_mm) <= 0:
        raise ValueError(f"element {stop.element}: gap, lever and arm must be > 0 mm")
    return stop.gap_mm * arm_length_mm / stop.lever_mm


def stop_verdicts(plan: Plan, full_scale_force_N: float,
                  model: str = "closed-form") -> list[StopVerdict]:
    """Every hard stop of ``plan`` against its element's rating and yield.

    Args:
        plan: the design's plan; a construction without stops gives ``[]``.
        full_scale_force_N: the rated full-scale force (N).
        model: the stiffness and stress level (closed-form or beam).

    Returns:
        One verdict per stop, in element order.

    Raises:
        DesignError: the material has no yield strength.
    """
    if not plan.hard_stops:
        return []
    from tactcad.mechanics.element_strength import plan_strength

    records = {r.element: r for r in plan_strength(plan, full_scale_force_N, model)}
    out = []
    for stop in plan.hard_stops:
        r = records[stop.element]
        engage = engagement_travel_mm(stop, plan.element(stop.element).geometry.arm_length_mm)
        rated = full_scale_force_N / r.stiffness_N_per_mm
        yielded = r.yield_limited_force_N / r.stiffness_N_per_mm
        fatigue_N, fatigue = fatigue_limit_N(r)
        out.append(StopVerdict(stop.element, stop.kind, stop.gap_mm, stop.cut_mm, engage, rated,
                               yielded, r.stiffness_N_per_mm, rated < engage < yielded,
                               fatigue_N / r.stiffness_N_per_mm, fatigue))
    return out


def engagement_force_N(multiple: float, rated_N: float, fatigue_N: float) -> float:
    """The force (N) a stop is set to engage at: ``multiple`` x the rating, or midway between
    the rating and the element's lowest fatigue limit where that is lower (an overload the
    stop takes then never cycles the element past its fatigue limits)."""
    return min(multiple * rated_N, (rated_N + fatigue_N) / 2) if fatigue_N > rated_N \
        else multiple * rated_N


def stop_gap_for(multiple: float, rated_tip_mm: float, stop: HardStop,
                 arm_length_mm: float) -> float:
    """The gap at the arm's end (mm) that engages at ``multiple`` x the rated
    tip deflection (the inverse of :func:`engagement_travel_mm`)."""
    return multiple * rated_tip_mm * stop.lever_mm / arm_length_mm
