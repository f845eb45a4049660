"""The K_obj a silicon die reads and the errors that enter it, term by term.

A unit of the die (a measuring beam and the reference beam paired with it) is pressed into
the tissue until the stiffer reference carries the rated force; R = e_m / e_r of the two
deflections gives K_obj by eq. 3 with the die's nominal K_m and K_r
(:func:`tactcad.mechanics.lumped_model.object_stiffness`). Each term below perturbs what
the die is or reads and gives the K_obj eq. 3 then reads, relative to the true one, at the
ends and the geometric middle of the K_obj range (1 sigma; a +- bound taken uniform, its
sigma bound / sqrt 3):

* read-out noise: each deflection read to the bridge's force resolution over its K
  (:func:`tactcad.products.silicon_die.mechanics.piezoresistor.die_readout`), the two independent;
* device layer: both beams one layer, so K_r and K_m move together by 3 dt / t
  (dt: the SOI maker's +- on the layer); eq. 3 with the nominal K reads the shift;
* cavity alignment: the cavities' outer edges are the two rows' roots, so the front
  masks' shift across the die against them lengthens one row's beams and shortens the
  other's (K ~ L^-3): K_r / K_m moves;
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
  bias of the uncoupled eq. 3 (removed by the coupled inversion, as on the metal arrays).

The first four are each beam's K measured in calibration (eq. 4-6) or the temperature
held; they are given before any correction. Units: N/mm, N, um, K.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

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


def _read(k_m: float, k_r: float, ks: np.ndarray, r) -> np.ndarray:
    """K_obj eq. 3 reads from ``r`` with the nominal K (N/mm) over the true ``ks``, minus 1;
    inf where ``r`` leaves eq. 3's range 1 < R < K_r / K_m (no K_obj reads it)."""
    from tactcad.mechanics.lumped_model import object_stiffness

    read = [float(object_stiffness(float(x), k_m, k_r)) if 1.0 < x < k_r / k_m else math.inf
            for x in np.atleast_1d(r)]
    return np.asarray(read) / ks - 1.0


def _shifted(k_m: float, k_r: float, ks: np.ndarray, s_m: float, s_r: float) -> np.ndarray:
    """The read error when the true K are s_m K_m and s_r K_r."""
    from tactcad.mechanics.lumped_model import deflection_ratio

    r = np.array([float(deflection_ratio(s_m * k_m, s_r * k_r, k)) for k in ks])
    return _read(k_m, k_r, ks, r)


def readout_noise_term(plan, readout: dict, ks) -> np.ndarray:
    """The K_obj error of the read-out noise at each true K_obj ``ks`` (N/mm; relative, 1
    sigma): each deflection read to its bridge's force resolution over its K, the two
    independent, at the point where the reference carries the rated force; inf where R
    plus its noise leaves eq. 3's range 1 < R < K_r / K_m (unreadable)."""
    from tactcad.mechanics.lumped_model import deflection_ratio

    k_m, k_r = plan.k_m_N_per_mm, plan.k_r_N_per_mm
    e_r = plan.full_scale_force_N / k_r
    r = np.array([float(deflection_ratio(k_m, k_r, k)) for k in ks])
    e_m = r * e_r
    s_r = readout["rows"]["reference"]["force_resolution_N"] / k_r / e_r
    s_m = readout["rows"]["measuring"]["force_resolution_N"] / k_m / e_m
    return np.abs(_read(k_m, k_r, np.asarray(ks, float), r + r * np.hypot(s_r, s_m)))


