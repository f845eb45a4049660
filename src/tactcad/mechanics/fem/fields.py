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


def cell_vertex_gradients(field: DisplacementField, cells: np.ndarray | None = None
                          ) -> np.ndarray:
    """Displacement gradient of the P2 field at the vertices of each cell (not averaged).

    Args:
        field: a solve's displacement field.
        cells: the cells to evaluate (indices; ``None``: every cell).

    Returns:
        ``grad[i, j, e, k] = d u_i / d x_j`` at local vertex k of cell e (of ``cells``),
        shape (dim, dim, n_cells, dim + 1), under the field's force.
    """
    from tactcad.mechanics.fem.fem2d import basis_gradients

    sb = field.basis
    mesh = sb.mesh
    dim = mesh.dim()
    ref = mesh.init_refdom().p  # (dim, dim + 1): local vertex k of every cell
    cells = np.arange(mesh.nelements) if cells is None else np.asarray(cells)
    u = field.displacement
    return basis_gradients(sb, [u[c::dim] for c in range(dim)], cells, ref)


def vertex_stress(field: DisplacementField) -> np.ndarray:
    """Cauchy stress at every mesh vertex, averaged over the element's cells sharing it
    (a bonded layer's cells are left out: their stress is not the element's; a vertex of
    the layer alone reads 0).

    Returns:
        shape (n_vertices, 3, 3), MPa, under the field's force.
    """
    mesh = field.basis.mesh
    dim = mesh.dim()
    cells = None if field.body_cells is None else np.flatnonzero(field.body_cells)
    grad = cell_vertex_gradients(field, cells)
    eps = 0.5 * (grad + grad.transpose(1, 0, 2, 3))
    tr = np.einsum("iiek->ek", eps)
    nv = mesh.p.shape[1]
    cell_sig = np.zeros((3, 3) + tr.shape)
    cell_sig[:dim, :dim] = 2.0 * field.mu * eps
    for i in range(dim):
        cell_sig[i, i] += field.lam * tr
    if dim == 2 and field.plane == "strain":
        cell_sig[2, 2] = field.lam * tr
    verts = mesh.t if cells is None else mesh.t[:, cells]  # vertex of local vertex k in cell e
    out = np.zeros((nv, 3, 3))
    count = np.bincount(verts.ravel(), minlength=nv).astype(float)
    for i in range(3):
        for j in range(3):
            out[:, i, j] = np.bincount(verts.ravel(), weights=cell_sig[i, j].T.ravel(),
                                       minlength=nv)
    return out / np.maximum(count, 1.0)[:, None, None]


# ---------------------------------------------------------------------------
# The strain a bonded gauge averages: eps_xx on the flat top face (3D)
# ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class FaceStrain:
    """eps_xx of a 3D solve on the flat top face, exactly as the P2 field has it.

    Each boundary triangle of the face carries the strain of the one tetrahedron it
    bounds at its three corners; a P2 displacement's strain is linear in a
    straight cell, so the face's strain is piecewise linear (discontinuous
    between triangles) and :func:`face_rectangle_average` integrates it exactly.

    Attributes:
        corners_mm: (x, z) of each triangle's corners, shape (m, 3, 2) (mm).
        strain_per_N: eps_xx at those corners per newton of tip force, shape (m, 3) (1/N).
        sym_plane_z: z of the half model's mid-plane (mm), or None for a whole model.
    """

    corners_mm: np.ndarray
    strain_per_N: np.ndarray
    sym_plane_z: float | None


def top_face_strain(field: DisplacementField, y_top_mm: float, *,
                    tol_mm: float = 1e-7) -> FaceStrain:
    """eps_xx on the boundary face y = ``y_top_mm`` of a 3D solve, per newton.

    Raises:
        ValueError: a 2D field, or no boundary triangle lies on that face.
    """
    mesh = field.basis.mesh
    if mesh.dim() != 3:
        raise ValueError("top_face_strain needs a 3D field")
    facets = mesh.boundary_facets()
    verts = mesh.facets[:, facets]
    on_face = np.all(np.abs(mesh.p[1, verts] - y_top_mm) < tol_mm, axis=0)
    if not on_face.any():
        raise ValueError(f"no boundary face at y = {y_top_mm} mm")
    facets, verts = facets[on_face], verts[:, on_face]
    cells = mesh.f2t[0, facets]
    exx = cell_vertex_gradients(field, cells)[0, 0]  # (m, 4): at the cell's local vertices
    local = np.argmax(mesh.t[:, cells][None, :, :] == verts[:, None, :], axis=1)  # (3, m)
    strain = np.take_along_axis(exx, local.T, axis=1) / field.force_N
    corners = mesh.p[[0, 2]][:, verts].transpose(2, 1, 0)
    return FaceStrain(corners, strain, field.sym_plane_z)


