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
    dR = R * np.hypot(force_resolution_N / F_m, dF_r / F_r)
    dk = np.abs(dk_dr) * dR
    return {"K_obj_N_per_mm": k_obj, "R": R, "dR_dKobj_per_N_per_mm": 1.0 / dk_dr,
            "force_measuring_N": F_m, "force_reference_N": F_r, "R_resolution": dR,
            "K_obj_resolution_N_per_mm": dk, "K_obj_resolution_rel": dk / k_obj}




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
    there is no unit.
    """
    k_obj = np.atleast_1d(np.asarray(k_obj, float))
    best = np.full(k_obj.shape, np.inf)
    for u in units:
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
