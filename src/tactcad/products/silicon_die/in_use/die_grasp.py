"""The grasp on a silicon die: the jaw of the die's mount closes on tissue, and each column's
two beams are read as a unit, as the metal arrays' grasp reads theirs
(:mod:`tactcad.in_use.grasp_experiment`, whose contact, stops and readings this module uses
unchanged).

The die's tips (mm, the jaw's frame of :class:`tactcad.products.silicon_die.design.die_mount.DieMount`: x along
the jaw from its heel, y across it from its axis):

* each beam's post is a rigid flat punch of the post's face at the post's centre on the
  die's place in the pocket, on the beam's spring (K_r or K_m at the closed form);
* its radius is its distance from the pin along the jaw: a column's two posts share one x,
  so each unit is paired at equal radius by construction;
* its hard stop engages when the beam's free end meets its cavity's floor
  (:meth:`tactcad.products.silicon_die.design.mems_die.DiePlan.stop_engagement_um`, the nominal depth);
* its rating is the most the beam carries in use
  (:meth:`tactcad.products.silicon_die.design.mems_die.DiePlan.rated_force_N`: the die's
  full-scale force on a reference beam, less on a measuring beam), as strength and verify
  rate it;
* its overload limit is the force at which its root reaches the mean strength of etched
  silicon (:data:`tactcad.products.silicon_die.design.mems_die.BOSCH_MEAN_STRENGTH_MPA`);
* the die's face stays out of the tissue while every post's travel less its deflection is
  below the post's height proud of the face: past it the face meets the tissue, which the
  punch model does not carry, and the units whose posts it reaches do not read
  (:func:`with_face_contact`).

The jaw: the pin of the mount's jaw (the jaw's ``pin_inset_mm``), the jaw from the pin to its
tip (``pin_to_tip_mm``; the jaw's own ``jaw_length_mm`` runs from its heel), its opening
(the jaw's ``opening_angle_deg``) and the tissue's thickness (the grasp's default unless
given). Units: mm, N, N/mm, degrees.
"""

from __future__ import annotations

import math

import numpy as np

from tactcad.products.silicon_die.design.die_mount import DieMount
from tactcad.products.silicon_die.design.mems_die import BOSCH_MEAN_STRENGTH_MPA, DiePlan
from tactcad.in_use.grasp_experiment import (DEFAULT_PROFILE, DEFAULT_SLAB_MM, LayoutGrasp, Tips,
                                             check_kobj, grasp_layout)
from tactcad.in_use.jaw_kinematics import JawGeometry
from tactcad.mechanics.contact import Punch

UM = 1e-3  # mm per um


def die_tips(plan: DiePlan, mount: DieMount) -> Tips:
    """The die's posts as the grasp's tips, labelled by beam number (see the module doc)."""
    post = plan.post_um * UM
    x = [mount.die_x0_mm + b.x_um * UM for b in plan.beams]
    y = [(b.tip_y_um - plan.die_width_um / 2) * UM for b in plan.beams]
    stiffness = {"reference": plan.k_r_N_per_mm, "measuring": plan.k_m_N_per_mm}
    return Tips(tuple(b.number for b in plan.beams),
                np.array([xi - mount.pin_x_mm for xi in x]),
                [Punch(xi, yi, post, post) for xi, yi in zip(x, y)],
                np.array([stiffness[b.role] for b in plan.beams]),
                np.array([plan.stop_engagement_um(b)[0] * UM for b in plan.beams]),
                np.array([breaking_force_N(plan, b) for b in plan.beams]),
                np.array([plan.rated_force_N(b) for b in plan.beams]))


def breaking_force_N(plan: DiePlan, beam) -> float:
    """The tip force at which ``beam``'s root peak (K_t x 6 F L / (w t^2), on its fillets)
    reaches the mean strength of etched silicon (N): the rated force scaled by the mean
    strength over the root's peak stress at it."""
    return (plan.full_scale_force_N * BOSCH_MEAN_STRENGTH_MPA
            / plan.peak_stress_MPa_at_rating(beam))


def default_grasp_force_N(plan: DiePlan) -> float:
    """The grasp force a die's grasp closes to unless told (N): half of each beam's own
    rated force (:meth:`DiePlan.rated_force_N`), summed over the beams."""
    return round(0.5 * sum(plan.rated_force_N(b) for b in plan.beams), 12)


