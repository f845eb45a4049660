"""The K_obj a silicon die reads and the errors that enter it, term by term.

A unit of the die (a measuring beam and the reference beam paired with it) is pressed into
the tissue until the stiffer reference carries the rated force, every post pressing one
half-space (:mod:`tactcad.in_use.tissue_coupling`); R = e_m / e_r of the two deflections
gives K_obj by the coupled inversion with the die's nominal K_m and K_r
(:func:`tactcad.in_use.tissue_coupling.coupled_object_stiffness`, eq. 3 corrected for the
coupling, as a corrected die reads). Each term below perturbs what the die is or reads and
gives the K_obj the coupled inversion then reads, relative to the true one, at the ends and
the geometric middle of the K_obj range (1 sigma; a +- bound taken uniform, its sigma
bound / sqrt 3):

* read-out noise: each deflection on the coupled sample read to the bridge's force
  resolution over its K
  (:func:`tactcad.products.silicon_die.mechanics.piezoresistor.die_readout`), the two independent;
* device layer: both beams one layer, so K_r and K_m move together by 3 dt / t
  (dt: the SOI maker's +- on the layer); the reading with the nominal K reads the shift;
* cavity alignment: the cavities' outer edges are the two rows' roots, so the front
  masks' shift across the die against them lengthens one row's beams and shortens the
  other's (K ~ L^-3): K_r / K_m moves, every beam of a row alike;
* temperature: silicon's modulus along <110> falls by 64 ppm/K (Bourgeois et al., Proc.
  IEEE Int. Frequency Control Symp. 1997, pp. 791-799; Gysin et al., Phys. Rev. B 69,
  045403 (2004)), both beams alike, over the stated temperature step; the resistors'
  sensitivity drift cancels in R (one doping, one temperature);
* resistor zero drift: each beam's resistor and its on-die reference of the same implant
  make a half bridge, so their common TCR cancels and the zero moves by their mismatch,
  (V_bias / 4) TCR m per K (:func:`tactcad.products.silicon_die.mechanics.piezoresistor.die_readout`,
  :func:`~tactcad.products.silicon_die.mechanics.piezoresistor.resistor_tcr_per_K`): over the same step each
  beam reads a force it does not carry, both rows alike in sign, each over its own
  sensitivity (a reading tared at another temperature);
* tissue coupling: the tips press one tissue (rigid flat punches of the posts' faces on a
  half-space, :mod:`tactcad.in_use.tissue_coupling`), which eq. 2 alone leaves out: the
  bias of the uncoupled eq. 3 (shown, not summed: the coupled inversion removes it, as on
  the metal arrays), and the coupled model's own error that remains;
* post coplanarity: a measuring post standing below its reference (or above it) by twice
  the posts' height tolerance (the process's, :data:`~tactcad.products.silicon_die.
  vocabulary.soi_process.POST_HEIGHT_TOLERANCE_REL` of their height) meets the tissue later
  (sooner), through the coupled model with the tips offset
  (:func:`tactcad.in_use.tissue_coupling.offset_ratio`). As made it is shown, not summed: a
  post mismatch of a micron is as large as the reference's whole travel, so every die is
  zeroed on a rigid flat, and what that leaves (each beam's deflection resolution and the
  flat's flatness) is the term summed. With ``kobj_accuracy_rel`` stated, the record
  :attr:`DieBudget.tip_height` carries the post-height tolerance the accuracy needs, which
  the drawing and ``verify`` read as the metal arrays' tip height
  (:mod:`tactcad.in_use.tip_height_drawing`).

The first four are each beam's K measured in calibration (eq. 4-6) or the temperature
held; they are given before any correction. Units: N/mm, N, um, K.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from tactcad.products.silicon_die.design.mems_die import REFERENCE_TCR_MISMATCH_REL

#: <110> silicon's modulus temperature coefficient (1/K): -64 ppm/K (module doc's sources).
SILICON_TCE_PER_K = -64e-6
#: The temperature step the budget takes (K), as the metal arrays' budget does.
TEMPERATURE_STEP_K = 5.0
#: The term of eq. 3 read without the tips' coupling: shown, not summed (the coupled
#: inversion removes it; what it leaves is the next term).
UNCOUPLED = "tissue coupling, eq. 3 uncoupled"
COUPLED = "tissue coupling, after the coupled inversion"
#: The posts' height mismatch as the process leaves it: shown, not summed (every die is
#: zeroed on a rigid flat); what the zeroing leaves is the next term.
AS_MADE = "post coplanarity, as made"
ZEROED = "post coplanarity, zeroed on a flat"
#: Flatness of the flat a die's posts are zeroed on (mm): an optical flat of the finest grade
#: its makers list, lambda/20 at 633 nm (32 nm); the metal arrays' gauge block face
#: (:data:`tactcad.in_use.tip_zeroing.ZEROING_FLAT_FLATNESS_MM`, 0.15 um) would alone be a
#: sixth of a die's smallest travels.
OPTICAL_FLAT_FLATNESS_MM = 633e-6 / 20
#: The terms a budget shows and leaves out of its root sum square.
SHOWN_NOT_SUMMED = (UNCOUPLED, AS_MADE)


@dataclass(frozen=True)
class DieBudget:
    """Each term's relative K_obj error (1 sigma) at each K_obj, and their root sum square.

    Attributes:
        k_obj_N_per_mm: the K_obj values (N/mm), shape (3,).
        terms: term -> relative error at each K_obj, shape (3,).
        reasons: term -> how it is sized.
    """

    k_obj_N_per_mm: np.ndarray
    terms: dict
    reasons: dict
    tip_height: dict | None = None

    @property
    def total_rel(self) -> np.ndarray:
        return np.sqrt(sum(np.asarray(v) ** 2 for k, v in self.terms.items()
                           if k not in SHOWN_NOT_SUMMED))

    def as_json(self) -> dict:
        return {"k_obj_N_per_mm": self.k_obj_N_per_mm.tolist(),
                "terms_rel": {k: np.asarray(v).tolist() for k, v in self.terms.items()},
                "rss_rel": self.total_rel.tolist(),
                "rss_leaves_out": " and ".join(k for k in SHOWN_NOT_SUMMED if k in self.terms),
                "reasons": dict(self.reasons),
                **({} if self.tip_height is None else {"tip_height": dict(self.tip_height)})}


class _DieUnit(NamedTuple):
    """The die's middle unit on the coupled sample (every post pressing one half-space)."""

    sample: object
    stiffness: dict
    pair: tuple[int, int]
    references: frozenset


