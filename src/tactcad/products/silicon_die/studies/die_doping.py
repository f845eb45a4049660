"""The die's resistor doping: of the stock boron implant doses, the one whose bridge drifts
least per newton of signal.

A die's bridge has one active resistor and, beside it on the frame, a reference of the same
implant: their common TCR cancels and the zero moves by their mismatch, (V_bias / 4) TCR m
per kelvin (m a fixed share of the TCR), while the signal per newton goes with the
piezoresistance factor P(N, T). The zero drift in newtons per kelvin is
therefore (V_bias / 4) TCR(N) / sensitivity, and its dependence on the doping is TCR(N) /
P(N): the geometry, the bias and the beam cancel. Both fall with the doping at first (the
mobility's temperature dependence weakens as impurity scattering takes over), then P falls
faster than the TCR, so the ratio has a minimum near 3e18 cm^-3. The noise (Johnson and
Hooge) falls as the dose rises and is not what binds: the die resolves a few parts in 1e5
of its rating at any stock dose (``tactcad readout``).

Sources: TCR from Arora, Hauser and Roulston's hole mobility (IEEE TED 29, 1982; every
acceptor ionised, :func:`tactcad.products.silicon_die.mechanics.piezoresistor.resistor_tcr_per_K`); P(N, T) from
Richter et al. (J. Appl. Phys. 104, 2008; :func:`~tactcad.products.silicon_die.mechanics.piezoresistor.piezoresistance_factor`).
Units: cm^-2 (dose), cm^-3 (concentration), 1/K.
"""

from __future__ import annotations

import functools

from tactcad.errors import DesignError

from tactcad.products.silicon_die.design.mems_die import JUNCTION_DEPTH_UM
from tactcad.products.silicon_die.mechanics.piezoresistor import (piezoresistance_factor,
                                                                  resistor_tcr_per_K)

#: The doses searched (cm^-2): a 1-2-5 series over what a boron implant for piezoresistors
#: takes (light doses give 1e17 cm^-3 over the junction, heavy ones 1e20).
STOCK_DOSES_PER_CM2 = (5e12, 1e13, 2e13, 5e13, 1e14, 2e14, 5e14, 1e15, 2e15, 5e15)
#: The die's working temperature the drift is judged at (K).
DOPING_TEMPERATURE_K = 300.0


def acceptors_of_dose(dose_per_cm2: float) -> float:
    """Boron concentration (cm^-3) of a dose spread evenly over the junction's depth."""
    return dose_per_cm2 / (JUNCTION_DEPTH_UM * 1e-4)


def drift_per_sensitivity_per_K(dose_per_cm2: float,
                                temperature_K: float = DOPING_TEMPERATURE_K) -> float:
    """TCR(N) / P(N, T) (1/K): the bridge's zero drift per unit of its signal, up to
    the geometry's factor, at the dose's concentration."""
    n = acceptors_of_dose(dose_per_cm2)
    return resistor_tcr_per_K(n, temperature_K) / piezoresistance_factor(n, temperature_K)


@functools.lru_cache(maxsize=8)  # every die plan asks it; the stock does not change
def chosen_implant_dose(doses: tuple[float, ...] = STOCK_DOSES_PER_CM2) -> tuple[float, str]:
    """(dose cm^-2, why): of ``doses`` (a tuple), the one with the least
    :func:`drift_per_sensitivity_per_K`, with the runner-up and the worst in the reason.

    Raises:
        ValueError: no dose given.
    """
    if not doses:
        raise ValueError("doses: at least one")
    ranked = sorted(doses, key=drift_per_sensitivity_per_K)
    best, worst = ranked[0], ranked[-1]

    def words(dose: float) -> str:
        return (f"{dose:.2g} cm^-2 ({acceptors_of_dose(dose):.2g} cm^-3, TCR / P "
                f"{1e6 * drift_per_sensitivity_per_K(dose):.0f} ppm/K)")

    why = (f"of the stock doses {min(doses):.2g} ... {max(doses):.2g} cm^-2 (1-2-5 series), "
           f"the one whose bridge drifts least per newton of signal, TCR / P(N, T) at "
           f"{DOPING_TEMPERATURE_K:g} K (Arora et al. 1982's mobility, Richter et al. 2008's "
           f"P): {words(best)}"
           + (f"; next {words(ranked[1])}" if len(ranked) > 1 else "")
           + (f"; worst {words(worst)}" if len(ranked) > 2 else "")
           + "; the noise falls with the dose and does not bind")
    return best, why


