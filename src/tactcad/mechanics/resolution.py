"""K_obj resolution of one sensing unit (eq. 1-3) when its forces are read to a resolution,
and of an array of units (its best unit at each K_obj).

Units: N, N/mm.
"""

from __future__ import annotations

from typing import NamedTuple, Sequence

import numpy as np

#: Force resolution of the read-out (N): "force resolution >= 0.01 N" of the
#: calibration that the macro array's elements reached.
FORCE_RESOLUTION_N = 0.01
#: Points of the log grid over a K_obj range where the resolution is evaluated.
KOBJ_POINTS = 41


def unit_resolution(k_m: float, k_r: float, k_obj, full_scale_force_N: float,
                    force_resolution_N: float = FORCE_RESOLUTION_N, *,
                    force_resolution_reference_N: float | None = None) -> dict[str, np.ndarray]:
    """R, dR/dK_obj and the K_obj resolution at each K_obj (arrays, N/mm).

    The unit is pressed until the reference carries ``full_scale_force_N``;
    the measuring element then carries F R / X (eq. 1). Each force is read to
    ``force_resolution_N`` (the reference to ``force_resolution_reference_N``
    when given, e.g. each element's own read-out noise):
    dR/R = sqrt((dF_m/F_m)^2 + (dF_r/F_r)^2), and
    dK_obj = |dK_obj/dR| dR (eq. 3 sensitivity).

    Raises:
        LumpedDomainError: a stiffness outside eq. 2's domain.
    """
    from tactcad.mechanics.lumped_model import deflection_ratio, sensitivity

    k_obj = np.atleast_1d(np.asarray(k_obj, float))
    km, kr = np.full_like(k_obj, k_m), np.full_like(k_obj, k_r)
    R = deflection_ratio(km, kr, k_obj).value
    dk_dr = sensitivity(R, km, kr).value
    F_r = np.full_like(k_obj, full_scale_force_N)
    F_m = F_r * R * k_m / k_r
    dF_r = force_resolution_N if force_resolution_reference_N is None \
        else force_resolution_reference_N
    e_r = F_r / k_r
    dR = ratio_noise(R, e_r, force_resolution_N / k_m, dF_r / k_r)
    rel = noise_kobj_rel(R, k_obj / dk_dr, e_r, force_resolution_N / k_m, dF_r / k_r)
    return {"K_obj_N_per_mm": k_obj, "R": R, "dR_dKobj_per_N_per_mm": 1.0 / dk_dr,
            "force_measuring_N": F_m, "force_reference_N": F_r, "R_resolution": dR,
            "K_obj_resolution_N_per_mm": rel * k_obj, "K_obj_resolution_rel": rel}


def ratio_noise(ratio, deflection_r_mm, deflection_resolution_m_mm: float,
                deflection_resolution_r_mm: float) -> np.ndarray:
    """The standard deviation of R = e_m / e_r (eq. 2) when each deflection is read to its
    own resolution, independently (first order, GUM 5.1.2).

    Args:
        ratio: R at each K_obj (eq. 2 alone, or on a coupled sample).
        deflection_r_mm: the reference's deflection e_r (mm); e_m = R e_r.
        deflection_resolution_m_mm, deflection_resolution_r_mm: the measuring and the
            reference element's deflection resolution (mm, 1 sigma): force resolution / K.

    Returns:
        sigma_R = R sqrt((de_m / e_m)^2 + (de_r / e_r)^2) at each K_obj (array).
    """
    ratio = np.asarray(ratio, float)
    e_r = np.asarray(deflection_r_mm, float)
    return np.abs(ratio) * np.hypot(deflection_resolution_m_mm / (ratio * e_r),
                                    deflection_resolution_r_mm / e_r)


def noise_kobj_rel(ratio, ratio_per_ln_kobj, deflection_r_mm, deflection_resolution_m_mm: float,
                   deflection_resolution_r_mm: float) -> np.ndarray:
    """The relative K_obj error (1 sigma) a unit's read-out noise leaves: :func:`ratio_noise`
    over the slope dR/d ln K_obj of the inversion that reads K_obj from R. ``readout``'s and
    ``verify``'s K_obj resolution (:func:`unit_resolution`: eq. 2's R and slope) and the
    budget's read-out term (the coupled sample's R and slope,
    :func:`tactcad.in_use.kobj_budget.readout_noise`) are both this function.

    Args:
        ratio: R = e_m / e_r at each K_obj.
        ratio_per_ln_kobj: dR/d ln K_obj of the same model at each K_obj.
        deflection_r_mm: the reference's deflection e_r (mm).
        deflection_resolution_m_mm, deflection_resolution_r_mm: each element's deflection
            resolution (mm, 1 sigma): its force resolution through the read-out chain / K.

    Returns:
        sigma_K_obj / K_obj at each K_obj (array); inf where R does not move with K_obj
        (no K_obj can be read there).
    """
    with np.errstate(all="ignore"):
        rel = ratio_noise(ratio, deflection_r_mm, deflection_resolution_m_mm,
                          deflection_resolution_r_mm) / np.abs(ratio_per_ln_kobj)
    return np.where(np.isfinite(rel), rel, np.inf)


class ReadUnit(NamedTuple):
    """A sensing unit as read: its reference's K and force resolution, its measuring
    element's K and force resolution (N/mm, N, N/mm, N)."""

    k_r: float
    force_resolution_reference_N: float
    k_m: float
    force_resolution_measuring_N: float


def best_unit_resolution_rel(units: Sequence[ReadUnit], k_obj, full_scale_force_N: float
                             ) -> np.ndarray:
    """The relative K_obj resolution of an array at each K_obj (array, N/mm): its best
    unit's (:func:`unit_resolution` with each element's own force resolution); inf where
    there is no unit. Units read alike (a comb's columns) are worked out once: the least
    of equal arrays is either.
    """
    k_obj = np.atleast_1d(np.asarray(k_obj, float))
    best = np.full(k_obj.shape, np.inf)
    for u in dict.fromkeys(units):  # equal units once, in their order
        r = unit_resolution(u.k_m, u.k_r, k_obj, full_scale_force_N,
                            u.force_resolution_measuring_N,
                            force_resolution_reference_N=u.force_resolution_reference_N)
        best = np.minimum(best, r["K_obj_resolution_rel"])
    return best


def worst_resolution_rel(units: Sequence[ReadUnit], kobj_range: tuple[float, float],
                         full_scale_force_N: float) -> float:
    """The array's worst relative K_obj resolution over ``kobj_range`` ([LO, HI] N/mm,
    :data:`KOBJ_POINTS` log-spaced points, ends included); inf without a unit."""
    k_obj = np.geomspace(*kobj_range, KOBJ_POINTS)
    return float(np.max(best_unit_resolution_rel(units, k_obj, full_scale_force_N)))


def reads_within(resolution_rel, target_rel: float) -> np.ndarray:
    """Where a K_obj resolution reads K_obj: at most ``target_rel`` (the requirement's
    ``kobj_resolution_rel``). ``verify``'s readable K_obj range and the budget's readable
    units both judge so.

    Args:
        resolution_rel: relative K_obj resolution at each K_obj (:func:`unit_resolution`'s,
            or an array's best, :func:`best_unit_resolution_rel`).
        target_rel: the largest relative resolution that reads K_obj.

    Returns:
        A boolean array over the K_obj given.
    """
    return np.asarray(resolution_rel, float) <= target_rel
