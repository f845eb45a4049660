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

A hard stop's load path (a post pressed past its stop's engagement): the post's whole force
through its footprint (its compressive stress against :data:`POST_STRENGTH_MPA`), and the
beam's end pressed on its cavity's floor over that footprint, whose contact's edge carries
a surface tension of at most half the mean pressure (:func:`floor_edge_tension_MPa`), judged
on the same Weibull pair over the ring it falls off in (:func:`floors_force_scale`).

Units: MPa, um, N.
"""

from __future__ import annotations

import math

from tactcad.products.silicon_die.design.mems_die import (Beam, DiePlan, WeibullPair,
                                                          beam_weibull_risk, effective_area_um2,
                                                          force_scale_of_risk, weibull_risk)

__all__ = ["effective_area_um2", "failure_probability", "beam_failure_probability",
           "die_failure_probability", "force_scale_at_probability", "post_stress_MPa",
           "bearing_area_um2", "floor_edge_tension_MPa", "floor_effective_area_um2",
           "floors_force_scale"]


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


# -- a hard stop's load path: the post, and the cavity floor under the beam's end ----------

#: The posts' compressive limit (MPa): the tensile strength of cured SU-8, the weaker of the
#: posts' two processes (spun SU-8 or plated metal), taken for compression too, which a
#: cured epoxy takes above its tensile strength (conservative).
POST_STRENGTH_MPA = 60.0
POST_STRENGTH_SOURCE = ("SU-8's tensile strength, 60 MPa (MicroChem, SU-8 2000 Permanent "
                        "Epoxy Negative Photoresist, physical properties; McAleavey et al., "
                        "MRS Proc. 546, 1998, measured 120-130 MPa), taken as the post's "
                        "compressive limit: conservative for SU-8, more so for a plated post")
#: The largest surface tension at the edge of a contact over its mean pressure: outside a
#: circle loaded by any axisymmetric pressure, the surface's radial stress is
#: (1 - 2 nu) P / (2 pi r^2) (Johnson, *Contact Mechanics*, 1985, sec. 3.4), at its edge
#: (1 - 2 nu) / 2 of the mean pressure, at most 1/2 for any nu >= 0.
EDGE_TENSION_OVER_PRESSURE = 0.5
#: The error of a square footprint taken as the circle of its area in that bound (relative;
#: assumption: the square's corners concentrate the edge stress by about this much).
FOOTPRINT_SHAPE_ERROR_REL = 0.1


def post_stress_MPa(force_N: float, post_um: float) -> float:
    """The mean compressive stress in a post of side ``post_um`` (um, square) under the force
    ``force_N`` (N) on its face (MPa).

    Raises:
        ValueError: a post side not > 0.
    """
    if not post_um > 0:
        raise ValueError(f"post_um = {post_um!r}: > 0 um")
    return force_N / (post_um * post_um * 1e-6)


def bearing_area_um2(post_um: float, beam_width_um: float) -> float:
    """The beam's end pressed on its cavity's floor by the post over the post's footprint
    on the beam (um^2): post x min(post, beam width). The beam's spring gives way for the
    micrometre its tilt leaves under the post, so its end lies flat under a stop's force."""
    return post_um * min(post_um, beam_width_um)


def floor_edge_tension_MPa(force_N: float, area_um2: float) -> float:
    """The largest surface tension at the edge of a stop's contact (MPa): at most
    :data:`EDGE_TENSION_OVER_PRESSURE` of the mean pressure ``force_N`` / ``area_um2``
    (N, um^2), on the floor's face and the beam's alike."""
    return EDGE_TENSION_OVER_PRESSURE * force_N / (area_um2 * 1e-6)


def floor_effective_area_um2(area_um2: float, modulus: float) -> float:
    """The Weibull effective area of the tension ring around a contact of area ``area_um2``
    (um^2), its tension falling as (a / r)^2: int (a / r)^(2 m) 2 pi r dr from a to inf =
    pi a^2 / (m - 1), the contact's area over m - 1.

    Raises:
        ValueError: a modulus not > 1.
    """
    if not modulus > 1:
        raise ValueError(f"modulus = {modulus!r}: > 1")
    return area_um2 / (modulus - 1.0)


def floors_force_scale(forces_N, area_um2: float, pair: WeibullPair | None) -> float:
    """The factor on every stop's force at which the cavity floors fail: with a Weibull
    pair, where the die's floors under all the stops' forces ``forces_N`` (N) reach its
    accepted failure probability (their rings' risks summed,
    :func:`force_scale_of_risk`); without one, where the edge tension of the most loaded
    stop reaches the mean strength of etched silicon (inf at no force).

    Args:
        forces_N: each stop's force (N). area_um2: each contact's area (um^2).
        pair: the die's Weibull pair, or None.

    Returns:
        The factor (inf where no stop is loaded).
    """
    from tactcad.products.silicon_die.design.mems_die import BOSCH_MEAN_STRENGTH_MPA

    forces = [f for f in forces_N if f > 0]
    if not forces:
        return math.inf
    if pair is None:
        return BOSCH_MEAN_STRENGTH_MPA / floor_edge_tension_MPa(max(forces), area_um2)
    ring = floor_effective_area_um2(area_um2, pair.modulus)
    risk = sum(weibull_risk(ring, floor_edge_tension_MPa(f, area_um2), pair) for f in forces)
    return force_scale_of_risk(risk, pair.failure_probability_max, pair.modulus)