def doped_die_plan(targets, room, kobj_resolution_rel: float | None = None, **kwargs):
    """:func:`tactcad.products.silicon_die.design.mems_die.die_plan` with the implant dose of
    :func:`chosen_implant_dose` (and its reason), refused where its read-out cannot resolve
    K_obj, with its model's error to spare (:func:`resolves`), to ``kobj_resolution_rel`` (default
    :data:`~tactcad.products.silicon_die.design.mems_die.DEFAULT_KOBJ_RESOLUTION_REL`) anywhere in the range at
    the rated force (the read-out noise term of the die's budget,
    :func:`tactcad.products.silicon_die.in_use.die_budget.readout_noise_term`); ``kwargs`` as ``die_plan`` takes
    them. The plan's ``kobj_resolution_stated`` says whether ``kobj_resolution_rel`` was
    given (verify judges it) or is the default (reported, not judged).

    Raises:
        DesignError: as :func:`~tactcad.products.silicon_die.design.mems_die.die_plan`; ``--full-scale-force``
            too light to resolve K_obj (with the rating that does, where one designs).
    """
    import dataclasses

    from tactcad.products.silicon_die.design.mems_die import DEFAULT_KOBJ_RESOLUTION_REL

    target = DEFAULT_KOBJ_RESOLUTION_REL if kobj_resolution_rel is None else kobj_resolution_rel
    plan = die_plan_at(targets, room, targets.full_scale_force_N, kwargs)
    if not resolves(plan, target):
        raise _too_light(targets, room, plan, worst_readout_error_rel(plan), target, kwargs)
    return dataclasses.replace(plan, kobj_resolution_rel=float(target),
                               kobj_resolution_stated=kobj_resolution_rel is not None)


def resolves(plan, target: float) -> bool:
    """Whether ``plan``'s read-out resolves K_obj to ``target`` with its model's error to
    spare: its worst read-out error (:func:`worst_readout_error_rel`) below the target by
    more than the error ``verify``'s ``kobj_resolution_rel`` row carries
    (:func:`resolution_error_rel`), so that the row passes rather than stays undecided.

    Args:
        plan: the die. target: the K_obj resolution asked (relative, > 0).

    Returns:
        True when target / worst - 1 exceeds the error.
    """
    import math

    worst = worst_readout_error_rel(plan)
    if not (math.isfinite(worst) and worst > 0):
        return worst == 0
    error = resolution_error_rel(plan)
    return math.isfinite(error) and target / worst - 1.0 > error


def die_plan_at(targets, room, force_N: float, kwargs):
    """The doped die of ``targets`` at the rating ``force_N`` (N), without the resolution's
    refusal."""
    import dataclasses

    from tactcad.products.silicon_die.design.mems_die import die_plan

    dose, why = chosen_implant_dose()
    return die_plan(dataclasses.replace(targets, full_scale_force_N=force_N), room,
                    implant_dose_per_cm2=dose, dose_reason=why, **kwargs)


def worst_readout_error_rel(plan) -> float:
    """The die's largest K_obj error from its read-out noise over its K_obj range (ends and
    middle; relative, 1 sigma; inf where unreadable)."""
    import math

    import numpy as np

    from tactcad.products.silicon_die.in_use.die_budget import readout_noise_term
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout

    lo, hi = plan.kobj_range_N_per_mm
    return float(np.max(readout_noise_term(plan, die_readout(plan),
                                           np.array([lo, math.sqrt(lo * hi), hi]))))


