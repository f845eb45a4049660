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


@dataclass(frozen=True)
class _Grid:
    """One punch's uniform cells: first centre (x0, z0), pitch (dx, dz), counts (nx, nz) (mm);
    cells in row-major (ix, iz) order."""

    x0: float
    z0: float
    dx: float
    dz: float
    nx: int
    nz: int

    @property
    def count(self) -> int:
        return self.nx * self.nz

    def index(self) -> tuple[np.ndarray, np.ndarray]:
        """(ix, iz) of every cell, shape (count,) each."""
        ix, iz = np.meshgrid(np.arange(self.nx), np.arange(self.nz), indexing="ij")
        return ix.ravel(), iz.ravel()


def _grid(p: Punch, h: float) -> _Grid:
    nx = max(1, round(p.width_x_mm / h))
    nz = max(1, round(p.depth_z_mm / h))
    dx, dz = p.width_x_mm / nx, p.depth_z_mm / nz
    return _Grid(p.x_mm - p.width_x_mm / 2 + dx / 2, p.z_mm - p.depth_z_mm / 2 + dz / 2,
                 dx, dz, nx, nz)


def _kernel(ox: np.ndarray, oz: np.ndarray, hx: float, hz: float, near_mm: float) -> np.ndarray:
    """∫∫ dA / r over a source cell of half-edges (hx, hz) seen from a collocation point
    at offset (ox, oz) from its centre (mm); broadcasts. Within ``near_mm`` of the centre
    the exact rectangle integral, beyond it 3 x 3 Gauss quadrature of the point-load kernel."""
    points, weights = np.polynomial.legendre.leggauss(3)
    area = 4 * hx * hz
    far = np.zeros(np.broadcast(ox, oz).shape)
    with np.errstate(divide="ignore"):  # the own cell's point is replaced below
        for gi, wi in zip(points, weights):
            for gj, wj in zip(points, weights):
                far += wi * wj / 4 * area / np.hypot(ox - hx * gi, oz - hz * gj)
    near = np.broadcast_to(np.hypot(ox, oz) < near_mm, far.shape)
    far[near] = rectangle_integral(*(np.broadcast_to(v, far.shape)[near] for v in (ox, oz)),
                                   -hx, hx, -hz, hz)
    return far


def _block(target: _Grid, source: _Grid, near_mm: float) -> np.ndarray:
    """The influence of ``source``'s cells at ``target``'s collocation points, shape
    (target.count, source.count). On equal pitches every entry depends on the cells' index
    offset only, so the kernel is evaluated once per offset and gathered."""
    hx, hz = source.dx / 2, source.dz / 2
    ti, tk = target.index()
    si, sk = source.index()
    if target.dx == source.dx and target.dz == source.dz:
        di = np.arange(-(source.nx - 1), target.nx)
        dk = np.arange(-(source.nz - 1), target.nz)
        ox = (target.x0 - source.x0) + di * target.dx
        oz = (target.z0 - source.z0) + dk * target.dz
        table = _kernel(ox[:, None], oz[None, :], hx, hz, near_mm)
        return table[ti[:, None] - si[None, :] + source.nx - 1,
                     tk[:, None] - sk[None, :] + source.nz - 1]
    ox = (target.x0 + ti * target.dx)[:, None] - (source.x0 + si * source.dx)[None, :]
    oz = (target.z0 + tk * target.dz)[:, None] - (source.z0 + sk * source.dz)[None, :]
    return _kernel(ox, oz, hx, hz, near_mm)


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
    grids = [_grid(p, cell_mm) for p in punches]
    near_mm = NEAR_CELLS * max(max(g.dx, g.dz) for g in grids)
    a = np.block([[_block(t, s, near_mm) for s in grids] for t in grids])
    area = np.concatenate([np.full(g.count, g.dx * g.dz) for g in grids])
    owner = np.concatenate([np.full(g.count, k) for k, g in enumerate(grids)])
    incidence = np.zeros((len(owner), len(punches)))
    incidence[np.arange(len(owner)), owner] = 1.0
    # w = (1 - ν²) p I / (π E): the stiffness is π E/(1 - ν²) Σ area p per unit travel
    stiffness = np.pi * incidence.T @ (area[:, None] * _solve(a, incidence, _mirrors(grids)))
    return np.linalg.inv(0.5 * (stiffness + stiffness.T))


