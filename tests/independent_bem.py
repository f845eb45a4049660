"""An independent rigid-punch boundary-element model, to check tactcad.mechanics.contact with
a model of another discretisation: uniform cells (not graded), far cells by 3 x 3 Gauss
quadrature of the point-load kernel 1/r (not Love's closed form), near cells by the exact
rectangle integral written out here in logarithms, and first-order Richardson over two meshes
(the edge-singular pressure makes uniform cells converge at order 1). Half-space; compliances
at E/(1 - nu^2) = 1 MPa (mm/N)."""

from __future__ import annotations

import numpy as np

#: Cells nearer than this many cell edges get the exact rectangle integral.
NEAR_CELLS = 2.5


def _corner(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """A primitive of 1/sqrt(u^2 + v^2) in u and v, in logarithms (0 on the axes)."""
    rho = np.hypot(u, v)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(u != 0, u * np.log((v + rho) / np.abs(u)), 0.0)
        b = np.where(v != 0, v * np.log((u + rho) / np.abs(v)), 0.0)
    return a + b


def rectangle_integral(x, z, x1, x2, z1, z2):
    """Integral of 1/r over the rectangle [x1, x2] x [z1, z2] seen from (x, z) (mm)."""
    return (_corner(x2 - x, z2 - z) - _corner(x1 - x, z2 - z) - _corner(x2 - x, z1 - z)
            + _corner(x1 - x, z1 - z))


def _cells(punches, h):
    centres, half, owner = [], [], []
    for k, (x, z, w, d) in enumerate(punches):
        nx, nz = max(1, round(w / h)), max(1, round(d / h))
        gx, gz = np.meshgrid(x - w / 2 + (np.arange(nx) + 0.5) * w / nx,
                             z - d / 2 + (np.arange(nz) + 0.5) * d / nz, indexing="ij")
        centres.append(np.column_stack([gx.ravel(), gz.ravel()]))
        half.append(np.tile([w / nx / 2, d / nz / 2], (nx * nz, 1)))
        owner.append(np.full(nx * nz, k))
    return np.vstack(centres), np.vstack(half), np.concatenate(owner)


def compliance(punches, h: float) -> np.ndarray:
    """Compliance matrix (mm/N) of rigid punches ``(x, z, width_x, depth_z)`` on cells of
    about ``h`` (mm)."""
    c, half, owner = _cells(punches, h)
    area = 4 * half[:, 0] * half[:, 1]
    points, weights = np.polynomial.legendre.leggauss(3)
    a = np.zeros((len(c), len(c)))
    with np.errstate(divide="ignore"):
        for gi, wi in zip(points, weights):
            for gj, wj in zip(points, weights):
                qx = c[None, :, 0] + half[None, :, 0] * gi
                qz = c[None, :, 1] + half[None, :, 1] * gj
                a += wi * wj / 4 * area[None, :] / np.hypot(c[:, None, 0] - qx, c[:, None, 1] - qz)
    near = np.hypot(c[:, None, 0] - c[None, :, 0], c[:, None, 1] - c[None, :, 1]) \
        < NEAR_CELLS * 2 * half.max()
    i, j = np.nonzero(near)
    a[i, j] = rectangle_integral(c[i, 0], c[i, 1], c[j, 0] - half[j, 0], c[j, 0] + half[j, 0],
                                 c[j, 1] - half[j, 1], c[j, 1] + half[j, 1])
    incidence = np.zeros((len(owner), len(punches)))
    incidence[np.arange(len(owner)), owner] = 1.0
    # w = p I / (pi E*): the stiffness is pi E* sum(area p) per unit travel
    stiffness = np.pi * incidence.T @ (area[:, None] * np.linalg.solve(a, incidence))
    return np.linalg.inv(0.5 * (stiffness + stiffness.T))


def extrapolated_compliance(punches, h: float) -> np.ndarray:
    """First-order Richardson of :func:`compliance` on cells of ``h`` and ``h / 2`` (mm)."""
    return 2 * compliance(punches, h / 2) - compliance(punches, h)