def resolution_error_rel(plan) -> float:
    """The error of the die's worst read-out K_obj error (:func:`worst_readout_error_rel`):
    its largest change with each K moved by the closed form's error
    (:func:`tactcad.products.silicon_die.design.mems_die.k_moved_error_rel`), the error
    ``verify``'s ``kobj_resolution_rel`` row carries and the die's design keeps room for
    (:func:`resolves`).

    Args:
        plan: the die (:class:`~tactcad.products.silicon_die.design.mems_die.DiePlan`).

    Returns:
        The relative error (inf where the read-out is unreadable).
    """
    from tactcad.products.silicon_die.design.mems_die import k_moved_error_rel

    return k_moved_error_rel(plan, worst_readout_error_rel)


def _wider_ratio(targets, room, target: float, kwargs) -> float | None:
    """The least of 1.5, 2, 3, 5 and 10 times ``targets``' K_r / K_m (two digits) whose die
    designs and resolves K_obj to ``target`` at the same rating, or None."""
    import dataclasses

    for factor in (1.5, 2.0, 3.0, 5.0, 10.0):
        ratio = float(f"{targets.kr_over_km * factor:.2g}")
        try:
            plan = die_plan_at(dataclasses.replace(targets, kr_over_km=ratio), room,
                               targets.full_scale_force_N, kwargs)
        except DesignError:
            continue
        if resolves(plan, target):
            return ratio
    return None


def _too_light(targets, room, plan, worst: float, target: float, kwargs) -> DesignError:
    """The refusal of a rating too light to resolve K_obj: the read-out's error goes as one
    over the rating (the deflections as F, the force resolution fixed), so the rating that
    resolves it is F x worst / target (10 % more, two digits up), pasted where it designs
    and resolves it with its model's error to spare (:func:`resolves`)."""
    from tactcad.vocabulary.binding_limits import RESOLUTION

    import dataclasses
    import math

    force = targets.full_scale_force_N
    alternatives, heavier, error = [], force, worst
    for _ in range(8):  # eq. 3 amplifies the noise unevenly: a few steps of F x error / target
        # at least 10 % heavier: a read-out within its error of the target needs more
        scale = max(error / target, 1.0) if math.isfinite(error) else 1e3
        heavier = float(f"{1.1 * heavier * scale:.2g}")
        try:
            heavy = die_plan_at(targets, room, heavier, kwargs)
        except DesignError:
            break  # heavier than the die's other limits allow
        error = worst_readout_error_rel(heavy)
        if resolves(heavy, target):
            alternatives = [{"option": f"--full-scale-force {heavier:g}",
                             "words": f"a rating whose read-out resolves K_obj to "
                                      f"{100 * target:g} %"}]
            break
    read = ("leaves K_obj unreadable" if not math.isfinite(worst) else
            f"moves K_obj by {100 * worst:.3g} %"
            + ("" if worst > target else
               f", within its model's error ({100 * resolution_error_rel(plan):.2g} %) of "
               "the target, which verify could not pass"))
    if not alternatives:  # no rating helps: R hardly moves with K_obj at so close a ratio
        wider = _wider_ratio(targets, room, target, kwargs)
        if wider is not None:
            return DesignError(
                "--kr-over-km", targets.kr_over_km,
                f"a ratio whose R resolves K_obj to {100 * target:g} % (1 sigma) at the "
                f"{force:g} N rating", f"at K_r / K_m {targets.kr_over_km:g} the bridges' "
                f"noise {read} somewhere in {targets.k_obj_range_N_per_mm[0]:g} ... "
                f"{targets.k_obj_range_N_per_mm[1]:g} N/mm, and no heavier rating within "
                "the die's other limits resolves it",
                alternatives=[{"option": f"--kr-over-km {wider:g}",
                               "words": "the least of 1.5, 2, 3, 5, 10 x the ratio that "
                                        "designs and resolves K_obj"}], limit=RESOLUTION)
    return DesignError("--full-scale-force", force,
                       f"a rating whose read-out resolves K_obj to {100 * target:g} % (1 sigma)",
                       f"at {force:g} N the bridges' noise {read} somewhere in "
                       f"{targets.k_obj_range_N_per_mm[0]:g} ... "
                       f"{targets.k_obj_range_N_per_mm[1]:g} N/mm"
                       + ("" if alternatives else "; no heavier rating designs within the "
                          "die's other limits"),
                       alternatives=alternatives, limit=RESOLUTION)
