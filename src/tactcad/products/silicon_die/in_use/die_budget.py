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
  the metal arrays), and the coupled model's own error that remains.

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

    @property
    def total_rel(self) -> np.ndarray:
        return np.sqrt(sum(np.asarray(v) ** 2 for k, v in self.terms.items()
                           if k != UNCOUPLED))

    def as_json(self) -> dict:
        return {"k_obj_N_per_mm": self.k_obj_N_per_mm.tolist(),
                "terms_rel": {k: np.asarray(v).tolist() for k, v in self.terms.items()},
                "rss_rel": self.total_rel.tolist(), "rss_leaves_out": UNCOUPLED,
                "reasons": dict(self.reasons)}


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
    return DieBudget(ks, terms, reasons)


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
