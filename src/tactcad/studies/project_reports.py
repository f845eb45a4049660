"""A metal array's reports as ``tactcad readout``, ``thermal`` and ``budget`` print them with
``--json`` and :class:`tactcad.api.Project` returns them: one computation for the command
and the API, so both give the same numbers.

Units: N, N/mm, V, K, s; errors relative.
"""

from __future__ import annotations

from typing import Any, Callable

from tactcad.errors import DesignError


def readout_record(plan, model: str = "closed-form",
                   progress: Callable[[str], None] | None = None) -> Any:
    """The read-out chain of every element: gauge strain over the grid, K_v, K_v/K, the
    force and K_obj resolution (:func:`tactcad.mechanics.readout_chain.readout_report`);
    the paper's measured sensitivities are added beside them, for the paper's design only,
    by :func:`tactcad.paper.table1.with_measured_sensitivities`.

    Args:
        plan: the design's plan. model: ladder level of K and the strain field.
        progress: told what is solved (None: nothing).

    Returns:
        The report (``as_json()`` is ``tactcad readout --json``).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    from tactcad.mechanics.readout_chain import readout_report
    from tactcad.studies.verification import requirements_of

    return readout_report(plan, requirements_of(plan), model, progress or (lambda s: None))


def thermal_record(plan, model: str = "closed-form", element: int | None = None) -> Any:
    """Every element's zero and span drift per kelvin, self-heating offset and K_obj error
    per kelvin (:func:`tactcad.mechanics.thermal_drift.thermal_report`), or one element's.

    Args:
        plan: the design's plan. model: ladder level. element: one element's number, or
            None for all.

    Returns:
        The report (``as_json()`` is ``tactcad thermal --json``).

    Raises:
        DesignError: ``--element`` not an element of the design (the allowed numbers named).
    """
    from dataclasses import replace

    from tactcad.mechanics.thermal_drift import thermal_report
    from tactcad.studies.verification import requirements_of

    report = thermal_report(plan, requirements_of(plan), model)
    if element is None:
        return report
    chosen = [r for r in report.records if r["element"] == element]
    if not chosen:
        raise DesignError("--element", element, f"1 ... {len(report.records)}",
                          "an element number of the design")
    return replace(report, records=chosen)


def budget_record(plan, model: str = "closed-form", force_N: float | None = None,
                  delta_T_K: float | None = None, points: int | None = None,
                  calibrations: dict | None = None) -> tuple[dict, Any]:
    """The K_obj error budget of every sensing unit and of the array
    (:func:`tactcad.in_use.kobj_budget.kobj_budget`) at the design's K_obj range, with the
    reasons of its range and force.

    Args:
        plan: the design's plan. model: ladder level of K and the gauge strain.
        force_N: force on the reference at the reading (N; None: the design's full-scale
            force). delta_T_K: temperature step between tare and reading (K; None: the
            budget's default). points: K_obj grid points (None: the default).
        calibrations: measured calibrations' standard errors (``budget --calibration``),
            None: the expected errors of the calibration ``calibrate`` drives.

    Returns:
        (the record ``tactcad budget --json`` prints, the budget object).
    """
    from tactcad.in_use.kobj_budget import BUDGET_POINTS, DEFAULT_DELTA_T_K, kobj_budget
    from tactcad.studies.verification import calibration_gauge, requirements_of

    req = requirements_of(plan)
    force = req.full_scale_force_N if force_N is None else force_N
    budget = kobj_budget(plan, req.kobj_range_N_per_mm, force,
                         DEFAULT_DELTA_T_K if delta_T_K is None else delta_T_K, model,
                         calibrations=calibrations,
                         points=BUDGET_POINTS if points is None else points,
                         force_gauge=calibration_gauge(plan),
                         readable_within_rel=req.kobj_resolution_rel)
    record = {**budget.as_json(), "kobj_range_reason": req.reasons["kobj_range_N_per_mm"],
              "force_reason": "--force" if force_N is not None
              else f"full-scale force: {req.reasons['full_scale_force_N']}"}
    return record, budget


def crosstalk_record(plan, model: str = "stack-beam") -> tuple[dict, Any]:
    """The clamped stack's crosstalk (:func:`tactcad.mechanics.stack_crosstalk.plan_crosstalk`:
    the n x n gauge sensitivity, tip displacements, crosstalk_rel, the decoupling matrix)
    and, at the rated full-scale force, each gauge's crosstalk in newtons against its force
    resolution through the design's read-out chain (closed form).

    Args:
        plan: the design's plan. model: a crosstalk level (``stack-beam`` ...).

    Returns:
        (the record ``tactcad crosstalk --json`` prints, less its ``--sweep``; the result).

    Raises:
        UnknownCrosstalkModelError: ``model`` is no crosstalk level.
        DesignError: the plan's construction is no clamped stack.
    """
    from tactcad.mechanics.readout_chain import element_force_resolution_N
    from tactcad.mechanics.stack_crosstalk import crosstalk_in_force, plan_crosstalk
    from tactcad.studies.verification import rated_full_scale_force

    result = plan_crosstalk(plan, model)
    per_part = element_force_resolution_N(plan)
    step = {s.number: per_part[s.geometry.part_name]["dF"] for s in plan.slots}
    return {"design": plan.name, **result.as_json(),
            "in_force": crosstalk_in_force(result, rated_full_scale_force(plan), step)}, result