def _mirrors(grids: Sequence[_Grid]) -> list[np.ndarray]:
    """The cells' mirror images about the layout's centre lines
    (:func:`tactcad.mechanics.contact.mirror_maps`), in the order of ``grids``' cells."""
    from types import SimpleNamespace

    from tactcad.mechanics.contact import mirror_maps

    centres, half = [], []
    for g in grids:
        ix, iz = g.index()
        centres.append(np.column_stack([g.x0 + ix * g.dx, g.z0 + iz * g.dz]))
        half.append(np.tile([g.dx / 2, g.dz / 2], (g.count, 1)))
    return mirror_maps(SimpleNamespace(centres=np.vstack(centres), half=np.vstack(half)))


def _solve(a: np.ndarray, b: np.ndarray, maps: Sequence[np.ndarray] = ()) -> np.ndarray:
    """a⁻¹ b. A layout with mirror symmetry splits into a system per symmetry class
    (:func:`tactcad.mechanics.contact.solve_by_symmetry`: for two mirrors about an eighth
    of the work). Else cells of one size everywhere make ``a`` symmetric (each entry
    depends on the offset only) and positive definite (the 1/r kernel is): Cholesky, half
    the work of LU; else, or if Cholesky finds it not positive definite, LU."""
    import scipy.linalg

    if maps:
        from tactcad.mechanics.contact import solve_by_symmetry

        return solve_by_symmetry(a, b, list(maps))
    if np.allclose(a, a.T, rtol=1e-12, atol=0.0):
        try:
            return scipy.linalg.cho_solve(scipy.linalg.cho_factor(a, check_finite=False), b,
                                          check_finite=False)
        except np.linalg.LinAlgError:
            pass
    return np.linalg.solve(a, b)


@dataclass(frozen=True, eq=False)
class UniformCheck:
    """The check model's extrapolated compliance.

    Attributes:
        compliance_mm_per_N: C extrapolated from cells h and h/2, shape (m, m) (mm/N).
        error_rel: the largest relative change of a diagonal entry between the finer mesh
            and the extrapolation (its own mesh error, conservative at order 1).
        cell_mm: h (mm).
        coarser_mm_per_N: C extrapolated one step coarser, from cells 2h and h, shape
            (m, m) (mm/N): what a result read on the check changes by between the two
            extrapolations is its error estimate (the extrapolations themselves were seen
            to converge at about order 1, so the change bounds the remaining error).
    """

    compliance_mm_per_N: np.ndarray
    error_rel: float
    cell_mm: float
    coarser_mm_per_N: np.ndarray | None = None


def check_cell_mm(punches: Sequence[Punch]) -> float:
    """The check's coarser cell (mm): :data:`CHECK_CELL_MM`, at most an eighth of the
    smallest face edge, coarser where the finer mesh would pass :data:`MAX_CHECK_CELLS`."""
    smallest = min(min(p.width_x_mm, p.depth_z_mm) for p in punches)
    h = min(CHECK_CELL_MM, smallest / 8)
    area = sum(p.width_x_mm * p.depth_z_mm for p in punches)
    return max(h, 2 * float(np.sqrt(area / MAX_CHECK_CELLS)))


def finer_check_cell_mm(punches: Sequence[Punch], cell_mm: float) -> float | None:
    """The next check's cell (``cell_mm`` / 2, mm) where its finer mesh (cells of a
    quarter of ``cell_mm``) stays within :data:`MAX_CHECK_CELLS`; None where it would not."""
    area = sum(p.width_x_mm * p.depth_z_mm for p in punches)
    return cell_mm / 2 if area / (cell_mm / 4) ** 2 <= MAX_CHECK_CELLS else None


def uniform_check(punches: Sequence[Punch], cell_mm: float | None = None) -> UniformCheck:
    """First-order Richardson of :func:`uniform_compliance` on cells h and h/2
    (h: ``cell_mm``, default :func:`check_cell_mm`), with the extrapolation one step
    coarser (cells 2h and h) beside it, kept in the result store
    (:func:`tactcad.store.kept_result`) for the same punches: a re-export or verify of
    an unchanged design solves it once.

    Raises:
        ContactError: as :func:`uniform_compliance`.
    """
    from tactcad.store import kept_result

    h = check_cell_mm(punches) if cell_mm is None else float(cell_mm)
    return kept_result("uniform contact check", lambda: _uniform_check(punches, h),
                       tuple(punches), h)


def _uniform_check(punches: Sequence[Punch], h: float) -> UniformCheck:
    coarsest, coarse, fine = (uniform_compliance(punches, x) for x in (2 * h, h, h / 2))
    best = 2 * fine - coarse
    error = float(np.max(np.abs(np.diag(fine) / np.diag(best) - 1.0)))
    return UniformCheck(best, error, h, 2 * coarse - coarsest)
