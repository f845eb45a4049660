"""The fracture probability of a silicon die's beams, from a Weibull pair for its etched
silicon (:class:`tactcad.products.silicon_die.design.mems_die.WeibullPair`: the lab's own,
or the design default :data:`tactcad.products.silicon_die.design.mems_die.DESIGN_STRENGTH`
when the die's file states none).

Silicon breaks from surface flaws, brittle and size-dependent: a surface of effective area
A_eff at peak stress sigma breaks with P_f = 1 - exp(-(A_eff / A_0) (sigma / sigma_0)^m)
(Weibull's weakest link on a surface population, A_0 the area the pair was measured on:
e.g. Wachtman, Cannon and Matthewson, *Mechanical Properties of Ceramics*, 2nd ed.,
ch. 6). A cantilever tip-loaded out of plane carries sigma(x, z) = sigma_root (1 - x / L)
(2 z / t) (x from the root, z from the mid-plane); its tensile surfaces are the face under
tension, w wide, and the tensile half of each DRIE sidewall:

    A_eff = int (sigma / sigma_root)^m dA = L / (m + 1) (w + t / (m + 1)),

both taken as the pair's population (the lab's test structures are etched as the die is:
conservative for a polished face), at the root's nominal 6 F L / (w t^2). The root's
fillets carry the peak, K_t x the nominal
(:func:`tactcad.products.silicon_die.design.mems_die.root_stress_concentration`), over their
own small surface (:func:`tactcad.products.silicon_die.design.mems_die.fillet_effective_area_um2`:
each arc over the tensile half of the thickness and a square of side r of the face beside
it, all at the peak), added to the beam's risk. The beams break independently: the die's
P_f is 1 - prod(1 - P_f,i).

Units: MPa, um, N.
"""

from __future__ import annotations

import math

from tactcad.products.silicon_die.design.mems_die import (Beam, DiePlan, WeibullPair,
                                                          beam_weibull_risk, effective_area_um2,
                                                          force_scale_of_risk, weibull_risk)

__all__ = ["effective_area_um2", "failure_probability", "beam_failure_probability",
           "die_failure_probability", "force_scale_at_probability"]


def failure_probability(peak_MPa: float, area_um2: float, pair: WeibullPair) -> float:
    """P_f = 1 - exp(-(A_eff / A_0) (sigma / sigma_0)^m) of a surface of effective area
    ``area_um2`` at peak stress ``peak_MPa`` (0 at no tension)."""
    return -math.expm1(-weibull_risk(area_um2, peak_MPa, pair))


def beam_failure_probability(plan: DiePlan, beam: Beam, force_N: float) -> float:
    """``beam``'s P_f at the tip force ``force_N`` (N) with the plan's Weibull pair.

    Raises:
        ValueError: the plan states no Weibull pair.
    """
    if plan.weibull is None:
        raise ValueError(f"die {plan.name} states no Weibull pair")
    nominal = plan.stress_MPa_at_rating(beam) * force_N / plan.full_scale_force_N
    risk = beam_weibull_risk(beam.length_um, beam.width_um, beam.thickness_um, nominal,
                             plan.root_stress_concentration(beam), plan.root_fillet_um,
                             plan.weibull)
    return -math.expm1(-risk)


def die_failure_probability(plan: DiePlan, force_of) -> float:
    """The die's P_f with each beam at ``force_of(beam)`` (N): 1 - prod(1 - P_f,i)."""
    survive = 1.0
    for beam in plan.beams:
        survive *= 1.0 - beam_failure_probability(plan, beam, force_of(beam))
    return 1.0 - survive


def force_scale_at_probability(plan: DiePlan, force_of, probability: float) -> float:
    """The factor on every beam's force (``force_of(beam)``, N) at which the die's failure
    probability reaches ``probability``: every root's stress goes as its force, so the die's
    risk goes as s^m, P_f(s) = 1 - exp(-s^m sum_i risk_i), and
    s = (-ln(1 - P) / sum_i risk_i)^(1/m) (inf when no beam is in tension).

    Raises:
        ValueError: the plan states no Weibull pair, or ``probability`` not in (0, 1).
    """
    if plan.weibull is None:
        raise ValueError(f"die {plan.name} states no Weibull pair")
    if not 0.0 < probability < 1.0:
        raise ValueError(f"probability = {probability!r}: 0 < P < 1")
    risk = sum(-math.log1p(-beam_failure_probability(plan, b, force_of(b))) for b in plan.beams)
    return force_scale_of_risk(risk, probability, plan.weibull.modulus)
