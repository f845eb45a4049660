"""Stress fields of the FEM levels: nodal von Mises stress, the peak at the
flexure hinge, and VTU files for ParaView.

Stress recovery: the P2 displacement gives a strain that is linear in each
cell and discontinuous across cells. It is evaluated at the cell's vertices
and averaged over the cells that share a vertex (nodal averaging); at the
notch root, a boundary point where the stress peaks, this converges with
the mesh like the P2 stress itself (O(h^2)), so a Richardson extrapolation
over the three meshes of a level gives the converged peak and its error.

Constitutive law: sigma = lambda tr(eps) I + 2 mu eps with the solve's
Lame parameters; in plane stress (lambda = lambda*) sigma_zz = 0, in plane
strain sigma_zz = lambda (eps_xx + eps_yy). Von Mises:
sqrt(((s1 - s2)^2 + (s2 - s3)^2 + (s3 - s1)^2) / 2 + 3 (t12^2 + t23^2 + t31^2)).

VTU: the linear cells of the mesh (vertex nodes; a P2 field's vertex dofs
are its vertex values) with point data ``displacement`` (mm, 3 components)
and ``von_mises_MPa``; the 3D half model is mirrored about the mid-plane so
the file shows the whole element. Written with meshio.

Sources: scikit-fem documentation (``CellBasis`` with a given quadrature);
O. C. Zienkiewicz & J. Z. Zhu (1992), Int. J. Numer. Meth. Eng. 33, 1331
(nodal stress recovery); meshio documentation (``meshio.Mesh``, ``write``).

Units: mm, N, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tactcad.design.array_plan import ElementGeometry
from tactcad.mechanics.fem.fem2d import DisplacementField


def vertex_stress(field: DisplacementField) -> np.ndarray:
    """Cauchy stress at every mesh vertex, averaged over the cells sharing it.

    Returns:
        shape (n_vertices, 3, 3), MPa, under the field's force.
    """
    from skfem import CellBasis

    sb = field.basis
    mesh = sb.mesh
    dim = mesh.dim()
    ref = mesh.init_refdom().p  # (dim, dim + 1): local vertex k of every cell
    cb = CellBasis(mesh, sb.elem, quadrature=(ref, np.full(dim + 1, 1.0 / (dim + 1))))
    u = field.displacement
    # grad[i, j, e, k] = d u_i / d x_j at local vertex k of cell e
    grad = np.array([np.array(cb.interpolate(u[c::dim]).grad) for c in range(dim)])
    eps = 0.5 * (grad + grad.transpose(1, 0, 2, 3))
    tr = np.einsum("iiek->ek", eps)
    nv = mesh.p.shape[1]
    cell_sig = np.zeros((3, 3) + tr.shape)
    cell_sig[:dim, :dim] = 2.0 * field.mu * eps
    for i in range(dim):
        cell_sig[i, i] += field.lam * tr
    if dim == 2 and field.plane == "strain":
        cell_sig[2, 2] = field.lam * tr
    verts = mesh.t  # (dim + 1, n_cells): vertex of local vertex k in cell e
    out = np.zeros((nv, 3, 3))
    count = np.bincount(verts.ravel(), minlength=nv).astype(float)
    for i in range(3):
        for j in range(3):
            out[:, i, j] = np.bincount(verts.ravel(), weights=cell_sig[i, j].T.ravel(),
                                       minlength=nv)
    return out / np.maximum(count, 1.0)[:, None, None]


def von_mises(sigma: np.ndarray) -> np.ndarray:
    """Von Mises equivalent stress of stress tensors, shape (..., 3, 3) -> (...)."""
    s = sigma
    d = (s[..., 0, 0] - s[..., 1, 1]) ** 2 + (s[..., 1, 1] - s[..., 2, 2]) ** 2 \
        + (s[..., 2, 2] - s[..., 0, 0]) ** 2
    sh = s[..., 0, 1] ** 2 + s[..., 1, 2] ** 2 + s[..., 2, 0] ** 2
    return np.sqrt(0.5 * d + 3.0 * sh)


@dataclass(frozen=True)
class PeakStress:
    """Largest vertex von Mises stress at the flexure hinge.

    Attributes:
        von_mises_MPa: the peak under the field's force (MPa).
        per_newton_MPa_per_N: the peak per newton of tip force (MPa/N).
        location_mm: (x, y) or (x, y, z) of the vertex, element frame (mm).
    """

    von_mises_MPa: float
    per_newton_MPa_per_N: float
    location_mm: tuple[float, ...]


def notch_vertices(p: np.ndarray, g: ElementGeometry) -> np.ndarray:
    """Mask of vertices at the flexure hinge: |x - x_h| <= R and y at or above
    the notch centre (the web and the notch's upper half). This keeps out the
    clamp line, whose fixed corners are singular, and the tip-root fillet."""
    xh, R, yc = g.hinge_x_mm, g.notch_radius_mm, g.notch_centre_y_mm
    return (np.abs(p[0] - xh) <= R + 1e-9) & (p[1] >= yc - 1e-9)


def peak_notch_stress(field: DisplacementField, g: ElementGeometry) -> PeakStress:
    """Peak von Mises stress at the flexure hinge of one solve.

    Raises:
        RuntimeError: no mesh vertex lies in the hinge region.
    """
    p = field.basis.mesh.p
    mask = notch_vertices(p, g)
    if not mask.any():
        raise RuntimeError("no mesh vertex at the flexure hinge")
    vm = von_mises(vertex_stress(field))
    idx = np.nonzero(mask)[0]
    k = int(idx[np.argmax(vm[idx])])
    peak = float(vm[k])
    return PeakStress(peak, peak / field.force_N, tuple(float(c) for c in p[:, k]))


def write_vtu(path: str | Path, field: DisplacementField) -> Path:
    """Write the field as a VTU file (meshio) for ParaView.

    Point data: ``displacement`` (mm, shape (n, 3)) and ``von_mises_MPa`` (n,),
    under the solve's force. A 3D half model is mirrored about its mid-plane
    (u_z changes sign), so the file holds the whole element. Cells are the
    mesh's linear triangles or tetrahedra.

    Args:
        path: output file (``.vtu``); parent directories are created.
        field: a solve's :class:`~tactcad.mechanics.fem.fem2d.DisplacementField`.

    Returns:
        the path written.
    """
    import meshio

    mesh = field.basis.mesh
    dim = mesh.dim()
    nv = mesh.p.shape[1]
    pts = np.zeros((nv, 3))
    pts[:, :dim] = mesh.p.T
    disp = np.zeros((nv, 3))
    for c in range(dim):
        disp[:, c] = field.displacement[c::dim][:nv]  # P2 vertex dofs come first
    vm = von_mises(vertex_stress(field))
    cells = mesh.t.T.astype(np.int64)
    if field.sym_plane_z is not None:
        zm = field.sym_plane_z
        mirror = pts.copy()
        mirror[:, 2] = 2.0 * zm - mirror[:, 2]
        mdisp = disp.copy()
        mdisp[:, 2] *= -1.0
        pts = np.vstack([pts, mirror])
        disp = np.vstack([disp, mdisp])
        vm = np.concatenate([vm, vm])
        cells = np.vstack([cells, cells[:, [0, 2, 1, 3]] + nv])  # mirrored: keep orientation
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    # (meshio 5.3's VTU writer drops field data, so the force and K are not stored)
    meshio.Mesh(pts, [("triangle" if dim == 2 else "tetra", cells)],
                point_data={"displacement": disp, "von_mises_MPa": vm}).write(
        out, file_format="vtu")
    return out