def _die_unit(plan) -> _DieUnit:
    """The middle column's (measuring, reference) pair of ``plan``'s beams on one half-space
    (rigid flat punches of the posts' faces, :mod:`tactcad.in_use.tissue_coupling`) with
    the nominal K (N/mm) of each beam and the reference beams' numbers."""
    from tactcad.in_use.tissue_coupling import Tissue, coupled_sample_from_punches
    from tactcad.mechanics.contact import Punch

    side = plan.post_um * 1e-3
    punches = [Punch(b.x_um * 1e-3, b.tip_y_um * 1e-3, side, side) for b in plan.beams]
    sample = coupled_sample_from_punches([b.number for b in plan.beams], punches, Tissue())
    stiffness = {b.number: (plan.k_r_N_per_mm if b.role == "reference" else plan.k_m_N_per_mm)
                 for b in plan.beams}
    pair = (plan.beams[plan.columns + plan.columns // 2].number,
            plan.beams[plan.columns // 2].number)
    references = frozenset(b.number for b in plan.beams if b.role == "reference")
    return _DieUnit(sample, stiffness, pair, references)


def _coupled_r(unit: _DieUnit, ks, stiffness: dict | None = None) -> np.ndarray:
    """R = e_m / e_r of the die's unit on the coupled sample at each K_obj ``ks`` (N/mm),
    with the nominal K or the given ``stiffness`` (N/mm per beam)."""
    from tactcad.in_use.tissue_coupling import coupled_ratio

    return np.atleast_1d(coupled_ratio(unit.sample, stiffness or unit.stiffness, unit.pair,
                                       np.asarray(ks, float)))


def _read_error(unit: _DieUnit, ks, r) -> np.ndarray:
    """K_obj the coupled inversion reads from ``r`` with the nominal K (N/mm) over the true
    ``ks``, minus 1; inf where no K_obj in its bracket gives ``r`` (unreadable)."""
    from tactcad.in_use.tissue_coupling import coupled_object_stiffness
    from tactcad.mechanics.contact import ContactError

    def read(x: float) -> float:
        try:
            return coupled_object_stiffness(unit.sample, unit.stiffness, unit.pair, x)
        except ContactError:
            return math.inf

    return np.array([read(float(x)) for x in np.atleast_1d(r)]) / np.asarray(ks, float) - 1.0


def _shifted_error(unit: _DieUnit, ks, s_m: float, s_r: float) -> np.ndarray:
    """The read error when every measuring beam's true K is s_m times its nominal and every
    reference beam's s_r times its."""
    true = {n: k * (s_r if n in unit.references else s_m) for n, k in unit.stiffness.items()}
    return _read_error(unit, ks, _coupled_r(unit, ks, true))


def readout_noise_term(plan, readout: dict, ks) -> np.ndarray:
    """The K_obj error of the read-out noise at each true K_obj ``ks`` (N/mm; relative, 1
    sigma): each deflection on the coupled sample read to its bridge's force resolution
    over its K, the two independent, at the point where the reference carries the rated
    force, read by the coupled inversion; inf where R plus its noise is beyond what the
    coupled R spans (unreadable).

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan`.
        readout: its :func:`~tactcad.products.silicon_die.mechanics.piezoresistor.die_readout`.
        ks: the true K_obj values (N/mm).

    Returns:
        |relative K_obj error| at each of ``ks``.
    """
    unit = _die_unit(plan)
    k_m, k_r = plan.k_m_N_per_mm, plan.k_r_N_per_mm
    e_r = plan.full_scale_force_N / k_r
    r = _coupled_r(unit, ks)
    e_m = r * e_r
    s_r = readout["rows"]["reference"]["force_resolution_N"] / k_r / e_r
    s_m = readout["rows"]["measuring"]["force_resolution_N"] / k_m / e_m
    return np.abs(_read_error(unit, ks, r + r * np.hypot(s_r, s_m)))


def die_budget(plan, readout: dict | None = None) -> DieBudget:
    """The die's K_obj budget (see the module doc) at its K_obj range's ends and middle.

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan`.
        readout: :func:`tactcad.products.silicon_die.mechanics.piezoresistor.die_readout` of the plan (made
            here when not given).
    """
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout
    from tactcad.products.silicon_die.vocabulary.soi_process import CAVITY_ALIGNMENT_UM

    readout = readout or die_readout(plan)
    k_m, k_r = plan.k_m_N_per_mm, plan.k_r_N_per_mm
    lo, hi = plan.kobj_range_N_per_mm
    ks = np.array([lo, math.sqrt(lo * hi), hi])
    ref, meas = plan.beams[0], plan.beams[plan.columns]
    unit = _die_unit(plan)
    terms, reasons = {}, {}

    # the deflections on the coupled sample where the reference carries the rated force
    e_r = plan.full_scale_force_N / k_r
    e_m = _coupled_r(unit, ks) * e_r
    terms["read-out noise"] = readout_noise_term(plan, readout, ks)
    reasons["read-out noise"] = ("each deflection on the coupled sample to the bridge's force "
                                 "resolution over its K, the reference at the rated "
                                 f"{plan.full_scale_force_N:g} N, read by the coupled inversion")

    dt = plan.stack.device_tolerance_um / math.sqrt(3)
    s = 1 + 3 * dt / ref.thickness_um
    terms["device layer"] = np.abs(_shifted_error(unit, ks, s, s))
    reasons["device layer"] = (f"+-{plan.stack.device_tolerance_um:g} um on the "
                               f"{ref.thickness_um:g} um layer, both beams alike (K ~ t^3)")

    dl = CAVITY_ALIGNMENT_UM / math.sqrt(3)
    l_m, l_r = plan.bending_length_um(meas), plan.bending_length_um(ref)
    terms["cavity alignment"] = np.abs(_shifted_error(
        unit, ks, (l_m / (l_m + dl)) ** 3, (l_r / (l_r - dl)) ** 3))
    reasons["cavity alignment"] = (f"+-{CAVITY_ALIGNMENT_UM:g} um across the die: one row's "
                                   "beams longer, the other's shorter (K ~ (L + dL)^-3, dL "
                                   "the frame's give at the root)")

    st = 1 + SILICON_TCE_PER_K * TEMPERATURE_STEP_K / math.sqrt(3)
    terms["temperature"] = np.abs(_shifted_error(unit, ks, st, st))
    reasons["temperature"] = (f"{TEMPERATURE_STEP_K:g} K step, <110> silicon's modulus "
                              f"{SILICON_TCE_PER_K * 1e6:g} ppm/K on both beams; the resistors' "
                              "sensitivity drift cancels in R")

    d_temp = TEMPERATURE_STEP_K / math.sqrt(3)
    zero_r = readout["rows"]["reference"]["zero_drift_N_per_K"] * d_temp
    zero_m = readout["rows"]["measuring"]["zero_drift_N_per_K"] * d_temp
    terms["resistor zero drift"] = np.abs(_read_error(unit, ks, (e_m + zero_m / k_m)
                                                     / (e_r + zero_r / k_r)))
    reasons["resistor zero drift"] = (
        f"{TEMPERATURE_STEP_K:g} K step between tare and reading, each beam's half bridge with "
        f"its on-die reference: TCR {1e6 * readout['resistor_tcr_per_K']:+.0f} ppm/K, "
        f"cancelled to a {100 * REFERENCE_TCR_MISMATCH_REL:g} % mismatch (assumption), reads "
        f"{1e6 * zero_r / d_temp:.3g} uN per K on the reference, {1e6 * zero_m / d_temp:.3g} uN "
        "per K on the measuring beam")

    from tactcad.in_use.kobj_budget import COUPLING_MODEL_ERROR_REL

    coupling, mesh_error, why = _tissue_coupling(plan, unit, ks)
    terms[UNCOUPLED] = np.abs(coupling)
    reasons[UNCOUPLED] = why
    terms[COUPLED] = COUPLING_MODEL_ERROR_REL * np.abs(coupling) + mesh_error
    reasons[COUPLED] = (f"the punch model's own error ({COUPLING_MODEL_ERROR_REL:.0%} of the "
                        f"shift it predicts) and its mesh error ({mesh_error:.2%})")

    tol_mm, residual_mm = post_height_tolerance_mm(plan), mismatch_after_zeroing_mm(plan, readout)
    terms[AS_MADE] = post_mismatch_rel(plan, unit, ks, 2 * tol_mm)
    reasons[AS_MADE] = (f"the posts {plan.post_height_um:g} um high to +-{1e3 * tol_mm:.3g} um "
                        "(the process's), a measuring post up to twice that below or above its "
                        "reference, through the coupled model (shown, not summed: every die "
                        "is zeroed on an optical flat)")
    terms[ZEROED] = post_mismatch_rel(plan, unit, ks, residual_mm)
    reasons[ZEROED] = (f"zeroed on an optical flat: {1e3 * residual_mm:.3g} um of mismatch left "
                       "(each beam's deflection resolution and the flat's flatness)")
    budget = DieBudget(ks, terms, reasons)
    return DieBudget(ks, terms, reasons,
                     _tip_height_record(plan, unit, budget, tol_mm, residual_mm))


def post_height_tolerance_mm(plan) -> float:
    """The posts' height tolerance across the die (+- mm): the process's, a share
    (:data:`~tactcad.products.silicon_die.vocabulary.soi_process.POST_HEIGHT_TOLERANCE_REL`)
    of their height."""
    from tactcad.products.silicon_die.vocabulary.soi_process import POST_HEIGHT_TOLERANCE_REL

    return POST_HEIGHT_TOLERANCE_REL * plan.post_height_um * 1e-3


def mismatch_after_zeroing_mm(plan, readout: dict) -> float:
    """The post-height mismatch a zeroing on a rigid flat leaves (mm): each row's deflection
    resolution (its bridge's force resolution over its K) and the flat's flatness
    (:data:`OPTICAL_FLAT_FLATNESS_MM`), in quadrature."""
    rows = readout["rows"]
    return math.hypot(rows["reference"]["force_resolution_N"] / plan.k_r_N_per_mm,
                      rows["measuring"]["force_resolution_N"] / plan.k_m_N_per_mm,
                      OPTICAL_FLAT_FLATNESS_MM)


def post_mismatch_rel(plan, unit: _DieUnit, ks, mismatch_mm: float) -> np.ndarray:
    """The coupled inversion's worst |K_obj error| (either sign) at each true K_obj ``ks``
    (N/mm) when the unit's measuring post stands ``mismatch_mm`` (mm) off its reference's
    height, the reference at the rated force; inf where the reading has no answer (the
    measuring post clear of the tissue, or R beyond the inversion's bracket).

    Args:
        plan: the die. unit: its :func:`_die_unit`. ks: true K_obj values (N/mm).
        mismatch_mm: the two posts' height difference (mm, >= 0).

    Returns:
        |relative K_obj error| at each of ``ks``, shape (len(ks),).
    """
    from tactcad.in_use.tissue_coupling import coupled_object_stiffness, offset_ratio
    from tactcad.mechanics.contact import ContactError

    ks = np.atleast_1d(np.asarray(ks, float))
    out = np.zeros_like(ks)
    if mismatch_mm == 0:
        return out
    measuring, reference = unit.pair
    for i, k in enumerate(ks):
        for sign in (1.0, -1.0):
            half = sign * mismatch_mm / 2
            try:
                r = offset_ratio(unit.sample, unit.stiffness, unit.pair, float(k),
                                 plan.full_scale_force_N, {reference: half, measuring: -half})
                read = coupled_object_stiffness(unit.sample, unit.stiffness, unit.pair, r)
                out[i] = max(out[i], abs(read / k - 1.0))
            except ContactError:
                out[i] = np.inf
    return out


def _tip_height_record(plan, unit: _DieUnit, budget: DieBudget, tol_mm: float,
                       residual_mm: float) -> dict:
    """The budget's post-height record, read as the metal arrays' tip-height record is
    (:func:`tactcad.in_use.tip_height_drawing.choose_tip_height_tolerance`): the process's
    tolerance, the mismatch the zeroing leaves and, with ``kobj_accuracy_rel`` stated, the
    largest tolerance (+- mm) whose as-made term fits, at every K_obj, in what the other
    summed terms leave of the accuracy (None where they leave no room)."""
    accuracy = plan.kobj_accuracy_rel
    record = {"tolerance_mm": tol_mm, "mismatch_after_zeroing_mm": residual_mm,
              "kobj_accuracy_rel": accuracy, "tolerance_for_accuracy_mm": None}
    if accuracy is None:
        return record
    others_sq = sum(np.asarray(v) ** 2 for k, v in budget.terms.items()
                    if k not in SHOWN_NOT_SUMMED and k != ZEROED)
    room = accuracy ** 2 - others_sq
    if np.any(room <= 0) or not np.all(np.isfinite(room)):
        return record
    ks = budget.k_obj_N_per_mm

    def excess(tol: float) -> float:
        # an unreadable mismatch (inf) counts as far too large, finite for the root find
        return min(float(np.max(post_mismatch_rel(plan, unit, ks, 2 * tol) ** 2 / room)),
                   1e12) - 1.0

    record["tolerance_for_accuracy_mm"] = _largest_tolerance_mm(excess, residual_mm)
    return record


def _largest_tolerance_mm(excess, start_mm: float) -> float | None:
    """The root of ``excess(t)`` (increasing in the tolerance t, mm), bracketed by halving and
    doubling from ``start_mm``, to three digits as a drawing prints; None when no positive
    tolerance fits."""
    from scipy.optimize import brentq

    hi = max(start_mm, 1e-9)
    for _ in range(60):
        if excess(hi) >= 0:
            break
        hi *= 2
    lo = hi / 2
    while excess(lo) > 0:
        lo /= 2
        if lo < 1e-12:
            return None
    found = float(brentq(excess, lo, hi, rtol=1e-3)) if excess(hi) > 0 else hi
    return float(f"{found:.3g}")


def _tissue_coupling(plan, unit: _DieUnit, ks: np.ndarray) -> tuple[np.ndarray, float, str]:
    """(the uncoupled eq. 3's bias on the die's tips pressing one half-space (every tip),
    the contact model's mesh error, how)."""
    from tactcad.mechanics.lumped_model import object_stiffness

    k_m, k_r = plan.k_m_N_per_mm, plan.k_r_N_per_mm
    read = [float(object_stiffness(float(x), k_m, k_r)) if 1.0 < x < k_r / k_m else math.inf
            for x in _coupled_r(unit, ks)]  # beyond eq. 3's range no K_obj reads it
    return np.asarray(read) / ks - 1.0, float(unit.sample.error_rel), (
        "the middle unit, every post pressing one half-space (nu 0.5): eq. 3 alone reads the "
        "coupled R this far off (shown, not summed: the coupled inversion removes it)")


#: The procedure that makes a post-height tolerance unnecessary, as the die's drawing and
#: ``verify`` name it.
DIE_ZEROING_PROCEDURE = ("posts zeroed on an optical flat before use (the flat pressed on "
                         "every post in a few steps: each beam's deflection where all touch, "
                         "less the others', is its post's height, which the reading then takes "
                         "out, as tactcad calibrate --flat does for a metal array)")
#: What holds the posts' height, as the drawing's note names it.
POST_PROCESS_WORDS = "the posts' process (spun SU-8 or plating)"


def post_height_drawing(budget: DieBudget):
    """What the die's drawing holds the posts' height to, from the budget's post-height
    record: the process's tolerance, held where it fits the accuracy, else the zeroing on
    an optical flat named (:func:`tactcad.in_use.tip_height_drawing.
    choose_tip_height_tolerance`, the process's tolerance its floor: a drawing cannot ask a
    spun or plated post finer).

    Args:
        budget: the die's :class:`DieBudget`.

    Returns:
        :class:`tactcad.in_use.tip_height_drawing.TipHeightDrawing`, or None when the die
        states no ``kobj_accuracy_rel``.
    """
    from tactcad.in_use.tip_height_drawing import choose_tip_height_tolerance

    record = budget.tip_height or {}
    if record.get("kobj_accuracy_rel") is None:
        return None
    tol = record["tolerance_mm"]
    return choose_tip_height_tolerance(tol, record, floor_mm=tol, feature="Post height",
                                       process=POST_PROCESS_WORDS,
                                       zeroing=DIE_ZEROING_PROCEDURE)
