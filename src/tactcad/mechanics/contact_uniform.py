"""A second rigid-punch model of another discretisation, the check level of the tissue coupling.

:mod:`tactcad.mechanics.contact` grades its cells towards the faces' edges, takes Love's
closed-form rectangle kernel for every cell pair and extrapolates at order 2. This model
shares none of that: uniform cells, far cells by 3 x 3 Gauss quadrature of Boussinesq's
point-load kernel 1/r, near cells (within :data:`NEAR_CELLS` cell edges) by the exact
rectangle integral written here in logarithms, and first-order Richardson extrapolation
over two meshes (the edge-singular pressure under a rigid punch makes uniform cells
converge at order 1). Half-space only; every compliance scales as (1 - ν²)/E, so the
normalised compliance Ĉ = C / C₁ does not depend on E or ν.

``verify`` reads R made on this model's sample with the working model's coupled inversion,
as the stiffness ladder checks one level with the next: the K_obj the two disagree by is
the tissue row's bias (:func:`tactcad.studies.verification.tissue_coupling_record`).

Sources: J. Boussinesq (1885) and K. L. Johnson, *Contact Mechanics*, 1985, eq. 3.21
(point load), sec. 3.3 (uniform rectangle); L. F. Richardson (1927).

Units: mm, N; compliances at (1 - ν²)/E = 1 (mm/N).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from tactcad.mechanics.contact import ContactError, Punch

#: Cells nearer than this many cell edges get the exact rectangle integral.
NEAR_CELLS = 2.5
#: Cell edge of the coarser mesh (mm), at most an eighth of the smallest face edge.
CHECK_CELL_MM = 0.25
#: Largest mesh the check solves (cells of the finer mesh; a dense (n, n) matrix).
MAX_CHECK_CELLS = 8000


def _corner(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """A primitive of 1/√(u² + v²) in u and in v, in logarithms (0 on the axes)."""
    rho = np.hypot(u, v)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(u != 0, u * np.log((v + rho) / np.abs(u)), 0.0)
        b = np.where(v != 0, v * np.log((u + rho) / np.abs(v)), 0.0)
    return a + b


def rectangle_integral(x, z, x1, x2, z1, z2):
    """∫∫ dA / r over the rectangle [x1, x2] x [z1, z2] seen from (x, z) (mm); broadcasts."""
    return (_corner(x2 - x, z2 - z) - _corner(x1 - x, z2 - z) - _corner(x2 - x, z1 - z)
            + _corner(x1 - x, z1 - z))


def _cells(punches: Sequence[Punch], h: float):
    centres, half, owner = [], [], []
    for k, p in enumerate(punches):
        nx = max(1, round(p.width_x_mm / h))
        nz = max(1, round(p.depth_z_mm / h))
        gx, gz = np.meshgrid(p.x_mm - p.width_x_mm / 2 + (np.arange(nx) + 0.5) * p.width_x_mm / nx,
                             p.z_mm - p.depth_z_mm / 2 + (np.arange(nz) + 0.5) * p.depth_z_mm / nz,
                             indexing="ij")
        centres.append(np.column_stack([gx.ravel(), gz.ravel()]))
        half.append(np.tile([p.width_x_mm / nx / 2, p.depth_z_mm / nz / 2], (nx * nz, 1)))
        owner.append(np.full(nx * nz, k))
    return np.vstack(centres), np.vstack(half), np.concatenate(owner)


def uniform_compliance(punches: Sequence[Punch], cell_mm: float) -> np.ndarray:
    """Compliance matrix of rigid flat punches on uniform cells of about ``cell_mm`` (mm/N,
    shape (m, m), at (1 - ν²)/E = 1 MPa).

    Raises:
        ContactError: no punch or a cell size <= 0.
    """
    if not punches:
        raise ContactError("punches", 0, "at least one punch")
    if not (np.isfinite(cell_mm) and cell_mm > 0):
        raise ContactError("cell_mm", cell_mm, "> 0 mm")
    c, half, owner = _cells(punches, cell_mm)
    area = 4 * half[:, 0] * half[:, 1]
    points, weights = np.polynomial.legendre.leggauss(3)
    a = np.zeros((len(c), len(c)))
    with np.errstate(divide="ignore"):  # the own cell's point is replaced below
        for gi, wi in zip(points, weights):
            for gj, wj in zip(points, weights):
                qx = c[None, :, 0] + half[None, :, 0] * gi
                qz = c[None, :, 1] + half[None, :, 1] * gj
                a += wi * wj / 4 * area[None, :] / np.hypot(c[:, None, 0] - qx,
                                                            c[:, None, 1] - qz)
    near = np.hypot(c[:, None, 0] - c[None, :, 0], c[:, None, 1] - c[None, :, 1]) \
        < NEAR_CELLS * 2 * half.max()
    i, j = np.nonzero(near)
    a[i, j] = rectangle_integral(c[i, 0], c[i, 1], c[j, 0] - half[j, 0], c[j, 0] + half[j, 0],
                                 c[j, 1] - half[j, 1], c[j, 1] + half[j, 1])
    incidence = np.zeros((len(owner), len(punches)))
    incidence[np.arange(len(owner)), owner] = 1.0
    # w = (1 - ν²) p I / (π E): the stiffness is π E/(1 - ν²) Σ area p per unit travel
    stiffness = np.pi * incidence.T @ (area[:, None] * np.linalg.solve(a, incidence))
    return np.linalg.inv(0.5 * (stiffness + stiffness.T))


@dataclass(frozen=True, eq=False)
class UniformCheck:
    """The check model's extrapolated compliance.

    Attributes:
        compliance_mm_per_N: C extrapolated from cells h and h/2, shape (m, m) (mm/N).
        error_rel: the largest relative change of a diagonal entry between the finer mesh
            and the extrapolation (its own mesh error, conservative at order 1).
        cell_mm: h (mm).
    """

    compliance_mm_per_N: np.ndarray
    error_rel: float
    cell_mm: float


def check_cell_mm(punches: Sequence[Punch]) -> float:
    """The check's coarser cell (mm): :data:`CHECK_CELL_MM`, at most an eighth of the
    smallest face edge, coarser where the finer mesh would pass :data:`MAX_CHECK_CELLS`."""
    smallest = min(min(p.width_x_mm, p.depth_z_mm) for p in punches)
    h = min(CHECK_CELL_MM, smallest / 8)
    area = sum(p.width_x_mm * p.depth_z_mm for p in punches)
    return max(h, 2 * float(np.sqrt(area / MAX_CHECK_CELLS)))


def uniform_check(punches: Sequence[Punch]) -> UniformCheck:
    """First-order Richardson of :func:`uniform_compliance` on cells h and h/2
    (h: :func:`check_cell_mm`), kept in the result store (:func:`tactcad.store.kept_result`)
    for the same punches: a re-export or verify of an unchanged design solves it once.

    Raises:
        ContactError: as :func:`uniform_compliance`.
    """
    from tactcad.store import kept_result

    return kept_result("uniform contact check", lambda: _uniform_check(punches),
                       tuple(punches))


def _uniform_check(punches: Sequence[Punch]) -> UniformCheck:
    h = check_cell_mm(punches)
    coarse, fine = uniform_compliance(punches, h), uniform_compliance(punches, h / 2)
    best = 2 * fine - coarse
    error = float(np.max(np.abs(np.diag(fine) / np.diag(best) - 1.0)))
    return UniformCheck(best, error, h)
