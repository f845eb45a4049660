"""The ``comb-fem2d`` crosstalk level: one row's comb sheet as a plane-stress solid.

The elements of a comb flex in the sheet's plane, and so do the posts and the spine that
carry them: the whole row's sheet (spine, posts, notches, arms, tips; its exact wire-cut
outline, :func:`tactcad.geometry.profile.comb_sheet_profile`) is one plane-stress body of
the sheet's thickness (quadratic triangles, scikit-fem ``ElementTriP2`` on a gmsh mesh,
isoparametric on every arc: :mod:`tactcad.mechanics.fem.comb_sheet_mesh`). Each element's
bonded gauge is meshed with it, its glue line and carrier a region on the top face over the
web (its modulus spread over the sheet, as the stiffness ladder's fem2d meshes it,
:mod:`tactcad.mechanics.bonded_layer`).

Held where the fasteners hold it: each dowel pin's reamed hole has its rim fixed (a rigid
pin in an H7 hole); each screw holds the annulus under its head (from its clearance hole
to the head's diameter) fixed, the preload's friction taken to keep it from slipping. The
spacer, the other row and the jaw beyond the fasteners are rigid; the stop ledges stay
open (each stop gap is wider than the travel a unit force gives), so they carry nothing.
The rows meet only through the fixed fasteners: they do not couple here.

Loads: a unit force on each element's contact face in turn (a uniform traction along +y
over the face, the stiffness ladder's fem2d's direction). One sparse factorisation of the
row (SuperLU, :func:`tactcad.mechanics.fem.sparse_lu.spd_lu`) serves every load.

Read-outs, per gauge i and load j: the grid's mean eps_xx on its plane (the layer's top),
the difference of u_x at the grid's two ends (mesh vertices) over its length, exact for the
field; times the fem3d-fitted width factor of the face (the plane field's line over the
grid's width, :func:`tactcad.mechanics.gauge_strain.width_strain_factor`), as fem2d's
``grid_strain_per_N`` reads the diagonal. The factor scales a gauge's whole row of the
matrix, so crosstalk_rel and the decoupling matrix do not depend on it. Tip displacement:
the work-conjugate of the load, f_i^T K^-1 f_j (the mean along +y of face i under load j),
symmetric by construction.

Error estimate: two meshes (:data:`SIZE_FACTORS`: twice the fine mesh's sizes, then the
fine mesh); crosstalk_rel's change between them over 2^p - 1 with p = 2 (two levels cannot
observe the order; Richardson with the quadratic elements' order in the strain, as
:mod:`tactcad.mechanics.stack_fem3d`). On the 10 mm grasper's comb: 5.36e-7 +/- 2.7 % in
4-9 s on two cores (38 000 and 36 000 unknowns a row on the fine mesh); a third mesh with
half the fine sizes gives 5.30e-7 (1.2 % away; the three observe order 3).

Units: mm, N, MPa, s.
"""

from __future__ import annotations

import math
import time

import numpy as np

from tactcad.mechanics.comb_crosstalk import COMB_BASIS, CombInputs, comb_result
from tactcad.mechanics.crosstalk_ladder import CrosstalkResult, crosstalk_of
from tactcad.mechanics.fem.comb_sheet_mesh import Circle2, LayerBox, mesh_comb_sheet

#: Elements through each web at its neck on the fine mesh (the stiffness ladder's fem2d
#: takes 6 for K; the crosstalk, a ratio of strains, is converged with fewer: on the 10 mm
#: grasper's comb, 3 on the fine mesh gives crosstalk_rel 1.2 % from the mesh with half its
#: sizes, which costs three times as long).
WEB_DIVISIONS = 3.0
#: The two meshes' size factors: twice the fine mesh's sizes, then the fine mesh (ratio 2).
SIZE_FACTORS = (2.0, 1.0)
#: The order assumed for the two meshes' Richardson estimate (P2 elements, the strain).
ASSUMED_ORDER = 2.0


def layer_boxes(inputs: CombInputs, row: int) -> list[LayerBox]:
    """Each gauge's glue line and carrier on ``row``'s sheet (sheet frame, mm), in the
    row's element order."""
    out = []
    for k in inputs.row_elements(row):
        b, x0 = inputs.layers[k], inputs.offsets_mm[k]
        out.append(LayerBox(x0 + b.x0_mm, x0 + b.x1_mm, x0 + b.grid_x0_mm, x0 + b.grid_x1_mm,
                            b.face_y_mm, b.grid_plane_y_mm))
    return out