def _clip_polygon(poly: list, axis: int, bound: float, keep_below: bool) -> list:
    """Sutherland-Hodgman: the part of ``poly`` ((x, z) points) on one side of a line."""
    def inside(p):
        return p[axis] <= bound if keep_below else p[axis] >= bound

    out = []
    for k, cur in enumerate(poly):
        prev = poly[k - 1]
        if inside(cur) != inside(prev):
            s = (bound - prev[axis]) / (cur[axis] - prev[axis])
            out.append(prev + s * (cur - prev))
        if inside(cur):
            out.append(cur)
    return out


def face_rectangle_average(face: FaceStrain, x_span_mm: tuple[float, float],
                           z_span_mm: tuple[float, float]) -> float:
    """Mean of the face's eps_xx per newton over the rectangle x_span x z_span (1/N).

    Each face triangle is clipped to the rectangle and its linear strain
    integrated over the clipped polygon (exact for the piecewise-linear
    face strain). On a half model the rectangle is mirrored about the
    mid-plane first: its part beyond the mid-plane is read at the mirror z
    (the strain is symmetric), so a grid centred on the mid-plane averages
    the half it covers.

    Raises:
        ValueError: an empty rectangle, or one the face does not cover.
    """
    (x0, x1), (z0, z1) = sorted(x_span_mm), sorted(z_span_mm)
    if not (x1 > x0 and z1 > z0):
        raise ValueError(f"empty rectangle x {x_span_mm}, z {z_span_mm} (mm)")
    pieces = [(z0, z1)]
    zm = face.sym_plane_z
    if zm is not None and z1 > zm:  # fold the part past the mid-plane onto the half model
        pieces = [(min(z0, zm), zm)] if z0 < zm else []
        pieces.append((max(2 * zm - z1, 0.0), 2 * zm - max(z0, zm)))
    c, v = face.corners_mm, face.strain_per_N
    total = area = 0.0
    for za, zb in pieces:
        if zb <= za:
            continue
        near = ((c[:, :, 0].max(1) > x0) & (c[:, :, 0].min(1) < x1)
                & (c[:, :, 1].max(1) > za) & (c[:, :, 1].min(1) < zb))
        for tri, val in zip(c[near], v[near]):
            poly = [tri[0], tri[1], tri[2]]
            for axis, bound, below in ((0, x0, False), (0, x1, True), (1, za, False),
                                       (1, zb, True)):
                poly = _clip_polygon(poly, axis, bound, below) if poly else poly
            if len(poly) < 3:
                continue
            t = _linear_on_triangle(tri, val)
            for p, q in zip(poly[1:-1], poly[2:]):
                a = 0.5 * abs((p[0] - poly[0][0]) * (q[1] - poly[0][1])
                              - (q[0] - poly[0][0]) * (p[1] - poly[0][1]))
                total += a * (t(poly[0]) + t(p) + t(q)) / 3.0
                area += a
    want = (x1 - x0) * (z1 - z0)
    if not np.isclose(area, want, rtol=1e-6):
        raise ValueError(f"the top face covers {area:.6g} of the {want:.6g} mm^2 asked "
                         f"(x {x_span_mm}, z {z_span_mm} mm)")
    return total / area


def _linear_on_triangle(tri: np.ndarray, val: np.ndarray):
    """The linear function through ``val`` at the triangle's corners ((x, z) points)."""
    m = np.array([[tri[1][0] - tri[0][0], tri[2][0] - tri[0][0]],
                  [tri[1][1] - tri[0][1], tri[2][1] - tri[0][1]]])
    inv = np.linalg.inv(m)

    def f(p):
        l1, l2 = inv @ (np.asarray(p) - tri[0])
        return val[0] + l1 * (val[1] - val[0]) + l2 * (val[2] - val[0])
    return f


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
    return ((np.abs(p[0] - xh) <= R + 1e-9) & (p[1] >= yc - 1e-9)
            & (p[1] <= g.base_height_mm + 1e-9))  # not a bonded layer's above the face


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