def die_budget(plan, readout: dict | None = None) -> DieBudget:
    """The die's K_obj budget (see the module doc) at its K_obj range's ends and middle.

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan`.
        readout: :func:`tactcad.products.silicon_die.mechanics.piezoresistor.die_readout` of the plan (made
            here when not given).
    """
    from tactcad.mechanics.lumped_model import deflection_ratio
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout
    from tactcad.products.silicon_die.vocabulary.soi_process import CAVITY_ALIGNMENT_UM

    readout = readout or die_readout(plan)
    k_m, k_r = plan.k_m_N_per_mm, plan.k_r_N_per_mm
    lo, hi = plan.kobj_range_N_per_mm
    ks = np.array([lo, math.sqrt(lo * hi), hi])
    ref, meas = plan.beams[0], plan.beams[plan.columns]
    terms, reasons = {}, {}

    # the deflections where the reference carries the rated force
    e_r = plan.full_scale_force_N / k_r
    e_m = np.array([float(deflection_ratio(k_m, k_r, k)) for k in ks]) * e_r
    terms["read-out noise"] = readout_noise_term(plan, readout, ks)
    reasons["read-out noise"] = ("each deflection to the bridge's force resolution over its K, "
                                 f"the reference at the rated {plan.full_scale_force_N:g} N")

    dt = plan.stack.device_tolerance_um / math.sqrt(3)
    s = 1 + 3 * dt / ref.thickness_um
    terms["device layer"] = np.abs(_shifted(k_m, k_r, ks, s, s))
    reasons["device layer"] = (f"+-{plan.stack.device_tolerance_um:g} um on the "
                               f"{ref.thickness_um:g} um layer, both beams alike (K ~ t^3)")

    dl = CAVITY_ALIGNMENT_UM / math.sqrt(3)
    l_m, l_r = plan.bending_length_um(meas), plan.bending_length_um(ref)
    terms["cavity alignment"] = np.abs(_shifted(
        k_m, k_r, ks, (l_m / (l_m + dl)) ** 3, (l_r / (l_r - dl)) ** 3))
    reasons["cavity alignment"] = (f"+-{CAVITY_ALIGNMENT_UM:g} um across the die: one row's "
                                   "beams longer, the other's shorter (K ~ (L + dL)^-3, dL "
                                   "the frame's give at the root)")

    st = 1 + SILICON_TCE_PER_K * TEMPERATURE_STEP_K / math.sqrt(3)
    terms["temperature"] = np.abs(_shifted(k_m, k_r, ks, st, st))
    reasons["temperature"] = (f"{TEMPERATURE_STEP_K:g} K step, <110> silicon's modulus "
                              f"{SILICON_TCE_PER_K * 1e6:g} ppm/K on both beams; the resistors' "
                              "sensitivity drift cancels in R")

    d_temp = TEMPERATURE_STEP_K / math.sqrt(3)
    zero_r = readout["rows"]["reference"]["zero_drift_N_per_K"] * d_temp
    zero_m = readout["rows"]["measuring"]["zero_drift_N_per_K"] * d_temp
    terms["resistor zero drift"] = np.abs(_read(k_m, k_r, ks, (e_m + zero_m / k_m)
                                                / (e_r + zero_r / k_r)))
    reasons["resistor zero drift"] = (
        f"{TEMPERATURE_STEP_K:g} K step between tare and reading, each beam's half bridge with "
        f"its on-die reference: TCR {1e6 * readout['resistor_tcr_per_K']:+.0f} ppm/K, "
        f"cancelled to a {100 * REFERENCE_TCR_MISMATCH_REL:g} % mismatch (assumption), reads "
        f"{1e6 * zero_r / d_temp:.3g} uN per K on the reference, {1e6 * zero_m / d_temp:.3g} uN "
        "per K on the measuring beam")

    from tactcad.in_use.kobj_budget import COUPLING_MODEL_ERROR_REL

    coupling, mesh_error, why = _tissue_coupling(plan, ks)
    terms[UNCOUPLED] = np.abs(coupling)
    reasons[UNCOUPLED] = why
    terms[COUPLED] = COUPLING_MODEL_ERROR_REL * np.abs(coupling) + mesh_error
    reasons[COUPLED] = (f"the punch model's own error ({COUPLING_MODEL_ERROR_REL:.0%} of the "
                        f"shift it predicts) and its mesh error ({mesh_error:.2%})")
    return DieBudget(ks, terms, reasons)


def _tissue_coupling(plan, ks: np.ndarray) -> tuple[np.ndarray, float, str]:
    """(the uncoupled eq. 3's bias on the die's tips pressing one half-space (every tip),
    the contact model's mesh error, how)."""
    from tactcad.in_use.tissue_coupling import Tissue, coupled_ratio, coupled_sample_from_punches
    from tactcad.mechanics.contact import Punch

    side = plan.post_um * 1e-3
    punches = [Punch(b.x_um * 1e-3, b.tip_y_um * 1e-3, side, side) for b in plan.beams]
    numbers = [b.number for b in plan.beams]
    sample = coupled_sample_from_punches(numbers, punches, Tissue())
    stiffness = {b.number: (plan.k_r_N_per_mm if b.role == "reference" else plan.k_m_N_per_mm)
                 for b in plan.beams}
    unit = (plan.beams[plan.columns + plan.columns // 2].number,
            plan.beams[plan.columns // 2].number)  # the middle column's pair
    r = coupled_ratio(sample, stiffness, unit, ks, "array")
    bias = _read(plan.k_m_N_per_mm, plan.k_r_N_per_mm, ks, r)
    return bias, float(sample.error_rel), (
        "the middle unit, every post pressing one half-space (nu 0.5): eq. 3 alone reads the "
        "coupled R this far off (shown, not summed: the coupled inversion removes it)")