def solve_row(inputs: CombInputs, row: int, size_factor: float = 1.0,
              web_divisions: float = WEB_DIVISIONS) -> tuple[np.ndarray, np.ndarray, int]:
    """(gauge strain S (1/N, the grid's plane, before the width factor), tip compliance C
    (mm/N), unknowns) of ``row``'s elements under a unit force on each tip in turn."""
    import skfem
    from skfem import Basis, FacetBasis, LinearForm, asm

    from tactcad.mechanics.fem.fem2d import assemble_elasticity, skfem_mesh_of
    from tactcad.mechanics.fem.sparse_lu import spd_lu

    idx = inputs.row_elements(row)
    sheet = inputs.sheets[row]
    boxes = layer_boxes(inputs, row)
    heads = [Circle2((x, inputs.fastener_y_mm), inputs.screw_head_diameter_mm / 2)
             for x in inputs.screw_x_mm]
    sm = mesh_comb_sheet(sheet, boxes, heads, size_factor=size_factor,
                         web_divisions=web_divisions)
    mesh = skfem_mesh_of(sm.p, sm.t, sm.arcs)
    p2 = skfem.ElementTriP2()
    sb = Basis(mesh, p2, intorder=4)
    E, nu, b = inputs.youngs_modulus_MPa, inputs.poisson_ratio, inputs.sheet_mm
    # the spine (below every ledge) at its modulus factor (a what-if), the rest as made
    centre_y = mesh.p[1][mesh.t[:3]].mean(axis=0)
    Ec = np.where(centre_y < min(sheet.ledges_mm), E * inputs.spine_modulus_factor, E)
    lam, mu = Ec * nu / (1 - nu * nu), Ec / (2 * (1 + nu))
    for cells, k in zip(sm.layer_cells, idx):
        layer = inputs.layers[k]
        El, nul = layer.modulus_over_sheet_MPa(b), layer.poisson_ratio
        lam[cells], mu[cells] = El * nul / (1 - nul * nul), El / (2 * (1 + nul))
    n = 2 * int(sb.N)
    # held: each dowel hole's rim, each screw head's annulus
    tol = 1e-7
    rims = _facets_on_circles(mesh, [(x, inputs.fastener_y_mm) for x in inputs.dowel_x_mm],
                              inputs.dowel_diameter_mm / 2)
    held = np.union1d(sb.get_dofs(rims).all(),
                      np.unique(sb.element_dofs[:, np.flatnonzero(sm.head_cells)]))
    if len(rims) == 0 or not sm.head_cells.any():
        raise RuntimeError("the comb sheet's dowel rims or screw heads are not in the mesh")
    fixed = (2 * held[:, None] + np.arange(2)[None, :]).ravel()
    free = np.setdiff1d(np.arange(n), fixed)
    F = np.zeros((n, len(idx)))
    for j, k in enumerate(idx):
        g, x0 = sheet.elements[inputs.columns[k]], inputs.offsets_mm[k]
        lo, hi, y = x0 + g.overall_length_mm - g.tip_width_mm, x0 + g.overall_length_mm, \
            g.tip_top_y_mm
        face = mesh.facets_satisfying(
            lambda x, lo=lo, hi=hi, y=y: (np.abs(x[1] - y) < tol) & (x[0] > lo - tol)
            & (x[0] < hi + tol), boundaries_only=True)
        if len(face) == 0:
            raise RuntimeError(f"element {inputs.numbers[k]}'s contact face is not in the mesh")
        q = 1.0 / (g.tip_width_mm * b)
        fy = asm(LinearForm(lambda v, w, q=q: q * v), FacetBasis(mesh, p2, facets=face,
                                                                intorder=4)) * b
        F[1::2, j] = fy
    K = assemble_elasticity(sb, lam[:, None], mu[:, None], free=free) * b
    U = np.zeros_like(F)
    U[free] = spd_lu(K, dofs_per_node=2).solve(F[free])
    C = F.T @ U
    ux = U[0::2]
    S = np.zeros((len(idx), len(idx)))
    for a, ((v0, v1), box) in enumerate(zip(sm.grid_vertices, boxes)):
        S[a] = (ux[v1] - ux[v0]) / (box.grid_x1_mm - box.grid_x0_mm)
    return S, C, n


def _facets_on_circles(mesh, centres, radius: float, tol: float = 1e-7) -> np.ndarray:
    """Boundary facets whose two vertices lie on a circle of ``radius`` about one of
    ``centres`` (mm): the holes' rims."""
    bf = mesh.boundary_facets()
    ends = mesh.p[:, mesh.facets[:, bf]]  # (2, 2 ends, facets)
    on = np.zeros(len(bf), dtype=bool)
    for cx, cy in centres:
        r = np.hypot(ends[0] - cx, ends[1] - cy)
        on |= np.all(np.abs(r - radius) < tol * max(1.0, radius), axis=0)
    return bf[on]


def _matrices(inputs: CombInputs, size_factor: float) -> tuple[np.ndarray, np.ndarray]:
    n = len(inputs.numbers)
    S, C = np.zeros((n, n)), np.zeros((n, n))
    width = np.array(inputs.width_factor)
    for row in sorted(set(inputs.rows)):
        idx = inputs.row_elements(row)
        s, c, _ = solve_row(inputs, row, size_factor)
        S[np.ix_(idx, idx)] = width[idx][:, None] * s
        C[np.ix_(idx, idx)] = c
    return S, C


def estimate_comb_fem2d(inputs: CombInputs,
                        size_factors: tuple[float, float] = SIZE_FACTORS) -> CrosstalkResult:
    """The comb's rows as plane-stress solids on two meshes (``size_factors``: the coarse
    one's, then the fine one's): the fine mesh's matrices, the two meshes' Richardson
    error of crosstalk_rel (order :data:`ASSUMED_ORDER`).

    Raises:
        ValueError: size factors that are not two, positive and falling.
    """
    if len(size_factors) != 2 or not size_factors[0] > size_factors[1] > 0:
        raise ValueError(f"size_factors = {size_factors!r}: allowed two, coarse then fine, > 0")
    t0 = time.perf_counter()
    coarse = crosstalk_of(_matrices(inputs, size_factors[0])[0])[0]
    S, C = _matrices(inputs, size_factors[1])
    rel = crosstalk_of(S)[0]
    ratio = size_factors[0] / size_factors[1]
    error = abs(rel - coarse) / (ratio ** ASSUMED_ORDER - 1.0) / rel if rel else 0.0
    return comb_result("comb-fem2d", inputs, S, C,
                       error if math.isfinite(error) else math.inf, t0,
                       COMB_BASIS + "; the row's sheet as a plane-stress solid, its gauges' "
                       "glue lines and carriers meshed")
