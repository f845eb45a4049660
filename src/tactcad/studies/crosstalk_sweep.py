"""How the clamp plates' thickness, the bolt spacing and the spacers' grade change
the array's crosstalk: one crosstalk estimate per point, run on Dask (a
LocalCluster, or an existing scheduler by address, as the other sweeps).

Each point changes one input of the plan's stack
(:func:`tactcad.mechanics.stack_crosstalk.with_changes`) from the design's value;
the others stay at the design's. Units: mm, MPa, s.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

from tactcad.design.array_plan import Plan
from tactcad.mechanics.stack_crosstalk import StackInputs, estimate_crosstalk, stack_inputs, with_changes

#: Default sweep values: plate thickness (mm), bolt spacing (mm), spacer grades of the library.
PLATE_THICKNESSES_MM = (2.0, 3.0, 4.0, 6.0, 8.0)
BOLT_SPACINGS_MM = (3.0, 4.0, 6.0, 8.0)
SPACER_GRADES = ("6061-T6", "7075-T6", "Ti-6Al-4V-annealed", "17-4PH-H900")


@dataclass(frozen=True)
class SweepPoint:
    """One point: the stack with ``parameter`` at ``value`` (label for a grade)."""

    parameter: str
    value: float | str
    inputs: StackInputs
    model: str


def sweep_points(plan: Plan, model: str = "stack-beam",
                 thicknesses_mm: Sequence[float] = PLATE_THICKNESSES_MM,
                 spacings_mm: Sequence[float] = BOLT_SPACINGS_MM,
                 spacer_grades: Sequence[str] = SPACER_GRADES) -> list[SweepPoint]:
    """The points, one parameter changed at a time from the design's stack.

    Raises:
        CrosstalkInputError: a value out of its range. DesignError: an unknown grade.
    """
    base = stack_inputs(plan)
    points = [SweepPoint("plate_thickness_mm", t, with_changes(base, plate_thickness_mm=t), model)
              for t in thicknesses_mm]
    points += [SweepPoint("bolt_spacing_mm", s, with_changes(base, bolt_spacing_mm=s), model)
               for s in spacings_mm]
    points += [SweepPoint("spacer_grade", g, stack_inputs(plan, spacer_grade=g), model)
               for g in spacer_grades]
    return points


def evaluate_sweep_point(p: SweepPoint) -> dict:
    """One row: parameter, value, crosstalk_rel, its error estimate, wall time (s)."""
    r = estimate_crosstalk(p.inputs, p.model)
    return {"parameter": p.parameter, "value": p.value, "crosstalk_rel": r.crosstalk_rel,
            "error_estimate_rel": r.error_estimate_rel, "seconds": r.seconds,
            "worst_gauge": r.worst[0], "worst_loaded_element": r.worst[1]}


def crosstalk_sweep(points: Sequence[SweepPoint], mapper: Callable = map) -> list[dict]:
    """Every point's row, through ``mapper`` (``map`` in process, or
    :func:`tactcad.studies.sweeps.dask_mapper` of a client)."""
    return list(mapper(evaluate_sweep_point, points))