def die_units(plan: DiePlan) -> list[tuple[int, int]]:
    """Each column's (reference, measuring) beam numbers."""
    return [(plan.beams[c].number, plan.beams[plan.columns + c].number)
            for c in range(plan.columns)]


def die_jaw(mount: DieMount, opening_deg: float,
            slab_mm: float | None = None) -> JawGeometry:
    """The jaw the die is mounted in as the grasp's: the pin at the mount's ``pin_x_mm`` on
    the jaw's axis, the jaw from the pin to its tip (``pin_to_tip_mm``: the jaw's own length
    less the pin's inset), ``opening_deg`` open, the tissue
    ``slab_mm`` thick (default :data:`~tactcad.in_use.grasp_experiment.DEFAULT_SLAB_MM`).

    Raises:
        DesignError: a value out of the grasp's ranges (named).
    """
    return JawGeometry(mount.pin_x_mm, 0.0, mount.jaw_length_mm - mount.pin_x_mm, opening_deg,
                       DEFAULT_SLAB_MM if slab_mm is None else slab_mm)


def die_grasp(plan: DiePlan, mount: DieMount, jaw: JawGeometry, k_obj_N_per_mm: float,
              angle_deg: float | None = None, force_N: float | None = None,
              coupling: str = "layer", profile: str = DEFAULT_PROFILE) -> LayoutGrasp:
    """The die in its jaw closed on the tissue at ``angle_deg`` or to the grasp force
    ``force_N`` (one of them): every post's travel, deflection and forces against its own
    beam's rated force (:meth:`DiePlan.rated_force_N`) and its breaking force, every
    column's R and K_obj read (eq. 3) against the true one.

    Args:
        plan, mount: the die and its place in the jaw.
        jaw: :func:`die_jaw`.
        k_obj_N_per_mm: the tissue's true local stiffness under one post alone (N/mm),
            1e-06 ... 10000 (:func:`tactcad.in_use.grasp_experiment.check_kobj`).
        coupling: ``layer``, ``halfspace`` or ``none``; profile: ``wedge`` or ``slab``.

    Raises:
        DesignError: both or neither of angle and force, a force out of the jaw's reach,
            or a value out of range (named).
    """
    from tactcad.errors import DesignError

    if (angle_deg is None) == (force_N is None):
        raise DesignError("angle_deg / force_N", (angle_deg, force_N), "exactly one of them")
    check_kobj(k_obj_N_per_mm)
    return with_face_contact(grasp_layout(
        "as laid out", die_tips(plan, mount), die_units(plan), jaw, float(k_obj_N_per_mm),
        coupling, plan.full_scale_force_N, angle_deg, force_N, profile), mount.post_proud_mm)


def grasp_at_force(plan: DiePlan, mount: DieMount, force_N: float) -> LayoutGrasp:
    """The die's jaw closed to the grasp force ``force_N`` (N) on the grasp's default tissue:
    a wedge of the default thickness, coupled through its layer, K_obj the geometric mean of
    the die's range, the jaw at its own opening (``mount.opening_angle_deg``); what a die's
    ``max_grasp_force_N`` is judged on.

    Raises:
        DesignError: a force out of the jaw's reach (named).
    """
    lo, hi = plan.kobj_range_N_per_mm
    return die_grasp(plan, mount, die_jaw(mount, mount.opening_angle_deg), math.sqrt(lo * hi),
                     force_N=force_N)


def with_face_contact(layout: LayoutGrasp, post_proud_mm: float) -> LayoutGrasp:
    """``layout`` with each tip's ``face_in_contact`` (its travel less its deflection past
    ``post_proud_mm``: the tissue reaches the die's face beside the post) and each unit whose
    post it is marked as not reading, with why."""
    from dataclasses import replace

    tips = [{**t, "face_in_contact": t["travel_mm"] - t["deflection_mm"] > post_proud_mm}
            for t in layout.tips]
    touching = {t["site"] for t in tips if t["face_in_contact"]}
    units = []
    for u in layout.units:
        sites = [n for n in (u["reference"], u["measuring"]) if n in touching]
        if sites:
            why = "; ".join(filter(None, [u["why"], *(
                f"the face meets the tissue beside post {n}" for n in sites)]))
            u = {**u, "valid": False, "why": why}
        units.append(u)
    return replace(layout, tips=tips, units=units)
