"""Loads and samples of the virtual experiments, from the design's requirements.

The paper's design is evaluated with the paper's rig (3.235 N, then 100 g
steps) and its eight samples; any other design with samples spread over its
own K_obj range and loads that take the most loaded element up to its
full-scale force at the last step (the rig model is linear, so one unit
load gives the tip force per newton of grasping force).

Units: N, N/mm.
"""

from __future__ import annotations

import numpy as np

from tactcad.design.array_plan import Plan

#: Samples spread over the requirement's K_obj range (log-spaced, ends included).
DESIGN_SAMPLES = 5


def design_samples(plan: Plan, n: int = DESIGN_SAMPLES) -> list[float]:
    """Object stiffnesses (N/mm, 3 significant digits) log-spaced over the
    design's required K_obj range (:func:`tactcad.studies.verification.requirements_of`)."""
    from tactcad.studies.verification import requirements_of

    lo, hi = requirements_of(plan).kobj_range_N_per_mm
    return [float(f"{k:.3g}") for k in np.geomspace(lo, hi, n)]


def element_tip_force_per_newton(plan: Plan, stiffness: dict[int, float], samples,
                                 spec) -> dict[int, float]:
    """Each element's largest tip force (N) per newton of grasping force over
    ``samples`` (N/mm) in the evaluation rig (:func:`tactcad.mechanics.evaluation.simulate_rig`,
    linear: the tip forces at a load W are W times these).

    Raises:
        ContactError: a stiffness or sample <= 0, or a bad sample spec.
    """
    from tactcad.mechanics import evaluation as ev

    elements = ev.elements_from_plan(plan, stiffness)
    ref = ev.reference_element(elements)
    unit = None if spec.coupling == "none" else ev.unit_punch_compliance(elements, spec)
    per_sample = np.array([ev.simulate_rig(elements, float(s), spec, [1.0], ref, unit).tip_force_N[0]
                           for s in samples])
    return {e.number: float(f) for e, f in zip(elements, per_sample.max(axis=0))}


def tip_force_per_newton(plan: Plan, stiffness: dict[int, float], samples, spec) -> float:
    """Largest element tip force (N) per newton of grasping force over ``samples``."""
    return max(element_tip_force_per_newton(plan, stiffness, samples, spec).values())


def loads_to_full_scale(plan: Plan, stiffness: dict[int, float], samples, spec, n_steps: int,
                        full_scale_force_N: float) -> np.ndarray:
    """``n_steps`` grasping forces (N), equal steps up to the one at which the
    most loaded element carries ``full_scale_force_N``."""
    total = full_scale_force_N / tip_force_per_newton(plan, stiffness, samples, spec)
    return total * np.arange(1, n_steps + 1) / n_steps
